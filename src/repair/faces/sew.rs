//! Steps 1–2 on trimmed faces (Algorithm 1 and §3.1 with edges in place of patch borders):
//! the free edges of a B-rep (used by one face) are joined where they are one boundary
//! meant to be shared. Their end vertices within `u1` of each other are clustered and each
//! cluster moved to its mean (§4 iv, the corner averaging); then two free edges between the
//! same clusters whose curves lie within `u1` of each other (seven interior points each way,
//! closest points: evidence) become one edge, used by both faces, carrying both faces'
//! pcurves. The surfaces, trims and edge curves are not changed; an edge whose end moved
//! records the larger distance in its `vertex_gap`.
//!
//! Two vertices are never clustered when an edge joins their clusters (that edge would
//! collapse). Clustering links vertices within `u1` of a member (single linkage): a chain of
//! such steps can span more than `u1`. Shells that sewn edges connect become one shell (the lowest-numbered; solids
//! and occurrences that named the others name it).

use crate::brep::sew::curve_distance;
use crate::brep::{Brep, LoopKind};
use crate::geom::dist;
use serde::Serialize;
use std::collections::{BTreeMap, HashMap};

/// Two free edges joined into one.
#[derive(Clone, Debug, Serialize)]
pub struct SewnEdge {
    /// Source ids of the edge kept and of the edge it replaces.
    pub kept: String,
    pub removed: String,
    /// Source ids of the two faces.
    pub faces: [String; 2],
    /// Largest distance of seven interior points of each curve from the other (evidence).
    pub distance_evidence: f64,
}

/// What joining the free edges did.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Sewing {
    /// Vertices merged into another (clusters of more than one vertex, less one each).
    pub vertices_merged: usize,
    /// Largest distance a vertex moved to its cluster's mean.
    pub max_vertex_move: f64,
    pub edges_sewn: Vec<SewnEdge>,
    /// Free edges split where another free edge ends on their interior (T-junctions).
    pub t_splits: usize,
    /// Shells merged into another because sewn edges join them (a part written as one
    /// shell per face is one shell after sewing).
    pub shells_joined: usize,
}

/// Union–find over vertex indices.
struct Clusters(Vec<usize>);

impl Clusters {
    fn root(&mut self, mut v: usize) -> usize {
        while self.0[v] != v {
            self.0[v] = self.0[self.0[v]];
            v = self.0[v];
        }
        v
    }
}

/// The face using each free edge, and the shell of each face (first shell listing it).
fn owners(b: &Brep) -> (BTreeMap<usize, usize>, Vec<Option<usize>>) {
    let mut shell_of = vec![None; b.faces.len()];
    for (si, s) in b.shells.iter().enumerate() {
        for &(f, _) in &s.faces {
            if let Some(x) = shell_of.get_mut(f) {
                x.get_or_insert(si);
            }
        }
    }
    let free = super::angles::edge_uses(b)
        .into_iter()
        .filter_map(|(e, us)| match us[..] {
            [u] => Some((e, u.face)),
            _ => None,
        })
        .collect();
    (free, shell_of)
}

/// Join the free edges of `b` that are one boundary within `u1` (see the module comment).
pub fn sew_free_edges(b: &mut Brep, u1: f64) -> Sewing {
    let mut out = Sewing::default();
    let (free, shell_of) = owners(b);
    // Clusters of the free edges' end vertices (a grid of cells 2·u1).
    let mut cl = Clusters((0..b.vertices.len()).collect());
    let cell = 2.0 * u1.max(f64::MIN_POSITIVE);
    let key = |p: &[f64; 3]| p.map(|x| (x / cell).floor() as i64);
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    let ends: Vec<usize> = {
        let mut v: Vec<usize> = free
            .keys()
            .flat_map(|&e| [b.edges[e].start, b.edges[e].end])
            .filter(|v| *v < b.vertices.len())
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    // Per cluster root, the vertices its members are joined to by an edge (merged with the
    // clusters), so that whether an edge joins two clusters is a look at one list.
    let mut joined: HashMap<usize, Vec<usize>> = HashMap::new();
    for e in &b.edges {
        if e.start < b.vertices.len() && e.end < b.vertices.len() && e.start != e.end {
            joined.entry(e.start).or_default().push(e.end);
            joined.entry(e.end).or_default().push(e.start);
        }
    }
    let joins = |cl: &mut Clusters, joined: &HashMap<usize, Vec<usize>>, x: usize, y: usize| {
        joined
            .get(&x)
            .is_some_and(|vs| vs.iter().any(|v| cl.root(*v) == y))
    };
    for &v in &ends {
        let p = b.vertices[v].point;
        let k = key(&p);
        let mut near = Vec::new();
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let c = [
                        k[0].saturating_add(dx),
                        k[1].saturating_add(dy),
                        k[2].saturating_add(dz),
                    ];
                    if let Some(ws) = grid.get(&c) {
                        near.extend(
                            ws.iter()
                                .copied()
                                .filter(|w| dist(&b.vertices[*w].point, &p) <= u1),
                        );
                    }
                }
            }
        }
        for w in near {
            let (rv, rw) = (cl.root(v), cl.root(w));
            if rv != rw && !joins(&mut cl, &joined, rv, rw) {
                cl.0[rw] = rv;
                if let Some(vs) = joined.remove(&rw) {
                    joined.entry(rv).or_default().extend(vs);
                }
            }
        }
        grid.entry(k).or_default().push(v);
    }
    // Each cluster at its mean; every edge onto the clusters' roots.
    let mut members: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for &v in &ends {
        let r = cl.root(v);
        members.entry(r).or_default().push(v);
    }
    for (r, vs) in &members {
        if vs.len() < 2 {
            continue;
        }
        out.vertices_merged += vs.len() - 1;
        let n = vs.len() as f64;
        let mean = (0..3).map(|k| vs.iter().map(|v| b.vertices[*v].point[k]).sum::<f64>() / n);
        let mean: Vec<f64> = mean.collect();
        let mean = [mean[0], mean[1], mean[2]];
        for v in vs {
            out.max_vertex_move = out.max_vertex_move.max(dist(&b.vertices[*v].point, &mean));
        }
        b.vertices[*r].point = mean;
    }
    for e in b.edges.iter_mut() {
        if e.start < cl.0.len() && e.end < cl.0.len() {
            (e.start, e.end) = (cl.root(e.start), cl.root(e.end));
        }
    }
    for f in b.faces.iter_mut() {
        for l in f.loops.iter_mut() {
            if let LoopKind::Vertex(v) = &mut l.kind
                && *v < cl.0.len()
            {
                *v = cl.root(*v);
            }
        }
    }
    // T-junctions: free edges split where another free edge ends on their interior.
    out.t_splits = super::t_split::split_at_vertices(b, &free, u1);
    let (free, _) = if out.t_splits > 0 {
        owners(b)
    } else {
        (free, Vec::new())
    };
    // Free edges between the same clusters, paired where their curves agree.
    let mut by_ends: BTreeMap<(usize, usize), Vec<usize>> = BTreeMap::new();
    for &e in free.keys() {
        let (s, t) = (b.edges[e].start, b.edges[e].end);
        by_ends.entry((s.min(t), s.max(t))).or_default().push(e);
    }
    let mut replace: BTreeMap<usize, (usize, bool)> = BTreeMap::new();
    let mut joined_shells = Vec::new();
    for es in by_ends.values() {
        for (i, &a) in es.iter().enumerate() {
            if replace.contains_key(&a) || replace.values().any(|(k, _)| *k == a) {
                continue;
            }
            for &c in &es[i + 1..] {
                if replace.contains_key(&c) {
                    continue;
                }
                let (Some(ca), Some(cc)) = (&b.edges[a].curve, &b.edges[c].curve) else {
                    continue;
                };
                let d = curve_distance(&ca.nurbs, &cc.nurbs);
                if d > u1 {
                    continue;
                }
                let (fa, fc) = (free[&a], free[&c]);
                if let (Some(x), Some(y)) = (shell_of[fa], shell_of[fc])
                    && x != y
                {
                    joined_shells.push((x, y));
                }
                let same_way = if b.edges[a].start != b.edges[a].end {
                    b.edges[a].start == b.edges[c].start
                } else {
                    quarter_agrees(&ca.nurbs, &cc.nurbs)
                };
                out.edges_sewn.push(SewnEdge {
                    kept: b.edges[a].source.clone(),
                    removed: b.edges[c].source.clone(),
                    faces: [b.faces[fa].source.clone(), b.faces[fc].source.clone()],
                    distance_evidence: d,
                });
                replace.insert(c, (a, same_way));
                break;
            }
        }
    }
    for f in b.faces.iter_mut() {
        for l in f.loops.iter_mut() {
            if let LoopKind::Edges(oes) = &mut l.kind {
                for oe in oes.iter_mut() {
                    if let Some(&(a, same_way)) = replace.get(&oe.edge) {
                        oe.edge = a;
                        oe.forward = oe.forward == same_way;
                    }
                }
            }
        }
    }
    for (&c, &(a, _)) in &replace {
        let pcs = std::mem::take(&mut b.edges[c].pcurves);
        b.edges[a].pcurves.extend(pcs);
    }
    for e in b.edges.iter_mut() {
        if let Some(c) = e.curve.as_mut() {
            let (t0, t1) = c.nurbs.hom.domain();
            let (p, q) = (c.nurbs.eval(&t0), c.nurbs.eval(&t1));
            if let (Some(s), Some(t)) = (b.vertices.get(e.start), b.vertices.get(e.end)) {
                c.vertex_gap = c.vertex_gap.max(dist(&p, &s.point)).max(dist(&q, &t.point));
            }
        }
    }
    compact(b);
    out.shells_joined = join_shells(b, &joined_shells);
    out
}

/// Join the shells that sewn edges connect (pairs of shell indices): each group becomes its
/// lowest-numbered shell, holding every member's faces; solids and occurrences that named a
/// member name it. Returns the number of shells removed.
fn join_shells(b: &mut Brep, pairs: &[(usize, usize)]) -> usize {
    if pairs.is_empty() {
        return 0;
    }
    let mut cl = Clusters((0..b.shells.len()).collect());
    for &(x, y) in pairs {
        let (rx, ry) = (cl.root(x), cl.root(y));
        if rx != ry {
            // The lower index is the root.
            let (lo, hi) = (rx.min(ry), rx.max(ry));
            cl.0[hi] = lo;
        }
    }
    let roots: Vec<usize> = (0..b.shells.len()).map(|i| cl.root(i)).collect();
    for i in 0..b.shells.len() {
        let r = roots[i];
        if r != i {
            let faces = std::mem::take(&mut b.shells[i].faces);
            b.shells[r].faces.extend(faces);
        }
    }
    let kept: Vec<bool> = roots.iter().enumerate().map(|(i, r)| *r == i).collect();
    let map = renumber(&kept);
    let to = |i: usize| roots.get(i).map_or(i, |r| map[*r]);
    let mut k = 0;
    b.shells.retain(|_| {
        k += 1;
        kept[k - 1]
    });
    for s in b.solids.iter_mut() {
        s.outer = to(s.outer);
        let outer = s.outer;
        for v in s.voids.iter_mut() {
            *v = to(*v);
        }
        // A void joined to the outer shell or to another void is that shell.
        s.voids.retain(|v| *v != outer);
        s.voids.sort_unstable();
        s.voids.dedup();
    }
    for o in b.occurrences.iter_mut() {
        for s in o.shells.iter_mut() {
            *s = to(*s);
        }
        o.shells.sort_unstable();
        o.shells.dedup();
    }
    kept.iter().filter(|k| !**k).count()
}

/// Whether `c` runs the way `a` does, for closed edges: its quarter point is nearer `a`'s
/// quarter point than `a`'s three-quarter point.
fn quarter_agrees(
    a: &crate::spline::NurbsCurve<f64, 3>,
    c: &crate::spline::NurbsCurve<f64, 3>,
) -> bool {
    let at = |x: &crate::spline::NurbsCurve<f64, 3>, f: f64| {
        let (t0, t1) = x.hom.domain();
        x.eval(&(t0 + f * (t1 - t0)))
    };
    let q = at(c, 0.25);
    dist(&at(a, 0.25), &q) <= dist(&at(a, 0.75), &q)
}

/// Drop the edges no loop uses any more and the vertices no edge or vertex loop uses,
/// renumbering the references.
fn compact(b: &mut Brep) {
    let mut edge_used = vec![false; b.edges.len()];
    let mut vertex_used = vec![false; b.vertices.len()];
    for f in &b.faces {
        for l in &f.loops {
            match &l.kind {
                LoopKind::Edges(oes) => oes.iter().for_each(|oe| {
                    if let Some(x) = edge_used.get_mut(oe.edge) {
                        *x = true;
                    }
                }),
                LoopKind::Vertex(v) => {
                    if let Some(x) = vertex_used.get_mut(*v) {
                        *x = true;
                    }
                }
            }
        }
    }
    let edge_map = renumber(&edge_used);
    let mut k = 0;
    b.edges.retain(|_| {
        k += 1;
        edge_used[k - 1]
    });
    for e in &b.edges {
        for v in [e.start, e.end] {
            if let Some(x) = vertex_used.get_mut(v) {
                *x = true;
            }
        }
    }
    let vertex_map = renumber(&vertex_used);
    let mut k = 0;
    b.vertices.retain(|_| {
        k += 1;
        vertex_used[k - 1]
    });
    for e in b.edges.iter_mut() {
        e.start = vertex_map.get(e.start).copied().unwrap_or(e.start);
        e.end = vertex_map.get(e.end).copied().unwrap_or(e.end);
    }
    for f in b.faces.iter_mut() {
        for l in f.loops.iter_mut() {
            match &mut l.kind {
                LoopKind::Edges(oes) => oes.iter_mut().for_each(|oe| {
                    oe.edge = edge_map.get(oe.edge).copied().unwrap_or(oe.edge);
                }),
                LoopKind::Vertex(v) => *v = vertex_map.get(*v).copied().unwrap_or(*v),
            }
        }
    }
}

/// New indices of the kept items (an item not kept maps to its old index, never read).
fn renumber(kept: &[bool]) -> Vec<usize> {
    let mut next = 0;
    kept.iter()
        .enumerate()
        .map(|(i, k)| {
            if *k {
                next += 1;
                next - 1
            } else {
                i
            }
        })
        .collect()
}
