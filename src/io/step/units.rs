//! Length and plane-angle units of a STEP file: the units the representation context
//! assigns (GLOBAL_UNIT_ASSIGNED_CONTEXT), SI with prefix or conversion-based.

use super::part21::{Args, Inst, Part21};

/// `(length unit, factor turning plane angles into radians)`.
pub fn unit(p: &Part21) -> (Option<String>, f64) {
    let mut length = None;
    let mut angle = 1.0;
    let units: Vec<Inst> = unit_candidates(p)
        .iter()
        .filter_map(|id| p.entities.inst(*id))
        .collect();
    for e in units {
        // The first length unit: where representations differ (an assembly of parts in other
        // units) the model takes the first one's, usually the root's, and the assembly reader
        // scales the others into it.
        if e.is("LENGTH_UNIT") && length.is_none() {
            if let Some(si) = e.part("SI_UNIT") {
                let prefix = si.first().and_then(|v| v.enumeration()).unwrap_or("");
                length = Some(
                    match prefix {
                        "MILLI" => "mm",
                        "CENTI" => "cm",
                        "KILO" => "km",
                        "MICRO" => "um",
                        "" => "m",
                        _ => "m (prefixed)",
                    }
                    .to_string(),
                );
            } else if let Some(cb) = e.part("CONVERSION_BASED_UNIT")
                && let Some(n) = cb.first().and_then(|v| v.str())
            {
                length = Some(crate::model::normalize_unit(n));
            }
        }
        if e.is("PLANE_ANGLE_UNIT")
            && e.part("CONVERSION_BASED_UNIT")
                .and_then(|a| a.first())
                .is_some_and(|v| v.str().is_some_and(|n| n.eq_ignore_ascii_case("degree")))
        {
            angle = std::f64::consts::PI / 180.0;
        }
    }
    (length, angle)
}

/// Metres per unit of the length-unit instance `id`: an SI unit of length with its prefix, a
/// conversion-based unit (`conversion_factor` a `length_measure_with_unit`: its value times
/// its own unit's metres, followed at most 8 deep), or, failing that, a conversion-based unit
/// named inch, foot or a metric length. `None` for anything else.
pub(super) fn metres_per_unit(p: &Part21, id: u64) -> Option<f64> {
    metres_at(p, id, 0)
}

fn metres_at(p: &Part21, id: u64, depth: usize) -> Option<f64> {
    let e = p.entities.inst(id)?;
    if let Some(si) = e.part("SI_UNIT") {
        if si.get(1).and_then(|v| v.enumeration()) != Some("METRE") {
            return None;
        }
        let prefix = si.first().and_then(|v| v.enumeration()).unwrap_or("");
        let f = match prefix {
            "" => 1.0,
            "EXA" => 1e18,
            "PETA" => 1e15,
            "TERA" => 1e12,
            "GIGA" => 1e9,
            "MEGA" => 1e6,
            "KILO" => 1e3,
            "HECTO" => 1e2,
            "DECA" => 1e1,
            "DECI" => 1e-1,
            "CENTI" => 1e-2,
            "MILLI" => 1e-3,
            "MICRO" => 1e-6,
            "NANO" => 1e-9,
            "PICO" => 1e-12,
            "FEMTO" => 1e-15,
            "ATTO" => 1e-18,
            _ => return None,
        };
        return Some(f);
    }
    let cb = e.part("CONVERSION_BASED_UNIT")?;
    let factor = (depth < 8)
        .then(|| {
            let m = p.entities.inst(cb.get(1)?.reference()?)?;
            let a = m
                .part("LENGTH_MEASURE_WITH_UNIT")
                .filter(|a| a.len() >= 2)
                .or_else(|| m.part("MEASURE_WITH_UNIT"))?;
            let v = a.first()?.num()?;
            let base = metres_at(p, a.get(1)?.reference()?, depth + 1)?;
            Some(v * base).filter(|x| *x > 0.0 && x.is_finite())
        })
        .flatten();
    factor.or_else(|| match cb.first().and_then(|v| v.str()) {
        Some(n) => match crate::model::normalize_unit(n).as_str() {
            "inch" => Some(0.0254),
            "foot" => Some(0.3048),
            "m" => Some(1.0),
            "mm" => Some(1e-3),
            "cm" => Some(1e-2),
            "km" => Some(1e3),
            "um" => Some(1e-6),
            _ => None,
        },
        _ => None,
    })
}

/// Metres per length unit of the representation `rep` (its `context_of_items`, third
/// attribute, through the context's `global_unit_assigned_context`); `None` when the
/// representation, its context or a length unit there is missing.
pub(super) fn rep_metres(p: &Part21, rep: u64) -> Option<f64> {
    let ctx = representation_context(p.entities.inst(rep)?)?;
    let units = p.entities.inst(ctx)?.part("GLOBAL_UNIT_ASSIGNED_CONTEXT")?;
    unit_ids(units)
        .into_iter()
        .find(|id| p.entities.inst(*id).is_some_and(|e| e.is("LENGTH_UNIT")))
        .and_then(|id| metres_per_unit(p, id))
}

/// The `context_of_items` of a representation instance (simple or complex).
fn representation_context(e: Inst) -> Option<u64> {
    // The first such part with a context (a complex instance's subtype parts are empty).
    e.parts().find_map(|(n, a)| {
        n.ends_with("REPRESENTATION")
            .then(|| a.get(2)?.reference())
            .flatten()
    })
}

/// The unit instances a `global_unit_assigned_context`'s arguments name.
fn unit_ids(args: Args) -> Vec<u64> {
    let mut ids = vec![];
    args.iter().for_each(|v| v.refs(&mut ids));
    ids
}

/// The unit instances every representation context assigns, in table order.
fn assigned(p: &Part21) -> Vec<u64> {
    p.entities
        .insts()
        .filter_map(|(_, e)| e.part("GLOBAL_UNIT_ASSIGNED_CONTEXT"))
        .flat_map(unit_ids)
        .collect()
}

/// The instances that may hold the file's units: those the representation contexts assign
/// (`global_unit_assigned_context`), or every instance where no context assigns any.
fn unit_candidates(p: &Part21) -> Vec<u64> {
    let a = assigned(p);
    if a.is_empty() {
        p.entities.keys().copied().collect()
    } else {
        a
    }
}

/// Metres per unit of the file's length unit as [`unit`] chooses it (the first length unit a
/// representation context assigns, or the first length unit instance).
pub(super) fn model_metres(p: &Part21) -> Option<f64> {
    unit_candidates(p)
        .into_iter()
        .find(|id| {
            p.entities.inst(*id).is_some_and(|e| {
                e.is("LENGTH_UNIT") && (e.is("SI_UNIT") || e.is("CONVERSION_BASED_UNIT"))
            })
        })
        .and_then(|id| metres_per_unit(p, id))
}

/// Metres per unit of every distinct length unit the representation contexts assign (in
/// table order).
pub(super) fn context_lengths(p: &Part21) -> Vec<f64> {
    let mut out: Vec<f64> = vec![];
    for m in assigned(p)
        .into_iter()
        .filter(|id| p.entities.inst(*id).is_some_and(|e| e.is("LENGTH_UNIT")))
        .filter_map(|id| metres_per_unit(p, id))
    {
        if !out.contains(&m) {
            out.push(m);
        }
    }
    out
}
