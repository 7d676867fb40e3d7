//! Reading another system's intersection curves for `certify-ssi`.

/// Samples per foreign spline curve.
pub const CURVE_SAMPLES: usize = 200;

/// A foreign curve as points: `(name, kind, points)`.
pub type ForeignInput = (String, &'static str, Vec<[f64; 3]>);

/// The curves of a foreign result file: a model's space curves (sampled), or JSON
/// polylines (`[[[x,y,z],...],...]`, `{"curves": [...]}`, or a vericad `ssi` result).
pub fn read_foreign(path: &std::path::Path) -> Result<Vec<ForeignInput>, String> {
    let text = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    if let Ok(v) = serde_json::from_slice::<serde_json::Value>(&text) {
        let polys = if let Some(pairs) = v.get("pairs").and_then(|p| p.as_array()) {
            pairs
                .iter()
                .flat_map(|p| p["branches"].as_array().cloned().unwrap_or_default())
                .map(|b| b["points"].clone())
                .collect()
        } else if let Some(c) = v.get("curves").and_then(|c| c.as_array()) {
            c.clone()
        } else if let Some(c) = v.as_array() {
            c.clone()
        } else {
            Vec::new()
        };
        if !polys.is_empty() || v.get("pairs").is_some() {
            return polys
                .iter()
                .enumerate()
                .map(|(i, p)| {
                    let pts: Vec<[f64; 3]> = serde_json::from_value(p.clone()).map_err(|e| {
                        format!("{}: curve {i}: expected [[x,y,z],...]: {e}", path.display())
                    })?;
                    if pts.is_empty() {
                        // Nothing to check: certifying it would be vacuous.
                        return Err(format!("{}: curve {i}: no points", path.display()));
                    }
                    if pts.iter().flatten().any(|c| !c.is_finite()) {
                        return Err(format!(
                            "{}: curve {i}: non-finite coordinate",
                            path.display()
                        ));
                    }
                    Ok((format!("polyline {i}"), "polyline", pts))
                })
                .collect();
        }
    }
    let m = crate::io::read_model(path).map_err(|e| e.to_string())?;
    if m.curves.is_empty() {
        return Err(format!("{}: no curves found", path.display()));
    }
    Ok(m.curves
        .iter()
        .map(|c| {
            let s = c.geometry.to_space();
            let (t0, t1) = s.hom.domain();
            let pts = (0..CURVE_SAMPLES)
                .map(|k| s.eval(&(t0 + (t1 - t0) * k as f64 / (CURVE_SAMPLES - 1) as f64)))
                .collect();
            (c.name.clone(), "spline", pts)
        })
        .collect())
}
