//! Model-space boundaries of trimmed faces (144) built from the parameter-space curve where the
//! file prefers it: a curve on a surface (142) with PREF = 1 ("S∘B preferred": the sending
//! system's model-space copy CPTR is secondary and may be anything) or with no model-space
//! curve at all. Each linear piece of the parameter-space curve `B` is mapped exactly: a line
//! of the domain maps onto a rational Bézier curve of degree `p + q` in every knot rectangle
//! it crosses (Yang et al. §4, "mapping segments onto the surface"; the blossom formula of
//! `spline::compose::compose_line` on the homogeneous patch), the pieces joined C0 at the knot
//! lines. A Bézier piece of `B` of higher degree `d` is first cut where it crosses a knot line
//! of the surface (the roots of `u(t) − u_k` and `v(t) − v_k`, isolated on their Bernstein
//! coefficients by subdivision to 1e-13 of the piece), and each part, whose control points
//! then lie in one knot rectangle, maps onto a rational Bézier curve of degree `(p + q) d`
//! there (functional composition by blossoming, DeRose et al. 1993,
//! `spline::compose::compose`). The curve's parameter is `B`'s own, so `S(B(t))` and the
//! built curve agree at every `t` up to the rounding of the control points (a cut a rounding
//! error off the knot line leaves the part that much outside its rectangle, where the
//! patch's polynomial extends).
//!
//! Parameter-space curves that are rational, that leave the surface's domain, or whose
//! non-linear pieces cannot be cut into parts within one knot rectangle each are not mapped:
//! the caller keeps the model-space copy and says so.

use super::{R, Reader};
use crate::geom::Hom;
use crate::spline::BezierCurve;
use crate::spline::bspline_surface::BezierPatch;
use crate::spline::compose::{compose, compose_line};
use crate::spline::{BSplineCurve, NurbsCurve, NurbsSurface};

/// A model-space curve with its source id.
type Named = (String, NurbsCurve<f64, 3>);

/// `S(B(t))` for one linear piece `B(t) = a + (t − t0)/(t1 − t0) (b − a)`, `t ∈ [t0, t1]`,
/// over the Bézier patches of `S`: one rational Bézier piece per knot rectangle crossed.
fn image_of_line(
    patches: &[BezierPatch<Hom<f64, 3>>],
    (u_breaks, v_breaks): (&[f64], &[f64]),
    (a, b): ([f64; 2], [f64; 2]),
    (t0, t1): (f64, f64),
) -> Result<Vec<NurbsCurve<f64, 3>>, String> {
    // Where the line crosses interior knot lines, as fractions of the piece.
    let mut cuts = vec![0.0, 1.0];
    for (k, breaks) in [(0, u_breaks), (1, v_breaks)] {
        let d = b[k] - a[k];
        if d == 0.0 {
            continue;
        }
        for &x in &breaks[1..breaks.len().saturating_sub(1)] {
            let l = (x - a[k]) / d;
            if l > 0.0 && l < 1.0 {
                cuts.push(l);
            }
        }
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let at = |l: f64| -> [f64; 2] {
        if l == 0.0 {
            a
        } else if l == 1.0 {
            b
        } else {
            [a[0] + l * (b[0] - a[0]), a[1] + l * (b[1] - a[1])]
        }
    };
    let mut out = Vec::new();
    for w in cuts.windows(2) {
        let (pa, pb) = (at(w[0]), at(w[1]));
        let mid = [0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])];
        let Some(bp) = cell(patches, (mid, mid), (0.0, 0.0)) else {
            return Err(format!(
                "the point ({}, {}) of the parameter-space curve lies outside the surface's domain",
                mid[0], mid[1]
            ));
        };
        let c = compose_line(&bp.patch, &local(bp, pa), &local(bp, pb));
        let (ta, tb) = (t0 + w[0] * (t1 - t0), t0 + w[1] * (t1 - t0));
        out.push(nurbs_on(&c, ta, tb)?);
    }
    Ok(out)
}

/// The Bézier patch whose knot rectangle, grown by `(su, sv)`, holds the box `[lo, hi]`.
fn cell(
    patches: &[BezierPatch<Hom<f64, 3>>],
    (lo, hi): ([f64; 2], [f64; 2]),
    (su, sv): (f64, f64),
) -> Option<&BezierPatch<Hom<f64, 3>>> {
    patches.iter().find(|q| {
        q.u0 - su <= lo[0] && hi[0] <= q.u1 + su && q.v0 - sv <= lo[1] && hi[1] <= q.v1 + sv
    })
}

/// `p` in the patch's own coordinates (its knot rectangle mapped onto `[0, 1]²`).
fn local(bp: &BezierPatch<Hom<f64, 3>>, p: [f64; 2]) -> [f64; 2] {
    [
        (p[0] - bp.u0) / (bp.u1 - bp.u0),
        (p[1] - bp.v0) / (bp.v1 - bp.v0),
    ]
}

/// A homogeneous Bézier image as a rational curve on `[t0, t1]`.
fn nurbs_on(c: &BezierCurve<Hom<f64, 3>>, t0: f64, t1: f64) -> Result<NurbsCurve<f64, 3>, String> {
    let hom = BSplineCurve::from_bezier_on(c, t0, t1).map_err(|e| e.to_string())?;
    Ok(NurbsCurve { hom })
}

/// Parameters in `(0, 1)` where the Bernstein polynomial with coefficients `c` changes sign
/// or touches zero: subdivision at 1/2 until the coefficients have one strict sign (no root)
/// or the interval is below 1e-13 (its midpoint); roots closer than 1e-9 are merged. `None`
/// for more than `limit` roots or a polynomial that vanishes everywhere (a curve along the
/// knot line: no cut is needed there, and the caller cuts nowhere).
fn bernstein_roots(c: &[f64], limit: usize) -> Option<Vec<f64>> {
    let scale = c.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if scale == 0.0 {
        return None;
    }
    let mut out = Vec::new();
    let mut stack = vec![(c.to_vec(), 0.0f64, 1.0f64)];
    while let Some((b, a, e)) = stack.pop() {
        if b.iter().all(|x| *x > 0.0) || b.iter().all(|x| *x < 0.0) {
            continue;
        }
        if e - a < 1e-13 || b.iter().all(|x| x.abs() <= 1e-15 * scale) {
            let m = 0.5 * (a + e);
            if out.last().is_none_or(|l: &f64| (m - l).abs() > 1e-9) {
                out.push(m);
            }
            if out.len() > limit {
                return None;
            }
            continue;
        }
        // de Casteljau at 1/2 on the coefficients.
        let n = b.len();
        let (mut l, mut r, mut w) = (Vec::with_capacity(n), Vec::with_capacity(n), b);
        l.push(w[0]);
        r.push(w[n - 1]);
        for level in 1..n {
            for i in 0..n - level {
                w[i] = 0.5 * (w[i] + w[i + 1]);
            }
            l.push(w[0]);
            r.push(w[n - 1 - level]);
        }
        r.reverse();
        let m = 0.5 * (a + e);
        // Right half first on the stack: the left half is popped first, so roots come in order.
        stack.push((r, m, e));
        stack.push((l, a, m));
    }
    Some(out)
}

/// The parameters in `(0, 1)` where the 2D Bézier curve `b` crosses one of the interior knot
/// lines `breaks` (`[u breakpoints, v breakpoints]`), sorted, at least 1e-9 from the ends.
fn knot_crossings(b: &BezierCurve<[f64; 2]>, breaks: [&[f64]; 2]) -> Vec<f64> {
    let mut cuts = Vec::new();
    for (k, br) in breaks.iter().enumerate() {
        let lo = b.control.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
        let hi = b
            .control
            .iter()
            .map(|p| p[k])
            .fold(f64::NEG_INFINITY, f64::max);
        for &x in br.iter().filter(|x| lo < **x && **x < hi) {
            let c: Vec<f64> = b.control.iter().map(|p| p[k] - x).collect();
            cuts.extend(bernstein_roots(&c, 2 * c.len()).unwrap_or_default());
        }
    }
    cuts.retain(|t| *t > 1e-9 && *t < 1.0 - 1e-9);
    cuts.sort_by(f64::total_cmp);
    cuts.dedup_by(|a, b| (*a - *b).abs() <= 1e-9);
    cuts
}

/// `S(B(t))` for one polynomial Bézier piece `B` of degree `d > 1` on `[t0, t1]`: cut at its
/// crossings of the surface's knot lines ([`knot_crossings`]), each part's image on the patch
/// whose knot rectangle (within the slack `(su, sv)`) holds its control points — and so, by
/// the convex hull property, the part — a rational Bézier curve of degree `(p + q) d`
/// (`spline::compose::compose`, DeRose et al.). `Err` when a part still spans a knot line.
fn image_of_piece(
    patches: &[BezierPatch<Hom<f64, 3>>],
    breaks: [&[f64]; 2],
    b: &BezierCurve<[f64; 2]>,
    (su, sv): (f64, f64),
    (t0, t1): (f64, f64),
) -> Result<Vec<NurbsCurve<f64, 3>>, String> {
    let cuts = knot_crossings(b, breaks);
    let mut out = Vec::with_capacity(cuts.len() + 1);
    let (mut rest, mut from) = (b.clone(), 0.0);
    for &c in cuts.iter().chain(std::iter::once(&1.0)) {
        let part = if c < 1.0 {
            let (l, r) = rest.subdivide(&((c - from) / (1.0 - from)));
            rest = r;
            l
        } else {
            rest.clone()
        };
        let (a, e) = (
            t0 + (t1 - t0) * from,
            if c < 1.0 { t0 + (t1 - t0) * c } else { t1 },
        );
        out.push(image_in_one_cell(patches, &part, (su, sv), (a, e))?);
        from = c;
    }
    Ok(out)
}

/// The image of a part whose control points lie in one knot rectangle (see
/// [`image_of_piece`]).
fn image_in_one_cell(
    patches: &[BezierPatch<Hom<f64, 3>>],
    b: &BezierCurve<[f64; 2]>,
    (su, sv): (f64, f64),
    (t0, t1): (f64, f64),
) -> Result<NurbsCurve<f64, 3>, String> {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in &b.control {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let Some(bp) = cell(patches, (lo, hi), (su, sv)) else {
        return Err(format!(
            "a piece of degree {} spans a knot line of the surface ([{}, {}] x [{}, {}])",
            b.degree(),
            lo[0],
            hi[0],
            lo[1],
            hi[1]
        ));
    };
    let in_cell = BezierCurve {
        control: b.control.iter().map(|p| local(bp, *p)).collect(),
    };
    nurbs_on(&compose(&bp.patch, &in_cell), t0, t1)
}

impl Reader<'_> {
    /// The image on `s` of the parameter-space curve `bp` (a curve entity, x and y being u and
    /// v), one named curve per member as [`Reader::segments`] gives them; `Err` with the reason
    /// when a member cannot be mapped (see the module comment).
    pub(super) fn image_curves(
        &self,
        bp: usize,
        s: &NurbsSurface<f64, 3>,
    ) -> R<Result<Vec<Named>, String>> {
        let Some(segs) = self.segments(bp, 0)? else {
            return Ok(Err(format!("DE {bp} is not a converted curve")));
        };
        let (u0, u1, v0, v1) = s.hom.domain();
        // Trim curves often end a rounding error outside the domain; the patches' polynomials
        // extend there.
        let (su, sv) = (1e-9 * (u1 - u0), 1e-9 * (v1 - v0));
        let patches = s.hom.bezier_patches();
        let (u_breaks, v_breaks) = (s.hom.ku.breakpoints(), s.hom.kv.breakpoints());
        let mut out = Vec::with_capacity(segs.len());
        for (k, seg) in segs.iter().enumerate() {
            let name = format!("DE {bp}#{}", k + 1);
            let (pts, w) = seg.points_weights();
            if w.windows(2).any(|x| x[0] != x[1]) {
                return Ok(Err(format!("{name} is rational")));
            }
            if let Some(p) = pts.iter().find(|p| {
                !(p[0] >= u0 - su && p[0] <= u1 + su && p[1] >= v0 - sv && p[1] <= v1 + sv)
            }) {
                return Ok(Err(format!(
                    "{name} has the control point ({}, {}) outside the surface's domain [{u0}, {u1}] x [{v0}, {v1}]",
                    p[0], p[1]
                )));
            }
            let flat = seg.hom.map(|k| *k, |h| [h.wp[0] / h.w, h.wp[1] / h.w]);
            let mut pieces: Vec<NurbsCurve<f64, 3>> = Vec::new();
            for piece in flat.bezier_pieces() {
                let c = &piece.curve.control;
                let got = if c.len() == 2 {
                    if c[0] == c[1] {
                        continue;
                    }
                    image_of_line(
                        &patches,
                        (&u_breaks, &v_breaks),
                        (c[0], c[1]),
                        (piece.t0, piece.t1),
                    )
                } else {
                    image_of_piece(
                        &patches,
                        [&u_breaks, &v_breaks],
                        &piece.curve,
                        (su, sv),
                        (piece.t0, piece.t1),
                    )
                };
                match got {
                    Ok(p) => pieces.extend(p),
                    Err(why) => return Ok(Err(format!("{name}: {why}"))),
                }
            }
            let mut it = pieces.into_iter();
            let Some(mut c) = it.next() else {
                return Ok(Err(format!("{name} has no piece of positive length")));
            };
            for p in it {
                c = match c.joined(&p) {
                    Ok(j) => j,
                    Err(e) => return Ok(Err(format!("{name}: {e}"))),
                };
            }
            out.push((name, c));
        }
        Ok(Ok(out))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::construct::{Frame, cylinder};

    /// The cylinder of radius 2 about the z axis from z = 0 to 3, with its Bézier patches.
    fn cylinder_patches() -> (NurbsSurface<f64, 3>, Vec<BezierPatch<Hom<f64, 3>>>) {
        let f = Frame {
            o: [0.0; 3],
            x: [1.0, 0.0, 0.0],
            y: [0.0, 1.0, 0.0],
            z: [0.0, 0.0, 1.0],
        };
        let s = cylinder(&f, 2.0, 0.0, 3.0).unwrap();
        let patches = s.hom.bezier_patches();
        (s, patches)
    }

    fn bernstein3(c: &[[f64; 2]; 4], t: f64) -> [f64; 2] {
        let s = 1.0 - t;
        let b = [s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t];
        [0, 1].map(|k| (0..4).map(|i| b[i] * c[i][k]).sum())
    }

    /// A cubic domain curve inside one quarter of a cylinder of radius 2 (axis z, from z = 0 to
    /// 3): its image lies on the cylinder (x² + y² = 4) at the height the curve's `v` gives
    /// (z linear in v over [0, 1] → [0, 3]); checked at 41 parameters from the closed form.
    #[test]
    fn a_cubic_in_one_cell_maps_onto_the_cylinder() {
        let (s, patches) = cylinder_patches();
        let q = &patches[0];
        let (du, dv) = (q.u1 - q.u0, q.v1 - q.v0);
        let c = [[0.1, 0.2], [0.5, 0.9], [0.3, 0.1], [0.9, 0.7]]
            .map(|p| [q.u0 + p[0] * du, q.v0 + p[1] * dv]);
        let b = BezierCurve {
            control: c.to_vec(),
        };
        let img = image_in_one_cell(&patches, &b, (0.0, 0.0), (2.0, 5.0)).unwrap();
        assert_eq!(img.hom.degree(), 3 * (q.patch.p + q.patch.q));
        for i in 0..=40 {
            let t = i as f64 / 40.0;
            let x = img.eval(&(2.0 + 3.0 * t));
            let v = bernstein3(&c, t)[1];
            let (s0, s1) = s.hom.kv.domain();
            let z = 3.0 * (v - s0) / (s1 - s0);
            assert!((x[0].hypot(x[1]) - 2.0).abs() <= 1e-14, "{t}: {x:?}");
            assert!((x[2] - z).abs() <= 1e-14, "{t}: {x:?} vs z {z}");
        }
    }

    /// A cubic crossing the knot line between two quarters of the cylinder is cut there: two
    /// rational pieces, joined, every point on the cylinder at the height its `v` gives, and
    /// the cut where `u(t)` meets the knot (checked from the closed form of the cubic).
    #[test]
    fn a_cubic_across_a_knot_line_is_cut() {
        let (s, patches) = cylinder_patches();
        let u = patches[0].u1;
        let c = [
            [u - 0.2, 0.1],
            [u - 0.1, 0.9],
            [u + 0.05, 0.2],
            [u + 0.2, 0.6],
        ];
        let b = BezierCurve {
            control: c.to_vec(),
        };
        let breaks = [s.hom.ku.breakpoints(), s.hom.kv.breakpoints()];
        let got = image_of_piece(
            &patches,
            [&breaks[0], &breaks[1]],
            &b,
            (1e-9, 1e-9),
            (1.0, 3.0),
        )
        .unwrap();
        assert_eq!(got.len(), 2);
        // The cut: where u(t) = u, found here by bisection on the closed form.
        let (mut a, mut e) = (0.0, 1.0);
        for _ in 0..80 {
            let m = 0.5 * (a + e);
            if bernstein3(&c, m)[0] < u {
                a = m;
            } else {
                e = m;
            }
        }
        let (_, t_end) = got[0].hom.knots.domain();
        assert!(
            (t_end - (1.0 + 2.0 * a)).abs() <= 1e-12,
            "{t_end} vs {}",
            1.0 + 2.0 * a
        );
        let joined = got[0].joined(&got[1]).unwrap();
        let (s0, s1) = s.hom.kv.domain();
        for i in 0..=60 {
            let t = i as f64 / 60.0;
            let x = joined.eval(&(1.0 + 2.0 * t));
            let z = 3.0 * (bernstein3(&c, t)[1] - s0) / (s1 - s0);
            assert!((x[0].hypot(x[1]) - 2.0).abs() <= 1e-13, "{t}: {x:?}");
            assert!((x[2] - z).abs() <= 1e-13, "{t}: {x:?} vs z {z}");
        }
    }

    /// Roots of `(t − 0.2)(t − 0.5)(t − 0.9)` from its Bernstein coefficients; none for a
    /// polynomial of one sign; `None` for the zero polynomial.
    #[test]
    fn bernstein_roots_of_a_cubic() {
        // Power basis → Bernstein: f(t) = t³ − 1.6 t² + 0.73 t − 0.09.
        let (a0, a1, a2, a3) = (-0.09, 0.73, -1.6, 1.0);
        let b = [
            a0,
            a0 + a1 / 3.0,
            a0 + 2.0 * a1 / 3.0 + a2 / 3.0,
            a0 + a1 + a2 + a3,
        ];
        let r = bernstein_roots(&b, 6).unwrap();
        assert_eq!(r.len(), 3, "{r:?}");
        for (x, want) in r.iter().zip([0.2, 0.5, 0.9]) {
            assert!((x - want).abs() <= 1e-12, "{r:?}");
        }
        assert!(
            bernstein_roots(&[1.0, 0.2, 0.5, 3.0], 6)
                .unwrap()
                .is_empty()
        );
        assert!(bernstein_roots(&[0.0; 4], 6).is_none());
    }
}
