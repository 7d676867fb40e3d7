//! Model-space boundaries of trimmed faces (144) built from the parameter-space curve where the
//! file prefers it: a curve on a surface (142) with PREF = 1 ("S∘B preferred": the sending
//! system's model-space copy CPTR is secondary and may be anything) or with no model-space
//! curve at all. Each linear piece of the parameter-space curve `B` is mapped exactly: a line
//! of the domain maps onto a rational Bézier curve of degree `p + q` in every knot rectangle
//! it crosses (Yang et al. §4, "mapping segments onto the surface"; the blossom formula of
//! `spline::compose::compose_line` on the homogeneous patch), the pieces joined C0 at the knot
//! lines. The curve's parameter is `B`'s own, so `S(B(t))` and the built curve agree at every
//! `t` up to the rounding of the control points.
//!
//! Parameter-space curves that are not piecewise linear, or that are rational, or that leave the
//! surface's domain are not mapped: the caller keeps the model-space copy and says so.

use super::{R, Reader};
use crate::geom::Hom;
use crate::spline::bspline_surface::BezierPatch;
use crate::spline::compose::compose_line;
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
        let Some(bp) = patches
            .iter()
            .find(|q| q.u0 <= mid[0] && mid[0] <= q.u1 && q.v0 <= mid[1] && mid[1] <= q.v1)
        else {
            return Err(format!(
                "the point ({}, {}) of the parameter-space curve lies outside the surface's domain",
                mid[0], mid[1]
            ));
        };
        let local = |p: [f64; 2]| {
            [
                (p[0] - bp.u0) / (bp.u1 - bp.u0),
                (p[1] - bp.v0) / (bp.v1 - bp.v0),
            ]
        };
        let c = compose_line(&bp.patch, &local(pa), &local(pb));
        let (ta, tb) = (t0 + w[0] * (t1 - t0), t0 + w[1] * (t1 - t0));
        let d = c.control.len() - 1;
        let knots: Vec<f64> = (0..2 * (d + 1))
            .map(|i| if i <= d { ta } else { tb })
            .collect();
        let hom = BSplineCurve::new(knots, d, c.control).map_err(|e| e.to_string())?;
        out.push(NurbsCurve { hom });
    }
    Ok(out)
}

impl Reader<'_> {
    /// The image on `s` of the parameter-space curve `bp` (a curve entity, x and y being u and
    /// v), one named curve per member as [`Reader::segments`] gives them; `Err` with the reason
    /// when a member is not linear, rational or leaves the domain.
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
            if seg.hom.degree() != 1 {
                return Ok(Err(format!(
                    "{name} is of degree {}, not piecewise linear",
                    seg.hom.degree()
                )));
            }
            if w.windows(2).any(|x| x[0] != x[1]) {
                return Ok(Err(format!("{name} is rational")));
            }
            if let Some(p) = pts.iter().find(|p| {
                !(p[0] >= u0 - su && p[0] <= u1 + su && p[1] >= v0 - sv && p[1] <= v1 + sv)
            }) {
                return Ok(Err(format!(
                    "{name} passes through ({}, {}), outside the surface's domain [{u0}, {u1}] x [{v0}, {v1}]",
                    p[0], p[1]
                )));
            }
            let knots = seg.hom.knots.knots();
            let mut pieces: Vec<NurbsCurve<f64, 3>> = Vec::new();
            for i in 0..pts.len().saturating_sub(1) {
                let (t0, t1) = (knots[i + 1], knots[i + 2]);
                let (a, b) = ([pts[i][0], pts[i][1]], [pts[i + 1][0], pts[i + 1][1]]);
                if t1 <= t0 || a == b {
                    continue;
                }
                match image_of_line(&patches, (&u_breaks, &v_breaks), (a, b), (t0, t1)) {
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
