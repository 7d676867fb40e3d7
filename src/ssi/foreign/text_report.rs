//! The foreign-result certificate as text: [`CertifyReport`] printed per curve and per
//! vericad branch not found, with the notes and the verdict.

use super::CertifyReport;

impl std::fmt::Display for CertifyReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(
            f,
            "certify foreign SSI result ({}), tol {:e}, match distance {:e}, {} points",
            self.mode.replace('_', " "),
            self.tol,
            self.match_distance,
            self.points_checked
        )?;
        for c in &self.curves {
            writeln!(
                f,
                "  curve {} ({}, {} points): {} on the curve, {} off, {} on shared edges, {} outside the faces' trims, {} uncertified; distance to A <= {:.3e}, to B <= {:.3e}, to the intersection >= {:.3e}{} -> {}",
                c.index,
                c.kind,
                c.points_checked,
                c.points_on_curve,
                c.points_off,
                c.points_shared_edge,
                c.points_outside_faces,
                c.points_uncertified,
                c.dist_a_max,
                c.dist_b_max,
                c.dist_lower_max,
                c.curve_dist_max
                    .map(|r| format!(", a true curve point within {r:.3e} of every point"))
                    .unwrap_or_default(),
                match c.status {
                    "within_tol" => "within tol",
                    "off" => "NOT within tol (proven off)",
                    "shared_edge" => "on shared edges (not certified)",
                    "outside_faces" =>
                        "NOT within tol of the faces (on their surfaces outside the trims)",
                    _ => "NOT certified",
                }
            )?;
            for i in &c.issues {
                writeln!(
                    f,
                    "    point {} {:?}: {:?} ({})",
                    i.index, i.point, i.status, i.reason
                )?;
            }
        }
        writeln!(
            f,
            "  vericad branches: {} ({} missing from the foreign result, {} partly missing, {} not covered but unverified); vericad's coverage {}",
            self.branches.len(),
            self.missing_branches,
            self.partial_branches,
            self.unverified_branches,
            if self.vericad_no_missed_branches {
                "certified"
            } else {
                "NOT certified"
            }
        )?;
        for b in self.branches.iter().filter(|b| b.status != "found") {
            writeln!(
                f,
                "    faces ({}, {}) branch {} ({}, {} points): {} ({:.0}% covered){}",
                b.face_a,
                b.face_b,
                b.branch,
                if b.closed { "closed" } else { "open" },
                b.points,
                b.status,
                100.0 * b.covered_fraction,
                match (b.witness, b.witness_radius) {
                    (Some(w), Some(r)) => format!(
                        "; a true intersection point within {r:.2e} of {w:?} is proven farther than the match distance from every foreign curve"
                    ),
                    _ => String::new(),
                }
            )?;
        }
        for n in &self.notes {
            writeln!(f, "  - {n}")?;
        }
        writeln!(
            f,
            "  {} ({:.3} s)",
            if self.certified {
                "CERTIFIED: every foreign curve lies within tol of the intersection and none is missing"
            } else {
                "NOT CERTIFIED"
            },
            self.seconds
        )
    }
}
