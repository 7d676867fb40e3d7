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
mod geometry;
pub mod parse;
mod preferred;
mod topology;
mod trims;
pub mod write;
mod write_brep;
mod write_faces;

use crate::model::{Curve, CurveGeometry, Model, Outcome, Surface};
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
        crate::brep::seams::warn(&mut model);
    } else if !surface_of.is_empty()
        && surface_of.len() == model.surfaces.len()
        && surface_of.keys().all(|f| matches!(e[f].etype, 143 | 144))
    {
        // Trimmed and bounded faces only: sewn into a B-rep by their model-space boundaries.
        let sew_tol = tolerance.max(1e-7 * size);
        let mut notes = trims::PreferredNotes::default();
        let got = sewn(&r, (&surface_of, &model.surfaces), sew_tol, &mut notes)?;
        if !notes.mapped.is_empty() {
            warnings.push(format!(
                "{} trim boundar(ies) built on their surface from the parameter-space curve, which the file prefers (142 PREF = 1) or gives alone: {}",
                notes.mapped.len(),
                crate::model::list_ids(notes.mapped)
            ));
        }
        if !notes.kept.is_empty() {
            warnings.push(format!(
                "{} trim boundar(ies) prefer their parameter-space curve (142 PREF = 1) but could not be mapped onto the surface: {}",
                notes.kept.len(),
                notes.kept.iter().take(5).cloned().collect::<Vec<_>>().join("; ")
                    + &if notes.kept.len() > 5 {
                        format!("; and {} more", notes.kept.len() - 5)
                    } else {
                        String::new()
                    }
            ));
        }
        if let Some((b, st)) = got {
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
    (surface_of, surfaces): (&BTreeMap<usize, usize>, &[crate::model::Surface]),
    tol: f64,
    notes: &mut trims::PreferredNotes,
) -> R<Option<(crate::brep::Brep, crate::brep::sew::SewStats)>> {
    let mut faces = Vec::with_capacity(surface_of.len());
    for (f, si) in surface_of {
        // Faces with parameter-space trims have their surface in the trims' parametrization.
        let surface = surfaces
            .get(*si)
            .filter(|s| !s.trim_loops.is_empty())
            .map(|s| &s.nurbs);
        let Some(loops) = r.space_loops(*f, surface, notes)? else {
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
