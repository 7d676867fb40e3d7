//! `vericad batch`: arguments, their checks, the call into [`fn@crate::batch::run`], the summary.

use std::path::PathBuf;

/// Arguments of `vericad batch`.
#[derive(clap::Args, Debug)]
pub struct BatchArgs {
    /// Models: directories (searched recursively for .step/.stp/.igs/.iges/.json/.stl),
    /// files, or `@LIST` (a file with one path per line).
    #[arg(required = true)]
    pub inputs: Vec<String>,
    /// Job run on every model: `info` (counts), `ssi` (one-file intersection, certified or
    /// not) or `repair` (which repair, patches in and out, gaps left).
    #[arg(long)]
    pub job: String,
    /// JSONL output, one record per model, appended as models finish; models it already has
    /// records for are skipped (resume).
    #[arg(long)]
    pub out: PathBuf,
    /// Run only shard I of N (`I/N`): the models whose index in the sorted list is I mod N.
    #[arg(long, allow_hyphen_values = true)]
    pub shard: Option<String>,
    /// Time limit per model in seconds (the `ssi` job stops starting new face pairs and the
    /// record is `timeout`).
    #[arg(long, allow_hyphen_values = true)]
    pub time_limit_per_model: Option<f64>,
    /// Which repair the `repair` job runs: `auto` (the faces repair on a B-rep with trimmed
    /// faces, the patch-set repair otherwise, as `vericad repair`), `patches` or `faces`.
    #[arg(long, default_value = "auto")]
    pub repair_mode: String,
    /// Tolerance of the `ssi` job (model units).
    #[arg(long, default_value_t = 1e-6, allow_hyphen_values = true)]
    pub tol: f64,
    /// Worker threads (default: all cores; at most 1024).
    #[arg(long, allow_hyphen_values = true)]
    pub threads: Option<i64>,
    /// No progress lines on stderr (the summary is still printed).
    #[arg(long)]
    pub quiet: bool,
}

/// Run the command; returns the exit code: 0 every model `ok`, 3 some model not `ok` (see
/// its record), 2 bad arguments or an unreadable inputs list or output, 1 writing the records
/// failed.
pub fn run(a: BatchArgs) -> i32 {
    use crate::batch::{BatchError, Job, Options};
    let threads = match a.threads {
        None => None,
        Some(n) if (1..=super::MAX_THREADS as i64).contains(&n) => Some(n as usize),
        Some(n) => {
            return super::bad(format!(
                "--threads must be in 1..={}, not {n}",
                super::MAX_THREADS
            ));
        }
    };
    if let Some(t) = a.time_limit_per_model
        && !(t.is_finite() && t > 0.0)
    {
        return super::bad(format!(
            "--time-limit-per-model must be a positive number of seconds, not {t}"
        ));
    }
    if !(a.tol.is_finite() && a.tol > 0.0) {
        return super::bad(format!(
            "--tol must be a positive finite number, not {}",
            a.tol
        ));
    }
    let job = match a.job.as_str() {
        "info" => Job::Info,
        "ssi" => Job::Ssi {
            tol: a.tol,
            time_limit: a.time_limit_per_model,
        },
        "repair" => match a.repair_mode.parse() {
            Ok(mode) => Job::Repair(crate::repair::RepairParams::default(), mode),
            Err(e) => return super::bad(format!("--repair-mode: {e}")),
        },
        other => {
            return super::bad(format!(
                "--job must be `info`, `ssi` or `repair`, not `{other}`"
            ));
        }
    };
    let shard = match a.shard.as_deref().map(crate::batch::parse_shard) {
        None => None,
        Some(Ok(s)) => Some(s),
        Some(Err(e)) => return super::bad(e),
    };
    let opts = Options {
        inputs: a.inputs,
        job,
        out: a.out,
        shard,
        threads,
        progress: if a.quiet {
            crate::progress::Progress::default()
        } else {
            crate::progress::Progress::stderr()
        },
    };
    match crate::batch::run(&opts) {
        Ok(s) => {
            eprint!("{s}");
            if s.all_ok() {
                0
            } else {
                super::EXIT_UNCERTIFIED
            }
        }
        Err(e @ BatchError::OutWrite(..)) => {
            eprintln!("error: {e}");
            super::EXIT_FAILURE
        }
        Err(e) => super::bad(e),
    }
}
