//! The f64 path of the curve-on-surface algorithm: the same steps as the exact path, with
//! every quantity the certificate rests on *enclosed* in outward-rounded interval arithmetic
//! and every decision either certified by the enclosures or handed back (`Undecided`) so
//! the caller reruns the whole computation exactly. What it certifies is the same as the
//! exact path's: the exact curve on S defined by the f64 domain polyline (the blossom of the
//! exact surface on each f64 chord) is within the proven bound of `S(D)`; the printed f64
//! control points are within `control_point_rounding` (proven, from the enclosures) of it.
//!
//! Files: [`ibez`] (interval blossoms), [`cells`] (step 1a, 3), [`split`] (step 1b),
//! [`sides`] (step 2), [`distance`] (steps 3–4), [`map`] (step 6); the ε_T pass (step 5)
//! is the shared [`crate::curve_on_surface::g1::enforce_g1_with`].

pub mod cells;
pub mod distance;
pub mod ibez;
pub mod map;
pub mod midpatch;
pub mod rational;
pub mod sides;
pub mod span;
pub mod split;

use super::g1::{G1Ops, enforce_g1_with};
use super::{Chain, ChainSegment, CosError, CosInternal, Params};
use crate::spline::{BSplineCurve, BSplineSurface, BezierCurve};
use ibez::IP;

/// Why the f64 path stopped.
#[derive(Debug)]
pub enum FloatError {
    /// A real refusal (bad input, too many segments): the exact path would give the same.
    Cos(CosError),
    /// The enclosures could not decide something (named); rerun exactly.
    Undecided(Undecided),
}

/// What the `f64` enclosures could not decide (the exact path decides it).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Undecided {
    #[error("domain curve knots")]
    DomainKnots,
    /// The crossing of the domain curve, on the parameter window `t`, with a knot line.
    #[error("crossing of the domain curve (t in [{}, {}]) with the knot line {} = {knot}", t[0], t[1], if *along_u { "u" } else { "v" })]
    KnotLineCrossing {
        t: [f64; 2],
        along_u: bool,
        knot: f64,
    },
    #[error("whether the domain curve at t = {t} is inside the domain")]
    InsideDomain { t: f64 },
    #[error("the cell of the domain curve at t = {t}")]
    Cell { t: f64 },
    #[error("a patch of (nearly) zero width")]
    ZeroWidthPatch,
    #[error("overflow in the mapping, or a mapped weight not proven positive")]
    MappingOverflow,
    /// A weight of the rational patch on `cell` not proven positive by the enclosures.
    #[error("whether the weights of the patch on [{}, {}] x [{}, {}] are positive", cell[0], cell[1], cell[2], cell[3])]
    Weight { cell: [f64; 4] },
}

impl From<cells::CellError> for FloatError {
    /// A weight the enclosures cannot prove positive is undecided (the exact path decides);
    /// a bad knot vector is a refusal.
    fn from(e: cells::CellError) -> Self {
        match e {
            cells::CellError::Weight(cell) => FloatError::Undecided(Undecided::Weight { cell }),
            e => FloatError::Cos(e.into()),
        }
    }
}

/// A Bézier piece of D: enclosed control points, their midpoints, its global parameter range.
#[derive(Clone, Debug)]
pub struct Piece {
    pub ctrl: Vec<IP<2>>,
    /// Midpoints of `ctrl`, their largest coordinate radius and magnitude.
    pub ctrl_f64: Vec<[f64; 2]>,
    pub ctrl_r: f64,
    pub ctrl_mx: f64,
    pub t_lo: f64,
    pub t_hi: f64,
}

/// A segment: `pieces[piece]` on local `[t0, t1]` (f64), chord `a → b` in cell `cell`,
/// `ea`/`eb` proven distances from `a`/`b` to `D(t0)`/`D(t1)`, `h`/`k` once computed.
#[derive(Clone, Copy, Debug)]
pub struct FSeg {
    pub piece: usize,
    pub t0: f64,
    pub t1: f64,
    pub a: [f64; 2],
    pub b: [f64; 2],
    pub ea: f64,
    pub eb: f64,
    pub cell: usize,
    pub h: f64,
    pub k: f64,
    /// The rectangle on which `k` is a proven Lipschitz bound (inherited from the parent
    /// segment until the segment's own is needed).
    pub k_region: [f64; 4],
    /// Whether `k` was computed for this segment's own region.
    pub k_own: bool,
}

/// Run the algorithm in f64 with enclosures. For a rational surface `s` holds the
/// homogeneous points `w·P` and `weights` the weights ([`rational`]).
pub fn run(
    s: &BSplineSurface<[f64; 3]>,
    weights: Option<&[f64]>,
    d: &BSplineCurve<[f64; 2]>,
    params: &Params,
    progress: &mut dyn FnMut(&str, usize),
) -> Result<Chain, FloatError> {
    let cells = match weights {
        None => cells::FCells::new(s),
        Some(w) if w.len() == s.net.len() => cells::FCells::rational(s, w),
        Some(w) => {
            return Err(FloatError::Cos(
                CosInternal::Curve(crate::spline::SplineError::NetSize {
                    got: w.len(),
                    expected: s.net.len(),
                    what: "weights",
                })
                .into(),
            ));
        }
    };
    let (pieces, segs) = split::split(d, &cells)?;
    progress("split at knots and knot lines", segs.len());
    let after_split = segs.len();
    let (segs, side) = sides::make_single_sided(segs, &pieces, &cells);
    let distance = |segs| {
        distance::enforce_distance(
            segs,
            &pieces,
            &cells,
            params.eps_d,
            params.bound,
            params.max_segments,
        )
    };
    let segs = distance(segs)?;
    let after_distance = segs.len();
    progress("distance bound", segs.len());
    let closed = segs.len() > 1
        && segs.first().map(|f| f.a) == segs.last().map(|l| l.b)
        && d.eval(&d.domain().0) == d.eval(&d.domain().1);
    let tangent = |x: &FSeg, at_end: bool| -> Option<[f64; 3]> {
        Some(cells.get(x.cell).ok()?.tangent(&x.a, &x.b, at_end))
    };
    let (segs, g1s) = enforce_g1_with(
        segs,
        params.eps_t_deg,
        closed,
        params.max_segments,
        &G1Ops {
            tangents: |x: &FSeg| Some((tangent(x, false)?, tangent(x, true)?)),
            deviation: |x: &FSeg| x.h,
            param_len: |x: &FSeg| x.t1 - x.t0,
            split: |x: &FSeg| {
                let c = distance::sub_curve(x, &pieces);
                distance::split_at(x, distance::farthest_parameter(&c.m), &pieces, &cells)
            },
        },
    );
    let segs = distance(segs)?;
    progress("eps_T pass", segs.len());
    let (mapped, rounding) = map::map_segments(&segs, &cells)?;
    progress("mapped (enclosed)", mapped.len());
    let joints_exact = segs.windows(2).all(|w| w[0].b == w[1].a);
    let min_d = segs
        .iter()
        .map(|x| super::tolerance::tolerance_2d(params.eps_d, x.k))
        .fold(f64::INFINITY, f64::min);
    let segments = segs
        .iter()
        .zip(mapped)
        .map(|(x, (cps, weights))| ChainSegment {
            control_points: cps,
            weights,
            domain: [x.a, x.b],
            bound: (x.k * x.h).next_up(),
            domain_curve: (params.evidence_samples > 0).then(|| BezierCurve {
                control: distance::sub_curve(x, &pieces).m,
            }),
        })
        .collect();
    Ok(Chain {
        segments,
        rounding,
        joints_exact,
        side,
        g1: g1s,
        bezier_patches: cells.count(),
        patches_built: cells.built(),
        domain_bezier_pieces: pieces.len(),
        after_split,
        after_distance,
        min_2d_tolerance: min_d,
        arithmetic: "f64 with interval enclosures and exact predicates".into(),
    })
}

impl From<CosError> for FloatError {
    fn from(e: CosError) -> Self {
        FloatError::Cos(e)
    }
}

#[cfg(test)]
mod tests {
    use super::Undecided;

    /// The reasons read as they did when they were strings (the text goes into the result's
    /// `arithmetic` field and the progress line).
    #[test]
    fn undecided_reasons_read_as_before() {
        let k = Undecided::KnotLineCrossing {
            t: [0.25, 0.5],
            along_u: false,
            knot: 0.375,
        };
        assert_eq!(
            k.to_string(),
            "crossing of the domain curve (t in [0.25, 0.5]) with the knot line v = 0.375"
        );
        assert_eq!(
            Undecided::InsideDomain { t: 0.5 }.to_string(),
            "whether the domain curve at t = 0.5 is inside the domain"
        );
        assert_eq!(
            Undecided::Cell { t: 1.0 }.to_string(),
            "the cell of the domain curve at t = 1"
        );
        assert_eq!(Undecided::DomainKnots.to_string(), "domain curve knots");
    }
}
