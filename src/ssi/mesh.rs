//! Mesh-only mode (paper §4: "If the intersection is performed on surface triangulations,
//! then the refinement step is skipped, and the piecewise linear curve produced from the
//! intersection of triangles is the end result"). Same exact triangle test, topology and
//! tracer as for parametric surfaces.

use super::SsiError;
use super::pair::build_topology;
use super::report::{BranchOut, EndKind, PairOut, PairStats};
use super::trace::{check_invariants, trace};
use super::tri_tri::Feature;
use crate::geom::dist;
use crate::geom::tri_tree::{TriTree, triangle_box};
use crate::model::Triangulation;
use rustc_hash::FxHashMap as HashMap;
use std::time::Instant;

fn tri(m: &Triangulation, t: u32) -> [[f64; 3]; 3] {
    let v = m.triangles[t as usize];
    std::array::from_fn(|k| m.vertices[v[k] as usize])
}

/// How many triangles of `m` use each of the edges `queries` (vertex pairs, smaller index
/// first): one pass over the triangles, looking up only edges whose smaller vertex is a query
/// vertex (the branch ends are few; the mesh's edges are millions).
fn edge_use(m: &Triangulation, queries: &[(u32, u32)]) -> HashMap<(u32, u32), u32> {
    let mut count: HashMap<(u32, u32), u32> = queries.iter().map(|&e| (e, 0)).collect();
    if count.is_empty() {
        return count;
    }
    let mut mark = vec![false; m.vertices.len()];
    for &(a, _) in count.keys() {
        if let Some(x) = mark.get_mut(a as usize) {
            *x = true;
        }
    }
    for t in &m.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let e = (a.min(b), a.max(b));
            if mark[e.0 as usize]
                && let Some(c) = count.get_mut(&e)
            {
                *c += 1;
            }
        }
    }
    count
}

/// The edge features (vertex pairs, smaller first) of side `a` (or `b`) at the open branches'
/// end points.
fn end_edges(
    topo: &super::topology::Topology,
    branches: &[super::trace::Branch],
    a: bool,
) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    for br in branches.iter().filter(|b| !b.closed) {
        for &p in [br.points[0], br.points[br.points.len() - 1]].iter() {
            let id = topo.points[p as usize].id;
            if let Feature::Edge(x, y) = if a { id.a } else { id.b } {
                out.push((x.min(y), x.max(y)));
            }
        }
    }
    out
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
        return Err(SsiError::InvalidMesh { a: ids.0, b: ids.1 });
    }
    let tree = |m: &Triangulation| {
        let boxes: Vec<_> = (0..m.triangles.len() as u32)
            .map(|t| triangle_box(&tri(m, t)))
            .collect();
        TriTree::build(&boxes)
    };
    // The two trees are independent: built side by side where a second worker is free.
    let (ta, tb) = rayon::join(|| tree(a), || tree(b));
    let pairs = ta.overlapping_pairs(&tb);
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
        return Err(SsiError::MeshStopped);
    };
    let branches = trace(&mut topo);
    check_invariants(&topo, &branches)?;
    let (ea, eb) = (
        edge_use(a, &end_edges(&topo, &branches, true)),
        edge_use(b, &end_edges(&topo, &branches, false)),
    );
    let boundary = |f: Feature, e: &HashMap<(u32, u32), u32>| matches!(f, Feature::Edge(x, y) if e.get(&(x.min(y), x.max(y))) == Some(&1));
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
        // Where an edge of one mesh meets an edge of the other, the symbolic perturbation
        // makes two crossing points (edge of A through a triangle of B, and the reverse) at
        // one location, computed by two formulas: a point no farther from the one before than
        // their two bounds allow is not listed again (each listed point keeps its own bound
        // to its exact crossing, a point of the meshes' intersection).
        let mut listed: Vec<([f64; 3], f64)> = Vec::with_capacity(pts.len());
        let same = |a: &([f64; 3], f64), b: &([f64; 3], f64)| dist(&a.0, &b.0) <= a.1 + b.1;
        for &p in &pts {
            let x = (topo.points[p as usize].xyz, topo.points[p as usize].err);
            if !listed.last().is_some_and(|l| same(l, &x)) {
                listed.push(x);
            }
        }
        if br.closed && listed.len() > 2 && same(&listed[0], &listed[listed.len() - 1]) {
            listed.pop();
        }
        stats.merged_points += pts.len() - listed.len();
        out.push(BranchOut {
            closed: br.closed,
            points: listed.iter().map(|l| l.0).collect(),
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
            tangents: Vec::new(),
            // The crossing points' bounds are distances to the exact crossing of the meshes,
            // a point of their intersection curve.
            dist_curve_max: Some(err),
            curve_uncertified_points: 0,
            curve_radius: listed.iter().map(|l| Some(l.1)).collect(),
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
        common_borders: Vec::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A grid of `n × n` squares over `[0, 1]²` at height `z(x, y)`, two triangles each.
    fn grid(n: u32, z: impl Fn(f64, f64) -> f64) -> Triangulation {
        let mut vertices = Vec::new();
        for i in 0..=n {
            for j in 0..=n {
                let (x, y) = (i as f64 / n as f64, j as f64 / n as f64);
                vertices.push([x, y, z(x, y)]);
            }
        }
        let id = |i: u32, j: u32| i * (n + 1) + j;
        let mut triangles = Vec::new();
        for i in 0..n {
            for j in 0..n {
                triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        Triangulation {
            name: String::new(),
            vertices,
            triangles,
        }
    }

    /// A tilted grid crossing a flat one: one open branch whose two ends lie on the border
    /// edges (used by one triangle), and the edge counts agree with a full count.
    #[test]
    fn branch_ends_on_the_border_are_boundary_ends() {
        let a = grid(7, |_, _| 0.0);
        let b = grid(9, |x, y| 0.3 * x + 0.1 * y - 0.17);
        let r = intersect_meshes(&a, &b, (0, 1)).unwrap();
        assert_eq!(r.branches.len(), 1);
        let br = &r.branches[0];
        assert!(!br.closed);
        assert_eq!(br.ends, vec![EndKind::Boundary, EndKind::Boundary]);
        // The counts of the queried edges equal those of a count over every edge.
        let all: Vec<(u32, u32)> = a
            .triangles
            .iter()
            .flat_map(|t| (0..3).map(move |k| (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]))))
            .collect();
        let some = edge_use(&a, &all[..10]);
        // The same lattice under both: every crossing of a grid line is an edge of A meeting
        // an edge of B, two perturbed crossing points at one location, listed once.
        let c = grid(7, |x, y| 0.3 * x + 0.1 * y - 0.17);
        let r = intersect_meshes(&a, &c, (0, 1)).unwrap();
        assert_eq!(r.branches.len(), 1);
        let p = &r.branches[0].points;
        assert!(p.windows(2).all(|w| dist(&w[0], &w[1]) > 1e-12), "{p:?}");
        assert_eq!(r.branches[0].curve_radius.len(), p.len());
        assert!(r.stats.merged_points > 0);
        assert_eq!(p.len() - 1 + r.stats.merged_points, r.stats.segments);
        assert!(p.len() >= 8, "{}", p.len());
        for e in &all[..10] {
            assert_eq!(some[e], all.iter().filter(|f| *f == e).count() as u32);
        }
    }
}
