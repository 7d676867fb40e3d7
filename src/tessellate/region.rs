//! A trimmed face's region in its surface's parameter plane: the closed polygons of its loops
//! ([`super::polygons::face_polygons`]), tested by the even-odd rule with exact orientation signs
//! against the polygon edges, periodic directions taken modulo their period.
//!
//! The polygons join points of the loops' edges projected onto the surface; between them they
//! are chords in the parameter plane. The decision is exact *for the polygon*; against the true
//! trim curves it is evidence, within the polygon's distance from them (about the chordal error
//! of the edge sampling).

use super::domain::BoundaryPoint;
use crate::predicates::orient2d;
use crate::scalar::Sign;

/// The parameter-plane region of one face of a B-rep.
#[derive(Clone, Debug)]
pub struct FaceRegion {
    /// The model surface the face lies on.
    pub surface: usize,
    /// Closed polygons (the last point joins the first); inside = odd number of crossings.
    pub polys: Vec<Vec<[f64; 2]>>,
    /// Period of each parameter, when the surface is closed in it.
    pub period: [Option<f64>; 2],
    /// The surface's parameter domain `[u0, u1, v0, v1]`.
    pub domain: [f64; 4],
    /// A loop is declared outer but runs clockwise about the face's normal on a closed
    /// surface: the polygons outline the rest of the surface (the loops' orientation), the
    /// declaration says the loop's inside. Either reading is possible; results that rest on
    /// the face are not certified.
    pub ambiguous: bool,
}

impl FaceRegion {
    pub fn new(
        surface: usize,
        polys: &[Vec<BoundaryPoint>],
        period: [Option<f64>; 2],
        domain: [f64; 4],
    ) -> FaceRegion {
        FaceRegion {
            surface,
            polys: polys
                .iter()
                .map(|p| p.iter().map(|b| b.uv).collect::<Vec<_>>())
                .filter(|p| p.len() >= 3)
                .collect(),
            period,
            domain,
            ambiguous: false,
        }
    }

    /// The shifts by whole periods under which a parameter point is tested (no allocation:
    /// the box tests call this for every box of the coverage's crossing searches).
    fn shifts(&self) -> impl Iterator<Item = [f64; 2]> {
        let ks = |d: usize| -> ([f64; 5], usize) {
            match self.period[d] {
                Some(p) => ([0.0, -p, p, -2.0 * p, 2.0 * p], 5),
                None => ([0.0; 5], 1),
            }
        };
        let ((a, na), (b, nb)) = (ks(0), ks(1));
        (0..na).flat_map(move |i| (0..nb).map(move |j| [a[i], b[j]]))
    }

    /// Even-odd rule for one point (no shift); a point on a polygon edge counts as inside.
    fn inside_once(&self, p: &[f64; 2]) -> bool {
        let mut odd = false;
        for poly in &self.polys {
            for k in 0..poly.len() {
                let (a, b) = (&poly[k], &poly[(k + 1) % poly.len()]);
                if (a[1] > p[1]) != (b[1] > p[1]) {
                    let o = orient2d(a, b, p);
                    if o == Sign::Zero {
                        return true;
                    }
                    let upward = b[1] > a[1];
                    if (o == Sign::Positive) == upward {
                        odd = !odd;
                    }
                }
            }
        }
        odd
    }

    /// Whether `uv` lies in the face (under some shift by whole periods in the polygons, on an
    /// edge counting as in them).
    pub fn inside(&self, uv: &[f64; 2]) -> bool {
        self.shifts()
            .any(|s| self.inside_once(&[uv[0] + s[0], uv[1] + s[1]]))
    }

    /// Whether the parameter box `[u0, u1, v0, v1]`, widened by `margin` (a fraction of the
    /// domain's extent in each direction) and by the labels' rounding ([`LABEL_ULPS`]), lies
    /// wholly outside the face: no polygon edge meets
    /// it and its centre is outside (under every shift).
    pub fn box_outside(&self, b: &[f64; 4], margin: f64) -> bool {
        let mu = margin * (self.domain[1] - self.domain[0]).abs();
        let mv = margin * (self.domain[3] - self.domain[2]).abs();
        for s in self.shifts() {
            let (lo, hi) = widened(b, mu, mv, s);
            let centre = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
            if self.inside_once(&centre) {
                return false;
            }
            for poly in &self.polys {
                for k in 0..poly.len() {
                    if segment_meets_box(&poly[k], &poly[(k + 1) % poly.len()], &lo, &hi) {
                        return false;
                    }
                }
            }
        }
        true
    }
    /// Whether the parameter box `[u0, u1, v0, v1]`, widened by the labels' rounding
    /// ([`LABEL_ULPS`]), lies wholly inside the face: under some
    /// shift by whole periods, no polygon edge meets the closed box and its centre is inside
    /// (the box is connected and crosses no edge, so every point of it is on the centre's
    /// side of every polygon).
    pub fn box_inside(&self, b: &[f64; 4]) -> bool {
        self.shifts().any(|s| {
            let (lo, hi) = widened(b, 0.0, 0.0, s);
            let centre = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
            self.inside_once(&centre)
                && self.polys.iter().all(|poly| {
                    (0..poly.len()).all(|k| {
                        !segment_meets_box(&poly[k], &poly[(k + 1) % poly.len()], &lo, &hi)
                    })
                })
        })
    }
    /// The polygon edges meeting the parameter box `[u0, u1, v0, v1]` widened by `margin` (a
    /// fraction of the domain's extent in each direction) and by the labels' rounding
    /// ([`LABEL_ULPS`]), each with the shift by whole periods under which it meets the box
    /// ([`LoopEdge`]). Every point `x` of the box on the border of the face — the points `x`
    /// with `x + s` in a polygon for some shift `s`, taken exactly — lies on one of them.
    pub fn edges_meeting(&self, b: &[f64; 4], margin: f64) -> Vec<LoopEdge> {
        let mu = margin * (self.domain[1] - self.domain[0]).abs();
        let mv = margin * (self.domain[3] - self.domain[2]).abs();
        let mut out = Vec::new();
        for s in self.shifts() {
            let (lo, hi) = widened(b, mu, mv, s);
            for poly in &self.polys {
                for k in 0..poly.len() {
                    let (p, q) = (&poly[k], &poly[(k + 1) % poly.len()]);
                    if segment_meets_box(p, q, &lo, &hi) {
                        out.push((*p, *q, s));
                    }
                }
            }
        }
        out
    }
}

/// Half-ulps of rounding a box's labels may carry: labels made by repeated rounded midpoints
/// (`0.5 * (a + b)`, within half an ulp of the exact midpoint each time) stay within
/// `n / 2` ulps of the exact box after `n` halvings; the box tests below widen every box by
/// this many ulps of its largest coordinate (an ulp of `x` is at most `ε |x|`), so they hold
/// for the exact boxes of fewer than 512 halvings (the coverage refinement and its crossing
/// searches make at most a few hundred).
pub const LABEL_ULPS: f64 = 256.0;

/// The box `[u0, u1, v0, v1]` shifted by `s` and widened by `mu`, `mv` and by [`LABEL_ULPS`]
/// ulps of its largest coordinate before and after the shift (which the shift's own rounding
/// moves by half an ulp of the latter; the margin is doubled for the rounding of the
/// widening itself).
fn widened(b: &[f64; 4], mu: f64, mv: f64, s: [f64; 2]) -> ([f64; 2], [f64; 2]) {
    let big = (0..4).fold(0.0f64, |m, k| {
        m.max(b[k].abs()).max((b[k] + s[k / 2]).abs())
    });
    let pad = LABEL_ULPS * f64::EPSILON * big;
    let (pu, pv) = (mu + 2.0 * pad, mv + 2.0 * pad);
    (
        [b[0] - pu + s[0], b[2] - pv + s[1]],
        [b[1] + pu + s[0], b[3] + pv + s[1]],
    )
}

/// A loop polygon's edge `(a, b, s)`: the segment from `a` to `b` of the polygon, which
/// bounds the face at the points `x` with `x + s` on it (`s` a shift by whole periods; the
/// segment itself is not shifted, so it is the polygon's exact edge).
pub type LoopEdge = ([f64; 2], [f64; 2], [f64; 2]);

/// Liang–Barsky: whether the segment `a b` meets the closed box `lo..hi`.
fn segment_meets_box(a: &[f64; 2], b: &[f64; 2], lo: &[f64; 2], hi: &[f64; 2]) -> bool {
    clip_segment(a, b, lo, hi).is_some()
}

/// Liang–Barsky: the range `[t0, t1] ⊆ [0, 1]` of `t` with `a + t (b − a)` in the closed box
/// `lo..hi`, `None` when the segment misses it (rounded: callers widen the box for that).
pub fn clip_segment(
    a: &[f64; 2],
    b: &[f64; 2],
    lo: &[f64; 2],
    hi: &[f64; 2],
) -> Option<(f64, f64)> {
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for d in 0..2 {
        let delta = b[d] - a[d];
        for (p, q) in [(-delta, a[d] - lo[d]), (delta, hi[d] - a[d])] {
            if p == 0.0 {
                if q < 0.0 || q.is_nan() {
                    return None;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
                if t0 > t1 {
                    return None;
                }
            }
        }
    }
    Some((t0, t1))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square_with_hole() -> FaceRegion {
        FaceRegion {
            surface: 0,
            polys: vec![
                vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
                vec![[0.4, 0.4], [0.6, 0.4], [0.6, 0.6], [0.4, 0.6]],
            ],
            period: [None, None],
            domain: [0.0, 1.0, 0.0, 1.0],
            ambiguous: false,
        }
    }

    #[test]
    fn even_odd_with_a_hole() {
        let r = square_with_hole();
        assert!(r.inside(&[0.2, 0.2]));
        assert!(!r.inside(&[0.5, 0.5]));
        assert!(!r.inside(&[1.5, 0.5]));
        assert!(r.inside(&[1.0, 0.5]), "on an edge counts as inside");
        assert!(r.box_outside(&[0.45, 0.55, 0.45, 0.55], 0.0));
        assert!(!r.box_outside(&[0.45, 0.55, 0.45, 0.55], 0.1));
        assert!(!r.box_outside(&[0.1, 0.2, 0.1, 0.2], 0.0));
        assert!(r.box_outside(&[2.0, 3.0, 2.0, 3.0], 0.01));
        assert!(r.box_inside(&[0.1, 0.2, 0.1, 0.2]));
        assert!(
            !r.box_inside(&[0.35, 0.45, 0.35, 0.45]),
            "crosses the hole's edge"
        );
        assert!(!r.box_inside(&[0.45, 0.55, 0.45, 0.55]), "in the hole");
        assert!(
            !r.box_inside(&[0.9, 1.1, 0.2, 0.3]),
            "crosses the outer edge"
        );
        assert!(
            !r.box_inside(&[0.1, 0.4, 0.0, 0.1]),
            "touches the outer edge"
        );
    }

    #[test]
    fn periodic_points_shifted_into_the_polygon() {
        // A band u in [0.5, 1.5] of a surface periodic in u with period 1 (domain [0, 1]).
        let r = FaceRegion {
            surface: 0,
            polys: vec![vec![[0.5, 0.0], [1.5, 0.0], [1.5, 0.3], [0.5, 0.3]]],
            period: [Some(1.0), None],
            domain: [0.0, 1.0, 0.0, 1.0],
            ambiguous: false,
        };
        assert!(r.inside(&[0.1, 0.1]));
        assert!(r.inside(&[0.9, 0.1]));
        assert!(!r.inside(&[0.1, 0.5]));
        assert!(r.box_inside(&[0.05, 0.1, 0.1, 0.2]), "inside one period on");
        assert!(!r.box_inside(&[0.4, 0.6, 0.1, 0.2]), "crosses u = 0.5");
    }
}
