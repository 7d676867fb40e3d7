//! A bounding-volume hierarchy over axis-aligned boxes in 3D (median split on the longest
//! axis): box queries and nearest-item search. Culling only: a query returns every item
//! whose box meets the query box (comparisons on the stored `f64` boxes, no rounding), and
//! callers decide each candidate themselves.

/// A node: its box and either two children or a range of `order`.
#[derive(Clone, Debug)]
struct Node {
    lo: [f64; 3],
    hi: [f64; 3],
    /// Children (`left`, `right`) or, for a leaf, `start..end` of `order`.
    a: usize,
    b: usize,
    leaf: bool,
}

/// The hierarchy: item indices refer to the boxes it was built from.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    order: Vec<usize>,
    boxes: Vec<([f64; 3], [f64; 3])>,
}

const LEAF: usize = 4;

fn merge(boxes: &[([f64; 3], [f64; 3])], items: &[usize]) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &i in items {
        for k in 0..3 {
            lo[k] = lo[k].min(boxes[i].0[k]);
            hi[k] = hi[k].max(boxes[i].1[k]);
        }
    }
    (lo, hi)
}

/// Squared distance from `p` to the box `lo..hi` (0 inside).
pub fn box_dist2(p: &[f64; 3], lo: &[f64; 3], hi: &[f64; 3]) -> f64 {
    (0..3)
        .map(|k| {
            let d = (lo[k] - p[k]).max(p[k] - hi[k]).max(0.0);
            d * d
        })
        .sum()
}

impl Bvh {
    /// Build over `boxes` (`(min, max)` per item). Boxes with NaN coordinates are never
    /// returned by queries (every comparison with NaN is false).
    pub fn build(boxes: Vec<([f64; 3], [f64; 3])>) -> Bvh {
        let mut t = Bvh {
            nodes: Vec::new(),
            order: (0..boxes.len()).collect(),
            boxes,
        };
        if !t.order.is_empty() {
            t.split(0, t.order.len());
        }
        t
    }

    fn split(&mut self, start: usize, end: usize) -> usize {
        let (lo, hi) = merge(&self.boxes, &self.order[start..end]);
        let id = self.nodes.len();
        self.nodes.push(Node {
            lo,
            hi,
            a: start,
            b: end,
            leaf: true,
        });
        if end - start <= LEAF {
            return id;
        }
        let axis = (0..3)
            .max_by(|&i, &j| (hi[i] - lo[i]).total_cmp(&(hi[j] - lo[j])))
            .unwrap_or(0);
        let mid = (start + end) / 2;
        let boxes = &self.boxes;
        self.order[start..end].select_nth_unstable_by(mid - start, |&x, &y| {
            let cx = boxes[x].0[axis] + boxes[x].1[axis];
            let cy = boxes[y].0[axis] + boxes[y].1[axis];
            cx.total_cmp(&cy)
        });
        let left = self.split(start, mid);
        let right = self.split(mid, end);
        self.nodes[id] = Node {
            lo,
            hi,
            a: left,
            b: right,
            leaf: false,
        };
        id
    }

    /// Call `f` with every item whose box meets the closed box `lo..hi`.
    pub fn query(&self, lo: &[f64; 3], hi: &[f64; 3], f: &mut dyn FnMut(usize)) {
        if self.nodes.is_empty() {
            return;
        }
        let meets = |a: &[f64; 3], b: &[f64; 3]| (0..3).all(|k| a[k] <= hi[k] && lo[k] <= b[k]);
        let mut stack = vec![0usize];
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n];
            if !meets(&node.lo, &node.hi) {
                continue;
            }
            if node.leaf {
                for &i in &self.order[node.a..node.b] {
                    if meets(&self.boxes[i].0, &self.boxes[i].1) {
                        f(i);
                    }
                }
            } else {
                stack.push(node.a);
                stack.push(node.b);
            }
        }
    }

    /// The item minimizing `dist2(item)` (a squared distance from `p` that is at least the
    /// squared distance from `p` to the item's box), with that value; `None` without items.
    pub fn nearest(
        &self,
        p: &[f64; 3],
        dist2: &mut dyn FnMut(usize) -> f64,
    ) -> Option<(usize, f64)> {
        if self.nodes.is_empty() {
            return None;
        }
        let mut best: Option<(usize, f64)> = None;
        let mut heap = std::collections::BinaryHeap::new();
        heap.push(Near(-box_dist2(p, &self.nodes[0].lo, &self.nodes[0].hi), 0));
        while let Some(Near(neg, n)) = heap.pop() {
            if best.is_some_and(|b| -neg > b.1) {
                break;
            }
            let node = &self.nodes[n];
            if node.leaf {
                for &i in &self.order[node.a..node.b] {
                    let d = dist2(i);
                    if best.is_none_or(|b| d < b.1) {
                        best = Some((i, d));
                    }
                }
            } else {
                for c in [node.a, node.b] {
                    let d = box_dist2(p, &self.nodes[c].lo, &self.nodes[c].hi);
                    heap.push(Near(-d, c));
                }
            }
        }
        best
    }
}

/// Heap entry: negated squared box distance (a max-heap pops the nearest first).
struct Near(f64, usize);
impl PartialEq for Near {
    fn eq(&self, o: &Self) -> bool {
        self.0.total_cmp(&o.0).is_eq()
    }
}
impl Eq for Near {}
impl PartialOrd for Near {
    fn partial_cmp(&self, o: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Near {
    fn cmp(&self, o: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&o.0)
    }
}
