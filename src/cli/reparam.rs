//! `vericad reparam`: arguments, the call into [`crate::reparam::job`], the summary.

use std::path::PathBuf;

/// Arguments of `vericad reparam`.
#[derive(clap::Args, Debug)]
pub struct ReparamArgs {
    /// Model file, optionally `:FACE` (default: every face).
    pub model: String,
    /// ε: largest deviation E_max between the new and the given surface (model units).
    #[arg(long, default_value_t = 1e-4, allow_hyphen_values = true)]
    pub tol: f64,
    /// The new surfaces (format from the extension: .igs, .step, .json).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// JSON report.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// SVG: a uniform parameter grid on the given and the new surface, side by side.
    #[arg(long)]
    pub svg: Option<PathBuf>,
    /// VTK PolyData (.vtp): both surfaces and grids, with spacing ratios.
    #[arg(long)]
    pub vtk: Option<PathBuf>,
    /// Most parameter lines inserted per face.
    #[arg(long, default_value_t = 500, allow_hyphen_values = true)]
    pub max_lines: usize,
    /// Skip the proven deviation bound (costly on curved faces): the measured E_max decides.
    #[arg(long)]
    pub no_bound: bool,
    #[command(flatten)]
    pub memory: super::memory::MemoryArg,
    /// Print the result as JSON instead of the human summary.
    #[arg(long)]
    pub json: bool,
}

/// Run the command; returns the exit code (0 every face within tol, 3 some face not, 2 bad
/// input, 1 failure).
pub fn run(a: ReparamArgs) -> i32 {
    if let Err(e) = a.memory.watch("reparam") {
        return super::bad(e);
    }
    let params = crate::reparam::Params {
        tol: a.tol,
        max_lines: a.max_lines,
        prove_bound: !a.no_bound,
        ..Default::default()
    };
    let outputs = crate::reparam::job::Outputs {
        progress: crate::progress::Progress::stderr(),
        model: a.out.as_deref(),
        report: a.report.as_deref(),
        svg: a.svg.as_deref(),
        vtk: a.vtk.as_deref(),
    };
    super::output::finish_checked(
        crate::reparam::job::run(&a.model, &params, outputs),
        a.json,
        |r| r.within_tol,
        |e| e.is_bad_input(),
    )
}
