//! The reader's account of the entities it reads (STEP: every surface and curve instance;
//! IGES: every directory entry, attributes such as colours included): per source entity
//! kind (`B_SPLINE_SURFACE_WITH_KNOTS`, `LINE`, IGES `128`, `314`, ...) how many instances
//! the file holds (`read`) and what became of each one:
//!
//! - `converted`: became a model surface or curve;
//! - `used`: consumed as part of something else (the basis surface of a trimmed surface,
//!   the surface of a face, the curve of an edge, a boundary or generatrix curve, the
//!   transformation matrix an entry points to), counted without ids;
//! - `unsupported`: not turned into model geometry because the reader does not handle it
//!   (ids and a note);
//! - `invalid`: refused for a fault in its data (ids and the reason).
//!
//! Invariant, per kind: `read == converted + used + unsupported + invalid`
//! ([`Accounting::check`]). Readers record one [`Outcome`] per instance, so nothing read is
//! dropped without a line.

use serde::Serialize;
use std::collections::BTreeMap;

/// One instance that did not become model geometry: its id and why.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Skipped {
    /// Source id: `"#123"` (STEP instance) or `"DE 45"` (IGES directory entry).
    pub id: String,
    /// Why it was skipped (the kind's note for unsupported ones, the fault for invalid ones).
    pub reason: String,
}

/// The account of one source entity kind.
#[derive(Clone, Debug, PartialEq, Eq, Default, Serialize)]
pub struct KindAccount {
    /// Instances of this kind in the file.
    pub read: usize,
    /// Instances that became model surfaces or curves.
    pub converted: usize,
    /// Instances consumed as part of another entity (which has its own account).
    pub used: usize,
    /// Instances the reader does not convert.
    pub unsupported: Vec<Skipped>,
    /// Instances refused for a fault in their data.
    pub invalid: Vec<Skipped>,
}

impl KindAccount {
    /// `converted + used + unsupported + invalid`: what the reader says became of the
    /// instances (equal to `read` when the account is balanced).
    pub fn accounted(&self) -> usize {
        self.converted + self.used + self.unsupported.len() + self.invalid.len()
    }
}

/// What became of one instance.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Outcome {
    Converted,
    Used,
    /// Not handled by the reader (with a note).
    Unsupported(String),
    /// Refused for a fault (with the reason).
    Invalid(String),
}

/// The accounts of a file, by source entity kind (empty for models not read from STEP or
/// IGES).
#[derive(Clone, Debug, PartialEq, Eq, Default, Serialize)]
pub struct Accounting {
    pub kinds: BTreeMap<String, KindAccount>,
}

/// An account whose parts do not add up to what was read.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "entity kind {kind}: read {read}, accounted {accounted} (converted + used + unsupported + invalid)"
)]
pub struct Unbalanced {
    pub kind: String,
    pub read: usize,
    pub accounted: usize,
}

impl Accounting {
    /// Record one instance of `kind` with id `id`, read from the file, and its outcome.
    pub fn record(&mut self, kind: &str, id: String, outcome: Outcome) {
        let a = self.kinds.entry(kind.to_string()).or_default();
        a.read += 1;
        match outcome {
            Outcome::Converted => a.converted += 1,
            Outcome::Used => a.used += 1,
            Outcome::Unsupported(reason) => a.unsupported.push(Skipped { id, reason }),
            Outcome::Invalid(reason) => a.invalid.push(Skipped { id, reason }),
        }
    }
    /// Whether no entity was accounted.
    pub fn is_empty(&self) -> bool {
        self.kinds.is_empty()
    }
    /// The invariant `read == converted + used + unsupported + invalid` for every kind; the
    /// first kind that breaks it otherwise.
    pub fn check(&self) -> Result<(), Unbalanced> {
        for (k, a) in &self.kinds {
            if a.read != a.accounted() {
                return Err(Unbalanced {
                    kind: k.clone(),
                    read: a.read,
                    accounted: a.accounted(),
                });
            }
        }
        Ok(())
    }
    /// The sums over all kinds.
    pub fn total(&self) -> KindAccount {
        let mut t = KindAccount::default();
        for a in self.kinds.values() {
            t.read += a.read;
            t.converted += a.converted;
            t.used += a.used;
            t.unsupported.extend(a.unsupported.iter().cloned());
            t.invalid.extend(a.invalid.iter().cloned());
        }
        t
    }
    /// Readable lines: one per kind with unsupported or invalid instances (ids listed, at
    /// most a few), then the total line.
    pub fn lines(&self) -> Vec<String> {
        let mut out = Vec::new();
        let ids = |v: &[Skipped]| super::list_ids(v.iter().map(|s| s.id.clone()));
        for (k, a) in &self.kinds {
            if a.unsupported.is_empty() && a.invalid.is_empty() {
                continue;
            }
            let mut l = format!(
                "{k}: read {}, converted {}, used {}",
                a.read, a.converted, a.used
            );
            if !a.unsupported.is_empty() {
                l += &format!(
                    ", unsupported {} ({})",
                    a.unsupported.len(),
                    ids(&a.unsupported)
                );
            }
            if !a.invalid.is_empty() {
                l += &format!(", invalid {} ({})", a.invalid.len(), ids(&a.invalid));
            }
            out.push(l);
        }
        if !self.kinds.is_empty() {
            let t = self.total();
            out.push(format!(
                "total: {} entities of {} kind(s) read, {} converted, {} used, {} unsupported, {} invalid",
                t.read,
                self.kinds.len(),
                t.converted,
                t.used,
                t.unsupported.len(),
                t.invalid.len()
            ));
        }
        out
    }
}
