//! Reading another system's intersection curves for `certify-ssi`.

/// Samples per foreign spline curve.
pub const CURVE_SAMPLES: usize = 200;

/// A foreign curve as points: `(name, kind, points)`.
pub type ForeignInput = (String, &'static str, Vec<[f64; 3]>);

/// Why a foreign result file gave no curves to check; each names the file (a model that
/// cannot be read: as its reader says).
#[derive(Debug, thiserror::Error)]
pub enum ForeignError {
    #[error("{path}: {reason}")]
    Io { path: String, reason: String },
    #[error("{path}: curve {index}: expected [[x,y,z],...]: {reason}")]
    NotPoints {
        path: String,
        index: usize,
        reason: String,
    },
    /// Nothing to check: certifying it would be vacuous.
    #[error("{path}: curve {index}: no points")]
    Empty { path: String, index: usize },
    #[error("{path}: curve {index}: non-finite coordinate")]
    NotFinite { path: String, index: usize },
    #[error(transparent)]
    Model(#[from] crate::io::ReadError),
    #[error("{path}: no curves found")]
    NoCurves { path: String },
}

/// The curves of a foreign result file: a model's space curves (sampled), or JSON
/// polylines (`[[[x,y,z],...],...]`, `{"curves": [...]}`, or a vericad `ssi` result; a
/// branch of one in cubic pieces is its pieces sampled within `tol / 4` of them,
/// `cubic_branch`).
pub fn read_foreign(path: &std::path::Path, tol: f64) -> Result<Vec<ForeignInput>, ForeignError> {
    let name = || path.display().to_string();
    let text = std::fs::read(path).map_err(|e| ForeignError::Io {
        path: name(),
        reason: e.to_string(),
    })?;
    if let Ok(v) = serde_json::from_slice::<serde_json::Value>(&text) {
        let polys = if let Some(pairs) = v.get("pairs").and_then(|p| p.as_array()) {
            pairs
                .iter()
                .flat_map(|p| p["branches"].as_array().cloned().unwrap_or_default())
                .map(|b| cubic_branch(&b, tol).unwrap_or_else(|| b["points"].clone()))
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
                    let pts: Vec<[f64; 3]> =
                        serde_json::from_value(p.clone()).map_err(|e| ForeignError::NotPoints {
                            path: name(),
                            index: i,
                            reason: e.to_string(),
                        })?;
                    if pts.is_empty() {
                        return Err(ForeignError::Empty {
                            path: name(),
                            index: i,
                        });
                    }
                    if pts.iter().flatten().any(|c| !c.is_finite()) {
                        return Err(ForeignError::NotFinite {
                            path: name(),
                            index: i,
                        });
                    }
                    Ok((format!("polyline {i}"), "polyline", pts))
                })
                .collect();
        }
    }
    let m = crate::io::read_model(path)?;
    if m.curves.is_empty() {
        return Err(ForeignError::NoCurves { path: name() });
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

/// A vericad branch in cubic pieces (with `tangents`) as the polyline of its pieces
/// ([`super::hermite::densify`], within `tol / 4` of them, at most 4096 chords a piece);
/// `None` for a branch of chords or one whose fields do not parse (then read as points).
fn cubic_branch(b: &serde_json::Value, tol: f64) -> Option<serde_json::Value> {
    use super::hermite::{Jet, branch_pieces, densify, pack};
    let tangents: Vec<Option<Jet>> = serde_json::from_value(b.get("tangents")?.clone()).ok()?;
    let field = |k: &str| b.get(k).cloned();
    let pts: Vec<[f64; 3]> = serde_json::from_value(field("points")?).ok()?;
    let ua: Vec<[f64; 2]> = serde_json::from_value(field("uv_a")?).ok()?;
    let ub: Vec<[f64; 2]> = serde_json::from_value(field("uv_b")?).ok()?;
    let closed = b.get("closed")?.as_bool()?;
    if tangents.len() != pts.len() || ua.len() != pts.len() || ub.len() != pts.len() {
        return None;
    }
    let packed = pack(&pts, &ua, &ub);
    let mut out: Vec<[f64; 3]> = Vec::new();
    for h in branch_pieces(&packed, &tangents, closed) {
        let (poly, _) = densify(&h, 0.25 * tol, 4096);
        let skip = usize::from(!out.is_empty());
        out.extend(poly.into_iter().skip(skip));
    }
    if pts.len() == 1 {
        out.push(pts[0]);
    }
    serde_json::to_value(out).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each refusal names the file and the curve, in the words they had as strings.
    #[test]
    fn refusals_name_file_and_curve() {
        let dir = std::env::temp_dir().join(format!("vericad-foreign-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let f = dir.join("c.json");
        std::fs::write(&f, r#"{"curves": [[[0, 0, 0], [1, 0, 0]], []]}"#).unwrap();
        let e = read_foreign(&f, 1e-6).unwrap_err();
        assert_eq!(
            e.to_string(),
            format!("{}: curve 1: no points", f.display())
        );
        std::fs::write(&f, r#"{"curves": [[[0, 0]]]}"#).unwrap();
        let e = read_foreign(&f, 1e-6).unwrap_err();
        assert!(matches!(e, ForeignError::NotPoints { index: 0, .. }), "{e}");
        assert!(
            e.to_string().starts_with(&format!(
                "{}: curve 0: expected [[x,y,z],...]: ",
                f.display()
            )),
            "{e}"
        );
        let missing = dir.join("missing.json");
        assert!(matches!(
            read_foreign(&missing, 1e-6),
            Err(ForeignError::Io { .. })
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
