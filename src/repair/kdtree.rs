//! A 3D k-d tree over points (Bentley '75), for the nearest-corner queries of Algorithm 1.

/// Balanced k-d tree: the points sorted so that each subtree is a contiguous range with its
/// median at the middle, split along `depth % 3`.
pub struct KdTree {
    pts: Vec<([f64; 3], u32)>,
}

impl KdTree {
    pub fn new(points: &[[f64; 3]]) -> KdTree {
        let mut pts: Vec<([f64; 3], u32)> = points
            .iter()
            .enumerate()
            .map(|(i, p)| (*p, i as u32))
            .collect();
        fn build(p: &mut [([f64; 3], u32)], depth: usize) {
            if p.len() <= 1 {
                return;
            }
            let k = depth % 3;
            let m = p.len() / 2;
            p.select_nth_unstable_by(m, |a, b| a.0[k].total_cmp(&b.0[k]).then(a.1.cmp(&b.1)));
            let (l, r) = p.split_at_mut(m);
            build(l, depth + 1);
            build(&mut r[1..], depth + 1);
        }
        build(&mut pts, 0);
        KdTree { pts }
    }

    /// Up to `k` nearest points within `radius` of `x` (indices and distances, nearest
    /// first, ties by index), skipping those `skip` rejects.
    pub fn nearest(
        &self,
        x: &[f64; 3],
        k: usize,
        radius: f64,
        skip: &dyn Fn(u32) -> bool,
    ) -> Vec<(u32, f64)> {
        let mut best: Vec<(u32, f64)> = Vec::new();
        fn rec(
            p: &[([f64; 3], u32)],
            depth: usize,
            x: &[f64; 3],
            k: usize,
            radius: f64,
            skip: &dyn Fn(u32) -> bool,
            best: &mut Vec<(u32, f64)>,
        ) {
            if p.is_empty() {
                return;
            }
            let m = p.len() / 2;
            let (q, id) = p[m];
            let d = ((q[0] - x[0]).powi(2) + (q[1] - x[1]).powi(2) + (q[2] - x[2]).powi(2)).sqrt();
            if d <= radius && !skip(id) {
                best.push((id, d));
                best.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
                best.truncate(k);
            }
            let axis = depth % 3;
            let diff = x[axis] - q[axis];
            let (near, far) = if diff <= 0.0 {
                (&p[..m], &p[m + 1..])
            } else {
                (&p[m + 1..], &p[..m])
            };
            rec(near, depth + 1, x, k, radius, skip, best);
            let bound = if best.len() == k {
                best[k - 1].1.min(radius)
            } else {
                radius
            };
            if diff.abs() <= bound {
                rec(far, depth + 1, x, k, radius, skip, best);
            }
        }
        rec(&self.pts, 0, x, k, radius, skip, &mut best);
        best
    }
}
