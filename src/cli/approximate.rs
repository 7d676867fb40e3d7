//! `vericad approximate`: arguments, the call into
//! [`crate::approx::coons::layout_job`], the summary.

use std::path::PathBuf;

/// Arguments of `vericad approximate`.
#[derive(clap::Args, Debug)]
pub struct ApproximateArgs {
    /// Model file with the original surfaces (.json, .step/.stp, .igs/.iges).
    pub model: PathBuf,
    /// Layout file: boundary curves by id and the approximants, each naming its four sides
    /// by curve id (docs/coons.md, "Many approximants").
    #[arg(long)]
    pub layout: PathBuf,
    /// Largest deviation accepted at the error samples (model units).
    #[arg(long, default_value_t = 1e-3, allow_hyphen_values = true)]
    pub tol: f64,
    /// Initial resolution M of every approximant (unless the layout gives one).
    #[arg(long, default_value_t = 8, allow_hyphen_values = true)]
    pub m: i64,
    /// Initial resolution N of every approximant (unless the layout gives one).
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
    /// All approximants in one file (format from the extension: .igs, .step, .json).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// JSON report: per approximant M × N, measured error, reason; per shared curve the
    /// gap, the move, bit-identity.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// VTK PolyData (.vtp) of all approximants.
    #[arg(long)]
    pub vtk: Option<PathBuf>,
    /// Print the report as JSON.
    #[arg(long)]
    pub json: bool,
}

/// Run the command; returns the exit code (0 all within tol, 3 some not, 2 bad input, 1
/// failure).
pub fn run(a: ApproximateArgs) -> i32 {
    let count = |name: &str, v: i64| -> Result<usize, String> {
        if (1..=1024).contains(&v) {
            Ok(v as usize)
        } else {
            Err(format!("--{name} {v}: must lie in 1..=1024"))
        }
    };
    let parsed = (|| {
        Ok::<_, String>((
            count("m", a.m)?,
            count("n", a.n)?,
            count("max-resolution", a.max_resolution)?,
            count("k", a.k)?,
        ))
    })();
    let (m, n, max_resolution, k) = match parsed {
        Ok(v) => v,
        Err(e) => return super::bad(e),
    };
    let params = crate::approx::coons::Params {
        tol: a.tol,
        m,
        n,
        max_resolution,
        closure: a.closure,
        k_nearest: k,
        ..Default::default()
    };
    let outputs = crate::approx::coons::layout_job::Outputs {
        model: a.out.as_deref(),
        report: a.report.as_deref(),
        vtk: a.vtk.as_deref(),
    };
    match crate::approx::coons::layout_job::run(&a.model, &a.layout, &params, outputs) {
        Ok(r) => {
            super::print(&r.report, a.json);
            if r.report.within_tol {
                0
            } else {
                super::EXIT_UNCERTIFIED
            }
        }
        Err(e) if e.is_bad_input() => super::bad(e),
        Err(e) => {
            eprintln!("error: {e}");
            super::EXIT_FAILURE
        }
    }
}
