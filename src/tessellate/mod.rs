//! Trimmed tessellation of a B-rep: every edge sampled once (its samples are the vertices
//! both faces use along it, so the mesh has no cracks), every face triangulated inside its
//! loops in its surface's parameter plane ([`face`]), and the face's trimmed area.
//!
//! The loops' parameter points come from projecting the edge samples onto the face's surface
//! (the files at hand carry no pcurves); seams and poles are handled in [`domain`]. This is
//! an approximation for viewing and meshing, not a certified quantity: its chordal error is
//! what the sampling gives (edge length `h`, at most π/12 of turn per segment), measured on
//! request ([`MeshParams::measure`]) and brought under a tolerance by [`chordal::mesh_within`].

pub mod bound;
pub mod chordal;
pub mod domain;
pub mod face;
pub mod outline;
pub mod polygons;
pub mod region;
pub mod simple;
pub mod surfaces;
pub mod trimmed;

use crate::brep::{Brep, LoopKind};
use crate::geom::dist;
use crate::model::{Model, Triangulation};
use domain::FaceSurface;

/// Sampling parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshParams {
    /// Target edge length as a fraction of the model's bounding-box diagonal.
    pub relative_edge: f64,
    /// Largest turn of a curve or iso-curve over one segment (radians).
    pub max_turn: f64,
    /// Measure the mesh's chordal deviation ([`BrepMesh::deviation`], [`chordal`]).
    pub measure: bool,
    /// With `measure`: also prove a bound on it ([`BrepMesh::bound`], [`bound`]; several
    /// interval evaluations per triangle).
    pub prove: bool,
}

impl Default for MeshParams {
    fn default() -> Self {
        MeshParams {
            relative_edge: 1.0 / 40.0,
            max_turn: std::f64::consts::PI / 12.0,
            measure: false,
            prove: false,
        }
    }
}

impl MeshParams {
    /// The finer sampling used for trimmed areas (edge length 1/150 of the diagonal, at
    /// most 3° of turn per segment).
    pub fn for_area() -> Self {
        MeshParams {
            relative_edge: 1.0 / 150.0,
            max_turn: std::f64::consts::PI / 60.0,
            measure: false,
            prove: false,
        }
    }
}

/// The triangulation of a B-rep with what it could not triangulate.
#[derive(Clone, Debug, Default)]
pub struct BrepMesh {
    pub triangulation: Triangulation,
    /// Per B-rep face: its triangles (a range of `triangulation.triangles`) and trimmed area,
    /// or why it has none.
    pub faces: Vec<Result<(std::ops::Range<usize>, f64), String>>,
    /// The largest measured chordal deviation of the triangles from their faces and of the
    /// edge segments from their curves (evidence: sampled, see [`chordal`]), when
    /// [`MeshParams::measure`] asked for it.
    pub deviation: Option<f64>,
    /// The largest distance of an edge's mesh point from a face's surface (at the point's
    /// projected parameters), when measured: edges that lie off their faces' surfaces (within
    /// the file's tolerance) put this floor under [`BrepMesh::deviation`].
    pub floor: Option<f64>,
    /// The largest proven chordal bound over the triangles that have one, and how many have
    /// none ([`bound`]), when [`MeshParams::prove`] asked for it.
    pub bound: Option<(f64, usize)>,
}

impl BrepMesh {
    /// One line per face without triangles, naming the face.
    pub fn issues(&self, brep: &Brep) -> Vec<String> {
        self.faces
            .iter()
            .zip(&brep.faces)
            .filter_map(|(r, f)| {
                r.as_ref()
                    .err()
                    .map(|e| format!("face {}: not triangulated: {e}", f.source))
            })
            .collect()
    }
}

/// Number of segments for a curve sampled at `pts`: length over `h`, turn over `max_turn`.
fn segments(pts: &[[f64; 3]], h: f64, max_turn: f64) -> usize {
    let len: f64 = pts
        .windows(2)
        .map(|w| crate::geom::dist(&w[0], &w[1]))
        .sum();
    let mut turn = 0.0;
    for w in pts.windows(3) {
        let (a, b) = (
            crate::geom::Point::sub(&w[1], &w[0]),
            crate::geom::Point::sub(&w[2], &w[1]),
        );
        let (la, lb) = (crate::geom::norm(&a), crate::geom::norm(&b));
        if la > 0.0 && lb > 0.0 {
            turn += (crate::geom::dot(&a, &b) / (la * lb))
                .clamp(-1.0, 1.0)
                .acos();
        }
    }
    ((len / h).ceil().max((turn / max_turn).ceil())).clamp(1.0, 2000.0) as usize
}

/// A sample point of an edge: its mesh vertex and position.
type Sample = (usize, [f64; 3]);

/// Every edge sampled once: its samples from start to end vertex (`None`: no 3D curve) and
/// the curve's points halfway (in its parameter) between consecutive samples. New sample
/// points are appended to `t.vertices`.
struct EdgeSamples {
    samples: Vec<Option<Vec<Sample>>>,
    halves: Vec<Vec<[f64; 3]>>,
}

fn sample_edges(brep: &Brep, h: f64, max_turn: f64, t: &mut Triangulation) -> EdgeSamples {
    let mut samples: Vec<Option<Vec<Sample>>> = Vec::with_capacity(brep.edges.len());
    let mut halves: Vec<Vec<[f64; 3]>> = Vec::with_capacity(brep.edges.len());
    for e in &brep.edges {
        let Some(c) = &e.curve else {
            samples.push(None);
            halves.push(vec![]);
            continue;
        };
        let (t0, t1) = c.nurbs.hom.domain();
        let probe: Vec<[f64; 3]> = (0..=256)
            .map(|i| c.nurbs.eval(&(t0 + (t1 - t0) * i as f64 / 256.0)))
            .collect();
        let n = segments(&probe, h, max_turn).max(1);
        let mut s = vec![(e.start, brep.vertices[e.start].point)];
        for i in 1..n {
            let p = c.nurbs.eval(&(t0 + (t1 - t0) * i as f64 / n as f64));
            t.vertices.push(p);
            s.push((t.vertices.len() - 1, p));
        }
        s.push((e.end, brep.vertices[e.end].point));
        samples.push(Some(s));
        halves.push(
            (0..n)
                .map(|i| {
                    c.nurbs
                        .eval(&(t0 + (t1 - t0) * (i as f64 + 0.5) / n as f64))
                })
                .collect(),
        );
    }
    EdgeSamples { samples, halves }
}

/// The loops of face `fi` projected into its parameter plane, and its vertex loop's vertex.
fn face_rings(
    brep: &Brep,
    fi: usize,
    es: &EdgeSamples,
    fs: &FaceSurface,
) -> Result<(Vec<domain::Ring>, Option<usize>), String> {
    let f = &brep.faces[fi];
    let mut rings = Vec::new();
    let mut vertex_loop = None;
    // Edges already traversed by this face's loops (a second traversal is a seam copy).
    let mut traversed = std::collections::BTreeSet::new();
    for l in &f.loops {
        match &l.kind {
            LoopKind::Vertex(v) => vertex_loop = Some(*v),
            LoopKind::Edges(edges) => {
                let mut pts: Vec<(usize, [f64; 3])> = Vec::new();
                let mut breaks: Vec<bool> = Vec::new();
                let mut mids: Vec<Option<[f64; 3]>> = Vec::new();
                let order: Vec<_> = if l.orientation {
                    edges.iter().map(|o| (o.edge, o.forward)).collect()
                } else {
                    edges.iter().rev().map(|o| (o.edge, !o.forward)).collect()
                };
                for (e, fwd) in order {
                    let Some(s) = &es.samples[e] else {
                        return Err(format!("edge {} has no curve", brep.edges[e].source));
                    };
                    let n = s.len();
                    let second = !traversed.insert(e);
                    let hv = &es.halves[e];
                    for k in 0..n - 1 {
                        pts.push(if fwd { s[k] } else { s[n - 1 - k] });
                        mids.push(Some(if fwd { hv[k] } else { hv[n - 2 - k] }));
                        breaks.push(second && k == 0);
                    }
                }
                if !pts.is_empty() {
                    rings.push(domain::ring(fs, &pts, &mids, &breaks));
                }
            }
        }
    }
    Ok((rings, vertex_loop))
}

/// How face `f`'s loops are read ([`outline::Sense`]): its normal's sense, and whether one of
/// its edge loops is declared outer.
fn sense_of(f: &crate::brep::Face) -> outline::Sense {
    outline::Sense {
        same_sense: f.same_sense,
        declared_outer: f
            .loops
            .iter()
            .any(|l| l.outer && matches!(l.kind, LoopKind::Edges(_))),
    }
}

/// Faces a shell uses reversed (`oriented_face` with orientation .F.).
fn reversed_in_shell(brep: &Brep) -> Vec<bool> {
    let mut r = vec![false; brep.faces.len()];
    for sh in &brep.shells {
        for (fi, o) in &sh.faces {
            if !o {
                r[*fi] = true;
            }
        }
    }
    r
}

/// Triangulate every face of `brep` (surfaces from `model`).
pub fn mesh_brep(model: &Model, brep: &Brep, params: &MeshParams) -> BrepMesh {
    let size = brep.extent();
    let h = size * params.relative_edge;
    let mut t = Triangulation {
        name: "trimmed faces".into(),
        vertices: brep.vertices.iter().map(|v| v.point).collect(),
        triangles: vec![],
    };
    let es = sample_edges(brep, h, params.max_turn, &mut t);
    let mut deviation = params.measure.then(|| {
        es.samples
            .iter()
            .zip(&es.halves)
            .filter_map(|(s, hv)| {
                let pts: Vec<[f64; 3]> = s.as_ref()?.iter().map(|x| x.1).collect();
                Some(chordal::edge_deviation(&pts, hv))
            })
            .fold(0.0, f64::max)
    });
    let mut floor = params.measure.then_some(0.0);
    let mut proven = (params.measure && params.prove).then_some((0.0f64, 0usize));
    // Faces a shell uses reversed: their triangles turn the other way (the region is the
    // face's own).
    let reversed = reversed_in_shell(brep);
    let mut faces = Vec::with_capacity(brep.faces.len());
    for (fi, f) in brep.faces.iter().enumerate() {
        let Some(si) = f.surface else {
            faces.push(Err("no surface".to_string()));
            continue;
        };
        let fs = FaceSurface::new(&model.surfaces[si].nurbs, size);
        let (rings, vertex_loop) = match face_rings(brep, fi, &es, &fs) {
            Ok(r) => r,
            Err(e) => {
                faces.push(Err(e));
                continue;
            }
        };
        if let Some(f) = floor.as_mut() {
            // Edge samples off the face's surface (at their projected parameters): the mesh
            // follows the edges, so no finer sampling brings the deviation below this.
            for p in rings.iter().flat_map(|r| &r.points) {
                *f = chordal::worst(*f, dist(&fs.eval(&p.uv), &t.vertices[p.vertex]));
            }
        }
        let first = t.triangles.len();
        let mut add = |p: [f64; 3]| {
            t.vertices.push(p);
            t.vertices.len() - 1
        };
        match face::mesh_face(
            &fs,
            rings,
            vertex_loop,
            sense_of(f),
            h,
            params.max_turn,
            &mut add,
        ) {
            Ok(m) => {
                if let Some(d) = deviation.as_mut() {
                    let v = &t.vertices;
                    let corners = m.triangles.iter().map(|x| x.map(|i| v[i]));
                    let e = chordal::face_deviation(corners, &m.uv, |q| fs.eval(q));
                    *d = d.max(e);
                }
                if let Some(p) = proven.as_mut() {
                    let bs = bound::BoundSurface {
                        s: fs.s,
                        domain: fs.domain,
                        periodic: fs.period.map(|x| x.is_some()),
                    };
                    let v = &t.vertices;
                    let corners = m.triangles.iter().map(|x| x.map(|i| v[i]));
                    let goal = 2.0 * deviation.unwrap_or(0.0);
                    let (b, n) = bound::mesh_bound(&bs, corners, &m.uv, goal);
                    *p = (p.0.max(b), p.1 + n);
                }
                let flip = reversed[fi];
                t.triangles.extend(m.triangles.iter().map(|x| {
                    let x = x.map(|i| i as u32);
                    if flip { [x[0], x[2], x[1]] } else { x }
                }));
                faces.push(Ok((first..t.triangles.len(), m.area)));
            }
            Err(e) => faces.push(Err(e.to_string())),
        }
    }
    BrepMesh {
        triangulation: t,
        faces,
        deviation,
        floor,
        bound: proven,
    }
}

/// The parameter-plane region of every face of `brep` ([`region::FaceRegion`]: its closed
/// polygons from the edges sampled as `params` says), or why it has none.
pub fn face_regions(
    model: &Model,
    brep: &Brep,
    params: &MeshParams,
) -> Vec<Result<region::FaceRegion, String>> {
    let size = brep.extent();
    let h = size * params.relative_edge;
    let mut t = Triangulation {
        name: String::new(),
        vertices: brep.vertices.iter().map(|v| v.point).collect(),
        triangles: vec![],
    };
    let es = sample_edges(brep, h, params.max_turn, &mut t);
    let mut extra = t.vertices.len();
    brep.faces
        .iter()
        .enumerate()
        .map(|(fi, f)| {
            let si = f.surface.ok_or_else(|| "no surface".to_string())?;
            let fs = FaceSurface::new(&model.surfaces[si].nurbs, size);
            let (rings, vertex_loop) = face_rings(brep, fi, &es, &fs)?;
            let mut add = |_: [f64; 3]| {
                extra += 1;
                extra - 1
            };
            // A loop declared outer that runs clockwise about the normal on a closed surface,
            // with no loop winding around it: the orientation says the face is the rest of the
            // surface, the declaration its inside (files written with loops about the
            // surface's normal for a reversed face read so). Outlined by the orientation, and
            // said.
            let sense = sense_of(f);
            let loops: Vec<&[domain::BoundaryPoint]> =
                rings.iter().map(|r| r.points.as_slice()).collect();
            let ambiguous = sense.declared_outer
                && rings.iter().all(|r| r.winding == [0, 0])
                && outline::holes_only(&fs, &loops, sense);
            let polys = polygons::face_polygons(
                &fs,
                rings,
                vertex_loop,
                sense,
                h,
                params.max_turn,
                &mut add,
            )
            .map_err(|e| e.to_string())?;
            let mut r = region::FaceRegion::new(si, &polys, fs.period, fs.domain);
            r.ambiguous = ambiguous;
            Ok(r)
        })
        .collect()
}

/// The trimmed area of every face of `brep`, from the fine sampling
/// ([`MeshParams::for_area`]): `∫∫ |S_u × S_v| du dv` over the parameter triangles.
pub fn face_areas(model: &Model, brep: &Brep) -> Vec<crate::model::info::FaceArea> {
    let mesh = mesh_brep(model, brep, &MeshParams::for_area());
    brep.faces
        .iter()
        .zip(mesh.faces)
        .map(|(f, r)| crate::model::info::FaceArea {
            face: f.source.clone(),
            area: r.as_ref().ok().map(|x| x.1),
            note: r.err(),
        })
        .collect()
}

/// The summary `vericad info` prints: [`crate::model::info::summarize`], and for a B-rep the
/// trimmed area of each face ([`face_areas`]) and whether each edge lies on its faces
/// ([`crate::brep::edge_check::check_edges`]).
pub fn model_info(model: &Model) -> crate::model::info::ModelInfo {
    let mut info = crate::model::info::summarize(model);
    if let Some(b) = &model.brep {
        info.face_areas = face_areas(model, b);
        info.edge_checks = Some(crate::brep::edge_check::check_edges(b, model));
    }
    info
}
