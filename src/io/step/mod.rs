//! STEP (ISO 10303-21) reader and writer for AP203/AP214/AP242 geometry: B-spline surfaces
//! and curves (simple and rational complex instances), planes, cylindrical, conical,
//! spherical and toroidal surfaces, surfaces of revolution and linear extrusion (all
//! converted exactly to NURBS with their placements), ADVANCED_FACE / FACE_SURFACE to list
//! faces, and length units. Any schema name is accepted: the geometry entities are the same.
//!
//! Faces are the ADVANCED_FACE/FACE_SURFACE instances; a file without faces (a bare patch
//! set) contributes every surface instance that no other surface references. Analytic
//! surfaces take their extent from the face's boundary points (planes: the bounding
//! rectangle in the plane; cylinders and cones: the axial range, full turn); spheres and tori
//! are full. Anything skipped is counted in the model's warnings, and every surface and
//! curve instance has its outcome in the model's accounts (`account`).

mod account;
mod assembly;
mod edge_curve;
mod entities;
mod occurrences;
pub mod part21;
mod shells;
mod topology;
mod transform_operator;
mod units;
use entities::Reader;
use units::unit;
pub mod write;
mod write_topology;

use crate::brep::IssueKind;
use crate::model::{Curve, CurveGeometry, Model, Outcome, Surface};
use std::collections::{BTreeMap, BTreeSet};

/// A fault in a STEP file: where and why.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{file}: {location}: {reason}")]
pub struct StepError {
    pub file: String,
    /// `line N` for syntax faults, `#N` for an entity.
    pub location: String,
    pub reason: String,
}

/// Surface entities that are recognised but not converted (reported when a bare patch set
/// holds them).
const UNSUPPORTED_SURFACES: [&str; 3] = [
    "OFFSET_SURFACE",
    "CURVE_BOUNDED_SURFACE",
    "DEGENERATE_TOROIDAL_SURFACE",
];

const SURFACE_TYPES: [&str; 9] = [
    "B_SPLINE_SURFACE_WITH_KNOTS",
    "RECTANGULAR_TRIMMED_SURFACE",
    "PLANE",
    "CYLINDRICAL_SURFACE",
    "CONICAL_SURFACE",
    "SPHERICAL_SURFACE",
    "TOROIDAL_SURFACE",
    "SURFACE_OF_REVOLUTION",
    "SURFACE_OF_LINEAR_EXTRUSION",
];

/// Largest vertex-to-curve distance accepted without a report: the file's length
/// uncertainty (`uncertainty_measure_with_unit` of a `length_measure`), but at least `1e-9`
/// times the diagonal of the box of all 3D points (files declare uncertainties like
/// `1e-17` that f64 coordinates cannot meet).
fn vertex_tolerance(p: &part21::Part21) -> f64 {
    let mut unc: f64 = 0.0;
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for (_, e) in p.entities.insts() {
        if let Some(a) = e.part("UNCERTAINTY_MEASURE_WITH_UNIT")
            && let Some((name, t)) = a.first().and_then(|v| v.typed())
            && name == "LENGTH_MEASURE"
            && let Some(x) = t.first().and_then(|x| x.num())
            && x.is_finite()
        {
            unc = unc.max(x);
        }
        if let Some(a) = e.part("CARTESIAN_POINT")
            && let Some(c) = a.get(1).and_then(|v| v.list_numbers())
            && c.len() == 3
        {
            for (i, x) in c.into_iter().enumerate() {
                if let Some(x) = x {
                    lo[i] = lo[i].min(x);
                    hi[i] = hi[i].max(x);
                }
            }
        }
    }
    let d: f64 = (0..3)
        .map(|i| (hi[i] - lo[i]).max(0.0).powi(2))
        .sum::<f64>()
        .sqrt();
    unc.max(1e-9 * if d.is_finite() { d } else { 0.0 })
}

/// Read STEP text. `file` names the source in errors and warnings.
pub fn from_str(text: &str, file: &str) -> Result<Model, StepError> {
    from_str_with(text, file, crate::io::ReadOptions::current())
}

/// [`from_str`] with explicit options (skip invalid faces or refuse the file).
pub fn from_str_with(
    text: &str,
    file: &str,
    opt: crate::io::ReadOptions,
) -> Result<Model, StepError> {
    from_part21(parse_text(text, file)?, file, opt)
}

/// A syntax fault of `file` as a [`StepError`] naming its line.
fn syntax(e: part21::SyntaxError, file: &str) -> StepError {
    StepError {
        file: file.into(),
        location: format!("line {}", e.line),
        reason: e.reason,
    }
}

/// The Part 21 table of STEP text; a syntax fault names its line.
fn parse_text(text: &str, file: &str) -> Result<part21::Part21, StepError> {
    part21::parse(text).map_err(|e| syntax(e, file))
}

/// The model of a parsed STEP file: everything read from the table, which is then dropped
/// before the assembly's occurrences are placed.
fn from_part21(
    p: part21::Part21,
    file: &str,
    opt: crate::io::ReadOptions,
) -> Result<Model, StepError> {
    let read = read_table(&p, file, opt)?;
    drop(p);
    Ok(read.finish())
}

/// What [`read_table`] found; [`TableRead::finish`] makes the model of it.
struct TableRead {
    model: Model,
    tree: Option<assembly::Tree>,
    /// Metres per unit of the representation contexts' distinct length units.
    lengths: Vec<f64>,
    /// Warnings that follow the assembly's.
    later: Vec<String>,
}

impl TableRead {
    fn finish(self) -> Model {
        let TableRead {
            mut model,
            tree,
            lengths,
            later,
        } = self;
        if let Some(tree) = tree {
            occurrences::apply(&mut model, tree);
        }
        if lengths.len() > 1 && model.brep.as_ref().is_none_or(|b| b.occurrences.is_empty()) {
            model.warnings.push(format!(
                "the representation contexts use {} length units ({} m); no product structure places them, so every item keeps its file numbers in the model's unit",
                lengths.len(),
                lengths.iter().map(|m| format!("{m:e}")).collect::<Vec<_>>().join(", ")
            ));
        }
        model.warnings.extend(later);
        let degenerate = model.degeneracy_warnings();
        model.warnings.extend(degenerate);
        model
    }
}

/// Everything the model takes from the table `p` (see [`from_part21`]).
fn read_table(
    p: &part21::Part21,
    file: &str,
    opt: crate::io::ReadOptions,
) -> Result<TableRead, StepError> {
    let (unit, angle_scale) = unit(p);
    let r = Reader {
        p,
        file,
        angle_scale,
    };
    let mut model = Model {
        unit,
        ..Model::default()
    };
    let faces: Vec<(u64, u64)> = p
        .entities
        .insts()
        .filter_map(|(id, e)| {
            let a = e.part("ADVANCED_FACE").or_else(|| e.part("FACE_SURFACE"))?;
            Some((id, a.get(2)?.reference()?))
        })
        .collect();
    // Entities referenced by a surface entity (a bare patch set's surfaces are the ones no
    // other surface uses, e.g. not the basis of an offset surface).
    let mut referenced = BTreeSet::new();
    if faces.is_empty() {
        for (_, e) in p.entities.insts() {
            if SURFACE_TYPES
                .iter()
                .chain(&UNSUPPORTED_SURFACES)
                .any(|t| e.is(t))
            {
                referenced.extend(e.refs());
            }
        }
    }
    let targets: Vec<(Option<u64>, u64)> = if !faces.is_empty() {
        faces.iter().map(|(f, s)| (Some(*f), *s)).collect()
    } else {
        p.entities
            .insts()
            .filter(|(id, e)| SURFACE_TYPES.iter().any(|t| e.is(t)) && !referenced.contains(id))
            .map(|(id, _)| (None, id))
            .collect()
    };
    // Surface entities of a bare patch set that this reader cannot convert: named, not
    // dropped silently.
    let mut skipped: BTreeMap<String, Vec<u64>> = BTreeMap::new();
    // What became of each visited surface and curve instance (the model's accounts).
    let mut outcomes: BTreeMap<u64, Outcome> = BTreeMap::new();
    if faces.is_empty() {
        for (id, e) in p.entities.insts() {
            if let Some(t) = UNSUPPORTED_SURFACES.iter().find(|t| e.is(t))
                && !SURFACE_TYPES.iter().any(|t| e.is(t))
                && !referenced.contains(&id)
            {
                skipped.entry(t.to_string()).or_default().push(id);
                outcomes.insert(id, Outcome::Unsupported(account::NOT_CONVERTED.into()));
            }
        }
    }
    // Model surface index of each face (for the B-rep), and why each face whose surface could
    // not be converted has none (an unsupported type, or invalid data skipped).
    let mut surface_of: BTreeMap<u64, usize> = BTreeMap::new();
    let mut no_surface: BTreeMap<u64, IssueKind> = BTreeMap::new();
    let mut invalid_faces = Vec::new();
    for (face, sid) in targets {
        let got = match r.surface(sid, face) {
            Ok(got) => got,
            Err(e) if opt.skip_invalid_faces => {
                outcomes.insert(sid, Outcome::Invalid(e.reason.clone()));
                if let Some(f) = face {
                    no_surface.insert(f, IssueKind::InvalidSurface(e.reason.clone()));
                }
                let what = face.map_or(format!("surface #{sid}"), |f| format!("face #{f}"));
                invalid_faces.push(format!("{what} ({}: {})", e.location, e.reason));
                continue;
            }
            Err(e) => return Err(e),
        };
        match got {
            Some((nurbs, kind)) => {
                if let Some(f) = face {
                    surface_of.insert(f, model.surfaces.len());
                }
                outcomes.insert(sid, Outcome::Converted);
                let reversed = face
                    .and_then(|f| p.entities.inst(f))
                    .and_then(|e| e.part("ADVANCED_FACE").or_else(|| e.part("FACE_SURFACE")))
                    .and_then(|a| a.get(3))
                    .and_then(|v| v.enumeration())
                    == Some("F");
                model.surfaces.push(Surface {
                    name: face.map_or(format!("#{sid}"), |f| format!("face #{f}")),
                    source: Some(format!("#{}", face.unwrap_or(sid))),
                    kind,
                    reversed,
                    ..Surface::new("", nurbs)
                })
            }
            None => {
                let ty = r.get(sid)?.name().to_string();
                if let Some(f) = face {
                    no_surface.insert(f, IssueKind::UnsupportedSurface(ty.clone()));
                }
                skipped.entry(ty).or_default().push(face.unwrap_or(sid));
                outcomes
                    .entry(sid)
                    .or_insert_with(|| Outcome::Unsupported(account::NOT_CONVERTED.into()));
            }
        }
    }
    if !faces.is_empty() {
        let brep =
            topology::TopologyReader::new(&r, vertex_tolerance(p)).read(&surface_of, &no_surface);
        model.warnings.extend(brep.report.warning_lines());
        model.brep = Some(brep);
        crate::brep::seams::warn(&mut model);
    }
    // The assembly is placed once the table is dropped (`TableRead::finish`).
    let tree = if faces.is_empty() {
        None
    } else {
        assembly::read(&r)
    };
    let lengths = units::context_lengths(p);
    // Free B-spline curves (not referenced by edges or surfaces are still listed); one
    // that cannot be read is reported with its id and reason.
    let mut bad_curves = Vec::new();
    for (id, e) in p.entities.insts() {
        if e.is(account::CURVE) {
            match r.bspline_curve(id, e) {
                Ok(c) => {
                    model.curves.push(Curve {
                        name: format!("#{id}"),
                        geometry: CurveGeometry::Space(c),
                    });
                    outcomes.insert(id, Outcome::Converted);
                }
                Err(e) => {
                    outcomes.insert(id, Outcome::Invalid(e.reason.clone()));
                    bad_curves.push(format!("{}: {}", e.location, e.reason))
                }
            }
        }
    }
    let mut later = Vec::new();
    for (k, ids) in skipped {
        later.push(format!(
            "{} surface(s) of type {k} not supported, skipped: {}",
            ids.len(),
            crate::model::list_ids(ids.iter().map(|i| format!("#{i}")))
        ));
    }
    for f in invalid_faces {
        later.push(format!("invalid {f}: skipped (--skip-invalid)"));
    }
    for b in bad_curves {
        later.push(format!("invalid B-spline curve skipped: {b}"));
    }
    model.accounts = account::account(p, &outcomes, model.brep.as_ref().map(|b| &b.report));
    for (_, e) in p.entities.insts() {
        let name = if e.is_complex() {
            format!("({})", e.parts().map(|x| x.0).collect::<Vec<_>>().join(" "))
        } else {
            e.name().to_string()
        };
        *model.source_entities.entry(name).or_insert(0) += 1;
    }
    Ok(TableRead {
        model,
        tree,
        lengths,
        later,
    })
}

/// Read a STEP file.
pub fn read(path: &std::path::Path) -> Result<Model, StepError> {
    let name = path.display().to_string();
    // Read and parsed piece by piece: the file's text is not held beside its table.
    let p = std::fs::File::open(path)
        .map_err(part21::ReadFault::Io)
        .and_then(part21::read)
        .map_err(|e| match e {
            part21::ReadFault::Syntax(e) => syntax(e, &name),
            part21::ReadFault::Io(e) => StepError {
                file: name.clone(),
                location: "(file)".into(),
                reason: e.to_string(),
            },
        })?;
    from_part21(p, &name, crate::io::ReadOptions::current())
}
