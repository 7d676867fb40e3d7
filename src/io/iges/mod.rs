//! IGES 5.3 reader and writer. Fixed 80-column S/G/D/P/T sections; delimiters from the Global
//! section; Hollerith strings; Fortran `D` exponents; transformation matrices (124) applied.
//!
//! Faces: the trimmed (144) and bounded (143) surfaces, the faces (510) of B-rep shells, and
//! every surface no face references (untrimmed patch sets). Surfaces: rational B-spline (128),
//! surface of revolution (120, full turn) and tabulated cylinder (122) converted exactly to
//! NURBS; generatrices and directrices from 126, 110 (line) and 100 (arc). Unsupported
//! entities are counted by type in the model's warnings, never dropped silently; every
//! directory entry has its outcome in the model's accounts (`account`).

mod account;
mod analytic;
pub mod parse;
mod topology;
mod trims;
pub mod write;
mod write_brep;

use crate::geom::Point;
use crate::model::{Curve, CurveGeometry, Model, Outcome, Surface, SurfaceKind};
use crate::spline::{NurbsCurve, NurbsSurface, construct};
use std::collections::{BTreeMap, BTreeSet};

/// A fault in an IGES file: where and why.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{file}: {location}: {reason}")]
pub struct IgesError {
    pub file: String,
    /// `line N`, `DE N` (directory entry) or `(file)`.
    pub location: String,
    pub reason: String,
}

pub use parse::{Entry, Param, Parsed, parse};

/// An affine map `x ↦ R x + T`.
type Affine = ([[f64; 3]; 3], [f64; 3]);

struct Reader<'a> {
    e: &'a BTreeMap<usize, Entry>,
    file: &'a str,
    /// Curve entities still allowed to be expanded (composite members count each time they
    /// are reached): nested composite curves that share members expand exponentially.
    budget: std::cell::Cell<usize>,
}

/// Expansion budget of a file: curve entities reached through composite curves and
/// boundaries, in total, at most this plus [`EXPANSION_PER_ENTITY`] per directory entry.
pub const EXPANSION_BASE: usize = 100_000;
/// See [`EXPANSION_BASE`].
pub const EXPANSION_PER_ENTITY: usize = 16;

type R<T> = Result<T, IgesError>;

impl Reader<'_> {
    fn err<T>(&self, de: usize, reason: impl Into<String>) -> R<T> {
        Err(IgesError {
            file: self.file.into(),
            location: format!("DE {de}"),
            reason: reason.into(),
        })
    }
    fn nums(&self, de: usize, from: usize, n: usize) -> R<Vec<f64>> {
        let p = &self.e[&de].params;
        (from..from + n)
            .map(|i| match p.get(i) {
                Some(Param::Num(x)) => Ok(*x),
                Some(Param::Empty) => Ok(0.0),
                _ => self.err(de, format!("parameter {i} missing or not a number")),
            })
            .collect()
    }
    fn ptr(&self, de: usize, i: usize) -> R<usize> {
        let v = self.nums(de, i, 1)?[0];
        if v < 1.0 || v.fract() != 0.0 || !self.e.contains_key(&(v as usize)) {
            return self.err(
                de,
                format!("parameter {i} is not a valid directory pointer ({v})"),
            );
        }
        Ok(v as usize)
    }
    /// The affine map of entity `de`'s transformation chain: `x ↦ R x + T`.
    fn transform(&self, de: usize) -> R<Option<Affine>> {
        let mut t = self.e[&de].transform;
        let mut acc: Option<Affine> = None;
        let mut guard = 0;
        while t != 0 {
            guard += 1;
            if guard > 64 || !self.e.contains_key(&t) || self.e[&t].etype != 124 {
                return self.err(de, "transformation pointer is not a chain of 124 entities");
            }
            let m = self.nums(t, 1, 12)?;
            let (r, tr) = (
                [[m[0], m[1], m[2]], [m[4], m[5], m[6]], [m[8], m[9], m[10]]],
                [m[3], m[7], m[11]],
            );
            // IGES prescribes a rotation (orthonormal R); scalings occur in practice and are
            // applied, but a singular map collapses the geometry and is refused.
            // Determinant of R scaled to largest entry 1 (no overflow for any finite R).
            let scale = r.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
            let q = r.map(|row| row.map(|x| x / scale));
            let det = q[0][0] * (q[1][1] * q[2][2] - q[1][2] * q[2][1])
                - q[0][1] * (q[1][0] * q[2][2] - q[1][2] * q[2][0])
                + q[0][2] * (q[1][0] * q[2][1] - q[1][1] * q[2][0]);
            if scale == 0.0 || det.abs() <= 1e-12 {
                return self.err(
                    de,
                    format!("transformation matrix DE {t} is singular or nearly so (entries up to {scale:e}, determinant relative to them {det:e}): it collapses the geometry"),
                );
            }
            // Apply the inner (entity's own) first, then the outer: acc = outer ∘ acc.
            acc = Some(match acc {
                None => (r, tr),
                Some((ar, at)) => {
                    let nr = std::array::from_fn(|i| {
                        std::array::from_fn(|j| (0..3).map(|k| r[i][k] * ar[k][j]).sum())
                    });
                    let nt = std::array::from_fn(|i| {
                        (0..3).map(|k| r[i][k] * at[k]).sum::<f64>() + tr[i]
                    });
                    (nr, nt)
                }
            });
            t = self.e[&t].transform;
        }
        Ok(acc)
    }
    fn apply(&self, de: usize, pts: &mut [[f64; 3]]) -> R<()> {
        if let Some((r, t)) = self.transform(de)? {
            for (k, p) in pts.iter_mut().enumerate() {
                let q: [f64; 3] = std::array::from_fn(|i| {
                    r[i][0] * p[0] + r[i][1] * p[1] + r[i][2] * p[2] + t[i]
                });
                if !q.iter().all(|x| x.is_finite()) {
                    return self.err(
                        de,
                        format!(
                            "transformation DE {} maps control point {k} ({:e}, {:e}, {:e}) to a non-finite point",
                            self.e[&de].transform, p[0], p[1], p[2]
                        ),
                    );
                }
                *p = q;
            }
        }
        Ok(())
    }
    fn b128(&self, de: usize) -> R<NurbsSurface<f64, 3>> {
        let h = self.nums(de, 1, 4)?;
        let (k1, k2, m1, m2) = (h[0] as usize, h[1] as usize, h[2] as usize, h[3] as usize);
        if k1 > 10_000 || k2 > 10_000 || m1 > 64 || m2 > 64 {
            return self.err(de, "implausible control-net size or degree");
        }
        let (nu, nv) = (k1 + 1, k2 + 1);
        let mut i = 10;
        let ku = self.nums(de, i, k1 + m1 + 2)?;
        i += k1 + m1 + 2;
        let kv = self.nums(de, i, k2 + m2 + 2)?;
        i += k2 + m2 + 2;
        let w = self.nums(de, i, nu * nv)?;
        i += nu * nv;
        let c = self.nums(de, i, 3 * nu * nv)?;
        let mut pts: Vec<[f64; 3]> = vec![[0.0; 3]; nu * nv];
        let mut ws = vec![0.0; nu * nv];
        for jv in 0..nv {
            for iu in 0..nu {
                let k = iu + jv * nu;
                pts[iu * nv + jv] = [c[3 * k], c[3 * k + 1], c[3 * k + 2]];
                ws[iu * nv + jv] = w[k];
            }
        }
        self.apply(de, &mut pts)?;
        NurbsSurface::new(ku, m1, kv, m2, nu, nv, pts, ws).or_else(|e| self.err(de, e.to_string()))
    }
    /// A curve entity (126, 110, 100) as a NURBS curve in model space.
    fn curve(&self, de: usize) -> R<Option<NurbsCurve<f64, 3>>> {
        let e = &self.e[&de];
        let c = match e.etype {
            126 => {
                let h = self.nums(de, 1, 2)?;
                let (k, m) = (h[0] as usize, h[1] as usize);
                if k > 100_000 || m > 64 {
                    return self.err(de, "implausible curve size or degree");
                }
                let knots = self.nums(de, 7, k + m + 2)?;
                let w = self.nums(de, 7 + k + m + 2, k + 1)?;
                let c = self.nums(de, 7 + k + m + 2 + k + 1, 3 * (k + 1))?;
                let mut pts: Vec<[f64; 3]> = c.chunks(3).map(|p| [p[0], p[1], p[2]]).collect();
                self.apply(de, &mut pts)?;
                NurbsCurve::new(knots, m, pts, w).or_else(|e| self.err(de, e.to_string()))?
            }
            110 => {
                let v = self.nums(de, 1, 6)?;
                let mut pts = vec![[v[0], v[1], v[2]], [v[3], v[4], v[5]]];
                self.apply(de, &mut pts)?;
                NurbsCurve::new(vec![0.0, 0.0, 1.0, 1.0], 1, pts, vec![1.0, 1.0])
                    .or_else(|e| self.err(de, e.to_string()))?
            }
            100 => {
                let v = self.nums(de, 1, 7)?;
                let (zt, c, st, en) = (v[0], [v[1], v[2]], [v[3], v[4]], [v[5], v[6]]);
                let r = ((st[0] - c[0]).powi(2) + (st[1] - c[1]).powi(2)).sqrt();
                if r.is_nan() || r <= 0.0 {
                    return self.err(de, "arc of zero radius");
                }
                let a0 = (st[1] - c[1]).atan2(st[0] - c[0]);
                let mut a1 = (en[1] - c[1]).atan2(en[0] - c[0]);
                while a1 <= a0 + 1e-15 {
                    a1 += std::f64::consts::TAU;
                }
                let f = construct::Frame {
                    o: [c[0], c[1], zt],
                    x: [1.0, 0.0, 0.0],
                    y: [0.0, 1.0, 0.0],
                    z: [0.0, 0.0, 1.0],
                };
                let mut arc =
                    construct::arc(&f, r, a0, a1).or_else(|e| self.err(de, e.to_string()))?;
                let (mut pts, w) = arc.points_weights();
                self.apply(de, &mut pts)?;
                arc = NurbsCurve::new(arc.hom.knots.knots().to_vec(), 2, pts, w)
                    .or_else(|e| self.err(de, e.to_string()))?;
                arc
            }
            _ => return Ok(None),
        };
        Ok(Some(c))
    }
    /// A curve or composite curve (102) as its list of segments; `None` for unsupported
    /// members.
    fn segments(&self, de: usize, depth: usize) -> R<Option<Vec<NurbsCurve<f64, 3>>>> {
        if depth > 16 {
            return self.err(de, "composite curves nested too deeply");
        }
        match self.budget.get().checked_sub(1) {
            Some(b) => self.budget.set(b),
            None => {
                return self.err(
                    de,
                    format!(
                        "composite curves expand to more curve segments than the file's expansion budget ({} + {} per entity = {}): members are shared too often",
                        EXPANSION_BASE,
                        EXPANSION_PER_ENTITY,
                        EXPANSION_BASE + EXPANSION_PER_ENTITY * self.e.len()
                    ),
                );
            }
        }
        if self.e[&de].etype == 102 {
            let n = self.nums(de, 1, 1)?[0] as usize;
            let mut out = Vec::new();
            for k in 0..n.min(100_000) {
                match self.segments(self.ptr(de, 2 + k)?, depth + 1)? {
                    Some(v) => out.extend(v),
                    None => return Ok(None),
                }
            }
            return Ok(Some(out));
        }
        Ok(self.curve(de)?.map(|c| vec![c]))
    }
    /// `s` (built in the definition space of entity `de` from its member curves) moved by
    /// `de`'s own transformation (124) into model space: the control points mapped, exact
    /// for NURBS (affine invariance).
    fn placed(&self, de: usize, s: NurbsSurface<f64, 3>) -> R<NurbsSurface<f64, 3>> {
        if self.e[&de].transform == 0 {
            return Ok(s);
        }
        let (mut pts, w) = s.points_weights();
        self.apply(de, &mut pts)?;
        let h = &s.hom;
        NurbsSurface::new(
            h.ku.knots().to_vec(),
            h.ku.degree(),
            h.kv.knots().to_vec(),
            h.kv.degree(),
            h.ku.n_ctrl(),
            h.kv.n_ctrl(),
            pts,
            w,
        )
        .or_else(|e| self.err(de, e.to_string()))
    }
    /// The NURBS form of surface entity `de`; `face`: the face using it (unbounded analytic
    /// surfaces span its points).
    fn surface(&self, de: usize, face: usize) -> R<Option<(NurbsSurface<f64, 3>, SurfaceKind)>> {
        if analytic::ANALYTIC.contains(&self.e[&de].etype) {
            let pts = match self.e[&face].etype {
                _ if face == de => vec![],
                510 => self.face_points(face),
                143 | 144 => self
                    .space_loops(face)?
                    .into_iter()
                    .flatten()
                    .flat_map(|l| l.curves)
                    .flat_map(|(_, c)| c.points_weights().0)
                    .collect(),
                _ => vec![],
            };
            return self.analytic(de, &pts);
        }
        match self.e[&de].etype {
            128 => Ok(Some((self.b128(de)?, SurfaceKind::BSpline))),
            120 => {
                let axis = self.ptr(de, 1)?;
                let generatrix = self.ptr(de, 2)?;
                let (Some(a), Some(g)) = (self.curve(axis)?, self.curve(generatrix)?) else {
                    return Ok(None);
                };
                let (ap, _) = a.points_weights();
                let d = ap[ap.len() - 1].sub(&ap[0]);
                let l = crate::geom::norm(&d);
                if l == 0.0 || !l.is_finite() {
                    return self.err(
                        de,
                        format!("axis DE {axis} has length {l:e}: not a usable direction"),
                    );
                }
                // SA, TA (parameters 3, 4 of the 120): the angular range, radians.
                let sa = self.nums(de, 3, 2)?;
                let (sa, ta) = (
                    sa[0],
                    if sa[1] > sa[0] {
                        sa[1]
                    } else {
                        sa[0] + std::f64::consts::TAU
                    },
                );
                let s = construct::revolve_curve_range(&ap[0], &d.scale(&(1.0 / l)), &g, sa, ta)
                    .or_else(|e| self.err(de, e.to_string()))?;
                Ok(Some((self.placed(de, s)?, SurfaceKind::Revolution)))
            }
            122 => {
                let dir = self.ptr(de, 1)?;
                let Some(c) = self.curve(dir)? else {
                    return Ok(None);
                };
                let end = self.nums(de, 2, 3)?;
                let start = c.eval(&c.hom.domain().0);
                let s = construct::extrude(
                    &c,
                    &[end[0] - start[0], end[1] - start[1], end[2] - start[2]],
                )
                .or_else(|e| self.err(de, e.to_string()))?;
                Ok(Some((self.placed(de, s)?, SurfaceKind::Extrusion)))
            }
            _ => Ok(None),
        }
    }
}

const SURFACES: [i64; 9] = [128, 120, 122, 108, 190, 192, 194, 196, 198];

/// Read IGES text.
pub fn from_str(text: &str, file: &str) -> Result<Model, IgesError> {
    from_str_with(text, file, crate::io::ReadOptions::current())
}

/// [`from_str`] with explicit options (skip invalid faces or refuse the file).
pub fn from_str_with(
    text: &str,
    file: &str,
    opt: crate::io::ReadOptions,
) -> Result<Model, IgesError> {
    let (e, unit, resolution, mut warnings, no_params) = parse(text, file)?;
    let r = Reader {
        e: &e,
        file,
        budget: std::cell::Cell::new(EXPANSION_BASE + EXPANSION_PER_ENTITY * e.len()),
    };
    let mut model = Model {
        unit,
        ..Model::default()
    };
    // Faces and the surfaces they use.
    let mut faces: Vec<(usize, usize)> = Vec::new();
    let mut used = BTreeSet::new();
    for (de, x) in &e {
        let sp = match x.etype {
            144 => Some(r.ptr(*de, 1)?),
            143 => Some(r.ptr(*de, 2)?),
            510 => Some(r.ptr(*de, 1)?),
            _ => None,
        };
        if let Some(s) = sp {
            faces.push((*de, s));
            used.insert(s);
        }
    }
    for (de, x) in &e {
        if SURFACES.contains(&x.etype) && !used.contains(de) {
            // Surfaces referenced as generatrix-free parts are faces of an untrimmed patch set.
            faces.push((*de, *de));
        }
    }
    faces.sort();
    let mut skipped: BTreeMap<i64, usize> = BTreeMap::new();
    // What became of each visited entry (the model's accounts).
    let mut outcomes: BTreeMap<usize, Outcome> = BTreeMap::new();
    // Model surface index of each face DE (the B-rep's faces refer to them).
    let mut surface_of: BTreeMap<usize, usize> = BTreeMap::new();
    let mut invalid_faces = Vec::new();
    for (face, s) in faces {
        // With --skip-invalid a face whose surface or trims are invalid is skipped and
        // accounted; an exhausted expansion budget still refuses the file.
        let skip = |e: IgesError, outcomes: &mut BTreeMap<usize, Outcome>, surface_bad: bool| {
            if !opt.skip_invalid_faces || r.budget.get() == 0 {
                return Err(e);
            }
            outcomes.insert(face, Outcome::Invalid(e.reason.clone()));
            if s != face && surface_bad {
                outcomes.insert(s, Outcome::Invalid(e.reason.clone()));
            } else if s != face {
                outcomes.entry(s).or_insert(Outcome::Used);
            }
            Ok(format!("face DE {face} ({}: {})", e.location, e.reason))
        };
        let got = match r.surface(s, face) {
            Ok(got) => got,
            Err(e) => {
                invalid_faces.push(skip(e, &mut outcomes, true)?);
                continue;
            }
        };
        match got {
            Some((nurbs, kind)) => {
                // Parameter-space curves are in IGES's parametrization of the surface, which
                // is the NURBS form's only for B-spline surfaces and those built from curves.
                let trims = if kind.is_analytic() && analytic::ANALYTIC.contains(&e[&s].etype) {
                    Ok((vec![], 0))
                } else {
                    r.trims(face)
                };
                let (trim_loops, missing) = match trims {
                    Ok(t) => t,
                    Err(e) => {
                        invalid_faces.push(skip(e, &mut outcomes, false)?);
                        continue;
                    }
                };
                outcomes.insert(face, Outcome::Converted);
                if s != face {
                    outcomes.entry(s).or_insert(Outcome::Used);
                }
                surface_of.insert(face, model.surfaces.len());
                // A 510 face's loops are kept in the B-rep whatever their parameter-space curves.
                if missing > 0 && e[&face].etype != 510 {
                    warnings.push(format!("DE {face}: {missing} boundary(ies) without a parameter-space curve, not kept as trims"));
                }
                model.surfaces.push(Surface {
                    name: format!("DE {face}"),
                    source: Some(format!("DE {face}")),
                    kind,
                    trim_loops,
                    ..Surface::new("", nurbs)
                })
            }
            None => {
                *skipped.entry(e[&s].etype).or_insert(0) += 1;
                let note = format!(
                    "{} (surface DE {s}, type {})",
                    account::NOT_CONVERTED,
                    e[&s].etype
                );
                outcomes.insert(face, Outcome::Unsupported(note.clone()));
                outcomes.entry(s).or_insert(Outcome::Unsupported(note));
            }
        }
    }
    for (de, x) in &e {
        if x.etype == 126
            && !x.dependent()
            && let Some(c) = r.curve(*de)?
        {
            model.curves.push(Curve {
                name: format!("DE {de}"),
                geometry: CurveGeometry::Space(c),
            });
            outcomes.insert(*de, Outcome::Converted);
        }
    }
    let known = [
        100, 102, 104, 106, 110, 116, 120, 122, 123, 124, 126, 128, 141, 142, 143, 144, 186, 190,
        192, 194, 196, 198, 212, 314, 402, 406, 502, 504, 508, 510, 514,
    ];
    let mut other: BTreeMap<i64, usize> = BTreeMap::new();
    for x in e.values() {
        if !known.contains(&x.etype) {
            *other.entry(x.etype).or_insert(0) += 1;
        }
    }
    for f in invalid_faces {
        warnings.push(format!("invalid {f}: skipped (--skip-invalid)"));
    }
    for (t, n) in skipped {
        warnings.push(format!(
            "{n} face surface(s) of entity type {t} not supported, skipped"
        ));
    }
    for (t, n) in other {
        warnings.push(format!("{n} entit(ies) of type {t} not supported, skipped"));
    }
    // The file's resolution, but at least 1e-9 times the diagonal of the control points' box
    // (as for STEP's uncertainty).
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in model
        .surfaces
        .iter()
        .flat_map(|s| s.nurbs.points_weights().0)
    {
        for i in 0..3 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    let size = crate::geom::dist(&lo, &hi);
    let size = if size.is_finite() { size } else { 0.0 };
    let tolerance = resolution.unwrap_or(0.0).max(1e-9 * size);
    if e.values().any(|x| x.etype == 510) {
        model.brep = Some(topology::read(&r, &surface_of, tolerance));
    } else if !surface_of.is_empty()
        && surface_of.len() == model.surfaces.len()
        && surface_of.keys().all(|f| matches!(e[f].etype, 143 | 144))
    {
        // Trimmed and bounded faces only: sewn into a B-rep by their model-space boundaries.
        let sew_tol = tolerance.max(1e-7 * size);
        if let Some((b, st)) = sewn(&r, &surface_of, sew_tol)? {
            warnings.push(format!(
                "B-rep sewn from the {} faces' boundary curves (tolerance {sew_tol:e}): {} edge(s) shared by two faces, {} free, {} used more than twice, {} degenerate piece(s) left out",
                b.faces.len(),
                st.shared,
                st.free,
                st.more,
                st.degenerate
            ));
            model.brep = Some(b);
        } else {
            warnings.push(
                "no B-rep: a face boundary has no model-space curve (or one not converted); faces keep their parameter-space trims".into(),
            );
        }
    }
    if let Some(b) = &model.brep {
        warnings.extend(b.report.warning_lines());
    }
    let from_topology = model.brep.is_some() && e.values().any(|x| x.etype == 510);
    model.accounts = account::account(&e, &outcomes, from_topology, &no_params);
    warnings.extend(model.degeneracy_warnings());
    model.warnings = warnings;
    for x in e.values() {
        *model
            .source_entities
            .entry(format!("{} (form {})", x.etype, x.form))
            .or_insert(0) += 1;
    }
    Ok(model)
}

/// The B-rep of a file of trimmed (144) and bounded (143) faces, sewn by their model-space
/// boundary curves; `None` when a face's boundary has none.
fn sewn(
    r: &Reader,
    surface_of: &BTreeMap<usize, usize>,
    tol: f64,
) -> R<Option<(crate::brep::Brep, crate::brep::sew::SewStats)>> {
    let mut faces = Vec::with_capacity(surface_of.len());
    for (f, si) in surface_of {
        let Some(loops) = r.space_loops(*f)? else {
            return Ok(None);
        };
        let s = r.ptr(*f, if r.e[f].etype == 143 { 2 } else { 1 })?;
        faces.push(crate::brep::sew::FaceBoundary {
            source: format!("DE {f}"),
            surface: *si,
            surface_source: format!("DE {s}"),
            loops,
        });
    }
    Ok(Some(crate::brep::sew::sew(&faces, tol)))
}

/// Read an IGES file.
pub fn read(path: &std::path::Path) -> Result<Model, IgesError> {
    let name = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|e| IgesError {
        file: name.clone(),
        location: "(file)".into(),
        reason: e.to_string(),
    })?;
    from_str(&String::from_utf8_lossy(&bytes), &name)
}
