//! The STEP reader's account of its geometric entities ([`crate::model::Accounting`]):
//! every surface instance (the kinds the reader converts and the ones it recognises but does
//! not) and every `B_SPLINE_CURVE_WITH_KNOTS`, each with one outcome.

use super::part21::Part21;
use super::{SURFACE_TYPES, UNSUPPORTED_SURFACES};
use crate::model::{Accounting, Outcome};
use std::collections::{BTreeMap, BTreeSet};

/// Surface kinds accounted besides [`SURFACE_TYPES`] and [`UNSUPPORTED_SURFACES`].
const OTHER_SURFACES: [&str; 2] = ["SURFACE_REPLICA", "ORIENTED_SURFACE"];

/// The free-curve kind the reader converts.
pub(super) const CURVE: &str = "B_SPLINE_CURVE_WITH_KNOTS";

/// Note for an unsupported instance of a kind the reader does not convert.
pub(super) const NOT_CONVERTED: &str = "surface type (or its basis or profile curve) not converted";

/// The account of a file. `outcomes` holds what the reader decided for the instances it
/// visited (face surfaces, bare patch-set surfaces, curves); a visited instance of another
/// kind makes its entity name an accounted kind too. Every other instance of an
/// accounted kind is `used` when another instance references it (its account is the
/// referencing entity's), otherwise unsupported: it is neither a face's surface nor used.
pub(super) fn account(p: &Part21, outcomes: &BTreeMap<u64, Outcome>) -> Accounting {
    let mut kinds: Vec<&str> = SURFACE_TYPES
        .iter()
        .chain(&UNSUPPORTED_SURFACES)
        .chain(&OTHER_SURFACES)
        .copied()
        .chain([CURVE])
        .collect();
    for id in outcomes.keys() {
        if let Some(e) = p.entities.get(id)
            && !kinds.iter().any(|k| e.is(k))
            && !e.name().is_empty()
        {
            kinds.push(e.name());
        }
    }
    let mut referenced = BTreeSet::new();
    for e in p.entities.values() {
        referenced.extend(e.refs());
    }
    let mut acc = Accounting::default();
    for (id, e) in &p.entities {
        let Some(kind) = kinds.iter().find(|k| e.is(k)) else {
            continue;
        };
        let outcome = match outcomes.get(id) {
            Some(o) => o.clone(),
            None if referenced.contains(id) => Outcome::Used,
            None => Outcome::Unsupported("not the surface of a face, not referenced".into()),
        };
        acc.record(kind, format!("#{id}"), outcome);
    }
    acc
}
