//! Step 1 (§3.1–3.2): the four boundary curves of a local approximant, as curves of the
//! model (by index or name) or as polylines, oriented into one closed loop and checked:
//! consecutive curves meet, no side has zero length, the loop does not cross itself. Points
//! are then taken uniformly in arc length ([`BoundaryCurve::at`]).
//!
//! Arc length is measured along a dense polyline of the curve (64 samples per knot span,
//! at least 256); a point at an arc-length fraction is evaluated on the curve itself at the
//! parameter interpolated between the two samples around it, so it lies on the curve.

use super::CoonsError;
use crate::geom::{Point, cross, dist, dot, norm};
use crate::model::{CurveGeometry, Model};
use crate::predicates::orient2d;
use crate::scalar::Sign;
use crate::spline::NurbsCurve;
use serde::Deserialize;

/// A reference to a model curve: its index or its name.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(untagged)]
pub enum CurveRef {
    Index(usize),
    Name(String),
}

/// One boundary curve as written in the boundary file: `{"curve": 3}`,
/// `{"curve": "name", "reversed": true}` or `{"polyline": [[x, y, z], ...]}`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct CurveSpec {
    #[serde(default)]
    pub curve: Option<CurveRef>,
    #[serde(default)]
    pub polyline: Option<Vec<[f64; 3]>>,
    /// Traverse the curve backwards (the loop is oriented automatically otherwise).
    #[serde(default)]
    pub reversed: bool,
    /// A name for messages (default: `#k` or the model curve's name).
    #[serde(default)]
    pub name: Option<String>,
}

/// The boundary file: four curves in loop order (sides `J = 0`, `I = M`, `J = N`, `I = 0`).
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct BoundarySpec {
    pub curves: Vec<CurveSpec>,
}

impl BoundarySpec {
    /// Parse the JSON text; a fault names its JSON path.
    pub fn parse(text: &str) -> Result<BoundarySpec, CoonsError> {
        let de = &mut serde_json::Deserializer::from_str(text);
        serde_path_to_error::deserialize(de)
            .map_err(|e| CoonsError::Boundary(format!("{}: {}", e.path(), e.inner())))
    }
}

#[derive(Clone, Debug)]
enum Source {
    Nurbs {
        curve: NurbsCurve<f64, 3>,
        t: Vec<f64>,
    },
    Polyline,
}

/// A boundary curve with its arc-length table.
#[derive(Clone, Debug)]
pub struct BoundaryCurve {
    pub name: String,
    /// Dense samples along the curve (the polyline's own vertices for a polyline).
    pub samples: Vec<[f64; 3]>,
    /// Cumulative chord length at each sample.
    cum: Vec<f64>,
    /// Total length.
    pub length: f64,
    source: Source,
}

fn finite(p: &[f64; 3]) -> bool {
    p.iter().all(|c| c.is_finite())
}

impl BoundaryCurve {
    /// A polyline through `pts` (at least two points, all finite).
    pub fn from_polyline(name: &str, pts: Vec<[f64; 3]>) -> Result<BoundaryCurve, CoonsError> {
        let why = |w: String| CoonsError::Curve {
            curve: name.to_string(),
            why: w,
        };
        if pts.len() < 2 {
            return Err(why(format!(
                "a polyline needs at least 2 points, got {}",
                pts.len()
            )));
        }
        if let Some(k) = pts.iter().position(|p| !finite(p)) {
            return Err(why(format!("point {k} is not finite")));
        }
        Ok(Self::with_samples(name, pts, Source::Polyline))
    }

    /// A NURBS curve, sampled densely for its arc length.
    pub fn from_nurbs(name: &str, c: NurbsCurve<f64, 3>) -> Result<BoundaryCurve, CoonsError> {
        let spans = c.hom.knots.interior_breaks().len() + 1;
        let n = (64 * spans).clamp(256, 8192);
        let (t0, t1) = c.hom.domain();
        let t: Vec<f64> = (0..=n)
            .map(|i| t0 + (t1 - t0) * i as f64 / n as f64)
            .collect();
        let pts: Vec<[f64; 3]> = t.iter().map(|t| c.eval(t)).collect();
        if let Some(k) = pts.iter().position(|p| !finite(p)) {
            return Err(CoonsError::Curve {
                curve: name.to_string(),
                why: format!("not finite at t = {:e}", t[k]),
            });
        }
        Ok(Self::with_samples(name, pts, Source::Nurbs { curve: c, t }))
    }

    fn with_samples(name: &str, samples: Vec<[f64; 3]>, source: Source) -> BoundaryCurve {
        let mut cum = Vec::with_capacity(samples.len());
        let mut s = 0.0;
        cum.push(0.0);
        for w in samples.windows(2) {
            s += dist(&w[0], &w[1]);
            cum.push(s);
        }
        BoundaryCurve {
            name: name.to_string(),
            samples,
            cum,
            length: s,
            source,
        }
    }

    /// The same curve traversed backwards.
    pub fn reversed(&self) -> BoundaryCurve {
        let samples: Vec<[f64; 3]> = self.samples.iter().rev().copied().collect();
        let source = match &self.source {
            Source::Polyline => Source::Polyline,
            Source::Nurbs { curve, t } => Source::Nurbs {
                curve: curve.clone(),
                t: t.iter().rev().copied().collect(),
            },
        };
        Self::with_samples(&self.name, samples, source)
    }

    pub fn start(&self) -> [f64; 3] {
        self.samples[0]
    }
    pub fn end(&self) -> [f64; 3] {
        self.samples[self.samples.len() - 1]
    }

    /// The point at fraction `f ∈ [0, 1]` of the arc length (on the curve itself).
    pub fn at(&self, f: f64) -> [f64; 3] {
        let s = f.clamp(0.0, 1.0) * self.length;
        let k = self
            .cum
            .partition_point(|c| *c < s)
            .clamp(1, self.cum.len() - 1);
        let (c0, c1) = (self.cum[k - 1], self.cum[k]);
        let lam = if c1 > c0 {
            ((s - c0) / (c1 - c0)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        match &self.source {
            Source::Polyline => self.samples[k - 1].lerp(&self.samples[k], &lam),
            Source::Nurbs { curve, t } => curve.eval(&(t[k - 1] + (t[k] - t[k - 1]) * lam)),
        }
    }
}

/// The closed loop of four curves: side `k` runs from `corners[k]` to `corners[k + 1]`.
#[derive(Clone, Debug)]
pub struct Loop {
    pub sides: [BoundaryCurve; 4],
    /// Corner `k`: midpoint of the end of side `k − 1` and the start of side `k`.
    pub corners: [[f64; 3]; 4],
    /// Gap between the end of side `k − 1` and the start of side `k`.
    pub gaps: [f64; 4],
    /// Sides traversed against their stored direction.
    pub reversed: [bool; 4],
    pub perimeter: f64,
}

impl Loop {
    /// Point of side `k` at arc-length fraction `f`; the ends are the corners.
    pub fn side_point(&self, k: usize, f: f64) -> [f64; 3] {
        if f <= 0.0 {
            self.corners[k]
        } else if f >= 1.0 {
            self.corners[(k + 1) % 4]
        } else {
            self.sides[k].at(f)
        }
    }
    /// Names of the four curves, for messages.
    pub fn names(&self) -> String {
        self.sides.each_ref().map(|s| s.name.as_str()).join(", ")
    }
}

/// Resolve the boundary file against the model: four curves, each a model space curve or a
/// polyline.
pub fn resolve(
    spec: &BoundarySpec,
    model: &Model,
) -> Result<Vec<(BoundaryCurve, bool)>, CoonsError> {
    if spec.curves.len() != 4 {
        return Err(CoonsError::Boundary(format!(
            "expected 4 boundary curves, got {}",
            spec.curves.len()
        )));
    }
    let mut out = Vec::with_capacity(4);
    for (k, c) in spec.curves.iter().enumerate() {
        let label = c.name.clone().unwrap_or_else(|| format!("#{k}"));
        let curve = match (&c.curve, &c.polyline) {
            (Some(r), None) => {
                let (idx, name) =
                    match r {
                        CurveRef::Index(i) => (*i, format!("{label} (model curve {i})")),
                        CurveRef::Name(n) => {
                            let i = model.curves.iter().position(|m| &m.name == n).ok_or_else(
                                || CoonsError::Curve {
                                    curve: label.clone(),
                                    why: format!("the model has no curve named `{n}`"),
                                },
                            )?;
                            (i, format!("{label} (model curve `{n}`)"))
                        }
                    };
                let m = model.curves.get(idx).ok_or_else(|| CoonsError::Curve {
                    curve: label.clone(),
                    why: format!(
                        "the model has no curve {idx} (it has {})",
                        model.curves.len()
                    ),
                })?;
                match &m.geometry {
                    CurveGeometry::Space(s) => BoundaryCurve::from_nurbs(&name, s.clone())?,
                    CurveGeometry::Domain(_) => {
                        return Err(CoonsError::Curve {
                            curve: name,
                            why: "is a curve in a parameter plane, not in space".into(),
                        });
                    }
                }
            }
            (None, Some(p)) => BoundaryCurve::from_polyline(&label, p.clone())?,
            _ => {
                return Err(CoonsError::Curve {
                    curve: label,
                    why: "give exactly one of `curve` and `polyline`".into(),
                });
            }
        };
        out.push((curve, c.reversed));
    }
    Ok(out)
}

/// Orient the four curves into a loop and check it: ends meet within `closure`, no side of
/// zero length, no self-crossing (decided by exact `orient2d` on the loop's polygon seen
/// along its Newell normal).
pub fn close_loop(curves: Vec<(BoundaryCurve, bool)>, closure: f64) -> Result<Loop, CoonsError> {
    let mut cs: Vec<BoundaryCurve> = Vec::with_capacity(4);
    let mut reversed = [false; 4];
    for (k, (c, rev)) in curves.into_iter().enumerate() {
        reversed[k] = rev;
        cs.push(if rev { c.reversed() } else { c });
    }
    if cs.len() != 4 {
        return Err(CoonsError::Boundary(format!(
            "expected 4 boundary curves, got {}",
            cs.len()
        )));
    }
    let perimeter: f64 = cs.iter().map(|c| c.length).sum();
    for c in &cs {
        if c.length.is_nan() || c.length <= 1e-12 * perimeter {
            return Err(CoonsError::Degenerate {
                curve: c.name.clone(),
                length: c.length,
            });
        }
    }
    // Orientation: side 0 as given unless its start (not its end) meets side 1.
    let near = |p: &[f64; 3], c: &BoundaryCurve| dist(p, &c.start()).min(dist(p, &c.end()));
    if !reversed[0] && near(&cs[0].start(), &cs[1]) < near(&cs[0].end(), &cs[1]) {
        cs[0] = cs[0].reversed();
        reversed[0] = true;
    }
    for k in 1..4 {
        let e = cs[k - 1].end();
        if !reversed[k] && dist(&e, &cs[k].end()) < dist(&e, &cs[k].start()) {
            cs[k] = cs[k].reversed();
            reversed[k] = true;
        }
    }
    let mut gaps = [0.0; 4];
    let mut corners = [[0.0; 3]; 4];
    for k in 0..4 {
        let prev = &cs[(k + 3) % 4];
        let (e, s) = (prev.end(), cs[k].start());
        gaps[k] = dist(&e, &s);
        if gaps[k].is_nan() || gaps[k] > closure {
            return Err(CoonsError::NotClosed {
                from: prev.name.clone(),
                to: cs[k].name.clone(),
                gap: gaps[k],
                closure,
            });
        }
        corners[k] = e.lerp(&s, &0.5);
    }
    let sides: [BoundaryCurve; 4] = match cs.try_into() {
        Ok(s) => s,
        Err(_) => return Err(CoonsError::Boundary("expected 4 boundary curves".into())),
    };
    let lp = Loop {
        sides,
        corners,
        gaps,
        reversed,
        perimeter,
    };
    check_crossing(&lp)?;
    Ok(lp)
}

/// The loop's polygon (at most 128 segments per side) seen along its Newell normal: no two
/// non-adjacent segments may meet.
fn check_crossing(lp: &Loop) -> Result<(), CoonsError> {
    let mut poly: Vec<([f64; 3], usize)> = Vec::new();
    for k in 0..4 {
        let s = &lp.sides[k];
        let n = s.samples.len() - 1;
        let step = n.div_ceil(128).max(1);
        poly.push((lp.corners[k], k));
        let mut i = step;
        while i < n {
            poly.push((s.samples[i], k));
            i += step;
        }
    }
    let mut normal = [0.0; 3];
    for i in 0..poly.len() {
        let (p, q) = (&poly[i].0, &poly[(i + 1) % poly.len()].0);
        normal = normal.add(&cross(p, q));
    }
    let nn = norm(&normal);
    if nn.is_nan() || nn <= 1e-12 * lp.perimeter * lp.perimeter {
        return Err(CoonsError::Flat(lp.names()));
    }
    let z = normal.scale(&(1.0 / nn));
    let helper = if z[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let e1 = cross(&z, &helper);
    let e1 = e1.scale(&(1.0 / norm(&e1)));
    let e2 = cross(&z, &e1);
    let pts: Vec<[f64; 2]> = poly
        .iter()
        .map(|(p, _)| [dot(p, &e1), dot(p, &e2)])
        .collect();
    let m = pts.len();
    for i in 0..m {
        let (a, b) = (&pts[i], &pts[(i + 1) % m]);
        for j in i + 2..m {
            if i == 0 && j == m - 1 {
                continue;
            }
            let (c, d) = (&pts[j], &pts[(j + 1) % m]);
            if segments_meet(a, b, c, d) {
                return Err(CoonsError::SelfCrossing {
                    a: lp.sides[poly[i].1].name.clone(),
                    b: lp.sides[poly[j].1].name.clone(),
                });
            }
        }
    }
    Ok(())
}

/// Whether closed segments `ab` and `cd` share a point (exact orientation signs).
fn segments_meet(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2], d: &[f64; 2]) -> bool {
    let (o1, o2) = (orient2d(a, b, c), orient2d(a, b, d));
    let (o3, o4) = (orient2d(c, d, a), orient2d(c, d, b));
    let within = |p: &[f64; 2], q: &[f64; 2], r: &[f64; 2]| {
        (0..2).all(|k| r[k] >= p[k].min(q[k]) && r[k] <= p[k].max(q[k]))
    };
    if o1 != o2
        && o3 != o4
        && o1 != Sign::Zero
        && o2 != Sign::Zero
        && o3 != Sign::Zero
        && o4 != Sign::Zero
    {
        return true;
    }
    (o1 == Sign::Zero && within(a, b, c))
        || (o2 == Sign::Zero && within(a, b, d))
        || (o3 == Sign::Zero && within(c, d, a))
        || (o4 == Sign::Zero && within(c, d, b))
}
