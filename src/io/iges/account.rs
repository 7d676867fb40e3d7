//! The IGES reader's account of its geometric entities ([`crate::model::Accounting`]): every
//! surface and face entity (128, 120, 122, 108, 114, 118, 140, 143, 144, 190–198, 510) and
//! every curve entity (100, 102, 104, 110, 112, 126, 130), each with one outcome. Kinds are
//! named by entity type number (`"128"`).

use super::Entry;
use crate::model::{Accounting, Outcome};
use std::collections::BTreeMap;

/// Surface and face entity types accounted.
const SURFACES: [i64; 15] = [
    108, 114, 118, 120, 122, 128, 140, 143, 144, 190, 192, 194, 196, 198, 510,
];
/// Curve entity types accounted.
const CURVES: [i64; 7] = [100, 102, 104, 110, 112, 126, 130];

/// Note for an unsupported surface or face.
pub(super) const NOT_CONVERTED: &str = "surface type (or its generatrix or axis) not converted";

/// Whether directory entry `x` is physically or logically dependent (its subordinate entity
/// switch, digits 3–4 of the right-aligned eight-digit status field, is not `00`): part of
/// another entity.
fn dependent(x: &Entry) -> bool {
    let s = format!("{:0>8}", x.status.trim().replace(' ', "0"));
    s.get(2..4).is_some_and(|d| d != "00")
}

/// The account of a file. `outcomes` holds what the reader decided for the entries it
/// visited (faces, their surfaces, untrimmed surfaces, free 126 curves). Every other entry
/// of an accounted type is `used` when it is dependent (its subordinate switch is set) or
/// is the model-space curve of a 504 edge, otherwise unsupported (an independent entity the
/// reader does not convert).
pub(super) fn account(
    e: &BTreeMap<usize, Entry>,
    outcomes: &BTreeMap<usize, Outcome>,
) -> Accounting {
    let mut edge_curves = std::collections::BTreeSet::new();
    for x in e.values().filter(|x| x.etype == 504) {
        // 504: N, then per edge CURV, SVP, SV, TVP, TV.
        let n = x.params.get(1).and_then(|p| p.num()).unwrap_or(0.0);
        let n = if n.is_finite() && n > 0.0 {
            n as usize
        } else {
            0
        };
        for k in 0..n.min(x.params.len()) {
            if let Some(c) = x.params.get(2 + 5 * k).and_then(|p| p.num())
                && c >= 1.0
                && c.is_finite()
            {
                edge_curves.insert(c as usize);
            }
        }
    }
    let mut acc = Accounting::default();
    for (de, x) in e {
        if !SURFACES.contains(&x.etype) && !CURVES.contains(&x.etype) {
            continue;
        }
        let outcome = match outcomes.get(de) {
            Some(o) => o.clone(),
            None if dependent(x) || edge_curves.contains(de) => Outcome::Used,
            None => {
                Outcome::Unsupported("independent entity of a type not converted on its own".into())
            }
        };
        acc.record(&x.etype.to_string(), format!("DE {de}"), outcome);
    }
    acc
}
