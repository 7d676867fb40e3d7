//! The memory budget of a job: a limit in bytes and a probe that says how many bytes are in
//! use (the `vericad` binary counts its heap with a counting global allocator; the library
//! installs none). Long computations consult it at their cooperative checkpoints (the same
//! places that check a cancel flag or a time limit, [`crate::ssi::control`]); the first
//! checkpoint that finds the heap over the limit records where, and the job stops with the
//! typed [`MemoryExhausted`] error naming the budget, the limit, the use and the step.
//!
//! The figure is the live heap the probe reports, sampled at checkpoints: the job stops at
//! the first checkpoint past the limit, so the peak may exceed the limit by what one step
//! allocates between two checkpoints.

use std::sync::{Arc, Mutex, OnceLock};

/// Largest number of worker threads a job accepts (`--threads`, the Python `threads=`): each
/// worker has its own stack.
pub const MAX_THREADS: usize = 1024;

/// Bytes of heap in use, as the probe of the running program counts them.
pub type MemoryProbe = dyn Fn() -> usize + Send + Sync;

/// A job's memory ran past its budget.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "budget exhausted: memory (limit {} MB, in use {} MB) at {step}",
    mb(*limit),
    mb(*in_use)
)]
pub struct MemoryExhausted {
    /// The limit, bytes.
    pub limit: usize,
    /// Heap in use when the checkpoint found the limit passed, bytes.
    pub in_use: usize,
    /// The step running (the last step a checkpoint reported).
    pub step: String,
}

/// Bytes as megabytes (10⁶ bytes), one decimal.
fn mb(bytes: usize) -> String {
    format!("{:.1}", bytes as f64 / 1e6)
}

/// A limit, the probe, the step last reported and, once passed, where.
pub struct MemoryBudget {
    limit: usize,
    probe: Arc<MemoryProbe>,
    step: Mutex<String>,
    exhausted: OnceLock<MemoryExhausted>,
}

impl std::fmt::Debug for MemoryBudget {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("MemoryBudget")
            .field("limit", &self.limit)
            .field("exhausted", &self.exhausted.get())
            .finish()
    }
}

impl MemoryBudget {
    /// A budget of `limit` bytes measured by `probe`.
    pub fn new(limit: usize, probe: Arc<MemoryProbe>) -> Arc<MemoryBudget> {
        Arc::new(MemoryBudget {
            limit,
            probe,
            step: Mutex::new("start".into()),
            exhausted: OnceLock::new(),
        })
    }
    /// The limit, bytes.
    pub fn limit(&self) -> usize {
        self.limit
    }
    /// Heap in use now, bytes.
    pub fn in_use(&self) -> usize {
        (self.probe)()
    }
    /// Name the step now running (reported in the error if the budget runs out in it).
    pub fn enter(&self, step: impl Into<String>) {
        if let Ok(mut s) = self.step.lock() {
            *s = step.into();
        }
    }
    /// A checkpoint: whether the budget is exhausted (now, or at an earlier checkpoint). The
    /// first checkpoint over the limit records the use and the step.
    pub fn check(&self) -> bool {
        if self.exhausted.get().is_some() {
            return true;
        }
        let in_use = self.in_use();
        if in_use <= self.limit {
            return false;
        }
        let step = self.step.lock().map_or_else(|_| "?".into(), |s| s.clone());
        let _ = self.exhausted.set(MemoryExhausted {
            limit: self.limit,
            in_use,
            step,
        });
        true
    }
    /// Where the budget ran out, if it did.
    pub fn exhausted(&self) -> Option<&MemoryExhausted> {
        self.exhausted.get()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    #[test]
    fn the_first_checkpoint_past_the_limit_is_recorded() {
        let use_ = Arc::new(AtomicUsize::new(1_000_000));
        let u = use_.clone();
        let b = MemoryBudget::new(2_000_000, Arc::new(move || u.load(Ordering::Relaxed)));
        b.enter("triangulate");
        assert!(!b.check());
        use_.store(2_500_000, Ordering::Relaxed);
        b.enter("refine branches");
        assert!(b.check());
        use_.store(9_000_000, Ordering::Relaxed);
        b.enter("coverage");
        assert!(b.check());
        let e = b.exhausted().unwrap();
        assert_eq!((e.in_use, e.step.as_str()), (2_500_000, "refine branches"));
        assert_eq!(
            e.to_string(),
            "budget exhausted: memory (limit 2.0 MB, in use 2.5 MB) at refine branches"
        );
    }
}
