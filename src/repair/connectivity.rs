//! Step 1 — patch connectivity (paper §3, Algorithm 1) and T-connectivity (Fig. 5).
//!
//! Corners of all patches go into a k-d tree. For each corner `V` of patch `P`, the at most
//! three closest corners of other patches within `u1` are found; for such a corner `V_i` of
//! patch `Q`, the corner next to `V` along `P`'s edge must lie within `u1` of the corner next
//! to `V_i` along one of `Q`'s two edges at `V_i`: then the two edges (and patches) are
//! connected — with opposite directions (consistently oriented neighbours) or the same
//! direction (one of the patches is flipped).
//!
//! T-connectivity: a corner within `u1` of the *interior* of another patch's edge (farther
//! than `u1` from both of its ends) splits that patch there (knot insertion: `sub_patch` of
//! the homogeneous net, the geometry unchanged up to the rounding of the new control points),
//! creating a connectivity vertex; connectivity is then recomputed. Candidates come from a
//! box tree (corners grown by `u1` against edge control-polygon boxes, which hold the edges).

use super::edges::{closest_on_curve, collapsed, corners, edge_curve, edge_uv};
use super::kdtree::KdTree;
use crate::geom::dist;
use crate::geom::tri_tree::TriTree;
use crate::spline::NurbsSurface;
use serde::Serialize;

/// Edge `ep` of patch `p` meets edge `eq` of patch `q`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub struct Connection {
    pub p: usize,
    pub ep: usize,
    pub q: usize,
    pub eq: usize,
    /// Both edges run the same way: one of the two patches is flipped.
    pub same_direction: bool,
}

/// Algorithm 1 on the patches' corners.
pub fn connect(patches: &[NurbsSurface<f64, 3>], u1: f64) -> Vec<Connection> {
    let cs: Vec<[[f64; 3]; 4]> = patches.iter().map(corners).collect();
    let flat: Vec<[f64; 3]> = cs.iter().flatten().copied().collect();
    let tree = KdTree::new(&flat);
    let mut out = std::collections::BTreeSet::new();
    for (p, c4) in cs.iter().enumerate() {
        for c in 0..4 {
            let (v, next) = (c4[c], c4[(c + 1) % 4]);
            if v == next {
                continue; // collapsed edge (degenerate side of a triangular patch)
            }
            let skip = |id: u32| id as usize / 4 == p;
            for (id, _) in tree.nearest(&v, 3, u1, &skip) {
                let (q, d) = (id as usize / 4, id as usize % 4);
                let qc = &cs[q];
                // Q's edge d-1 runs (d-1 -> d): opposite to P's edge c (c -> c+1).
                if dist(&next, &qc[(d + 3) % 4]) < u1 && qc[(d + 3) % 4] != qc[d] {
                    out.insert(canonical(Connection {
                        p,
                        ep: c,
                        q,
                        eq: (d + 3) % 4,
                        same_direction: false,
                    }));
                }
                // Q's edge d runs (d -> d+1): the same way.
                if dist(&next, &qc[(d + 1) % 4]) < u1 && qc[(d + 1) % 4] != qc[d] {
                    out.insert(canonical(Connection {
                        p,
                        ep: c,
                        q,
                        eq: d,
                        same_direction: true,
                    }));
                }
            }
        }
    }
    out.into_iter().collect()
}

fn canonical(c: Connection) -> Connection {
    if (c.p, c.ep) <= (c.q, c.eq) {
        c
    } else {
        Connection {
            p: c.q,
            ep: c.eq,
            q: c.p,
            eq: c.ep,
            same_direction: c.same_direction,
        }
    }
}

/// A corner of one patch lying on the interior of another patch's edge.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct TJunction {
    /// The patch whose corner it is, and the corner.
    pub corner_patch: usize,
    pub corner: usize,
    /// The patch whose edge is split, the edge, and the split parameter (u for south/north,
    /// v for east/west).
    pub patch: usize,
    pub edge: usize,
    pub parameter: f64,
    pub distance: f64,
}

/// T-junctions: corners within `u1` of another patch's edge interior.
pub fn t_junctions(patches: &[NurbsSurface<f64, 3>], u1: f64) -> Vec<TJunction> {
    let cs: Vec<[[f64; 3]; 4]> = patches.iter().map(corners).collect();
    let corner_boxes: Vec<([f32; 3], [f32; 3])> = cs
        .iter()
        .flatten()
        .map(|c| {
            let lo: [f64; 3] = std::array::from_fn(|k| c[k] - u1);
            let hi: [f64; 3] = std::array::from_fn(|k| c[k] + u1);
            crate::geom::Aabb { min: lo, max: hi }.to_f32_outward()
        })
        .collect();
    let curves: Vec<_> = (0..patches.len())
        .flat_map(|p| (0..4).map(move |e| (p, e)))
        .map(|(p, e)| edge_curve(&patches[p], e))
        .collect();
    let edge_boxes: Vec<([f32; 3], [f32; 3])> = curves
        .iter()
        .map(
            |c| match crate::geom::Aabb::of_points(c.points_weights().0.iter()) {
                Some(b) => b.to_f32_outward(),
                None => ([0.0; 3], [0.0; 3]),
            },
        )
        .collect();
    let pairs = TriTree::build(&corner_boxes).overlapping_pairs(&TriTree::build(&edge_boxes));
    let mut out: Vec<TJunction> = Vec::new();
    for (ci, ei) in pairs {
        let (cp, c) = (ci as usize / 4, ci as usize % 4);
        let (q, e) = (ei as usize / 4, ei as usize % 4);
        if cp == q || collapsed(&curves[ei as usize]) {
            continue;
        }
        let v = cs[cp][c];
        let (a, b) = (cs[q][e], cs[q][(e + 1) % 4]);
        if dist(&v, &a) < u1 || dist(&v, &b) < u1 {
            continue;
        }
        let (t, _, d) = closest_on_curve(&curves[ei as usize], &v);
        if d < u1 {
            let uv = edge_uv(&patches[q], e, t);
            let mut parameter = if e % 2 == 0 { uv[0] } else { uv[1] };
            // Prefer an interior knot of the patch whose edge point is also within u1 of the
            // corner: the split then falls on the patch's own break, leaving no sliver.
            let h = &patches[q].hom;
            let kv = if e % 2 == 0 { &h.ku } else { &h.kv };
            let (lo, hi) = kv.domain();
            let mut best = f64::INFINITY;
            for k in kv.breakpoints() {
                if k <= lo || k >= hi {
                    continue;
                }
                let at = if e % 2 == 0 {
                    patches[q].eval(&k, &uv[1])
                } else {
                    patches[q].eval(&uv[0], &k)
                };
                let dk = dist(&at, &v);
                if dk < u1 && dk < best {
                    best = dk;
                    parameter = k;
                }
            }
            // One split per patch edge location (several corners may sit at one T).
            if !out.iter().any(|o| {
                o.patch == q
                    && o.edge == e
                    && (o.parameter - parameter).abs() <= 1e-12 * parameter.abs().max(1.0)
            }) {
                out.push(TJunction {
                    corner_patch: cp,
                    corner: c,
                    patch: q,
                    edge: e,
                    parameter,
                    distance: d,
                });
            }
        }
    }
    out.sort_by(|x, y| {
        (x.patch, x.edge)
            .cmp(&(y.patch, y.edge))
            .then(x.parameter.total_cmp(&y.parameter))
    });
    out
}

/// Split patch `s` at `t` in u (`along_u`) or v: the two halves.
pub fn split(
    s: &NurbsSurface<f64, 3>,
    along_u: bool,
    t: f64,
) -> Option<(NurbsSurface<f64, 3>, NurbsSurface<f64, 3>)> {
    let (u0, u1, v0, v1) = s.hom.domain();
    let (a, b) = if along_u {
        (
            s.hom.sub_patch(&u0, &t, &v0, &v1).ok()?,
            s.hom.sub_patch(&t, &u1, &v0, &v1).ok()?,
        )
    } else {
        (
            s.hom.sub_patch(&u0, &u1, &v0, &t).ok()?,
            s.hom.sub_patch(&u0, &u1, &t, &v1).ok()?,
        )
    };
    Some((NurbsSurface { hom: a }, NurbsSurface { hom: b }))
}
