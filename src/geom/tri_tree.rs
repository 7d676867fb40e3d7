//! Space-partitioning trees over triangles and tree-against-tree culling (the SSI steps 2–3 of
//! paper A §4,
//! "Intersection preprocessing using a tree structure", Fig. 16).
//!
//! As in the paper, the tree is binary with one triangle per leaf (at most `2N - 1` nodes for
//! `N` triangles), every node holding a box just large enough for its children. Boxes are
//! stored in `f32` and rounded *outward* from the exact `f64` triangle bounds
//! ([`Aabb::to_f32_outward`]), so a box always contains its triangle and no pair that could
//! intersect is culled; the closed-interval overlap test keeps touching pairs.

use crate::geom::Aabb;

#[derive(Clone, Copy, Debug)]
struct Node {
    lo: [f32; 3],
    hi: [f32; 3],
    /// Leaf: `!triangle`; inner: index of the left child (the right child follows it).
    link: u32,
    right: u32,
}

const LEAF: u32 = 1 << 31;

/// A triangle's box with its id, while the tree is built.
#[derive(Clone, Copy)]
struct Item {
    lo: [f32; 3],
    hi: [f32; 3],
    id: u32,
}

impl Item {
    /// The box centre along `k` (the split key).
    fn centre(&self, k: usize) -> f32 {
        0.5 * self.lo[k] + 0.5 * self.hi[k]
    }
}

/// A bounding-volume tree over triangles.
#[derive(Clone, Debug, Default)]
pub struct TriTree {
    nodes: Vec<Node>,
}

fn overlap(a: &Node, b: &Node) -> bool {
    (0..3).all(|k| a.lo[k] <= b.hi[k] && b.lo[k] <= a.hi[k])
}

/// The `f32` box of one triangle, rounded outward.
pub fn triangle_box(t: &[[f64; 3]; 3]) -> ([f32; 3], [f32; 3]) {
    match Aabb::of_points(t.iter()) {
        Some(b) => b.to_f32_outward(),
        None => ([f32::NEG_INFINITY; 3], [f32::INFINITY; 3]),
    }
}

impl TriTree {
    /// Build top-down, splitting at the median centroid along the longest axis.
    pub fn build(boxes: &[([f32; 3], [f32; 3])]) -> TriTree {
        let mut tree = TriTree {
            nodes: Vec::with_capacity(2 * boxes.len()),
        };
        if boxes.is_empty() {
            return tree;
        }
        // The boxes travel with their ids: the median selections below then read contiguous
        // memory instead of following each id into `boxes` (same comparisons, same tree).
        let mut items: Vec<Item> = boxes
            .iter()
            .enumerate()
            .map(|(i, &(lo, hi))| Item {
                lo,
                hi,
                id: i as u32,
            })
            .collect();
        tree.nodes.push(Node {
            lo: [0.0; 3],
            hi: [0.0; 3],
            link: 0,
            right: 0,
        });
        tree.fill(0, &mut items);
        tree
    }

    fn fill(&mut self, at: usize, items: &mut [Item]) {
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        for it in items.iter() {
            for k in 0..3 {
                lo[k] = lo[k].min(it.lo[k]);
                hi[k] = hi[k].max(it.hi[k]);
            }
        }
        if items.len() == 1 {
            self.nodes[at] = Node {
                lo,
                hi,
                link: LEAF | items[0].id,
                right: 0,
            };
            return;
        }
        let axis = (0..3)
            .max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b])))
            .unwrap_or(0);
        let m = items.len() / 2;
        items.select_nth_unstable_by(m, |a, b| {
            a.centre(axis)
                .total_cmp(&b.centre(axis))
                .then(a.id.cmp(&b.id))
        });
        let left = self.nodes.len();
        for _ in 0..2 {
            self.nodes.push(Node {
                lo: [0.0; 3],
                hi: [0.0; 3],
                link: 0,
                right: 0,
            });
        }
        self.nodes[at] = Node {
            lo,
            hi,
            link: left as u32,
            right: left as u32 + 1,
        };
        let (l, r) = items.split_at_mut(m);
        self.fill(left, l);
        self.fill(left + 1, r);
    }

    pub fn len(&self) -> usize {
        self.nodes.len()
    }
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Every pair `(a, b)` of triangles whose boxes overlap, sorted.
    pub fn overlapping_pairs(&self, other: &TriTree) -> Vec<(u32, u32)> {
        let mut out = Vec::new();
        if self.nodes.is_empty() || other.nodes.is_empty() {
            return out;
        }
        let mut stack = vec![(0usize, 0usize)];
        while let Some((i, j)) = stack.pop() {
            let (a, b) = (&self.nodes[i], &other.nodes[j]);
            if !overlap(a, b) {
                continue;
            }
            let (la, lb) = (a.link & LEAF != 0, b.link & LEAF != 0);
            match (la, lb) {
                (true, true) => out.push((a.link & !LEAF, b.link & !LEAF)),
                (true, false) => {
                    stack.push((i, b.link as usize));
                    stack.push((i, b.right as usize));
                }
                (false, true) => {
                    stack.push((a.link as usize, j));
                    stack.push((a.right as usize, j));
                }
                (false, false) => {
                    let size = |n: &Node| (0..3).map(|k| n.hi[k] - n.lo[k]).fold(0.0, f32::max);
                    if size(a) >= size(b) {
                        stack.push((a.link as usize, j));
                        stack.push((a.right as usize, j));
                    } else {
                        stack.push((i, b.link as usize));
                        stack.push((i, b.right as usize));
                    }
                }
            }
        }
        out.sort_unstable();
        out
    }
}
