//! Cooperative control of a long intersection run: a cancel flag the caller may set from
//! another thread (e.g. a Ctrl-C handler), and progress reports from inside a face pair — a
//! single pair of large faces can run for minutes, so a report per finished pair is not
//! enough. The pipeline checks the flag (and the time limit) between stages and every few
//! thousand items inside the long loops; a stopped pair is returned with what it has,
//! marked incomplete, and the result is marked partial. With a memory budget
//! ([`crate::budget::MemoryBudget`]) the same checks consult the heap in use: past the
//! limit the run stops as if cancelled, and the budget records the step it was in.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

/// Where a face pair's work stands.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Stage {
    /// The faces, in the caller's numbering.
    pub pair: (usize, usize),
    /// The step running: `triangulate`, `tangential points`, `candidate triangle pairs`,
    /// `triangle intersections`, `refine branches`, `coverage`.
    pub step: &'static str,
    /// Items of the step done so far, and in all (0 when not known).
    pub done: usize,
    pub total: usize,
}

/// Receiver of [`Stage`] reports (called from worker threads).
pub type ProgressFn = dyn Fn(&Stage) + Send + Sync;

/// Cancel flag and progress receiver; the default has neither.
#[derive(Clone, Default)]
pub struct Control {
    /// Set it to stop the run: no new pair starts, running pairs stop at their next check.
    pub cancel: Option<Arc<AtomicBool>>,
    /// Receives progress from inside face pairs.
    pub progress: Option<Arc<ProgressFn>>,
    /// Memory budget consulted at every check (the run stops when it is exhausted).
    pub memory: Option<Arc<crate::budget::MemoryBudget>>,
}

impl std::fmt::Debug for Control {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Control")
            .field("cancel", &self.cancel)
            .field("progress", &self.progress.as_ref().map(|_| "fn"))
            .field("memory", &self.memory)
            .finish()
    }
}

impl Control {
    /// A control with a fresh cancel flag, and the flag.
    pub fn cancellable() -> (Control, Arc<AtomicBool>) {
        let flag = Arc::new(AtomicBool::new(false));
        (
            Control {
                cancel: Some(flag.clone()),
                ..Control::default()
            },
            flag,
        )
    }

    /// Cancelled by the flag, or stopped by the memory budget (checked here).
    pub fn cancelled(&self) -> bool {
        self.cancel
            .as_ref()
            .is_some_and(|c| c.load(Ordering::Relaxed))
            || self.memory.as_ref().is_some_and(|m| m.check())
    }

    /// Cancelled, or past `deadline`.
    pub fn stop(&self, deadline: Option<Instant>) -> bool {
        self.cancelled() || deadline.is_some_and(|d| Instant::now() > d)
    }

    pub fn report(&self, pair: (usize, usize), step: &'static str, done: usize, total: usize) {
        if let Some(m) = &self.memory {
            m.enter(format!("faces ({}, {}): {step}", pair.0, pair.1));
        }
        if let Some(p) = &self.progress {
            p(&Stage {
                pair,
                step,
                done,
                total,
            });
        }
    }
}

/// Items between two checks of the flag and the clock inside a long loop.
pub const CHECK_EVERY: usize = 4096;
