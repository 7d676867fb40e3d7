//! Step 5, preparation — a common topological i/j direction for neighbouring patches (paper
//! §5.2: "it must be possible to associate a topological i- and j-direction to each original
//! patch, i.e., view (at least locally) the patches as patch rows and patch columns").
//!
//! A patch's parametrization can be turned by any of the eight symmetries of the square
//! (u/v swap, reversal of u, of v, and their compositions); each is exact (the net permuted,
//! knots mirrored) and maps edges to edges. Starting from each patch not yet oriented (kept as
//! it is), a breadth-first search over the connections that grouping may cross gives every
//! reached neighbour the one symmetry under which its shared edge lies opposite the patch's
//! (east against west, north against south) and runs the other way (consistent orientation).
//! A patch reached again with another demand keeps its first orientation; that connection
//! then bounds groups (a corner of valence other than four, or a non-orientable cycle).

use super::connectivity::Connection;
use crate::spline::NurbsSurface;

/// A symmetry of the parameter square: first swap u and v, then reverse u, then reverse v.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct Orientation {
    pub swap: bool,
    pub reverse_u: bool,
    pub reverse_v: bool,
}

impl Orientation {
    fn all() -> impl Iterator<Item = Orientation> {
        (0..8).map(|k| Orientation {
            swap: k & 1 != 0,
            reverse_u: k & 2 != 0,
            reverse_v: k & 4 != 0,
        })
    }
    /// The edge (0 S, 1 E, 2 N, 3 W) that edge `e` becomes.
    pub fn edge(&self, e: usize) -> usize {
        let mut e = e;
        if self.swap {
            e = [3, 2, 1, 0][e];
        }
        if self.reverse_u {
            e = [0, 3, 2, 1][e];
        }
        if self.reverse_v {
            e = [2, 1, 0, 3][e];
        }
        e
    }
    /// Whether the symmetry reverses the traversal of the boundary (a reflection).
    pub fn reflects(&self) -> bool {
        self.swap ^ self.reverse_u ^ self.reverse_v
    }
    pub fn is_identity(&self) -> bool {
        *self == Orientation::default()
    }
}

fn mirror(k: &[f64]) -> Vec<f64> {
    let (a, b) = (k[0], k[k.len() - 1]);
    k.iter().rev().map(|x| a + b - x).collect()
}

/// The patch under the symmetry `o` (the same surface, reparametrized).
pub fn apply(s: &NurbsSurface<f64, 3>, o: &Orientation) -> NurbsSurface<f64, 3> {
    let mut h = s.hom.clone();
    if o.swap {
        let (nu, nv) = (h.nu(), h.nv());
        let mut net = Vec::with_capacity(nu * nv);
        for j in 0..nv {
            for i in 0..nu {
                net.push(h.at(i, j).clone());
            }
        }
        std::mem::swap(&mut h.ku, &mut h.kv);
        h.net = net;
    }
    let (nu, nv) = (h.nu(), h.nv());
    if o.reverse_u {
        let old = h.net.clone();
        for i in 0..nu {
            for j in 0..nv {
                h.net[i * nv + j] = old[(nu - 1 - i) * nv + j].clone();
            }
        }
        h.ku = crate::spline::KnotVector::new(mirror(h.ku.knots()), h.ku.degree(), nu)
            .unwrap_or_else(|_| h.ku.clone());
    }
    if o.reverse_v {
        let old = h.net.clone();
        for i in 0..nu {
            for j in 0..nv {
                h.net[i * nv + j] = old[i * nv + nv - 1 - j].clone();
            }
        }
        h.kv = crate::spline::KnotVector::new(mirror(h.kv.knots()), h.kv.degree(), nv)
            .unwrap_or_else(|_| h.kv.clone());
    }
    NurbsSurface { hom: h }
}

/// The connection between the reoriented patches.
pub fn transform(c: &Connection, o: &[Orientation]) -> Connection {
    let (a, b) = (&o[c.p], &o[c.q]);
    Connection {
        p: c.p,
        ep: a.edge(c.ep),
        q: c.q,
        eq: b.edge(c.eq),
        same_direction: c.same_direction ^ a.reflects() ^ b.reflects(),
    }
}

/// An orientation for every patch such that neighbours across the `usable` connections lie
/// east–west or north–south, consistently oriented, wherever the search can arrange it.
pub fn orient(n_patches: usize, connections: &[Connection]) -> Vec<Orientation> {
    let mut adj: Vec<Vec<usize>> = vec![Vec::new(); n_patches];
    for (k, c) in connections.iter().enumerate() {
        adj[c.p].push(k);
        adj[c.q].push(k);
    }
    let mut out: Vec<Option<Orientation>> = vec![None; n_patches];
    for seed in 0..n_patches {
        if out[seed].is_some() {
            continue;
        }
        out[seed] = Some(Orientation::default());
        let mut queue = std::collections::VecDeque::from([seed]);
        while let Some(x) = queue.pop_front() {
            let ox = out[x].unwrap_or_default();
            for &k in &adj[x] {
                let c = &connections[k];
                let (ex, y, ey) = if c.p == x {
                    (c.ep, c.q, c.eq)
                } else {
                    (c.eq, c.p, c.ep)
                };
                if out[y].is_some() || y == x {
                    continue;
                }
                let want = (ox.edge(ex) + 2) % 4;
                let refl = c.same_direction ^ ox.reflects();
                if let Some(oy) =
                    Orientation::all().find(|o| o.reflects() == refl && o.edge(ey) == want)
                {
                    out[y] = Some(oy);
                    queue.push_back(y);
                }
            }
        }
    }
    out.into_iter().map(Option::unwrap_or_default).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn symmetries_map_edges_like_the_net() {
        // Corner points of a bilinear patch identify its edges after any symmetry.
        let s = crate::spline::construct::bilinear(
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
        )
        .unwrap();
        let ends = |s: &NurbsSurface<f64, 3>, e: usize| {
            let c = super::super::edges::edge_curve(s, e);
            let (p, _) = c.points_weights();
            (p[0], p[p.len() - 1])
        };
        for o in Orientation::all() {
            let t = apply(&s, &o);
            for e in 0..4 {
                let (a, b) = ends(&s, e);
                let (c, d) = ends(&t, o.edge(e));
                if o.reflects() {
                    assert_eq!((a, b), (d, c), "{o:?} edge {e}");
                } else {
                    assert_eq!((a, b), (c, d), "{o:?} edge {e}");
                }
            }
        }
    }
}
