//! Length and plane-angle units of a STEP file: the units the representation context
//! assigns (GLOBAL_UNIT_ASSIGNED_CONTEXT), SI with prefix or conversion-based.

use super::part21::{Entity, Part21, Value};

/// `(length unit, factor turning plane angles into radians)`.
pub fn unit(p: &Part21) -> (Option<String>, f64) {
    let mut length = None;
    let mut angle = 1.0;
    // Prefer the units the representation context assigns; otherwise any unit instance.
    let assigned: Vec<u64> = p
        .entities
        .values()
        .filter_map(|e| e.part("GLOBAL_UNIT_ASSIGNED_CONTEXT"))
        .flat_map(|a| {
            let mut r = vec![];
            a.iter().for_each(|v| v.refs(&mut r));
            r
        })
        .collect();
    let units: Vec<&Entity> = if assigned.is_empty() {
        p.entities.values().collect()
    } else {
        assigned
            .iter()
            .filter_map(|id| p.entities.get(id))
            .collect()
    };
    for e in units {
        if e.is("LENGTH_UNIT") {
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
                && let Some(Value::Str(n)) = cb.first()
            {
                length = Some(crate::model::normalize_unit(n));
            }
        }
        if e.is("PLANE_ANGLE_UNIT")
            && e.part("CONVERSION_BASED_UNIT")
                .and_then(|a| a.first())
                .is_some_and(|v| matches!(v, Value::Str(n) if n.eq_ignore_ascii_case("degree")))
        {
            angle = std::f64::consts::PI / 180.0;
        }
    }
    (length, angle)
}
