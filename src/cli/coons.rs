//! `vericad coons`: arguments, the call into [`crate::approx::coons::job`], the summary.

use std::path::PathBuf;

/// The approximant's parameters, shared by `coons` and `approximate`.
#[derive(clap::Args, Debug)]
pub struct ParamArgs {
    /// Largest deviation accepted at the error samples (model units).
    #[arg(long, default_value_t = 1e-3, allow_hyphen_values = true)]
    pub tol: f64,
    /// Initial resolution M (for `approximate`: of every approximant the layout gives none).
    #[arg(long, default_value_t = 8, allow_hyphen_values = true)]
    pub m: i64,
    /// Initial resolution N (likewise).
    #[arg(long, default_value_t = 8, allow_hyphen_values = true)]
    pub n: i64,
    /// Largest M and N the refinement may reach.
    #[arg(long, default_value_t = 128, allow_hyphen_values = true)]
    pub max_resolution: i64,
    /// How far apart consecutive boundary curves' ends may be (default: tol).
    #[arg(long, allow_hyphen_values = true)]
    pub closure: Option<f64>,
    /// K: known projections per artificial projection.
    #[arg(long, default_value_t = 8, allow_hyphen_values = true)]
    pub k: i64,
}

impl ParamArgs {
    /// The library's parameters; counts must not be negative (the library checks the rest
    /// and names what is wrong).
    pub fn params(&self) -> Result<crate::approx::coons::Params, String> {
        let count = |name: &str, v: i64| -> Result<usize, String> {
            usize::try_from(v).map_err(|_| format!("--{name} {v}: must not be negative"))
        };
        Ok(crate::approx::coons::Params {
            tol: self.tol,
            m: count("m", self.m)?,
            n: count("n", self.n)?,
            max_resolution: count("max-resolution", self.max_resolution)?,
            closure: self.closure,
            k_nearest: count("k", self.k)?,
            ..Default::default()
        })
    }
}

/// Arguments of `vericad coons`.
#[derive(clap::Args, Debug)]
pub struct CoonsArgs {
    /// Model file with the original surfaces (.json, .step/.stp, .igs/.iges).
    pub model: PathBuf,
    /// Boundary file: four curves in loop order, each `{"curve": INDEX or "NAME"}` or
    /// `{"polyline": [[x, y, z], ...]}` (docs/coons.md).
    #[arg(long)]
    pub boundary: PathBuf,
    #[command(flatten)]
    pub params: ParamArgs,
    /// The approximant (format from the extension: .igs, .step, .json).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// JSON report.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// VTK PolyData (.vtp): approximant, projected points (hit / artificial), error samples.
    #[arg(long)]
    pub vtk: Option<PathBuf>,
    #[command(flatten)]
    pub memory: super::memory::MemoryArg,
    /// Print the report as JSON.
    #[arg(long)]
    pub json: bool,
}

/// Run the command; returns the exit code (0 within tol, 3 not within tol or the maximum
/// resolution reached, 2 bad input, 1 failure).
pub fn run(a: CoonsArgs) -> i32 {
    let params = match a.params.params() {
        Ok(p) => p,
        Err(e) => return super::bad(e),
    };
    if let Err(e) = a.memory.watch("coons") {
        return super::bad(e);
    }
    let outputs = crate::approx::coons::job::Outputs {
        progress: crate::progress::Progress::stderr(),
        model: a.out.as_deref(),
        report: a.report.as_deref(),
        vtk: a.vtk.as_deref(),
    };
    super::output::finish_checked(
        crate::approx::coons::job::run(&a.model, &a.boundary, &params, outputs),
        a.json,
        |r| r.approximant.within_tol,
        |e| e.is_bad_input(),
    )
}
