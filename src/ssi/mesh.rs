//! Mesh-only mode (paper §4: "If the intersection is performed on surface triangulations,
//! then the refinement step is skipped, and the piecewise linear curve produced from the
//! intersection of triangles is the end result"). Same exact triangle test, topology and
//! tracer as for parametric surfaces.

use super::SsiError;
use super::pair::build_topology;
use super::report::{BranchOut, EndKind, PairOut, PairStats};
use super::trace::{check_invariants, trace};
use super::tri_tri::Feature;
use crate::geom::tri_tree::{TriTree, triangle_box};
use crate::model::Triangulation;
use std::collections::HashMap;
use std::time::Instant;

fn tri(m: &Triangulation, t: u32) -> [[f64; 3]; 3] {
    let v = m.triangles[t as usize];
    std::array::from_fn(|k| m.vertices[v[k] as usize])
}

fn edge_use(m: &Triangulation) -> HashMap<(u32, u32), u32> {
    let mut c = HashMap::new();
    for t in &m.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *c.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    c
}

fn valid(m: &Triangulation) -> bool {
    let n = m.vertices.len() as u32;
    m.triangles.iter().all(|t| t.iter().all(|&v| v < n))
        && m.vertices.iter().all(|p| p.iter().all(|c| c.is_finite()))
}

/// Intersect two triangulations.
pub fn intersect_meshes(
    a: &Triangulation,
    b: &Triangulation,
    ids: (usize, usize),
) -> Result<PairOut, SsiError> {
    let t0 = Instant::now();
    if !valid(a) || !valid(b) {
        return Err(SsiError::Topology(format!(
            "triangulation {} or {} has a vertex index out of range or a non-finite coordinate",
            ids.0, ids.1
        )));
    }
    let tree = |m: &Triangulation| {
        let boxes: Vec<_> = (0..m.triangles.len() as u32)
            .map(|t| triangle_box(&tri(m, t)))
            .collect();
        TriTree::build(&boxes)
    };
    let pairs = tree(a).overlapping_pairs(&tree(b));
    let mut stats = PairStats {
        triangles_a: a.triangles.len(),
        triangles_b: b.triangles.len(),
        candidate_pairs: pairs.len(),
        ..Default::default()
    };
    let Some((mut topo, contacts)) = build_topology(
        &pairs,
        &|t| (tri(a, t), a.triangles[t as usize]),
        &|t| (tri(b, t), b.triangles[t as usize]),
        &mut stats,
        &|e| e,
        &|_, _| false,
    ) else {
        return Err(SsiError::Topology("mesh intersection stopped".into()));
    };
    let branches = trace(&mut topo);
    check_invariants(&topo, &branches).map_err(SsiError::Topology)?;
    let (ea, eb) = (edge_use(a), edge_use(b));
    let boundary = |f: Feature, e: &HashMap<(u32, u32), u32>| matches!(f, Feature::Edge(x, y) if e.get(&(x, y)) == Some(&1));
    let mut out = Vec::new();
    for br in &branches {
        let mut pts: Vec<u32> = br.points.clone();
        if br.closed {
            pts.pop();
        }
        let err = pts
            .iter()
            .map(|&p| topo.points[p as usize].err)
            .fold(0.0, f64::max);
        let ends = if br.closed {
            Vec::new()
        } else {
            [br.points[0], br.points[br.points.len() - 1]]
                .iter()
                .map(|&p| {
                    let pt = &topo.points[p as usize];
                    if pt.uses.len() > 2 {
                        EndKind::BranchPoint
                    } else if boundary(pt.id.a, &ea) || boundary(pt.id.b, &eb) {
                        EndKind::Boundary
                    } else {
                        EndKind::Unexplained
                    }
                })
                .collect()
        };
        out.push(BranchOut {
            closed: br.closed,
            points: pts.iter().map(|&p| topo.points[p as usize].xyz).collect(),
            uv_a: Vec::new(),
            uv_b: Vec::new(),
            dist_a_max: err,
            dist_b_max: err,
            ends,
            tangential_points: 0,
            unconverged_points: 0,
            inserted_points: 0,
            refused_insertions: 0,
            max_chord_deviation: 0.0,
            fit: None,
            // The crossing points' bounds are distances to the exact crossing of the meshes,
            // a point of their intersection curve.
            dist_curve_max: Some(err),
            curve_uncertified_points: 0,
            curve_radius: pts
                .iter()
                .map(|&p| Some(topo.points[p as usize].err))
                .collect(),
            curve_uncertified: Vec::new(),
            curve_cert: Vec::new(),
        });
    }
    stats.seconds = t0.elapsed().as_secs_f64();
    Ok(PairOut {
        a: ids.0,
        b: ids.1,
        branches: out,
        touch_points: Vec::new(),
        contacts,
        stats,
        coverage: None,
        complete: true,
        coincident: None,
        faces: None,
        tangent_contact: None,
    })
}
