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
    #[command(flatten)]
    pub params: super::coons::ParamArgs,
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
    #[command(flatten)]
    pub memory: super::memory::MemoryArg,
    /// Print the report as JSON.
    #[arg(long)]
    pub json: bool,
}

/// Run the command; returns the exit code (0 all within tol, 3 some not, 2 bad input, 1
/// failure).
pub fn run(a: ApproximateArgs) -> i32 {
    let params = match a.params.params() {
        Ok(p) => p,
        Err(e) => return super::bad(e),
    };
    if let Err(e) = a.memory.watch("approximate") {
        return super::bad(e);
    }
    let outputs = crate::approx::coons::layout_job::Outputs {
        progress: crate::progress::Progress::stderr(),
        model: a.out.as_deref(),
        report: a.report.as_deref(),
        vtk: a.vtk.as_deref(),
    };
    super::output::finish_checked(
        crate::approx::coons::layout_job::run(&a.model, &a.layout, &params, outputs)
            .map(|r| r.report),
        a.json,
        |r| r.within_tol,
        |e| e.is_bad_input(),
    )
}
