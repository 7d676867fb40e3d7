//! The IGES reader's account of every directory entry ([`crate::model::Accounting`]), each
//! with one outcome. Kinds are named by entity type number (`"128"`).
//!
//! - Entries the reader visited keep its outcome (faces, their surfaces, untrimmed surfaces,
//!   free 126 curves).
//! - Annotations and structure entities (colour definition 314, property 406, associativity
//!   402, line font 304, text template 312, general note 212, views and drawings 404/410,
//!   subfigures 308/408, null 0, …): not geometry and not carried into the model, so they are
//!   `unsupported` with a note saying so, whatever their status — a colour read is a colour
//!   lost, and the account says it.
//! - A transformation matrix (124) is `used` when an entry's directory field 7 points to it
//!   (the reader applies it to that entry).
//! - Any other entry is `used` when it is dependent (its subordinate switch is set: part of
//!   another entity, which has its own account), the model-space curve of a 504 edge, or a
//!   topology entity (502, 504, 508, 514, 186) of a file whose B-rep was built; otherwise it
//!   is an independent entity of a type the reader does not convert on its own:
//!   `unsupported`, with its id.
//! - A directory entry without parameter data is `invalid`, with its id.

use super::Entry;
use crate::model::{Accounting, Outcome};
use std::collections::{BTreeMap, BTreeSet};

/// Note for an unsupported surface or face.
pub(super) const NOT_CONVERTED: &str = "surface type (or its generatrix or axis) not converted";

/// Whether type `t` is not geometry: the null entity (0), an annotation entity (202–230)
/// or a structure entity (302–422: definitions, colours, properties, associativities,
/// views, drawings, subfigures) — IGES 5.3 chapter 4's numbering of the entity classes.
fn attribute(t: i64) -> bool {
    t == 0 || (200..500).contains(&t)
}

/// Topology entity types, read as the B-rep's vertices, edges, loops, shells and solids.
const TOPOLOGY: [i64; 5] = [186, 502, 504, 508, 514];

/// What an attribute type is, for its note.
fn attribute_note(t: i64) -> String {
    let what = match t {
        0 => "null entity",
        212 => "general note",
        314 => "colour definition",
        402 => "associativity instance",
        406 => "property",
        304 => "line font definition",
        308 => "subfigure definition",
        312 => "text display template",
        404 => "drawing",
        408 => "subfigure instance",
        410 => "view",
        200..300 => "annotation",
        _ => "structure entity",
    };
    format!("{what} (type {t}): not geometry, not carried into the model")
}

/// The model-space curves of 504 edge lists: per edge `CURV, SVP, SV, TVP, TV` after the
/// count `N` (IGES 5.3 §4.148).
fn edge_curves(e: &BTreeMap<usize, Entry>) -> BTreeSet<usize> {
    let mut out = BTreeSet::new();
    for x in e.values().filter(|x| x.etype == 504) {
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
                out.insert(c as usize);
            }
        }
    }
    out
}

/// The account of a file. `outcomes` holds what the reader decided for the entries it
/// visited; `brep`: whether the model's B-rep was read from the file's topology entities;
/// `no_params`: the `(DE, type)` of directory entries without parameter data (invalid).
pub(super) fn account(
    e: &BTreeMap<usize, Entry>,
    outcomes: &BTreeMap<usize, Outcome>,
    brep: bool,
    no_params: &[(usize, i64)],
) -> Accounting {
    let edge_curves = edge_curves(e);
    let transforms: BTreeSet<usize> = e.values().map(|x| x.transform).collect();
    let mut acc = Accounting::default();
    for (de, x) in e {
        let t = x.etype;
        let outcome = match outcomes.get(de) {
            Some(o) => o.clone(),
            None if attribute(t) => Outcome::Unsupported(attribute_note(t)),
            None if t == 124 && transforms.contains(de) => Outcome::Used,
            None if t == 124 => {
                Outcome::Unsupported("transformation matrix no entry refers to".into())
            }
            None if x.dependent() || edge_curves.contains(de) => Outcome::Used,
            None if brep && TOPOLOGY.contains(&t) => Outcome::Used,
            None => {
                Outcome::Unsupported("independent entity of a type not converted on its own".into())
            }
        };
        acc.record(&t.to_string(), format!("DE {de}"), outcome);
    }
    for (de, t) in no_params {
        let why = "no parameter data (no parameter line points to this directory entry)";
        acc.record(
            &t.to_string(),
            format!("DE {de}"),
            Outcome::Invalid(why.into()),
        );
    }
    acc
}
