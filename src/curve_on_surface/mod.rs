//! Curves on B-spline surfaces that lie exactly on the surface, with a proven Hausdorff
//! bound (Yang, Cao, Li, Zheng & Sun, "Approximate computation of curves on B-spline
//! surfaces", CAD 2008).
//!
//! Given a polynomial B-spline surface S and a B-spline curve D in its parameter domain,
//! build a domain polyline whose image under S — a chain of Bézier curves of degree `p + q`,
//! each *exactly* on S — is within `ε_D` of the exact image `S(D)`, with adjacent pieces
//! meeting at tangent angles at most `ε_T`. One file per step:
//! 1. [`cells`], [`split`] — Bézier patches of S; D split at its knots and at knot lines;
//! 2. [`sidedness`] — exact single-sided classification, double-sided pieces split;
//! 3. [`tolerance`] — the 2D tolerance `d` of eq. (12), scaled to each patch's spans;
//! 4. [`hausdorff`], [`distance`] — certified 2D Hausdorff bound, split at farthest points;
//! 5. [`g1`] — the ε_T pass (eqs. 18–22);
//! 6. [`map`] — chords mapped by blossoming, exact;
//! 7. [`evidence`] — dense-sample distances, reported as evidence.
//!
//! Two arithmetics run these steps ([`Arithmetic`]): [`float`] — f64 with every certified
//! quantity enclosed in interval arithmetic and the sign decisions made by exact predicates,
//! falling back to the exact path whenever an enclosure cannot decide — and the exact path
//! (Rational throughout), the reference. Both certify the same object: the exact curve on
//! S given by blossoming S on each chord of the f64 domain polyline.

pub mod casteljau;
pub mod cells;
pub mod distance;
pub mod evidence;
pub mod examples;
pub mod face;
pub mod face_job;
pub mod float;
pub mod g1;
pub mod hausdorff;
pub mod internal;
pub mod job;
pub mod map;
pub mod picture;
pub mod renner;
mod report;
pub mod segments;
pub mod sidedness;
pub mod split;
pub mod tolerance;

mod exact;

use crate::spline::{BSplineCurve, BSplineSurface, NurbsCurve, NurbsSurface};
use exact::exact_chain;
pub use internal::CosInternal;
pub(crate) use report::eval_segment;
use serde::Serialize;

/// Why the computation was refused or failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CosError {
    #[error(
        "the domain curve leaves the surface's parameter domain for t in [{t0}, {t1}] (at u,v = {at:?})"
    )]
    OutOfDomain { t0: f64, t1: f64, at: [f64; 2] },
    #[error(
        "this method is for polynomial surfaces only (the certified method takes rational ones)"
    )]
    RationalSurface,
    #[error("a weight of the surface's Bézier patch on [{}, {}] x [{}, {}] is not proven positive", cell[0], cell[1], cell[2], cell[3])]
    Weight { cell: [f64; 4] },
    #[error("rational domain curves are not supported (the domain curve must be polynomial)")]
    RationalCurve,
    #[error(
        "tolerances out of range: eps_d = {0} must be finite and positive, eps_t = {1} degrees must lie in (0, 180)"
    )]
    Tolerance(f64, f64),
    #[error("the degree-reduction tolerance must be finite and positive, not {0}")]
    ReductionTolerance(f64),
    #[error("more than {0} segments would be needed: the tolerance is too small for this input")]
    TooManySegments(usize),
    #[error("internal consistency check failed: {0}")]
    Internal(#[from] CosInternal),
}

/// Which Lipschitz bound turns the 3D tolerance into the 2D one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Bound {
    /// Eq. (12) of the paper, per Bézier patch, scaled to its spans.
    PaperEq12,
    /// The local refinement: hodograph hulls on each segment's rectangle, combined by
    /// Cauchy–Schwarz (never larger than eq. 12; still proven).
    Local,
}

impl Bound {
    /// The bound by its option name: `local` or `paper`; `None` for any other name.
    pub fn from_name(name: &str) -> Option<Bound> {
        match name {
            "local" => Some(Bound::Local),
            "paper" => Some(Bound::PaperEq12),
            _ => None,
        }
    }
}

/// Which arithmetic runs the steps.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Arithmetic {
    /// f64 with interval enclosures for every certified quantity and exact predicates for
    /// the decisions; reruns exactly when an enclosure cannot decide.
    Float,
    /// Rational throughout (the reference; control points are the exact blossoms).
    Exact,
}

/// User parameters.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Params {
    pub arithmetic: Arithmetic,
    /// Distance tolerance `ε_D` in model units.
    pub eps_d: f64,
    /// Angle tolerance `ε_T` in degrees.
    pub eps_t_deg: f64,
    /// Safety cap on the number of segments.
    pub max_segments: usize,
    /// Samples per segment for the measured evidence ([`evidence`]); 0 (the default): not
    /// measured. It proves nothing and can take most of a run's time, so it is asked for
    /// (`--evidence` on the command line).
    pub evidence_samples: usize,
    pub bound: Bound,
}

impl Params {
    /// The parameters from the command line's options: tolerances, bound, `--exact`, and the
    /// evidence samples per segment (0: none).
    pub fn from_options(
        tol: f64,
        angle: f64,
        bound: Bound,
        exact: bool,
        evidence: usize,
    ) -> Params {
        Params {
            eps_d: tol,
            eps_t_deg: angle,
            bound,
            arithmetic: if exact {
                Arithmetic::Exact
            } else {
                Arithmetic::Float
            },
            evidence_samples: evidence,
            ..Params::default()
        }
    }
}

impl Default for Params {
    fn default() -> Self {
        Params {
            arithmetic: Arithmetic::Float,
            eps_d: 1e-3,
            eps_t_deg: 10.0,
            max_segments: 200_000,
            evidence_samples: 0,
            bound: Bound::Local,
        }
    }
}

/// One output segment.
#[derive(Clone, Debug, Serialize)]
pub struct Segment {
    pub degree: usize,
    pub control_points: Vec<[f64; 3]>,
    /// The weights when the surface is rational (the segment is then a rational Bézier
    /// curve); absent for a polynomial surface.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub weights: Option<Vec<f64>>,
    /// Chord end points `[[u, v], [u, v]]` in the surface's parameter domain.
    pub domain: [[f64; 2]; 2],
    /// This segment's proven Hausdorff bound `K · h` to its piece of `S(D)`.
    pub bound: f64,
}

/// What is proven.
#[derive(Clone, Debug, Serialize)]
pub struct Certificate {
    pub eps_d: f64,
    pub eps_t_deg: f64,
    /// Proven upper bound on the Hausdorff distance between the exact output curve and the
    /// exact image `S(D)`: max over segments of `K · h` (eq. 11–12).
    pub hausdorff_bound: f64,
    /// The Lipschitz bound used.
    pub bound: Bound,
    /// Largest tangent angle between adjacent segments (computed in f64).
    pub max_angle_deg: f64,
    /// Junctions left above `ε_T` (corners of D or S that splitting cannot remove).
    pub unresolved_junctions: usize,
    /// Exact distance from the exact output curve to S: 0 by construction (blossoming).
    pub distance_to_surface: f64,
    /// Largest coordinate difference between the printed f64 control points and the exact
    /// ones (proven upper bound); for a rational surface, a proven bound on the distance
    /// between the curve the printed points and weights define and the exact one.
    pub control_point_rounding: f64,
    /// The arithmetic that produced the result (and why the exact rerun happened, if it did).
    pub arithmetic: String,
}

/// Measured, not proven; only when asked for ([`Params::evidence_samples`]).
#[derive(Clone, Debug, Serialize)]
pub struct Evidence {
    /// Whether the evidence was measured; when not, the other fields are 0.
    pub measured: bool,
    pub max_distance_sampled: f64,
    pub samples: usize,
    /// Time spent measuring (not part of `elapsed_ms`).
    pub elapsed_ms: f64,
}

/// The exact composition, for comparison (the "Exact" column of Table 2).
#[derive(Clone, Debug, Serialize)]
pub struct ExactReference {
    pub degree: usize,
    pub segments: usize,
    pub control_points: usize,
}

/// Counts of what each step did.
#[derive(Clone, Debug, Serialize)]
pub struct Steps {
    pub bezier_patches: usize,
    pub domain_bezier_pieces: usize,
    pub after_knot_line_split: usize,
    pub sidedness: sidedness::SidednessStats,
    pub after_distance: usize,
    pub g1: g1::G1Stats,
    pub min_2d_tolerance: f64,
    /// Bézier patches actually built (the f64 path builds only those the curve visits).
    pub patches_built: usize,
}

/// One segment as either path delivers it.
#[derive(Clone, Debug)]
pub struct ChainSegment {
    pub control_points: Vec<[f64; 3]>,
    /// The weights when the surface is rational.
    pub weights: Option<Vec<f64>>,
    pub domain: [[f64; 2]; 2],
    pub bound: f64,
    /// The domain curve piece this segment stands for, in f64 — kept only when evidence is
    /// measured (its sole use).
    pub domain_curve: Option<crate::spline::BezierCurve<[f64; 2]>>,
}

/// What either path delivers before the result is assembled.
#[derive(Clone, Debug)]
pub struct Chain {
    pub segments: Vec<ChainSegment>,
    pub rounding: f64,
    pub joints_exact: bool,
    pub side: sidedness::SidednessStats,
    pub g1: g1::G1Stats,
    pub bezier_patches: usize,
    pub patches_built: usize,
    pub domain_bezier_pieces: usize,
    pub after_split: usize,
    pub after_distance: usize,
    pub min_2d_tolerance: f64,
    pub arithmetic: String,
}

/// The result of [`approximate`].
#[derive(Clone, Debug, Serialize)]
pub struct CurveOnSurface {
    pub segments: Vec<Segment>,
    pub domain_polyline: Vec<[f64; 2]>,
    pub num_segments: usize,
    pub num_control_points: usize,
    /// B-spline form: degree, knots (integer breakpoints of multiplicity `degree`),
    /// control points (segments joined at their shared end points).
    pub bspline: BSplineForm,
    pub certificate: Certificate,
    pub evidence: Evidence,
    pub exact_reference: ExactReference,
    pub steps: Steps,
    /// Wall time of the algorithm and its certificate (the evidence is timed separately).
    pub elapsed_ms: f64,
}

/// The output as one B-spline curve.
#[derive(Clone, Debug, Serialize)]
pub struct BSplineForm {
    pub degree: usize,
    pub knots: Vec<f64>,
    pub control_points: Vec<[f64; 3]>,
    /// The weights when the surface is rational (each segment's scaled so that joints
    /// share one weight).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub weights: Option<Vec<f64>>,
    /// Whether consecutive exact segments share their end points exactly (C0, proven).
    pub joints_exact: bool,
}

/// Run the algorithm on a polynomial surface and a polynomial domain curve.
pub fn approximate(
    surface: &NurbsSurface<f64, 3>,
    curve: &NurbsCurve<f64, 2>,
    params: &Params,
) -> Result<CurveOnSurface, CosError> {
    approximate_with_progress(surface, curve, params, &mut |_, _| {})
}

/// [`approximate`], reporting each step's name and segment count to `progress`.
pub fn approximate_with_progress(
    surface: &NurbsSurface<f64, 3>,
    curve: &NurbsCurve<f64, 2>,
    params: &Params,
    progress: &mut dyn FnMut(&str, usize),
) -> Result<CurveOnSurface, CosError> {
    let start = std::time::Instant::now();
    if !(params.eps_d > 0.0
        && params.eps_d.is_finite()
        && params.eps_t_deg > 0.0
        && params.eps_t_deg < 180.0)
    {
        return Err(CosError::Tolerance(params.eps_d, params.eps_t_deg));
    }
    let (cpts, cw) = curve.points_weights();
    if cw.iter().any(|w| *w != cw[0]) {
        return Err(CosError::RationalCurve);
    }
    let rational = !surface.is_polynomial();
    let h = &surface.hom;
    // A rational surface runs on its homogeneous points `w·P` and its weights.
    let (net, weights) = if rational {
        let (n, w): (Vec<[f64; 3]>, Vec<f64>) = h.net.iter().map(|x| (x.wp, x.w)).unzip();
        (n, Some(w))
    } else {
        (surface.points_weights().0, None)
    };
    let s: BSplineSurface<[f64; 3]> = BSplineSurface {
        ku: h.ku.clone(),
        kv: h.kv.clone(),
        net,
    };
    let d: BSplineCurve<[f64; 2]> = BSplineCurve {
        knots: curve.hom.knots.clone(),
        control: cpts,
    };
    let chain = match params.arithmetic {
        Arithmetic::Exact => exact_chain(&s, weights.as_deref(), &d, params, progress)?,
        Arithmetic::Float => match float::run(&s, weights.as_deref(), &d, params, progress) {
            Ok(c) => c,
            Err(float::FloatError::Cos(e)) => return Err(e),
            Err(float::FloatError::Undecided(why)) => {
                progress(&format!("f64 enclosures undecided ({why}): exact rerun"), 0);
                let mut c = exact_chain(&s, weights.as_deref(), &d, params, progress)?;
                c.arithmetic = format!("exact (rerun: the f64 enclosures could not decide {why})");
                c
            }
        },
    };
    let bound = chain.segments.iter().map(|x| x.bound).fold(0.0, f64::max);
    if bound > params.eps_d {
        return Err(CosInternal::BoundAboveTolerance { bound }.into());
    }
    let (pdeg, qdeg) = s.degrees();
    let deg = pdeg + qdeg;
    // B-spline form: the segments joined at their shared end points; rational segments'
    // weights scaled so that each joint has one weight (the scaling leaves a rational Bézier
    // curve unchanged; its rounding is in the bound of `float::rational`).
    let mut bs_cps: Vec<[f64; 3]> = Vec::new();
    let mut bs_w: Vec<f64> = Vec::new();
    for (i, m) in chain.segments.iter().enumerate() {
        let skip = usize::from(i > 0);
        bs_cps.extend(m.control_points.iter().skip(skip).cloned());
        if let Some(w) = &m.weights {
            let f = match (bs_w.last(), w.first()) {
                (Some(l), Some(f)) if i > 0 => l / f,
                _ => 1.0,
            };
            bs_w.extend(w.iter().skip(skip).map(|x| x * f));
        }
    }
    let nseg = chain.segments.len();
    let mut knots = vec![0.0; deg + 1];
    for k in 1..nseg {
        knots.extend(std::iter::repeat_n(k as f64, deg));
    }
    knots.extend(std::iter::repeat_n(nseg as f64, deg + 1));
    let elapsed_ms = start.elapsed().as_secs_f64() * 1e3;
    let ev_start = std::time::Instant::now();
    let (ev, samples) = evidence::measure(surface, &chain.segments, params.evidence_samples);
    let evidence_ms = if params.evidence_samples > 0 {
        ev_start.elapsed().as_secs_f64() * 1e3
    } else {
        0.0
    };
    let mut polyline: Vec<[f64; 2]> = chain.segments.iter().map(|x| x.domain[0]).collect();
    if let Some(l) = chain.segments.last() {
        polyline.push(l.domain[1]);
    }
    let cdeg = d.degree();
    let after_split = chain.after_split;
    Ok(CurveOnSurface {
        num_segments: nseg,
        num_control_points: bs_cps.len(),
        segments: chain
            .segments
            .iter()
            .map(|m| Segment {
                degree: deg,
                control_points: m.control_points.clone(),
                weights: m.weights.clone(),
                domain: m.domain,
                bound: m.bound,
            })
            .collect(),
        domain_polyline: polyline,
        bspline: BSplineForm {
            degree: deg,
            knots,
            control_points: bs_cps,
            weights: rational.then_some(bs_w),
            joints_exact: chain.joints_exact,
        },
        certificate: Certificate {
            eps_d: params.eps_d,
            eps_t_deg: params.eps_t_deg,
            hausdorff_bound: bound,
            bound: params.bound,
            max_angle_deg: chain.g1.max_angle_deg,
            unresolved_junctions: chain.g1.unresolved_junctions,
            distance_to_surface: 0.0,
            control_point_rounding: chain.rounding,
            arithmetic: chain.arithmetic.clone(),
        },
        evidence: Evidence {
            measured: params.evidence_samples > 0,
            max_distance_sampled: ev,
            samples,
            elapsed_ms: evidence_ms,
        },
        exact_reference: ExactReference {
            degree: deg * cdeg,
            segments: after_split,
            control_points: after_split * deg * cdeg + 1,
        },
        steps: Steps {
            bezier_patches: chain.bezier_patches,
            domain_bezier_pieces: chain.domain_bezier_pieces,
            after_knot_line_split: after_split,
            sidedness: chain.side,
            after_distance: chain.after_distance,
            g1: chain.g1,
            min_2d_tolerance: chain.min_2d_tolerance,
            patches_built: chain.patches_built,
        },
        elapsed_ms,
    })
}
