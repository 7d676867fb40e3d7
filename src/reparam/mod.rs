//! Chord-length reparametrization of badly parametrized NURBS surfaces within a tolerance:
//! the RCA (Reconciled Curvature Arc length) method of Razdan, as described in §2 of
//! *CAGD techniques for surface grid generation* (see `docs/reparam.md`).
//!
//! One file per step of the paper:
//! * [`boundary`] — step 1: arc length (adaptive Gauss–Legendre per knot span) and curvature
//!   of the four boundary curves; interpolation points by arc length and curvature;
//! * [`reconcile`] — step 2: opposite boundaries reconciled into one parameter sequence per
//!   direction (`ξ_i` for u, `η_j` for v), knots by averaging (The NURBS Book eq. 9.8);
//! * [`interior`] — step 3: interior points, initial guess by intersecting domain lines, then
//!   the penalty relaxation (moves in the domain only), with a bound on the number of moves;
//! * [`surface`] — step 4: the C2 bicubic interpolating the grid at `(ξ_i, η_j)` (A9.4);
//! * [`error`] — `E_max`: one-sided distances between the new and the given surface by
//!   closest-point projection at dense samples (evidence), and the lines inserted where
//!   `E_max > ε` ("knot insertion at the worst point");
//! * [`bound`] — a proven bound on the Hausdorff distance between the new and the given
//!   surface (a mean-value form in interval arithmetic over parameter boxes, for the map φ
//!   interpolating the grid's domain points), or the hypothesis that failed;
//! * [`quality`] — the spacing ratio along iso-lines of a uniform parameter grid;
//! * [`plot`] — SVG (projected view, side by side) and VTK views of both surfaces;
//! * [`job`] — the `reparam` command: faces of a model file, outputs, report.

pub mod bound;
pub mod bound_box;
pub mod boundary;
pub mod error;
pub mod interior;
pub mod job;
pub mod plot;
pub mod quality;
pub mod reconcile;
pub mod redistribute;
pub mod surface;

use crate::spline::NurbsSurface;
use serde::Serialize;

/// Errors of the reparametrization: bad parameters or a surface it cannot treat.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ReparamError {
    /// The tolerance ε is not a positive finite number.
    #[error("tolerance {0:e} is not a positive finite number")]
    Tolerance(f64),
    /// Another parameter out of its range.
    #[error("parameter {name} = {value:e}: {why}")]
    Parameter {
        name: &'static str,
        value: f64,
        why: &'static str,
    },
    /// Two opposite borders are both single points: no parameter direction is left to
    /// measure arc length along (`u` or `v`).
    #[error("both borders in {0} collapse to points: the surface has no extent in that direction")]
    Collapsed(&'static str),
    /// The surface is not finite where evaluated (NaN or infinity).
    #[error("the surface evaluates to a non-finite point at (u, v) = ({0:e}, {1:e})")]
    NotFinite(f64, f64),
    /// A border has zero length in this parametrization although its control points differ,
    /// or the interpolation failed (singular system): a surface the method cannot treat.
    #[error("{0}")]
    Degenerate(String),
}

/// Parameters of the reparametrization.
#[derive(Clone, Debug, Serialize)]
pub struct Params {
    /// ε: the largest deviation `E_max` accepted between the new and the given surface.
    pub tol: f64,
    /// Step 1: largest turning angle of one piece between interpolation points (radians).
    pub max_turn: f64,
    /// Step 1: fewest pieces per boundary curve (at least 3, so cubics interpolate).
    pub min_pieces: usize,
    /// Step 1: most pieces per boundary curve.
    pub max_pieces: usize,
    /// Step 2: fractions of arc length closer than `merge` times the smallest gap of either
    /// opposite set are one point.
    pub merge: f64,
    /// Step 3: a move is accepted only if it lowers the total penalty by at least this.
    pub delta: f64,
    /// Step 3: the most accepted moves per relaxation (the theorem's bound is usually far
    /// larger; reaching this budget marks the result not converged).
    pub max_moves: usize,
    /// Step 3: alternating row/column redistributions before the relaxation (0: none).
    pub sweeps: usize,
    /// Step 3: smallest domain step of a move, relative to the domain's side.
    pub min_step: f64,
    /// Step 4: samples per grid cell and direction for `E_max`.
    pub samples_per_cell: usize,
    /// Step 4: the most parameter lines inserted (both directions together).
    pub max_lines: usize,
    /// Quality: intervals of the uniform parameter grid the spacing ratio is measured on.
    pub quality_grid: usize,
    /// Step 4: compute the proven deviation bound ([`bound`]); without it only the sampled
    /// evidence decides ε.
    pub prove_bound: bool,
    /// The proven bound: most parameter boxes evaluated per round.
    pub bound_boxes: usize,
    /// The proven bound: boxes are refined until their bound is at most this factor times the
    /// sampled `E_max` (at least 10⁻³ ε; at most ε when the samples are within ε).
    pub bound_ratio: f64,
    /// The most rounds of lines inserted because the proven bound exceeded ε although the
    /// samples did not (default 0: where the bound is loose, it is loose because of the
    /// method, not of the surface — see `docs/reparam.md` — and lines do not help).
    pub bound_rounds: usize,
}

impl Default for Params {
    fn default() -> Self {
        Params {
            tol: 1e-4,
            max_turn: 0.25,
            min_pieces: 3,
            max_pieces: 200,
            merge: 0.3,
            delta: 1e-10,
            max_moves: 300_000,
            sweeps: 30,
            min_step: 1e-9,
            samples_per_cell: 4,
            max_lines: 500,
            quality_grid: 20,
            prove_bound: true,
            bound_boxes: 20_000,
            bound_ratio: 2.0,
            bound_rounds: 0,
        }
    }
}

impl Params {
    /// Check every parameter; ε ≤ 0, NaN or infinite is [`ReparamError::Tolerance`].
    pub fn validate(&self) -> Result<(), ReparamError> {
        if !(self.tol > 0.0 && self.tol.is_finite()) {
            return Err(ReparamError::Tolerance(self.tol));
        }
        let bad = |name, value: f64, why| Err(ReparamError::Parameter { name, value, why });
        if !(self.max_turn > 0.0 && self.max_turn <= std::f64::consts::PI) {
            return bad("max_turn", self.max_turn, "must lie in (0, π]");
        }
        if self.min_pieces < 3 || self.max_pieces < self.min_pieces {
            return bad(
                "min_pieces",
                self.min_pieces as f64,
                "must be at least 3 and at most max_pieces",
            );
        }
        if !(self.merge >= 0.0 && self.merge < 0.5) {
            return bad("merge", self.merge, "must lie in [0, 0.5)");
        }
        if !(self.delta >= 1e-13 && self.delta.is_finite()) {
            return bad(
                "delta",
                self.delta,
                "must be at least 1e-13 (above the rounding of the penalty sums)",
            );
        }
        if !(self.min_step > 0.0 && self.min_step < 0.1) {
            return bad("min_step", self.min_step, "must lie in (0, 0.1)");
        }
        if self.samples_per_cell < 2 || self.samples_per_cell > 64 {
            return bad(
                "samples_per_cell",
                self.samples_per_cell as f64,
                "must lie in 2..=64",
            );
        }
        if !(self.bound_ratio >= 1.0 && self.bound_ratio.is_finite()) {
            return bad("bound_ratio", self.bound_ratio, "must be at least 1");
        }
        if self.bound_boxes < 16 {
            return bad(
                "bound_boxes",
                self.bound_boxes as f64,
                "must be at least 16",
            );
        }
        if self.quality_grid < 2 || self.quality_grid > 1000 {
            return bad(
                "quality_grid",
                self.quality_grid as f64,
                "must lie in 2..=1000",
            );
        }
        Ok(())
    }
}

/// What the relaxation of step 3 did, over all rounds.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Relaxation {
    /// Visits of points (each a local search to a point where no move lowers the penalty by δ).
    pub visits: usize,
    /// Accepted moves.
    pub moves: usize,
    /// The proven bound on accepted moves: `Σ_rounds P_start / (δ − γ)` (see
    /// [`interior::relax`]).
    pub move_bound: f64,
    /// Total penalty `P` of the paper's initial guess (domain line intersections).
    pub penalty_line_intersections: f64,
    /// `P` before the first relaxation (after the row/column sweeps) and after the last.
    pub penalty_initial: f64,
    pub penalty_final: f64,
    /// Every relaxation stopped because no point could move, not by the move budget.
    pub converged: bool,
}

/// `E_max` and where it occurs — measured at samples, *evidence*, not a bound.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Deviation {
    /// Largest distance from a sample of the new surface R to the given surface S
    /// (closest-point projection).
    pub r_to_s: f64,
    /// Largest distance from a sample of S to R (closest-point projection).
    pub s_to_r: f64,
    /// Largest `|R(ξ,η) − S(φ(ξ,η))|` with φ the bilinear map of the grid cells: at every
    /// sample it is at least both one-sided distances there (see `docs/reparam.md`).
    pub correspondence: f64,
    /// `E_max = max(r_to_s, s_to_r)`: measured, evidence.
    pub e_max: f64,
    /// The proven upper bound of the Hausdorff distance between R and S ([`bound`]), when
    /// its hypotheses hold (`FaceReport::bound` says which were checked, or why not).
    pub e_max_proven: Option<f64>,
    /// `(ξ, η)` of the worst sample.
    pub worst: [f64; 2],
    /// Number of samples.
    pub samples: usize,
}

/// The result for one surface.
#[derive(Clone, Debug)]
pub struct Reparametrized {
    /// The chord-length parametrized bicubic on `[0,1]²`.
    pub surface: NurbsSurface<f64, 3>,
    /// The interpolated grid: parameters, domain points in S, points in space.
    pub grid: interior::Grid,
    pub report: FaceReport,
}

/// The report for one surface.
#[derive(Clone, Debug, Serialize)]
pub struct FaceReport {
    /// Boundary curves `v = v0`, `v = v1`, `u = u0`, `u = u1`: arc length and the number of
    /// interpolation points chosen in step 1 (0 for a border that is a point).
    pub boundary_lengths: [f64; 4],
    pub boundary_points: [usize; 4],
    /// Borders that collapse to points (poles), same order.
    pub poles: [bool; 4],
    /// Opposite borders coincide (closed surface; handled as an open patch, see docs).
    pub closed_u: bool,
    pub closed_v: bool,
    /// Parameter lines `ξ_i`, `η_j` after step 2 and after refinement.
    pub lines_initial: [usize; 2],
    pub lines_final: [usize; 2],
    /// The final grid lines' parameters on the new surface: `R(ξ_i, η_j)` interpolates the
    /// grid point `Q_ij` (chord-length fractions in `[0, 1]`).
    pub xi: Vec<f64>,
    pub eta: Vec<f64>,
    /// Lines inserted by the `E_max` refinement and its rounds.
    pub lines_inserted: usize,
    pub rounds: usize,
    pub relaxation: Relaxation,
    pub deviation: Deviation,
    /// The proven bound's details (`None` when [`Params::prove_bound`] is off).
    pub bound: Option<bound::ProvenBound>,
    /// What decided ε: `"proven"` (a proven bound ≤ ε) or `"evidence"` (no proven bound,
    /// or one above ε: the sampled `E_max` alone, which is not a proof).
    pub decided_by: &'static str,
    /// The relaxation converged and `E_max ≤ ε`: proven (`within_tol_proven`) or at the
    /// samples only (`decided_by = "evidence"`).
    pub within_tol: bool,
    /// The relaxation converged and a proven bound ≤ ε exists.
    pub within_tol_proven: bool,
    pub control_points_before: [usize; 2],
    pub control_points_after: [usize; 2],
    pub rational_before: bool,
    pub spacing_before: quality::Spacing,
    pub spacing_after: quality::Spacing,
    pub seconds: f64,
}

/// Progress callback: a stage name and a count.
pub type Progress<'a> = &'a mut dyn FnMut(&str, usize);

/// Reparametrize `s` to chord length within `params.tol` (§2, steps 1–4).
pub fn reparametrize(
    s: &NurbsSurface<f64, 3>,
    params: &Params,
) -> Result<Reparametrized, ReparamError> {
    reparametrize_with_progress(s, params, &mut |_, _| {})
}

/// [`reparametrize`] reporting each refinement round to `progress`.
pub fn reparametrize_with_progress(
    s: &NurbsSurface<f64, 3>,
    params: &Params,
    progress: Progress,
) -> Result<Reparametrized, ReparamError> {
    params.validate()?;
    let t0 = std::time::Instant::now();
    let closure = crate::spline::closure::Closure::of(s);
    // Step 1: the four boundary curves.
    let sides = boundary::Side::ALL.map(|side| boundary::BoundaryCurve::new(s, side, &closure));
    let sides: [boundary::BoundaryCurve; 4] = {
        let [a, b, c, d] = sides;
        [a?, b?, c?, d?]
    };
    let fractions: Vec<Option<Vec<f64>>> = sides
        .iter()
        .map(|c| (!c.pole).then(|| c.interpolation_fractions(params)))
        .collect();
    // Step 2: reconcile v = v0 with v = v1 (→ ξ) and u = u0 with u = u1 (→ η).
    let xi = reconcile::reconcile(
        fractions[0].as_deref(),
        fractions[1].as_deref(),
        params.merge,
    )
    .ok_or(ReparamError::Collapsed("v (the borders v = v0 and v = v1)"))?;
    let eta = reconcile::reconcile(
        fractions[2].as_deref(),
        fractions[3].as_deref(),
        params.merge,
    )
    .ok_or(ReparamError::Collapsed("u (the borders u = u0 and u = u1)"))?;
    let lines_initial = [xi.len(), eta.len()];
    // Step 3: interior points.
    let mut grid = interior::Grid::initial(s, &sides, xi, eta)?;
    let mut relaxation = Relaxation {
        converged: true,
        penalty_line_intersections: grid.total_penalty(),
        ..Default::default()
    };
    redistribute::redistribute(s, &mut grid, params.sweeps)?;
    let all: Vec<(usize, usize)> = grid.interior_points().collect();
    let r = interior::relax(s, &mut grid, &all, params)?;
    progress("relaxation moves", r.moves);
    relaxation.penalty_initial = r.penalty_start;
    relaxation.add(&r);
    // Step 4: interpolate, measure, insert lines until E_max ≤ ε.
    let mut rounds = 0;
    let mut inserted = 0;
    let mut bound_rounds = 0;
    let prove = |rs: &NurbsSurface<f64, 3>, grid: &interior::Grid, e: f64| {
        params.prove_bound.then(|| {
            let target = bound::target(e, params.tol, params.bound_ratio);
            bound::prove(s, rs, grid, target, params.bound_boxes)
        })
    };
    let (surface, mut deviation, proven) = loop {
        let rs = surface::interpolate(&grid)?;
        let (dev, mut lines) = error::measure(s, &rs, &grid, params);
        rounds += 1;
        progress("E_max round", rounds);
        let full = inserted >= params.max_lines;
        if dev.e_max <= params.tol {
            let pb = prove(&rs, &grid, dev.e_max);
            let over = pb
                .as_ref()
                .and_then(|b| b.e_max_proven)
                .is_some_and(|b| b > params.tol);
            if !over || full || bound_rounds >= params.bound_rounds {
                break (rs, dev, pb);
            }
            // The proof exceeds ε where the samples do not: lines at its worst boxes.
            bound_rounds += 1;
            lines = pb.map_or(vec![], |b| bound::lines_over(&b, &grid, params.tol));
            if lines.is_empty() {
                let pb = prove(&rs, &grid, dev.e_max);
                break (rs, dev, pb);
            }
        } else if full || lines.is_empty() {
            let pb = prove(&rs, &grid, dev.e_max);
            break (rs, dev, pb);
        }
        let room = params.max_lines - inserted;
        let lines = error::limit(lines, room);
        inserted += lines.len();
        grid.insert_lines(s, &sides, &lines)?;
        redistribute::redistribute(s, &mut grid, params.sweeps)?;
        let all: Vec<(usize, usize)> = grid.interior_points().collect();
        let r = interior::relax(s, &mut grid, &all, params)?;
        progress("relaxation moves", r.moves);
        relaxation.add(&r);
    };
    relaxation.penalty_final = grid.total_penalty();
    deviation.e_max_proven = proven.as_ref().and_then(|b| b.e_max_proven);
    // A proven bound ≤ ε decides; otherwise the samples do, and the report says so
    // (`decided_by`, `within_tol_proven`, the bound's value and reason).
    let proven_ok = deviation.e_max_proven.is_some_and(|b| b <= params.tol);
    let decided_by = if proven_ok { "proven" } else { "evidence" };
    let within_tol = (proven_ok || deviation.e_max <= params.tol) && relaxation.converged;
    let within_tol_proven = proven_ok && relaxation.converged;
    let h = &s.hom;
    let report = FaceReport {
        boundary_lengths: sides.each_ref().map(|c| c.length),
        boundary_points: [0, 1, 2, 3].map(|k| fractions[k].as_ref().map_or(0, |f| f.len())),
        poles: sides.each_ref().map(|c| c.pole),
        closed_u: closure.seam_u,
        closed_v: closure.seam_v,
        lines_initial,
        lines_final: [grid.xi.len(), grid.eta.len()],
        xi: grid.xi.clone(),
        eta: grid.eta.clone(),
        lines_inserted: inserted,
        rounds,
        relaxation,
        deviation,
        bound: proven,
        decided_by,
        within_tol,
        within_tol_proven,
        control_points_before: [h.nu(), h.nv()],
        control_points_after: [surface.hom.nu(), surface.hom.nv()],
        rational_before: !s.is_polynomial(),
        spacing_before: quality::spacing(s, params.quality_grid),
        spacing_after: quality::spacing(&surface, params.quality_grid),
        seconds: t0.elapsed().as_secs_f64(),
    };
    Ok(Reparametrized {
        surface,
        grid,
        report,
    })
}

impl Relaxation {
    fn add(&mut self, r: &interior::RelaxStats) {
        self.visits += r.visits;
        self.moves += r.moves;
        self.move_bound += r.move_bound;
        self.converged &= r.converged;
    }
}
