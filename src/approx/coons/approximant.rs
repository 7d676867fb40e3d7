//! §3.1 and §3.6: one local approximant — steps 1–5 at resolution `M × N`, the discrete
//! error (17), and `M`, `N` doubled (the direction whose samples exceed the tolerance: `e`
//! raises `M`, `f` raises `N`, `g` both) until the error is within tolerance or the maximum
//! resolution is reached.

use super::boundary::{BoundarySpec, Loop, close_loop, resolve};
use super::discrete::{Grid, coons_patch};
use super::error::{Evidence, Proven, Sample, measure, prove};
use super::multiquadric::{FillStats, fill};
use super::normals::{normals, offset_distance, offsets};
use super::project::{Hit, OriginalMesh, project_grid, triangulate};
use super::{CoonsError, Params, bicubic};
use crate::geom::{Point, cross, dist};
use crate::model::Model;
use crate::spline::NurbsSurface;
use serde::Serialize;

/// One resolution tried.
#[derive(Clone, Debug, Serialize)]
pub struct Round {
    pub m: usize,
    pub n: usize,
    /// Grid points projected onto an original surface, of which refined by Newton.
    pub hits: usize,
    pub refined: usize,
    /// Artificial projections (multiquadric).
    pub artificial: usize,
    pub max_error: f64,
    pub measured: usize,
    pub skipped_gap: usize,
}

/// The report of one approximant.
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    pub params: Params,
    pub curves: [String; 4],
    /// Curves traversed against their stored direction.
    pub reversed: [bool; 4],
    /// Gaps between consecutive curves' ends (corner `k` joins curve `k−1` to curve `k`).
    pub corner_gaps: [f64; 4],
    pub boundary_lengths: [f64; 4],
    /// Eq. (7).
    pub offset_distance: f64,
    /// Original surfaces inside the offset hull, triangles considered.
    pub surfaces_considered: Vec<usize>,
    pub triangles: usize,
    pub rounds: Vec<Round>,
    /// The final resolution.
    pub m: usize,
    pub n: usize,
    pub fill: FillStats,
    /// Largest `‖S(u,v) − ((1−t) a + t b)‖` of the hits (Newton residual).
    pub max_hit_residual: f64,
    /// Largest distance between a boundary grid point after projection and the boundary
    /// curve's point it came from.
    pub boundary_shift: f64,
    /// Largest rounding defect of the C1 conditions (zero in exact arithmetic).
    pub c1_defect: f64,
    pub proven: Proven,
    pub evidence: Evidence,
    /// The measured error is within tolerance (evidence) and the proven facts hold.
    pub within_tol: bool,
    pub reason: String,
    /// Faces whose trimming could not be applied.
    pub warnings: Vec<String>,
    pub seconds: f64,
}

/// The approximant with what it was built from.
#[derive(Clone, Debug)]
pub struct Approximant {
    pub surface: NurbsSurface<f64, 3>,
    /// The discrete Coons patch `x` and the interpolated points `y` / `z`.
    pub coons: Grid<[f64; 3]>,
    pub points: Grid<[f64; 3]>,
    /// Which points are artificial projections.
    pub artificial: Grid<bool>,
    pub samples: Vec<Sample>,
    pub report: Report,
}

/// Progress callback: a stage name and a count.
pub type Progress<'a> = &'a mut dyn FnMut(&str, usize);

/// One approximant for the boundary file `spec` over the model's surfaces.
pub fn approximate(
    model: &Model,
    spec: &BoundarySpec,
    params: &Params,
) -> Result<Approximant, CoonsError> {
    approximate_with_progress(model, spec, params, &mut |_, _| {})
}

/// [`approximate`] reporting each stage to `progress`.
pub fn approximate_with_progress(
    model: &Model,
    spec: &BoundarySpec,
    params: &Params,
    progress: Progress,
) -> Result<Approximant, CoonsError> {
    params.validate()?;
    let curves = resolve(spec, model)?;
    let lp = close_loop(curves, params.closure.unwrap_or(params.tol))?;
    approximate_loop(model, &lp, params, progress)
}

struct Built {
    y: Grid<[f64; 3]>,
    artificial: Grid<bool>,
    surface: NurbsSurface<f64, 3>,
    hits: usize,
    refined: usize,
    fill: FillStats,
    max_residual: f64,
    boundary_shift: f64,
}

fn build(
    model: &Model,
    mesh: &OriginalMesh,
    x: &Grid<[f64; 3]>,
    a: &Grid<[f64; 3]>,
    b: &Grid<[f64; 3]>,
    params: &Params,
) -> Result<Built, CoonsError> {
    let (m, n) = (x.m, x.n);
    let hits: Grid<Option<Hit>> = project_grid(model, mesh, a, b);
    let found = hits.data.iter().flatten().count();
    let known = Grid {
        m,
        n,
        data: hits.data.iter().map(|h| h.map(|h| h.t)).collect(),
    };
    let (t, mut fill_stats) = if found > 0 {
        fill(
            &known,
            params.k_nearest,
            params.r_scale,
            params.mu,
            params.linear_precision,
        )?
    } else {
        (Grid::filled(m, n, 0.5), FillStats::default())
    };
    let mut y = x.clone();
    let mut artificial = Grid::filled(m, n, false);
    let mut max_residual: f64 = 0.0;
    for k in 0..y.data.len() {
        match &hits.data[k] {
            Some(h) => {
                y.data[k] = h.point;
                max_residual = max_residual.max(h.residual);
            }
            None => {
                let mut tk = t.data[k];
                if !(0.0..=1.0).contains(&tk) {
                    fill_stats.clamped += 1;
                    tk = tk.clamp(0.0, 1.0);
                }
                y.data[k] = a.data[k].lerp(&b.data[k], &tk);
                artificial.data[k] = true;
            }
        }
    }
    let mut boundary_shift: f64 = 0.0;
    for i in 0..=m {
        for j in 0..=n {
            if i == 0 || j == 0 || i == m || j == n {
                boundary_shift = boundary_shift.max(dist(y.at(i, j), x.at(i, j)));
            }
        }
    }
    let surface = bicubic::interpolant(&y)?;
    Ok(Built {
        y,
        artificial,
        surface,
        hits: found,
        refined: hits.data.iter().flatten().filter(|h| h.refined).count(),
        fill: fill_stats,
        max_residual,
        boundary_shift,
    })
}

/// Steps 2–6 for a checked loop.
pub fn approximate_loop(
    model: &Model,
    lp: &Loop,
    params: &Params,
    progress: Progress,
) -> Result<Approximant, CoonsError> {
    params.validate()?;
    let t0 = std::time::Instant::now();
    let fallback = {
        let c = &lp.corners;
        let nrm = cross(&c[2].sub(&c[0]), &c[3].sub(&c[1]));
        let l = crate::geom::norm(&nrm);
        if l > 0.0 {
            nrm.scale(&(1.0 / l))
        } else {
            [0.0, 0.0, 1.0]
        }
    };
    let (mut m, mut n) = (
        params.m.min(params.max_resolution),
        params.n.min(params.max_resolution),
    );
    let x0 = coons_patch(lp, m, n);
    let d = offset_distance(&x0, params.d_scale);
    if !(d > 0.0 && d.is_finite()) {
        return Err(CoonsError::Flat(lp.names()));
    }
    // The offset hull (box of all a, b), enlarged by a tenth of its diagonal so that the
    // finer grids of later rounds stay inside.
    let (a0, b0) = offsets(&x0, &normals(&x0, fallback), d);
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in a0.data.iter().chain(&b0.data) {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let pad = 0.1 * dist(&lo, &hi);
    let hull = (lo.map(|c| c - pad), hi.map(|c| c + pad));
    let mesh = triangulate(model, hull, params.triangles_per_span);
    progress("triangles", mesh.triangles.len());
    if mesh.triangles.is_empty() {
        return Err(CoonsError::FarFromSurfaces {
            curves: lp.names(),
            d,
            why: "no original surface meets the box of the offset points".into(),
        });
    }
    let mut rounds = Vec::new();
    loop {
        let x = coons_patch(lp, m, n);
        let (a, b) = offsets(&x, &normals(&x, fallback), d);
        let built = build(model, &mesh, &x, &a, &b, params)?;
        if built.hits == 0 {
            return Err(CoonsError::FarFromSurfaces {
                curves: lp.names(),
                d,
                why: "no segment a–b meets an original surface".into(),
            });
        }
        let (samples, ev) = measure(model, &mesh, &built.surface, &built.artificial);
        progress("resolution M", m);
        rounds.push(Round {
            m,
            n,
            hits: built.hits,
            refined: built.refined,
            artificial: built.fill.filled,
            max_error: ev.max_error,
            measured: ev.measured,
            skipped_gap: ev.skipped_gap,
        });
        let proven = prove(&built.surface, &built.y);
        let ok = ev.max_error <= params.tol && ev.measured > 0;
        let raise_m = ev.max_e > params.tol || ev.max_g > params.tol;
        let raise_n = ev.max_f > params.tol || ev.max_g > params.tol;
        let can_m = raise_m && m < params.max_resolution;
        let can_n = raise_n && n < params.max_resolution;
        let reason = if ev.measured == 0 {
            Some("no error sample away from the gaps: nothing measured".to_string())
        } else if ok {
            Some(format!(
                "measured error {:.3e} ≤ tol {:e} at {} samples (evidence)",
                ev.max_error, params.tol, ev.measured
            ))
        } else if !can_m && !can_n {
            Some(format!(
                "maximum resolution {} reached with measured error {:.3e} > tol {:e}",
                params.max_resolution, ev.max_error, params.tol
            ))
        } else {
            None
        };
        if let Some(reason) = reason {
            let report = Report {
                params: params.clone(),
                curves: lp.sides.each_ref().map(|s| s.name.clone()),
                reversed: lp.reversed,
                corner_gaps: lp.gaps,
                boundary_lengths: lp.sides.each_ref().map(|s| s.length),
                offset_distance: d,
                surfaces_considered: mesh.surfaces.clone(),
                triangles: mesh.triangles.len(),
                rounds,
                m,
                n,
                fill: built.fill,
                max_hit_residual: built.max_residual,
                boundary_shift: built.boundary_shift,
                c1_defect: bicubic::c1_defect(&built.surface, m, n),
                within_tol: ok && proven.interpolates_grid_points,
                proven,
                evidence: ev,
                reason,
                warnings: mesh.regions.warnings.clone(),
                seconds: t0.elapsed().as_secs_f64(),
            };
            return Ok(Approximant {
                surface: built.surface,
                coons: x,
                points: built.y,
                artificial: built.artificial,
                samples,
                report,
            });
        }
        if can_m {
            m = (2 * m).min(params.max_resolution);
        }
        if can_n {
            n = (2 * n).min(params.max_resolution);
        }
    }
}
