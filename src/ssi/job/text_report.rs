//! The `ssi` job's text report: the intersection result ([`SsiResult`]) printed as a summary,
//! one line per face pair with its branches and singular points, the tangent contacts, the
//! coverage counts and the certificate's statements.

use crate::ssi::report::{SingularKind, SsiResult};

impl std::fmt::Display for SsiResult {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let s = &self.summary;
        writeln!(f, "surface-surface intersection, tol {:e}", s.tol)?;
        writeln!(
            f,
            "  faces: {} x {}; pairs considered {}, culled by bounds {}, intersected {}, with curves {}",
            s.faces_a,
            s.faces_b,
            s.pairs_considered,
            s.pairs_culled_by_bounds,
            s.pairs_intersected,
            s.pairs_with_branches
        )?;
        writeln!(
            f,
            "  branches: {} ({} closed), {} points; largest proven distance to a surface {:.3e}, to the curve {} ({})",
            s.branches,
            s.closed_branches,
            s.points,
            s.dist_max,
            match s.dist_curve_max {
                Some(d) => format!("{d:.3e}"),
                None => format!("unproven at {} points", s.points_curve_uncertified),
            },
            if s.all_points_within_tol {
                "all within tol of the curve"
            } else {
                "NOT all proven within tol of the curve"
            }
        )?;
        if s.singular_points_proven + s.singular_points_uncertified > 0 {
            writeln!(
                f,
                "  singular points: {} proven (touching or branch point), {} uncertified",
                s.singular_points_proven, s.singular_points_uncertified
            )?;
        }
        for p in self
            .pairs
            .iter()
            .filter(|p| !p.branches.is_empty() || !p.touch_points.is_empty())
        {
            writeln!(
                f,
                "  faces ({}, {}): {} branches, {} tangential points, {} + {} triangles, {:.3} s",
                p.a,
                p.b,
                p.branches.len(),
                p.touch_points.len(),
                p.stats.triangles_a,
                p.stats.triangles_b,
                p.stats.seconds
            )?;
            for (j, b) in p.branches.iter().enumerate() {
                writeln!(
                    f,
                    "    branch {j}: {}, {} points{}, proven dist {:.2e} / {:.2e}, to the curve {}, ends: {}",
                    if b.closed { "closed" } else { "open" },
                    b.points.len(),
                    if b.tangents.is_empty() {
                        String::new()
                    } else {
                        let cubic = b.pieces().iter().filter(|h| h.dp != h.dq).count();
                        format!(" (cubic pieces: {cubic} cubic, the rest chords)")
                    },
                    b.dist_a_max,
                    b.dist_b_max,
                    match (b.dist_curve_max, b.curve_cert.len()) {
                        (Some(d), 0) => format!("{d:.2e}"),
                        (Some(d), n) => format!("{d:.2e} ({n} by sign change at a branch point)"),
                        (None, _) => format!("unproven at {} points", b.curve_uncertified_points),
                    },
                    if b.ends.is_empty() {
                        "none".to_string()
                    } else {
                        b.ends
                            .iter()
                            .map(|e| e.as_str())
                            .collect::<Vec<_>>()
                            .join(", ")
                    }
                )?;
            }
            for (j, t) in p.touch_points.iter().enumerate() {
                let Some(s) = &t.singular else { continue };
                let at = format!("({:.6}, {:.6}, {:.6})", t.point[0], t.point[1], t.point[2]);
                let what = match (s.kind, s.reason) {
                    (SingularKind::TouchingPoint, _) => "touching point, proven".to_string(),
                    (SingularKind::BranchPoint, _) => "branch point, proven".to_string(),
                    (SingularKind::Uncertified, Some(r)) => format!("uncertified ({})", r.as_str()),
                    (SingularKind::Uncertified, None) => "uncertified".to_string(),
                };
                let dist = s
                    .distance
                    .map(|d| format!(", distance at the root ≤ {:.1e}", d[1]))
                    .unwrap_or_default();
                writeln!(
                    f,
                    "    singular point {j} at {at}: {what}{dist}, {} branch ends",
                    t.branch_ends
                )?;
            }
        }
        for p in &self.pairs {
            let Some(c) = &p.tangent_contact else {
                continue;
            };
            let n = c.points.len();
            let at = |k: usize| match c.points.get(k) {
                Some(q) => format!("({:.6}, {:.6}, {:.6})", q[0], q[1], q[2]),
                None => "(not listed)".to_string(),
            };
            writeln!(
                f,
                "  faces ({}, {}): TANGENT CONTACT along a curve (measured): {} points from {} to {}, normals' sine <= {:.1e}, gap <= {:.1e}; {} tangential points and {} uncertified branches moved into it",
                p.a,
                p.b,
                n + c.points_not_listed(),
                at(0),
                at(n.saturating_sub(1)),
                c.max_sin_angle,
                c.max_gap,
                c.touch_points_moved,
                c.branches_moved
            )?;
        }
        for p in &self.pairs {
            for c in &p.common_borders {
                let n = c.points.len();
                let at = |k: usize| {
                    let q = c.points[k.min(n - 1)];
                    format!("({:.6}, {:.6}, {:.6})", q[0], q[1], q[2])
                };
                let what = match c.curve_radius_max {
                    Some(r) if c.exact => {
                        format!("exact: every point within {r:.1e} of the curve (proven)")
                    }
                    _ if c.exact => "exact, point bounds NOT proven".to_string(),
                    _ => format!(
                        "within {:.1e} (proven), whether the faces meet there NOT decided",
                        c.gap
                    ),
                };
                writeln!(
                    f,
                    "  faces ({}, {}): COMMON BORDER {} of A = {} of B{}: {n} points from {} to {}, {what}; {} branch points and {} touch points moved into it",
                    p.a,
                    p.b,
                    c.border_a,
                    c.border_b,
                    if c.reversed { " (reversed)" } else { "" },
                    at(0),
                    at(n.saturating_sub(1)),
                    c.branch_points_moved,
                    c.touch_points_moved
                )?;
            }
        }
        let cov: Vec<_> = self
            .pairs
            .iter()
            .filter_map(|p| p.coverage.as_ref())
            .collect();
        if !cov.is_empty() {
            let (pairs, free, near, tube, tr, unc, reg) =
                cov.iter().fold((0, 0, 0, 0, 0, 0, 0), |a, c| {
                    (
                        a.0 + c.pairs,
                        a.1 + c.free,
                        a.2 + c.near_output,
                        a.3 + c.near_shared_edges,
                        a.4 + c.transversal,
                        a.5 + c.uncertified,
                        a.6 + c.branch_point_regions,
                    )
                });
            let tube = if tube > 0 {
                format!(", {tube} in the tube around a shared edge")
            } else {
                String::new()
            };
            let reg = if reg > 0 {
                format!(", {reg} inside the proven region of a branch point")
            } else {
                String::new()
            };
            writeln!(
                f,
                "  coverage: {pairs} parameter-box pairs: {free} proven free, {near} within the match distance of the output{tube}, {tr} transversal with every border crossing near the output{reg}, {unc} uncertified"
            )?;
        }
        if s.partial {
            writeln!(
                f,
                "  PARTIAL RESULT: time limit reached, {} pairs not run",
                s.pairs_not_run
            )?;
        }
        for c in &s.certificate {
            writeln!(f, "  - {c}")?;
        }
        writeln!(f, "  time {:.3} s", s.seconds)
    }
}

#[cfg(test)]
mod tests {
    use crate::model::{Model, Surface};
    use crate::spline::construct::bilinear;
    use crate::ssi::{SsiParams, intersect_models};

    /// A face restriction can leave a tangent contact whose listed points all went to a
    /// shared edge while unlisted ones remain (occt-hammer.iges did: the report then
    /// indexed an empty polyline). The report names the count and says none is listed.
    #[test]
    fn a_contact_without_listed_points_is_reported() {
        let plane = |z0: f64, z1: f64| {
            let s = bilinear(
                [0.0, 0.0, z0],
                [1.0, 0.0, z0],
                [0.0, 1.0, z1],
                [1.0, 1.0, z1],
            );
            Surface::new("plane", s.expect("a finite bilinear patch"))
        };
        let m = Model {
            surfaces: vec![plane(0.0, 0.0), plane(-0.5, 0.5)],
            ..Default::default()
        };
        let mut r = intersect_models(&m, None, &SsiParams::default(), &|_, _| {})
            .expect("two crossing planes intersect");
        assert_eq!(r.pairs.len(), 1);
        r.pairs[0].tangent_contact =
            Some(super::super::super::tangent_contact::TangentContactOut {
                unlisted: vec![([0.0; 3], [0.0; 2], [0.0; 2]); 7],
                ..Default::default()
            });
        let text = r.to_string();
        assert!(
            text.contains("TANGENT CONTACT along a curve (measured): 7 points from (not listed)"),
            "{text}"
        );
    }
}
