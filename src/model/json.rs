//! The native JSON model format (`docs/model-format.md`), read with full validation.
//!
//! ```json
//! { "format": "vericad-model", "version": 1, "unit": "mm",
//!   "curves":   [ { "name": "c", "degree": 2, "knots": [0,0,0,1,1,1],
//!                   "control_points": [[0.1,0.1],[0.5,1.8],[0.8,0.1]], "weights": [1,1,1] } ],
//!   "surfaces": [ { "name": "s", "degree_u": 2, "degree_v": 2,
//!                   "knots_u": [...], "knots_v": [...],
//!                   "control_points": [[[x,y,z], ...], ...], "weights": [[...], ...] } ],
//!   "patch_sets": [ { "name": "body", "surfaces": [0] } ] }
//! ```
//! `knots` may be omitted for a Bézier curve/patch (then `degree + 1` control points per
//! direction and knots `[0^(p+1), 1^(p+1)]`); `weights` may be omitted (all 1). Curves with
//! 2-coordinate control points are domain curves `(u, v)`, with 3 coordinates space curves.

use super::{Curve, CurveGeometry, Model, ModelError, PatchSet, Surface};
use crate::spline::{KnotVector, NurbsCurve, NurbsSurface, SplineError};
use serde::{Deserialize, Serialize};

/// Format tag written into every file.
pub const FORMAT: &str = "vericad-model";

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawModel {
    #[serde(default)]
    format: Option<String>,
    #[serde(default)]
    version: Option<u32>,
    #[serde(default)]
    unit: Option<String>,
    #[serde(default)]
    curves: Vec<RawCurve>,
    #[serde(default)]
    surfaces: Vec<RawSurface>,
    #[serde(default)]
    patch_sets: Vec<RawPatchSet>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCurve {
    #[serde(default)]
    name: String,
    degree: usize,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    knots: Option<Vec<f64>>,
    control_points: Vec<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    weights: Option<Vec<f64>>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSurface {
    #[serde(default)]
    name: String,
    degree_u: usize,
    degree_v: usize,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    knots_u: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    knots_v: Option<Vec<f64>>,
    control_points: Vec<Vec<Vec<f64>>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    weights: Option<Vec<Vec<f64>>>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    trim_loops: Vec<RawTrimLoop>,
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    reversed: bool,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTrimLoop {
    outer: bool,
    curves: Vec<RawCurve>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPatchSet {
    #[serde(default)]
    name: String,
    surfaces: Vec<usize>,
}

struct Ctx<'a> {
    file: &'a str,
}

impl Ctx<'_> {
    fn err(&self, path: impl Into<String>, reason: impl Into<String>) -> ModelError {
        ModelError {
            file: self.file.to_string(),
            path: path.into(),
            reason: reason.into(),
        }
    }
    fn finite(&self, path: &str, xs: &[f64]) -> Result<(), ModelError> {
        match xs.iter().position(|x| !x.is_finite()) {
            Some(i) => Err(self.err(format!("{path}[{i}]"), "not a finite number")),
            None => Ok(()),
        }
    }
    fn knots(
        &self,
        path: &str,
        k: Option<Vec<f64>>,
        degree: usize,
        n: usize,
    ) -> Result<Vec<f64>, ModelError> {
        match k {
            Some(k) => {
                self.finite(path, &k)?;
                KnotVector::new(k.clone(), degree, n).map_err(|e| self.err(path, e.to_string()))?;
                Ok(k)
            }
            None => {
                if n != degree + 1 {
                    return Err(self.err(
                        path,
                        format!(
                            "knots omitted, so a Bézier piece is meant: needs degree + 1 = {} control points, got {n}",
                            degree + 1
                        ),
                    ));
                }
                let mut k = vec![0.0; degree + 1];
                k.extend(std::iter::repeat_n(1.0, degree + 1));
                Ok(k)
            }
        }
    }
    fn weights(&self, path: &str, w: Option<Vec<f64>>, n: usize) -> Result<Vec<f64>, ModelError> {
        match w {
            None => Ok(vec![1.0; n]),
            Some(w) => {
                if w.len() != n {
                    return Err(
                        self.err(path, format!("{} weights for {n} control points", w.len()))
                    );
                }
                self.finite(path, &w)?;
                if let Some(i) = w.iter().position(|x| *x <= 0.0) {
                    return Err(self.err(
                        format!("{path}[{i}]"),
                        format!("weight {} is not positive", w[i]),
                    ));
                }
                Ok(w)
            }
        }
    }
}

fn spline_err(ctx: &Ctx, path: &str, e: SplineError) -> ModelError {
    ctx.err(path, e.to_string())
}

fn point<const D: usize>(ctx: &Ctx, path: String, p: &[f64]) -> Result<[f64; D], ModelError> {
    if p.len() != D {
        return Err(ctx.err(
            path,
            format!("a point needs {D} coordinates, got {}", p.len()),
        ));
    }
    ctx.finite(&path, p)?;
    Ok(std::array::from_fn(|i| p[i]))
}

fn degree_ok(ctx: &Ctx, path: String, d: usize) -> Result<(), ModelError> {
    if d == 0 || d > crate::spline::MAX_DEGREE {
        return Err(ctx.err(
            path,
            format!(
                "degree {d} is not supported (1..={})",
                crate::spline::MAX_DEGREE
            ),
        ));
    }
    Ok(())
}

fn curve(ctx: &Ctx, i: usize, c: RawCurve) -> Result<Curve, ModelError> {
    curve_at(ctx, format!("curves[{i}]"), c)
}

fn curve_at(ctx: &Ctx, base: String, c: RawCurve) -> Result<Curve, ModelError> {
    degree_ok(ctx, format!("{base}.degree"), c.degree)?;
    let n = c.control_points.len();
    if n == 0 {
        return Err(ctx.err(format!("{base}.control_points"), "no control points"));
    }
    let dim = c.control_points[0].len();
    let knots = ctx.knots(&format!("{base}.knots"), c.knots, c.degree, n)?;
    let w = ctx.weights(&format!("{base}.weights"), c.weights, n)?;
    let pp = |j: usize| format!("{base}.control_points[{j}]");
    let geometry = match dim {
        2 => {
            let pts = c
                .control_points
                .iter()
                .enumerate()
                .map(|(j, p)| point::<2>(ctx, pp(j), p))
                .collect::<Result<Vec<_>, _>>()?;
            CurveGeometry::Domain(
                NurbsCurve::new(knots, c.degree, pts, w).map_err(|e| spline_err(ctx, &base, e))?,
            )
        }
        3 => {
            let pts = c
                .control_points
                .iter()
                .enumerate()
                .map(|(j, p)| point::<3>(ctx, pp(j), p))
                .collect::<Result<Vec<_>, _>>()?;
            CurveGeometry::Space(
                NurbsCurve::new(knots, c.degree, pts, w).map_err(|e| spline_err(ctx, &base, e))?,
            )
        }
        d => {
            return Err(ctx.err(
                pp(0),
                format!(
                    "control points need 2 (domain curve) or 3 (space curve) coordinates, got {d}"
                ),
            ));
        }
    };
    Ok(Curve {
        name: c.name,
        geometry,
    })
}

fn surface(ctx: &Ctx, i: usize, s: RawSurface) -> Result<Surface, ModelError> {
    let base = format!("surfaces[{i}]");
    degree_ok(ctx, format!("{base}.degree_u"), s.degree_u)?;
    degree_ok(ctx, format!("{base}.degree_v"), s.degree_v)?;
    let nu = s.control_points.len();
    if nu == 0 {
        return Err(ctx.err(format!("{base}.control_points"), "no control points"));
    }
    let nv = s.control_points[0].len();
    let mut pts = Vec::with_capacity(nu * nv);
    for (a, row) in s.control_points.iter().enumerate() {
        if row.len() != nv {
            return Err(ctx.err(
                format!("{base}.control_points[{a}]"),
                format!(
                    "row has {} points, row 0 has {nv}: the net must be rectangular",
                    row.len()
                ),
            ));
        }
        for (b, p) in row.iter().enumerate() {
            pts.push(point::<3>(
                ctx,
                format!("{base}.control_points[{a}][{b}]"),
                p,
            )?);
        }
    }
    let ku = ctx.knots(&format!("{base}.knots_u"), s.knots_u, s.degree_u, nu)?;
    let kv = ctx.knots(&format!("{base}.knots_v"), s.knots_v, s.degree_v, nv)?;
    let w = match s.weights {
        None => vec![1.0; nu * nv],
        Some(rows) => {
            if rows.len() != nu {
                return Err(ctx.err(
                    format!("{base}.weights"),
                    format!("{} weight rows for {nu} control-point rows", rows.len()),
                ));
            }
            let mut w = Vec::with_capacity(nu * nv);
            for (a, r) in rows.into_iter().enumerate() {
                w.extend(ctx.weights(&format!("{base}.weights[{a}]"), Some(r), nv)?);
            }
            w
        }
    };
    let nurbs = NurbsSurface::new(ku, s.degree_u, kv, s.degree_v, nu, nv, pts, w)
        .map_err(|e| spline_err(ctx, &base, e))?;
    let mut trim_loops = Vec::with_capacity(s.trim_loops.len());
    for (l, tl) in s.trim_loops.into_iter().enumerate() {
        let mut curves = Vec::with_capacity(tl.curves.len());
        for (k, c) in tl.curves.into_iter().enumerate() {
            let path = format!("{base}.trim_loops[{l}].curves[{k}]");
            match curve_at(ctx, path.clone(), c)?.geometry {
                CurveGeometry::Domain(d) => curves.push(d),
                CurveGeometry::Space(_) => {
                    return Err(ctx.err(
                        path,
                        "a trim curve lies in the parameter plane: 2 coordinates (u, v)",
                    ));
                }
            }
        }
        trim_loops.push(crate::model::TrimLoop {
            outer: tl.outer,
            curves,
        });
    }
    Ok(Surface {
        trim_loops,
        reversed: s.reversed,
        ..Surface::new(s.name, nurbs)
    })
}

/// Parse and validate model text. `file` names the source in error messages.
pub fn from_str(text: &str, file: &str) -> Result<Model, ModelError> {
    let ctx = Ctx { file };
    let de = &mut serde_json::Deserializer::from_str(text);
    let raw: RawModel = serde_path_to_error::deserialize(de).map_err(|e| {
        // serde_path_to_error writes `?` for a position it could not name (truncated input).
        let path = e.path().to_string();
        let path = path.trim_end_matches('?').trim_end_matches('.').to_string();
        let path = if path.is_empty() || path == "." {
            "(top level)".to_string()
        } else {
            path
        };
        ctx.err(path, e.into_inner().to_string())
    })?;
    if let Some(f) = &raw.format
        && f != FORMAT
    {
        return Err(ctx.err("format", format!("expected \"{FORMAT}\", got \"{f}\"")));
    }
    if let Some(v) = raw.version
        && v != 1
    {
        return Err(ctx.err("version", format!("version {v} is not supported (1)")));
    }
    let curves = raw
        .curves
        .into_iter()
        .enumerate()
        .map(|(i, c)| curve(&ctx, i, c))
        .collect::<Result<Vec<_>, _>>()?;
    let surfaces = raw
        .surfaces
        .into_iter()
        .enumerate()
        .map(|(i, s)| surface(&ctx, i, s))
        .collect::<Result<Vec<_>, _>>()?;
    let mut patch_sets = Vec::with_capacity(raw.patch_sets.len());
    for (i, p) in raw.patch_sets.into_iter().enumerate() {
        if let Some(j) = p.surfaces.iter().position(|&s| s >= surfaces.len()) {
            return Err(ctx.err(
                format!("patch_sets[{i}].surfaces[{j}]"),
                format!(
                    "surface index {} out of range ({} surfaces)",
                    p.surfaces[j],
                    surfaces.len()
                ),
            ));
        }
        patch_sets.push(PatchSet {
            name: p.name,
            surfaces: p.surfaces,
        });
    }
    Ok(Model {
        unit: raw.unit,
        curves,
        surfaces,
        patch_sets,
        triangulations: vec![],
        source_entities: Default::default(),
        warnings: vec![],
        brep: None,
        accounts: Default::default(),
    })
}

/// Read and validate a model file.
pub fn read(path: &std::path::Path) -> Result<Model, ModelError> {
    let name = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| ModelError {
        file: name.clone(),
        path: "(file)".into(),
        reason: e.to_string(),
    })?;
    from_str(&text, &name)
}

fn raw_curve<const D: usize>(name: &str, c: &NurbsCurve<f64, D>) -> RawCurve {
    let (pts, w) = c.points_weights();
    let rational = w.iter().any(|x| *x != 1.0);
    RawCurve {
        name: name.to_string(),
        degree: c.hom.degree(),
        knots: Some(c.hom.knots.knots().to_vec()),
        control_points: pts.iter().map(|p| p.to_vec()).collect(),
        weights: rational.then_some(w),
    }
}

/// Serialize a model to the native JSON format (pretty-printed). Every `f64` is written with
/// the shortest representation that reads back to the same bits, so a round trip is exact.
pub fn to_string(m: &Model) -> String {
    let raw = RawModel {
        format: Some(FORMAT.into()),
        version: Some(1),
        unit: m.unit.clone(),
        curves: m
            .curves
            .iter()
            .map(|c| match &c.geometry {
                CurveGeometry::Domain(g) => raw_curve(&c.name, g),
                CurveGeometry::Space(g) => raw_curve(&c.name, g),
            })
            .collect(),
        surfaces: m
            .surfaces
            .iter()
            .map(|s| {
                let (pts, w) = s.nurbs.points_weights();
                let h = &s.nurbs.hom;
                let nv = h.nv();
                RawSurface {
                    name: s.name.clone(),
                    degree_u: h.ku.degree(),
                    degree_v: h.kv.degree(),
                    knots_u: Some(h.ku.knots().to_vec()),
                    knots_v: Some(h.kv.knots().to_vec()),
                    control_points: pts
                        .chunks(nv)
                        .map(|r| r.iter().map(|p| p.to_vec()).collect())
                        .collect(),
                    weights: w
                        .iter()
                        .any(|x| *x != 1.0)
                        .then(|| w.chunks(nv).map(|r| r.to_vec()).collect()),
                    trim_loops: s
                        .trim_loops
                        .iter()
                        .map(|l| RawTrimLoop {
                            outer: l.outer,
                            curves: l.curves.iter().map(|c| raw_curve("", c)).collect(),
                        })
                        .collect(),
                    reversed: s.reversed,
                }
            })
            .collect(),
        patch_sets: m
            .patch_sets
            .iter()
            .map(|p| RawPatchSet {
                name: p.name.clone(),
                surfaces: p.surfaces.clone(),
            })
            .collect(),
    };
    serde_json::to_string_pretty(&raw).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> ModelError {
        from_str(text, "t.json").unwrap_err()
    }

    #[test]
    fn faults_name_path_and_reason() {
        let e = err(
            r#"{"surfaces":[{"degree_u":2,"degree_v":2,"knots_u":[0,0,0,1,0.5,1],"control_points":[[[0,0,0],[0,1,0],[0,2,0]],[[1,0,0],[1,1,0],[1,2,0]],[[2,0,0],[2,1,0],[2,2,0]]]}]}"#,
        );
        assert_eq!(e.path, "surfaces[0].knots_u");
        assert!(e.reason.contains("decrease"), "{e}");
        let e = err(r#"{"curves":[{"degree":1,"control_points":[[0,0],[1]]}]}"#);
        assert_eq!(e.path, "curves[0].control_points[1]");
        let e = err(r#"{"curves":[{"degree":1,"control_points":[[0,0],[1,1]],"weights":[1,-1]}]}"#);
        assert_eq!(e.path, "curves[0].weights[1]");
        let e = err(r#"{"curves":[{"degree":"two","control_points":[]}]}"#);
        assert_eq!(e.path, "curves[0].degree");
        let e = err(r#"{"curves":[{"degree":1,"control_points":[[0,0],[1e999,1]]}]}"#);
        assert!(e.path.starts_with("curves[0]"), "{e}");
        let e = err(
            r#"{"surfaces":[{"degree_u":1,"degree_v":1,"control_points":[[[0,0,0],[0,1,0]],[[1,0,0]]]}]}"#,
        );
        assert_eq!(e.path, "surfaces[0].control_points[1]");
        let e = err(r#"{"patch_sets":[{"surfaces":[3]}]}"#);
        assert_eq!(e.path, "patch_sets[0].surfaces[0]");
        let e = err(r#"{"curves":[{"degree":0,"control_points":[[0,0]]}]}"#);
        assert_eq!(e.path, "curves[0].degree");
        let e = err("{\"bogus\": 1}");
        assert!(e.reason.contains("unknown field"), "{e}");
        assert!(from_str("not json", "t.json").is_err());
    }
}
