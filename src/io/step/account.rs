//! The STEP reader's account of its geometric entities ([`crate::model::Accounting`]):
//! every surface instance (the kinds the reader converts and the ones it recognises but does
//! not) and every curve instance (ISO 10303-42 §4.4.1 `curve` subtypes: `line`, the conics,
//! `polyline`, the B-spline forms, `trimmed_curve`, `composite_curve`, `pcurve`,
//! `surface_curve` and its subtypes, offset curves, `curve_replica`), each with one outcome.
//!
//! A visited instance keeps the reader's outcome (faces' surfaces, bare patch-set surfaces,
//! `B_SPLINE_CURVE_WITH_KNOTS`, which the reader converts wherever it is). The B-rep
//! reader's report names every edge-geometry instance it refused (unsupported or invalid,
//! with the issue that says why); such an instance gets that outcome. Every other instance
//! is `used` when an entity that consumes geometry references it (an edge, a face, a
//! surface, another curve, the definitional representation of a pcurve); a reference from a
//! set or a presentation entity (a curve set, a shape representation's items, a style, a
//! layer) does not consume it. What is left is a free instance of a kind the reader does not
//! convert: `unsupported`, with its id.

use super::part21::{Inst, Part21};
use super::{SURFACE_TYPES, UNSUPPORTED_SURFACES};
use crate::brep::BrepReport;
use crate::model::{Accounting, Outcome};
use std::collections::BTreeMap;

/// Surface kinds accounted besides [`SURFACE_TYPES`] and [`UNSUPPORTED_SURFACES`].
const OTHER_SURFACES: [&str; 2] = ["SURFACE_REPLICA", "ORIENTED_SURFACE"];

/// The free-curve kind the reader converts.
pub(super) const CURVE: &str = "B_SPLINE_CURVE_WITH_KNOTS";

/// Curve kinds accounted besides [`CURVE`]: the instantiable subtypes of `curve` (ISO
/// 10303-42 §4.4.1–§4.4.36). The abstract supertypes (`curve`, `bounded_curve`, `conic`,
/// `b_spline_curve`) and `rational_b_spline_curve`, which only occur as parts of a complex
/// instance with one of these, are not kinds of their own. A complex instance counts once,
/// under the first kind of this list it holds.
pub(super) const CURVES: [&str; 22] = [
    "BEZIER_CURVE",
    "UNIFORM_CURVE",
    "QUASI_UNIFORM_CURVE",
    "LINE",
    "CIRCLE",
    "ELLIPSE",
    "HYPERBOLA",
    "PARABOLA",
    "POLYLINE",
    "TRIMMED_CURVE",
    "COMPOSITE_CURVE_ON_SURFACE",
    "COMPOSITE_CURVE",
    "COMPOSITE_CURVE_SEGMENT",
    "BOUNDARY_CURVE",
    "OUTER_BOUNDARY_CURVE",
    "SEAM_CURVE",
    "INTERSECTION_CURVE",
    "SURFACE_CURVE",
    "PCURVE",
    "DEGENERATE_PCURVE",
    "OFFSET_CURVE_3D",
    "OFFSET_CURVE_2D",
];

/// Curve kinds a complex instance may also hold that are accounted under their own name.
const MORE_CURVES: [&str; 3] = ["BOUNDED_PCURVE", "BOUNDED_SURFACE_CURVE", "CURVE_REPLICA"];

/// Note for an unsupported instance of a kind the reader does not convert.
pub(super) const NOT_CONVERTED: &str = "surface type (or its basis or profile curve) not converted";

/// Note for a free curve of a kind the reader does not convert.
const FREE_CURVE: &str =
    "free curve (not part of an edge, a surface or another curve) of a kind not converted";

/// Whether a reference from `e` does not consume the referenced geometry: `e` only groups
/// or presents items (a geometric set, the items of a shape representation, a style or a
/// layer assignment). The definitional representation of a pcurve does consume its curve.
fn groups_only(e: Inst) -> bool {
    const GROUPS: [&str; 6] = [
        "GEOMETRIC_CURVE_SET",
        "GEOMETRIC_SET",
        "STYLED_ITEM",
        "OVER_RIDING_STYLED_ITEM",
        "PRESENTATION_LAYER_ASSIGNMENT",
        "MAPPED_ITEM",
    ];
    let n = e.name();
    GROUPS.iter().any(|g| e.is(g))
        || (n.ends_with("REPRESENTATION") && n != "DEFINITIONAL_REPRESENTATION")
        || (n.ends_with("_ASSIGNMENT"))
}

/// What the B-rep report says of `id` when it refused it: unsupported or invalid, with the
/// first issue recorded for it.
fn refused(report: &BrepReport, id: &str) -> Option<Outcome> {
    let why = || {
        report.issues.iter().find(|i| i.entity == id).map_or_else(
            || "refused by the B-rep reader".into(),
            |i| i.kind.to_string(),
        )
    };
    let t = report.entities.values();
    if t.clone().any(|t| t.invalid.iter().any(|x| x == id)) {
        return Some(Outcome::Invalid(why()));
    }
    if t.clone().any(|t| t.unsupported.iter().any(|x| x == id)) {
        return Some(Outcome::Unsupported(why()));
    }
    None
}

/// The account of a file. `outcomes` holds what the reader decided for the instances it
/// visited (face surfaces, bare patch-set surfaces, B-spline curves); a visited instance of
/// another kind makes its entity name an accounted kind too. `report`: the B-rep reader's
/// report, when the file has faces.
pub(super) fn account(
    p: &Part21,
    outcomes: &BTreeMap<u64, Outcome>,
    report: Option<&BrepReport>,
) -> Accounting {
    let mut kinds: Vec<&str> = SURFACE_TYPES
        .iter()
        .chain(&UNSUPPORTED_SURFACES)
        .chain(&OTHER_SURFACES)
        .copied()
        .chain([CURVE])
        .chain(CURVES)
        .chain(MORE_CURVES)
        .collect();
    let n_surfaces = SURFACE_TYPES.len() + UNSUPPORTED_SURFACES.len() + OTHER_SURFACES.len();
    for id in outcomes.keys() {
        if let Some(e) = p.entities.inst(*id)
            && !kinds.iter().any(|k| e.is(k))
            && !e.name().is_empty()
        {
            kinds.push(e.name());
        }
    }
    // Per instance (in table order), whether a reference consumes it.
    let mut consumed = vec![false; p.entities.len()];
    for (_, e) in p.entities.insts().filter(|(_, e)| !groups_only(*e)) {
        for i in e.refs().into_iter().filter_map(|r| p.entities.index_of(r)) {
            consumed[i] = true;
        }
    }
    let mut acc = Accounting::default();
    for (i, (id, e)) in p.entities.insts().enumerate() {
        let Some(k) = kinds.iter().position(|k| e.is(k)) else {
            continue;
        };
        let sid = format!("#{id}");
        let outcome = match outcomes.get(&id) {
            Some(o) => o.clone(),
            None => match report.and_then(|r| refused(r, &sid)) {
                Some(o) => o,
                None if consumed[i] => Outcome::Used,
                None if k < n_surfaces => {
                    Outcome::Unsupported("not the surface of a face, not referenced".into())
                }
                None => Outcome::Unsupported(FREE_CURVE.into()),
            },
        };
        acc.record(kinds[k], sid, outcome);
    }
    acc
}
