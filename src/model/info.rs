//! A readable summary of a model: what `vericad info` prints.

use super::{CurveGeometry, Model};
use crate::geom::Aabb;
use serde::Serialize;

/// Summary of one surface.
#[derive(Clone, Debug, Serialize)]
pub struct SurfaceInfo {
    pub index: usize,
    pub name: String,
    pub degree: [usize; 2],
    pub control_net: [usize; 2],
    pub rational: bool,
    pub kind: super::SurfaceKind,
    pub source: Option<String>,
    pub domain: [f64; 4],
    /// Bounding box of the control net (contains the surface: convex hull property); `None`
    /// for a net with no finite box (a model built without [`super::Model::validate`]).
    pub bbox: Option<[[f64; 3]; 2]>,
}

/// Summary of one curve.
#[derive(Clone, Debug, Serialize)]
pub struct CurveInfo {
    pub index: usize,
    pub name: String,
    /// `"domain"` (u, v) or `"space"`.
    pub kind: &'static str,
    pub degree: usize,
    pub control_points: usize,
    pub rational: bool,
    pub domain: [f64; 2],
}

/// Summary of a model.
#[derive(Clone, Debug, Serialize)]
pub struct ModelInfo {
    pub unit: Option<String>,
    pub surfaces: Vec<SurfaceInfo>,
    pub curves: Vec<CurveInfo>,
    pub patch_sets: usize,
    /// Bounding box of all surface control nets.
    pub bbox: Option<[[f64; 3]; 2]>,
    /// Faces/surfaces by source kind (B-spline, plane, sphere, ...).
    pub surfaces_by_kind: std::collections::BTreeMap<String, usize>,
    /// Surfaces by degree `"p x q"`.
    pub surfaces_by_degree: std::collections::BTreeMap<String, usize>,
    pub bspline_rational: usize,
    pub bspline_polynomial: usize,
    pub analytic: usize,
    pub warnings: Vec<String>,
    /// Entity counts by type in the source file.
    pub source_entities: std::collections::BTreeMap<String, usize>,
    /// Triangulations: (name, vertices, triangles).
    pub triangulations: Vec<(String, usize, usize)>,
    /// Counts of the B-rep (faces, loops, edges, vertices, shells, solids), when the source
    /// has topology.
    pub topology: Option<crate::brep::BrepCounts>,
    /// What the reader did with each topology and edge-geometry entity (converted,
    /// unsupported, invalid, not read; with ids) and the topology issues.
    pub topology_report: Option<crate::brep::BrepReport>,
    /// The assembly tree (depth-first), when the source has one: each occurrence with its
    /// product, motion and placed solids and shells.
    pub assembly: Vec<crate::brep::Occurrence>,
    /// Trimmed area of each B-rep face (filled by callers that triangulate the faces).
    pub face_areas: Vec<FaceArea>,
    /// Whether each edge lies on the faces that use it (filled by callers that check).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub edge_checks: Option<crate::brep::edge_check::EdgeChecks>,
    /// What the reader did with each geometric entity, by source kind (empty for models not
    /// read from STEP or IGES).
    pub accounts: super::Accounting,
}

/// The trimmed area of one face, or why there is none.
#[derive(Clone, Debug, Serialize)]
pub struct FaceArea {
    /// Source id of the face.
    pub face: String,
    pub area: Option<f64>,
    pub note: Option<String>,
}

/// Summarize a model.
pub fn summarize(m: &Model) -> ModelInfo {
    let mut all: Option<Aabb<f64, 3>> = None;
    let surfaces = m
        .surfaces
        .iter()
        .enumerate()
        .map(|(index, s)| {
            let (pts, _) = s.nurbs.points_weights();
            let b = Aabb::of_points(pts.iter());
            match (&mut all, &b) {
                (Some(a), Some(b)) => {
                    a.include(&b.min);
                    a.include(&b.max);
                }
                (None, Some(b)) => all = Some(b.clone()),
                (_, None) => {}
            }
            let h = &s.nurbs.hom;
            let (u0, u1, v0, v1) = h.domain();
            SurfaceInfo {
                index,
                name: s.name.clone(),
                degree: [h.ku.degree(), h.kv.degree()],
                control_net: [h.nu(), h.nv()],
                rational: !s.nurbs.is_polynomial(),
                kind: s.kind,
                source: s.source.clone(),
                domain: [u0, u1, v0, v1],
                bbox: b.map(|b| [b.min, b.max]),
            }
        })
        .collect();
    let curves = m
        .curves
        .iter()
        .enumerate()
        .map(|(index, c)| {
            let (kind, degree, n, w, dom) = match &c.geometry {
                CurveGeometry::Domain(g) => (
                    "domain",
                    g.hom.degree(),
                    g.hom.control.len(),
                    g.points_weights().1,
                    g.hom.domain(),
                ),
                CurveGeometry::Space(g) => (
                    "space",
                    g.hom.degree(),
                    g.hom.control.len(),
                    g.points_weights().1,
                    g.hom.domain(),
                ),
            };
            CurveInfo {
                index,
                name: c.name.clone(),
                kind,
                degree,
                control_points: n,
                rational: w.iter().any(|x| *x != w[0]),
                domain: [dom.0, dom.1],
            }
        })
        .collect();
    let mut by_kind = std::collections::BTreeMap::new();
    for s in &m.surfaces {
        *by_kind.entry(format!("{:?}", s.kind)).or_insert(0) += 1;
    }
    let bs = |rational: bool| {
        m.surfaces
            .iter()
            .filter(|s| !s.kind.is_analytic() && s.nurbs.is_polynomial() != rational)
            .count()
    };
    let mut by_degree = std::collections::BTreeMap::new();
    for s in &m.surfaces {
        let (p, q) = s.nurbs.hom.degrees();
        *by_degree.entry(format!("{p}x{q}")).or_insert(0) += 1;
    }
    ModelInfo {
        unit: m.unit.clone(),
        surfaces_by_degree: by_degree,
        bspline_rational: bs(true),
        bspline_polynomial: bs(false),
        analytic: m.surfaces.iter().filter(|s| s.kind.is_analytic()).count(),
        surfaces_by_kind: by_kind,
        surfaces,
        curves,
        patch_sets: m.patch_sets.len(),
        bbox: all.map(|a| [a.min, a.max]),
        warnings: m.warnings.clone(),
        source_entities: m.source_entities.clone(),
        triangulations: m
            .triangulations
            .iter()
            .map(|t| (t.name.clone(), t.vertices.len(), t.triangles.len()))
            .collect(),
        topology: m.brep.as_ref().map(|b| b.counts()),
        topology_report: m.brep.as_ref().map(|b| b.report.clone()),
        assembly: m.brep.as_ref().map_or(vec![], |b| b.occurrences.clone()),
        face_areas: vec![],
        edge_checks: None,
        accounts: m.accounts.clone(),
    }
}

impl std::fmt::Display for ModelInfo {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(
            f,
            "{} surface(s), {} curve(s), {} patch set(s), unit: {}",
            self.surfaces.len(),
            self.curves.len(),
            self.patch_sets,
            self.unit.as_deref().unwrap_or("(none)")
        )?;
        writeln!(
            f,
            "  faces: {} B-spline ({} non-rational, {} rational), {} analytic (converted exactly to NURBS); by kind: {}",
            self.bspline_polynomial + self.bspline_rational,
            self.bspline_polynomial,
            self.bspline_rational,
            self.analytic,
            counts_text(&self.surfaces_by_kind)
        )?;
        if !self.source_entities.is_empty() {
            let mut top: Vec<_> = self.source_entities.iter().collect();
            top.sort_by(|a, b| b.1.cmp(a.1).then(a.0.cmp(b.0)));
            let shown: Vec<String> = top
                .iter()
                .take(12)
                .map(|(k, n)| format!("{k}: {n}"))
                .collect();
            writeln!(
                f,
                "  source entities ({} types): {}{}",
                top.len(),
                shown.join(", "),
                if top.len() > 12 { ", ..." } else { "" }
            )?;
        }
        for l in self.accounts.lines() {
            writeln!(f, "  geometry entities: {l}")?;
        }
        if let Some(t) = &self.topology {
            write!(f, "{t}")?;
        }
        if let Some(r) = &self.topology_report {
            let converted: Vec<String> = r
                .entities
                .iter()
                .filter(|(_, t)| t.converted > 0)
                .map(|(k, t)| format!("{k} {}", t.converted))
                .collect();
            writeln!(f, "  topology entities converted: {}", converted.join(", "))?;
        }
        if !self.assembly.is_empty() {
            writeln!(
                f,
                "  assembly: {} occurrence(s) (roots included), {} placed solid(s), {} placed shell(s)",
                self.assembly.len(),
                self.assembly.iter().map(|o| o.solids.len()).sum::<usize>(),
                self.assembly.iter().map(|o| o.shells.len()).sum::<usize>()
            )?;
            for o in &self.assembly {
                let r = &o.motion.rotation;
                writeln!(
                    f,
                    "    {:indent$}{} '{}' ({}): {} solid(s), {} shell(s); rotation rows {:?} {:?} {:?}, translation {:?}",
                    "",
                    o.source,
                    o.product,
                    o.definition,
                    o.solids.len(),
                    o.shells.len(),
                    r[0],
                    r[1],
                    r[2],
                    o.motion.translation,
                    indent = 2 * o.depth
                )?;
            }
        }
        if let Some(c) = &self.edge_checks {
            writeln!(
                f,
                "  edges on their faces: {} of {} edge-face pairs proven within {:.1e} (largest bound {:.1e}; pcurves' images against the edges), {} measured farther than that from their surfaces (evidence)",
                c.proven,
                c.pairs,
                c.tolerance,
                c.largest_bound,
                c.above_tolerance()
            )?;
            for x in &c.not_proven {
                writeln!(
                    f,
                    "  face {:<8} edge {:<8} not proven on its face{}{}{}",
                    x.face,
                    x.edge,
                    x.measured
                        .map(|m| format!(": samples up to {m:.2e} from the surface points found"))
                        .unwrap_or_default(),
                    if x.above_tolerance {
                        ", above the tolerance"
                    } else {
                        ""
                    },
                    match (x.bound, &x.unproven) {
                        (Some(b), _) => format!(" (proven bound {b:.2e})"),
                        (None, Some(w)) => format!(" ({w})"),
                        _ => String::new(),
                    }
                )?;
            }
        }
        if !self.face_areas.is_empty() {
            let total: f64 = self.face_areas.iter().filter_map(|a| a.area).sum();
            writeln!(
                f,
                "  trimmed area: {total} ({} of {} faces)",
                self.face_areas.iter().filter(|a| a.area.is_some()).count(),
                self.face_areas.len()
            )?;
            for a in &self.face_areas {
                match (a.area, &a.note) {
                    (Some(x), _) => writeln!(f, "  face {:<8} trimmed area {x}", a.face)?,
                    (None, n) => writeln!(
                        f,
                        "  face {:<8} no area: {}",
                        a.face,
                        n.as_deref().unwrap_or("")
                    )?,
                }
            }
        }
        for (n, v, t) in &self.triangulations {
            writeln!(
                f,
                "  triangulation '{n}': {v} vertices (welded), {t} triangles"
            )?;
        }
        if !self.surfaces_by_degree.is_empty() {
            writeln!(
                f,
                "  surfaces by degree: {}",
                counts_text(&self.surfaces_by_degree)
            )?;
        }
        for w in &self.warnings {
            writeln!(f, "  warning: {w}")?;
        }
        for s in &self.surfaces {
            writeln!(
                f,
                "  surface {:>3} {:<28} degree {}x{}  net {}x{}  {}  domain [{}, {}]x[{}, {}]",
                s.index,
                s.name,
                s.degree[0],
                s.degree[1],
                s.control_net[0],
                s.control_net[1],
                if s.rational { "rational" } else { "polynomial" },
                s.domain[0],
                s.domain[1],
                s.domain[2],
                s.domain[3]
            )?;
        }
        for c in &self.curves {
            writeln!(
                f,
                "  curve   {:>3} {:<28} {} curve, degree {}, {} control points, {}, t in [{}, {}]",
                c.index,
                c.name,
                c.kind,
                c.degree,
                c.control_points,
                if c.rational { "rational" } else { "polynomial" },
                c.domain[0],
                c.domain[1]
            )?;
        }
        if let Some(b) = self.bbox {
            writeln!(f, "  bounding box (control nets): {:?} .. {:?}", b[0], b[1])?;
        }
        Ok(())
    }
}

/// `"a 2, b 5"` for a map of counts (human output).
pub fn counts_text(m: &std::collections::BTreeMap<String, usize>) -> String {
    m.iter()
        .map(|(k, n)| format!("{k} {n}"))
        .collect::<Vec<_>>()
        .join(", ")
}
