//! Step 9a — point insertion: points are inserted on the true curve between consecutive
//! refined points of a branch until every chord's midpoint lies within `tol` of the true
//! curve point found from it (the Auxiliary Plane Method, [`super::refine`], started from the
//! chord's parameter midpoint). Near tangency the new points are moved onto the curve
//! ([`onto_curve`]) before chords are measured against it.

use super::branch::PairGeometry;
use super::krawczyk::{CurveCertificate, Uncertified, certify_on_curve};
use super::refine::{
    RefineParams, RefineStatus, Refined, auxiliary_plane, barycentric_uv, domain, sin_between,
};
use crate::geom::{dist, dist_to_segment};
use crate::spline::NurbsSurface;
use crate::spline::closure::Closure;
use crate::spline::project::point_d1;

/// The parameter midpoint of `a` and `b`, or `None` when they are more than a quarter of the
/// domain apart in a direction. In a closed direction (`seam`: `S(d0, ·) = S(d1, ·)`) the
/// midpoint is taken the short way round, across the seam, and brought back into the domain:
/// a branch ending at a point on the seam (a tangent point at `u = d1`, its neighbours just past
/// `u = d0`) is refined like any other. The midpoint only steers the refinement.
fn average_uv(a: &[f64; 2], b: &[f64; 2], dom: &[f64; 4], seam: [bool; 2]) -> Option<[f64; 2]> {
    let mut m = [0.0; 2];
    for k in 0..2 {
        let (lo, hi) = (dom[2 * k], dom[2 * k + 1]);
        let per = hi - lo;
        let (x, mut y) = (a[k], b[k]);
        if seam[k] && (x - y).abs() > 0.5 * per {
            y += if x > y { per } else { -per };
        }
        if (x - y).abs() > 0.25 * per {
            return None;
        }
        let mut c = 0.5 * (x + y);
        if c < lo {
            c += per;
        } else if c > hi {
            c -= per;
        }
        m[k] = c.clamp(lo, hi);
    }
    Some(m)
}

/// Which directions of `s` are closed (`[u, v]`), from the control net.
pub(super) fn seams(s: &NurbsSurface<f64, 3>) -> [bool; 2] {
    let c = Closure::of(s);
    [c.seam_u, c.seam_v]
}

pub(super) struct Inserter<'a, 'g> {
    pub(super) g: &'a PairGeometry<'g>,
    pub(super) prm: &'a RefineParams,
    pub(super) max_depth: u32,
    pub(super) inserted: usize,
    pub(super) max_dev: f64,
    pub(super) refused: usize,
    /// Asked before each insertion; once it says stop, nothing more is inserted.
    pub(super) stop: &'a dyn Fn() -> bool,
    pub(super) stopped: bool,
    /// Closed directions of A and of B ([`seams`]).
    pub(super) seam_a: [bool; 2],
    pub(super) seam_b: [bool; 2],
}

impl Inserter<'_, '_> {
    /// Points strictly between `p` and `q` (in order) so that every chord's midpoint lies within
    /// `tol` of the true curve point found from it.
    pub(super) fn between(
        &mut self,
        p: &Refined,
        q: &Refined,
        seg: (u32, u32),
        depth: u32,
        out: &mut Vec<Refined>,
    ) {
        if self.stopped || (self.stop)() {
            self.stopped = true;
            return;
        }
        let (da, db) = (domain(self.g.sa), domain(self.g.sb));
        let (ga, gb) = match (
            average_uv(&p.uv_a, &q.uv_a, &da, self.seam_a),
            average_uv(&p.uv_b, &q.uv_b, &db, self.seam_b),
        ) {
            (Some(a), Some(b)) => (a, b),
            _ => {
                let mid: [f64; 3] = std::array::from_fn(|k| 0.5 * (p.xyz[k] + q.xyz[k]));
                (
                    barycentric_uv(self.g.ma, seg.0, &mid),
                    barycentric_uv(self.g.mb, seg.1, &mid),
                )
            }
        };
        let mut m = auxiliary_plane(self.g.sa, self.g.sb, ga, gb, self.prm);
        if m.status == RefineStatus::Converged && small_angle(self.g, &m) {
            // Near tangency a point within tol of both surfaces can be far from the curve:
            // measure against the curve (elsewhere the refinement lands on it closely, and
            // every output point is certified against the curve afterwards anyway).
            let _ = onto_curve(self.g, &mut m, self.prm.tol);
        }
        let chord = dist(&p.xyz, &q.xyz);
        let mid: [f64; 3] = std::array::from_fn(|k| 0.5 * (p.xyz[k] + q.xyz[k]));
        if m.status != RefineStatus::Converged || dist(&m.xyz, &mid) > chord.max(self.prm.tol) {
            // The iteration went elsewhere (or broke down): keep the chord, say so.
            self.refused += 1;
            return;
        }
        let dev = dist_to_segment(&m.xyz, &p.xyz, &q.xyz);
        if dev > self.prm.tol && depth < self.max_depth {
            self.between(p, &m, seg, depth + 1, out);
            out.push(m);
            self.inserted += 1;
            self.between(&m, q, seg, depth + 1, out);
        } else {
            self.max_dev = self.max_dev.max(dev);
        }
    }
}

/// Whether the surfaces meet at `r` at an angle whose sine is below 1/4 (or the normals are
/// undefined there).
pub(super) fn small_angle(g: &PairGeometry, r: &Refined) -> bool {
    let s = if r.sin_angle.is_finite() {
        r.sin_angle
    } else {
        let (_, su, sv) = point_d1(g.sa, r.uv_a[0], r.uv_a[1]);
        let (_, rw, rt) = point_d1(g.sb, r.uv_b[0], r.uv_b[1]);
        sin_between(&su, &sv, &rw, &rt)
    };
    s.is_nan() || s < 0.25
}

/// The curve certificate of `r` ([`certify_on_curve`]); when its proven distance to the curve
/// exceeds `tol/8` (near tangency the refinement stops within tol of both surfaces, which can
/// be far from the curve), `r` moves to the centre of its certified root box and is
/// certified again there; the move is kept only when the new radius is smaller.
pub(super) fn onto_curve(
    g: &PairGeometry,
    r: &mut Refined,
    tol: f64,
) -> Result<CurveCertificate, Uncertified> {
    let c = certify_on_curve(g.sa, g.sb, &r.xyz, &r.uv_a, &r.uv_b)?;
    if c.radius <= tol / 8.0 {
        return Ok(c);
    }
    let (dom_a, dom_b) = (domain(g.sa), domain(g.sb));
    let uv_a = [
        c.params[0].mid().clamp(dom_a[0], dom_a[1]),
        c.params[1].mid().clamp(dom_a[2], dom_a[3]),
    ];
    let uv_b = [
        c.params[2].mid().clamp(dom_b[0], dom_b[1]),
        c.params[3].mid().clamp(dom_b[2], dom_b[3]),
    ];
    let (pa, pb) = (g.sa.eval(&uv_a[0], &uv_a[1]), g.sb.eval(&uv_b[0], &uv_b[1]));
    let xyz: [f64; 3] = std::array::from_fn(|k| 0.5 * (pa[k] + pb[k]));
    match certify_on_curve(g.sa, g.sb, &xyz, &uv_a, &uv_b) {
        Ok(c2) if c2.radius < c.radius => {
            r.xyz = xyz;
            r.uv_a = uv_a;
            r.uv_b = uv_b;
            r.gap = dist(&pa, &pb);
            r.sin_angle = f64::NAN;
            Ok(c2)
        }
        _ => Ok(c),
    }
}

#[cfg(test)]
mod tests {
    use super::average_uv;

    /// Midpoints across a closed direction go the short way round; in an open direction, or
    /// for points a quarter of the domain apart, there is none.
    #[test]
    fn midpoint_across_the_seam() {
        let dom = [0.0, 1.0, 0.0, 2.0];
        let m = average_uv(&[1.0, 0.5], &[0.0125, 0.5], &dom, [true, false]).unwrap();
        assert!((m[0] - 0.00625).abs() < 1e-15 && m[1] == 0.5, "{m:?}");
        let m = average_uv(&[0.0, 1.0], &[0.9875, 1.0], &dom, [true, false]).unwrap();
        assert!((m[0] - 0.99375).abs() < 1e-15 && m[1] == 1.0, "{m:?}");
        let m = average_uv(&[0.5, 1.99], &[0.5, 0.01], &dom, [false, true]).unwrap();
        assert_eq!(m, [0.5, 2.0]);
        assert!(average_uv(&[1.0, 0.5], &[0.0125, 0.5], &dom, [false, true]).is_none());
        assert!(average_uv(&[0.7, 0.5], &[0.2, 0.5], &dom, [true, true]).is_none());
        assert_eq!(
            average_uv(&[0.2, 0.5], &[0.3, 0.7], &dom, [true, true]),
            Some([0.25, 0.6])
        );
    }
}
