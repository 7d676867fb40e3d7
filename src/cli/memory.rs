//! `--max-memory <MB>`: the memory budget of one job ([`crate::budget::MemoryBudget`]).
//! The heap in use comes from a probe the program registers ([`set_memory_probe`]; the
//! `vericad` binary counts its heap with a counting global allocator). `ssi` and
//! `certify-ssi` consult the budget at the pipeline's cooperative checkpoints (the cancel
//! and time-limit checks) and stop there; `repair`, `curve-on-surface`, `reparam`, `coons`,
//! `approximate`, `convert` and `info`, which have no checkpoints, are watched from a second thread every few milliseconds and the command ends
//! with the same error (outputs are written atomically, so none is left half-written). The
//! error is `budget exhausted: memory (limit X MB, in use Y MB) at <step>`, exit code 1 (a
//! computation budget, like curve-on-surface's segment budget). 1 MB = 10⁶ bytes.

use crate::budget::{MemoryBudget, MemoryProbe};
use std::sync::{Arc, OnceLock};

static PROBE: OnceLock<fn() -> usize> = OnceLock::new();

/// `--max-memory MB`, for the commands without checkpoints (flattened into their arguments).
#[derive(clap::Args, Debug, Default)]
pub struct MemoryArg {
    /// Memory budget in megabytes (10⁶ bytes) of heap: past it the job stops with
    /// `budget exhausted: memory ...` and exit code 1.
    #[arg(long, allow_hyphen_values = true)]
    pub max_memory: Option<f64>,
}

impl MemoryArg {
    /// Start watching the budget for the job `step` (nothing without the option); `Err` is
    /// the message of a limit that cannot be had (bad input).
    pub(super) fn watch(&self, step: &str) -> Result<(), String> {
        let b = budget(self.max_memory)?;
        watch(&b, step);
        Ok(())
    }
}

/// Register the function that returns the heap in use, in bytes (once, at start).
pub fn set_memory_probe(probe: fn() -> usize) {
    let _ = PROBE.set(probe);
}

/// The budget `--max-memory MB` asks for (`None` without the option), or why it cannot be
/// had: a limit that is not a positive finite number, or no probe registered.
pub(super) fn budget(max_memory: Option<f64>) -> Result<Option<Arc<MemoryBudget>>, String> {
    let Some(mb) = max_memory else {
        return Ok(None);
    };
    if !(mb.is_finite() && mb > 0.0 && mb * 1e6 < usize::MAX as f64) {
        return Err(format!(
            "--max-memory must be a positive number of megabytes, not {mb}"
        ));
    }
    let Some(probe) = PROBE.get().copied() else {
        return Err(
            "--max-memory needs a memory probe, which this program does not register".into(),
        );
    };
    let probe: Arc<MemoryProbe> = Arc::new(probe);
    Ok(Some(MemoryBudget::new((mb * 1e6) as usize, probe)))
}

/// Watch `budget` from a second thread while a job without checkpoints runs: past the
/// limit, print the error and end the process with exit code 1.
pub(super) fn watch(budget: &Option<Arc<MemoryBudget>>, step: &str) {
    let Some(b) = budget.clone() else {
        return;
    };
    b.enter(step);
    std::thread::spawn(move || {
        loop {
            if b.check() {
                if let Some(e) = b.exhausted() {
                    eprintln!("error: {e}");
                }
                std::process::exit(super::EXIT_FAILURE);
            }
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
    });
}

/// The exit code and message when `budget` ran out during a job that returned: `Some(1)`
/// after printing the error, `None` when it did not run out.
pub(super) fn exhausted(budget: &Option<Arc<MemoryBudget>>) -> Option<i32> {
    let e = budget.as_ref()?.exhausted()?;
    eprintln!("error: {e}");
    Some(super::EXIT_FAILURE)
}
