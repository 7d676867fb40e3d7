//! Step 9a — point insertion: points are inserted on the true curve between consecutive
//! refined points of a branch until every chord's midpoint lies within `tol` of the true
//! curve point found from it (the Auxiliary Plane Method, [`super::refine`], started from the
//! chord's parameter midpoint). Near tangency the new points are moved onto the curve
//! (`newton_onto_curve`) before chords are measured against it.

use super::branch::PairGeometry;
use super::hermite::{P7, Piece, tangent_jet};
use super::jet_cache::JetCache;
use super::krawczyk::{CurveCertificate, Uncertified, certify_on_curve_cached, newton_on_curve};
use super::refine::{
    RefineParams, RefineStatus, Refined, auxiliary_plane, barycentric_uv, domain, sin_between,
};
use crate::geom::{dist, dist_to_segment};
use crate::spline::NurbsSurface;
use crate::spline::closure::Closure;
use crate::spline::project::point_d1;

/// The parameter point at fraction `f` from `a` to `b` (the midpoint for `f = 1/2`), or `None`
/// when they are more than a quarter of the domain apart in a direction. In a closed direction
/// (`seam`: `S(d0, ·) = S(d1, ·)`) it is taken the short way round, across the seam, and
/// brought back into the domain: a branch ending at a point on the seam (a tangent point at
/// `u = d1`, its neighbours just past `u = d0`) is refined like any other. It only steers the
/// refinement.
fn lerp_uv(
    a: &[f64; 2],
    b: &[f64; 2],
    f: f64,
    dom: &[f64; 4],
    seam: [bool; 2],
) -> Option<[f64; 2]> {
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
        let mut c = lerp(x, y, f);
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
    /// The true curve point found from the chord point at fraction `f` of `p → q` (its
    /// parameters interpolated the short way round, or from the mesh segment `seg`), moved onto
    /// the curve near tangency; `None` when the refinement broke down or went farther from the
    /// chord point than the chord is long.
    fn refine_at(&self, p: &Refined, q: &Refined, f: f64, seg: (u32, u32)) -> Option<Refined> {
        let (da, db) = (domain(self.g.sa), domain(self.g.sb));
        let at: [f64; 3] = std::array::from_fn(|k| lerp(p.xyz[k], q.xyz[k], f));
        let (ga, gb) = match (
            lerp_uv(&p.uv_a, &q.uv_a, f, &da, self.seam_a),
            lerp_uv(&p.uv_b, &q.uv_b, f, &db, self.seam_b),
        ) {
            (Some(a), Some(b)) => (a, b),
            _ => (
                barycentric_uv(self.g.ma, seg.0, &at),
                barycentric_uv(self.g.mb, seg.1, &at),
            ),
        };
        let mut m = auxiliary_plane(self.g.sa, self.g.sb, ga, gb, self.prm);
        if m.status == RefineStatus::Converged && small_angle(self.g, &m) {
            // Near tangency a point within tol of both surfaces can be far from the curve:
            // measure against the curve (elsewhere the refinement lands on it closely, and
            // every output point is certified against the curve afterwards anyway).
            newton_onto_curve(self.g, &mut m, self.prm.tol);
        }
        let chord = dist(&p.xyz, &q.xyz);
        (m.status == RefineStatus::Converged && dist(&m.xyz, &at) <= chord.max(self.prm.tol))
            .then_some(m)
    }

    /// Points strictly between `p` and `q` (in order) so that every chord's midpoint lies within
    /// `tol` of the true curve point found from it.
    ///
    /// A chord whose midpoint's curve point `m` lies `dev > tol` from it is split. On a smooth
    /// arc the deviation falls with the square of the chord's length, so `k` equal pieces
    /// deviate by about `dev / k²`: the chord is split into `k = ⌈1.1 √(dev / tol)⌉` pieces at
    /// once (curve points found from the chord points at `j / k`; `m` itself when `k = 2`),
    /// each piece checked again the same way. This gives about the fewest points that satisfy
    /// the criterion, where halving alone leaves pieces deviating between `tol / 4` and `tol`
    /// (up to 1.6× the points). Where a split point cannot be found, or the points do not run
    /// in order along the chord, the chord is halved at `m`. Splitting into `k` counts as
    /// `⌈log₂ k⌉` levels of the depth budget, as halving `k` times would.
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
        let Some(m) = self.refine_at(p, q, 0.5, seg) else {
            // The iteration went elsewhere (or broke down): keep the chord, say so.
            self.refused += 1;
            return;
        };
        // With cubic pieces ([`RefineParams::cubic`]) the Hermite piece from `p` to `q` when
        // both have a tangent jet ([`tangent_jet`]), else the chord.
        let (jp, jq) = if self.prm.cubic {
            (self.jet(p), self.jet(q))
        } else {
            (None, None)
        };
        let piece = jp
            .zip(jq)
            .and_then(|(a, b)| Piece::cubic(&packed(p), &a, &packed(q), &b));
        let (dev, power) = match piece {
            Some(h) => (self.piece_deviation(&h, p, q, &m, seg), 4.0),
            None => (dist_to_segment(&m.xyz, &p.xyz, &q.xyz), 2.0),
        };
        if dev <= self.prm.tol || depth >= self.max_depth {
            if dev.is_finite() {
                self.max_dev = self.max_dev.max(dev);
            } else {
                // A piece whose quarter points could not be found, at the depth limit: kept
                // unmeasured, as a chord whose midpoint cannot be found.
                self.refused += 1;
            }
            return;
        }
        let levels_left = self.max_depth - depth;
        // A chord between a point with a tangent jet and one without (a branch point, a
        // tangent end) is halved: the points inserted have jets, so the parts but the one at
        // the end without become cubic pieces, which the chords' square law would overcount.
        let one_sided = jp.is_some() != jq.is_some();
        let k = if one_sided {
            2
        } else {
            pieces(dev, self.prm.tol, levels_left, power)
        };
        if k > 2
            && let Some(xs) = self.split(p, q, &m, k, seg)
        {
            let next = depth + k.next_power_of_two().trailing_zeros();
            let mut prev = *p;
            for x in xs {
                self.between(&prev, &x, seg, next, out);
                out.push(x);
                self.inserted += 1;
                prev = x;
            }
            self.between(&prev, q, seg, next, out);
            return;
        }
        self.between(p, &m, seg, depth + 1, out);
        out.push(m);
        self.inserted += 1;
        self.between(&m, q, seg, depth + 1, out);
    }

    /// The tangent jet at `r` ([`tangent_jet`]).
    fn jet(&self, r: &Refined) -> Option<P7> {
        tangent_jet(self.g.sa, self.g.sb, &r.uv_a, &r.uv_b)
    }

    /// The largest distance from the piece `h` of the true curve points found from the chord
    /// points at `1/4`, `1/2` (`m`) and `3/4` (a measurement; infinite where one is not found,
    /// so that the piece is split).
    fn piece_deviation(
        &self,
        h: &Piece,
        p: &Refined,
        q: &Refined,
        m: &Refined,
        seg: (u32, u32),
    ) -> f64 {
        let mut dev = h.dist(&m.xyz);
        for f in [0.25, 0.75] {
            if dev > self.prm.tol {
                break;
            }
            dev = match self.refine_at(p, q, f, seg) {
                Some(x) => dev.max(h.dist(&x.xyz)),
                None => f64::INFINITY,
            };
        }
        dev
    }

    /// The `k − 1` curve points found from the chord points at `j / k` (`m` at `1/2`), when
    /// every one is found and they run strictly in order along the chord.
    fn split(
        &self,
        p: &Refined,
        q: &Refined,
        m: &Refined,
        k: u32,
        seg: (u32, u32),
    ) -> Option<Vec<Refined>> {
        let d: [f64; 3] = std::array::from_fn(|c| q.xyz[c] - p.xyz[c]);
        let dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if dd.is_nan() || dd <= 0.0 {
            return None;
        }
        let along = |x: &Refined| (0..3).map(|c| (x.xyz[c] - p.xyz[c]) * d[c]).sum::<f64>() / dd;
        let mut xs = Vec::with_capacity(k as usize - 1);
        let mut last = 0.0;
        for j in 1..k {
            let x = if 2 * j == k {
                *m
            } else {
                self.refine_at(p, q, j as f64 / k as f64, seg)?
            };
            let t = along(&x);
            if !(t > last && t < 1.0) {
                return None;
            }
            last = t;
            xs.push(x);
        }
        Some(xs)
    }
}

/// Number of pieces for a chord whose midpoint deviates by `dev > tol`: `⌈1.1 (dev / tol)^(1/power)⌉`
/// (`power` 2 for chords, 4 for Hermite pieces, whose error falls with the fourth power of
/// the length), at least 2, at most `2^levels_left` and 256.
fn pieces(dev: f64, tol: f64, levels_left: u32, power: f64) -> u32 {
    let want = (1.1 * (dev / tol).powf(1.0 / power)).ceil();
    let cap = (1u64 << levels_left.min(8)) as f64;
    if want.is_finite() {
        want.clamp(2.0, cap.max(2.0)) as u32
    } else {
        2
    }
}

/// `r` packed as `(x, y, z, u_A, v_A, s_B, t_B)`.
pub(super) fn packed(r: &Refined) -> P7 {
    [
        r.xyz[0], r.xyz[1], r.xyz[2], r.uv_a[0], r.uv_a[1], r.uv_b[0], r.uv_b[1],
    ]
}

fn lerp(a: f64, b: f64, f: f64) -> f64 {
    if f == 0.5 {
        0.5 * (a + b)
    } else {
        a + f * (b - a)
    }
}

/// Whether the surfaces meet at `r` at an angle whose sine is below 1/4 (or the normals are
/// undefined there).
pub(super) fn small_angle(g: &PairGeometry, r: &Refined) -> bool {
    let s = sin_at(g, r);
    s.is_nan() || s < 0.25
}

/// The sine of the angle between the surface normals at `r`'s parameters (NaN where a normal
/// is undefined).
fn sin_at(g: &PairGeometry, r: &Refined) -> f64 {
    if r.sin_angle.is_finite() {
        r.sin_angle
    } else {
        let (_, su, sv) = point_d1(g.sa, r.uv_a[0], r.uv_a[1]);
        let (_, rw, rt) = point_d1(g.sb, r.uv_b[0], r.uv_b[1]);
        sin_between(&su, &sv, &rw, &rt)
    }
}

/// Moves `r` onto the curve near tangency without certifying it (the certificate follows
/// for every output point, [`onto_curve`]): to the `f64` Newton solution `y` of the
/// certificate's system ([`newton_on_curve`]), `r` becoming `(S_A(y_uv) + S_B(y_st)) / 2`.
/// A point within `tol` of both surfaces meeting at an angle `θ` lies within about
/// `2 tol / sin θ` of the curve; the move is kept only when it is at most twice that (plus
/// `tol`) and the two surface points are no farther apart than before, so that the iteration
/// cannot carry the point to another part of the curve.
pub(super) fn newton_onto_curve(g: &PairGeometry, r: &mut Refined, tol: f64) {
    let sin = sin_at(g, r);
    if sin.is_nan() || sin <= 0.0 {
        return;
    }
    let Some(y) = newton_on_curve(g.sa, g.sb, &r.xyz, &r.uv_a, &r.uv_b) else {
        return;
    };
    let (uv_a, uv_b) = ([y[0], y[1]], [y[2], y[3]]);
    let (pa, pb) = (g.sa.eval(&uv_a[0], &uv_a[1]), g.sb.eval(&uv_b[0], &uv_b[1]));
    let xyz: [f64; 3] = std::array::from_fn(|k| 0.5 * (pa[k] + pb[k]));
    let gap = dist(&pa, &pb);
    if dist(&xyz, &r.xyz) <= 4.0 * tol / sin + tol && gap <= r.gap {
        *r = Refined {
            xyz,
            uv_a,
            uv_b,
            gap,
            sin_angle: f64::NAN,
            ..*r
        };
    }
}

/// The curve certificate of `r` ([`certify_on_curve`]); when its proven distance to the curve
/// exceeds `tol/8` (near tangency the refinement stops within tol of both surfaces, which can
/// be far from the curve), `r` moves to the centre of its certified root box and is
/// certified again there; the move is kept only when the new radius is smaller.
pub(super) fn onto_curve(
    g: &PairGeometry,
    r: &mut Refined,
    tol: f64,
    cache: Option<&JetCache>,
) -> Result<CurveCertificate, Uncertified> {
    let c = certify_on_curve_cached(g.sa, g.sb, &r.xyz, &r.uv_a, &r.uv_b, cache, tol / 8.0)?;
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
    match certify_on_curve_cached(g.sa, g.sb, &xyz, &uv_a, &uv_b, cache, tol / 8.0) {
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
    use super::{lerp_uv, pieces};

    /// Midpoints across a closed direction go the short way round; in an open direction, or
    /// for points a quarter of the domain apart, there is none.
    #[test]
    fn midpoint_across_the_seam() {
        let dom = [0.0, 1.0, 0.0, 2.0];
        let m = lerp_uv(&[1.0, 0.5], &[0.0125, 0.5], 0.5, &dom, [true, false]).unwrap();
        assert!((m[0] - 0.00625).abs() < 1e-15 && m[1] == 0.5, "{m:?}");
        let m = lerp_uv(&[0.0, 1.0], &[0.9875, 1.0], 0.5, &dom, [true, false]).unwrap();
        assert!((m[0] - 0.99375).abs() < 1e-15 && m[1] == 1.0, "{m:?}");
        let m = lerp_uv(&[0.5, 1.99], &[0.5, 0.01], 0.5, &dom, [false, true]).unwrap();
        assert_eq!(m, [0.5, 2.0]);
        assert!(lerp_uv(&[1.0, 0.5], &[0.0125, 0.5], 0.5, &dom, [false, true]).is_none());
        assert!(lerp_uv(&[0.7, 0.5], &[0.2, 0.5], 0.5, &dom, [true, true]).is_none());
        assert_eq!(
            lerp_uv(&[0.2, 0.5], &[0.3, 0.7], 0.5, &dom, [true, true]),
            Some([0.25, 0.6])
        );
    }

    /// A quarter of the way across the seam, the short way round.
    #[test]
    fn fraction_across_the_seam() {
        let dom = [0.0, 1.0, 0.0, 2.0];
        let m = lerp_uv(&[0.95, 0.5], &[0.05, 0.7], 0.25, &dom, [true, false]).unwrap();
        assert!(
            (m[0] - 0.975).abs() < 1e-15 && (m[1] - 0.55).abs() < 1e-15,
            "{m:?}"
        );
        let m = lerp_uv(&[0.95, 0.5], &[0.05, 0.5], 0.75, &dom, [true, false]).unwrap();
        assert!((m[0] - 0.025).abs() < 1e-15, "{m:?}");
    }

    /// Pieces: enough for `dev / k² ≤ tol / 1.21`, at least 2, capped by the depth left.
    #[test]
    fn pieces_follow_the_square_law() {
        assert_eq!(pieces(1.01e-7, 1e-7, 12, 2.0), 2);
        assert_eq!(pieces(4e-7, 1e-7, 12, 2.0), 3);
        assert_eq!(pieces(5.1e-4, 1e-7, 12, 2.0), 79);
        assert_eq!(pieces(5.1e-4, 1e-7, 3, 2.0), 8);
        assert_eq!(pieces(1.0, 1e-300, 12, 2.0), 256);
        assert_eq!(pieces(f64::INFINITY, 1e-7, 12, 2.0), 2);
        // Hermite pieces: the fourth-power law (16 = 2⁴: ⌈1.1 · 2⌉).
        assert_eq!(pieces(1.6e-6, 1e-7, 12, 4.0), 3);
        assert_eq!(pieces(1e-7 * 1e4, 1e-7, 12, 4.0), 11);
        for (dev, tol) in [(2e-7, 1e-7), (3.3e-3, 1e-6), (0.77, 1e-4)] {
            let k = pieces(dev, tol, 12, 2.0) as f64;
            assert!(dev / (k * k) <= tol / 1.21 * 1.0000001, "{dev} {tol} {k}");
            assert!(
                dev / ((k - 1.0) * (k - 1.0)) > tol / 1.21,
                "{dev} {tol} {k}"
            );
        }
    }
}
