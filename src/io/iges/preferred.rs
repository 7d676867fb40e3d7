//! Model-space boundaries of trimmed faces (144) built from the parameter-space curve where the
//! file prefers it: a curve on a surface (142) with PREF = 1 ("S∘B preferred": the sending
//! system's model-space copy CPTR is secondary and may be anything) or with no model-space
//! curve at all. Each linear piece of the parameter-space curve `B` is mapped exactly: a line
//! of the domain maps onto a rational Bézier curve of degree `p + q` in every knot rectangle
//! it crosses (Yang et al. §4, "mapping segments onto the surface"; the blossom formula of
//! `spline::compose::compose_line` on the homogeneous patch), the pieces joined C0 at the knot
//! lines. A Bézier piece of `B` of higher degree `d` whose control points lie in one knot
//! rectangle maps onto a rational Bézier curve of degree `(p + q) d` there (functional
//! composition by blossoming, DeRose et al. 1993, `spline::compose::compose`). The curve's
//! parameter is `B`'s own, so `S(B(t))` and the built curve agree at every `t` up to the
//! rounding of the control points.
//!
//! Parameter-space curves that are rational, that leave the surface's domain, or whose
//! non-linear pieces span a knot line of the surface are not mapped: the caller keeps the
//! model-space copy and says so.

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

/// `S(B(t))` for one polynomial Bézier piece `B` of degree `d > 1` on `[t0, t1]` whose
/// control points lie in one knot rectangle of `S` (within the slack `(su, sv)`): by the
/// convex hull property so does the piece, and its image on that patch is a rational Bézier
/// curve of degree `(p + q) d` (`spline::compose::compose`, DeRose et al.). A piece whose
/// control points span a knot line is not cut (that needs the roots of a polynomial): `Err`.
fn image_in_one_cell(
    patches: &[BezierPatch<Hom<f64, 3>>],
    b: &BezierCurve<[f64; 2]>,
    (su, sv): (f64, f64),
    (t0, t1): (f64, f64),
) -> Result<Vec<NurbsCurve<f64, 3>>, String> {
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
    Ok(vec![nurbs_on(&compose(&bp.patch, &in_cell), t0, t1)?])
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
                    image_in_one_cell(&patches, &piece.curve, (su, sv), (piece.t0, piece.t1))
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
        let got = image_in_one_cell(&patches, &b, (0.0, 0.0), (2.0, 5.0)).unwrap();
        let img = &got[0];
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

    /// A cubic whose control points straddle a knot line is refused with the reason, not cut.
    #[test]
    fn a_cubic_across_a_knot_line_is_refused() {
        let (_, patches) = cylinder_patches();
        let u = patches[0].u1;
        let b = BezierCurve {
            control: vec![
                [u - 0.01, 0.1],
                [u - 0.005, 0.2],
                [u + 0.005, 0.3],
                [u + 0.01, 0.4],
            ],
        };
        let e = image_in_one_cell(&patches, &b, (0.0, 0.0), (0.0, 1.0)).unwrap_err();
        assert!(e.contains("spans a knot line"), "{e}");
    }
}
