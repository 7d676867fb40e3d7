//! The driver's culling (paper §4, the driver: "until all possible surface pairs are
//! processed"): the pairs of faces whose bounding boxes overlap, found by a sweep along one
//! axis without listing all pairs; boxes of control nets (convex hull property).

use crate::geom::Aabb;
use crate::spline::NurbsSurface;

/// Pairs `(i, j)` of faces whose boxes overlap: `i < j` within `a` when `b` is `None`, else
/// `i` in `a`, `j` in `b`. A face without a box (not finite) pairs with every face when
/// is kept with every face for surfaces (nothing may be culled that could intersect) and
/// dropped for meshes (an empty mesh meets nothing).
pub(super) fn overlapping_pairs(
    a: &[Option<Aabb<f64, 3>>],
    b: Option<&[Option<Aabb<f64, 3>>]>,
    meshes: bool,
) -> Vec<(usize, usize)> {
    // Events sorted by the lower end of the boxes along the axis where their lower ends spread
    // most; side 0 = a, 1 = b.
    let sides: Vec<&[Option<Aabb<f64, 3>>]> = match b {
        Some(bb) => vec![a, bb],
        None => vec![a],
    };
    let spread = |k: usize| {
        let (lo, hi) = sides
            .iter()
            .flat_map(|l| l.iter().flatten())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), bx| {
                (l.min(bx.min[k]), h.max(bx.min[k]))
            });
        hi - lo
    };
    let axis = (0..3)
        .max_by(|&x, &y| spread(x).total_cmp(&spread(y)))
        .unwrap_or(0);
    let mut items: Vec<(f64, usize, usize)> = Vec::new();
    let mut unboxed: Vec<(usize, usize)> = Vec::new();
    for (side, list) in sides.iter().enumerate() {
        for (i, x) in list.iter().enumerate() {
            match x {
                Some(bx) => items.push((bx.min[axis], side, i)),
                None => unboxed.push((side, i)),
            }
        }
    }
    items.sort_by(|x, y| x.0.total_cmp(&y.0));
    let get = |side: usize, i: usize| sides[side][i].as_ref();
    let mut out = Vec::new();
    let mut active: Vec<(usize, usize)> = Vec::new();
    for &(lo, side, i) in &items {
        active.retain(|&(s2, j)| get(s2, j).is_some_and(|bx| bx.max[axis] >= lo));
        let me = get(side, i);
        for &(s2, j) in &active {
            let pair_ok = if b.is_some() { s2 != side } else { true };
            if pair_ok
                && let (Some(p), Some(q)) = (me, get(s2, j))
                && p.overlaps(q)
            {
                let (x, y) = if b.is_some() {
                    if side == 0 { (i, j) } else { (j, i) }
                } else {
                    (i.min(j), i.max(j))
                };
                out.push((x, y));
            }
        }
        active.push((side, i));
    }
    if !meshes {
        for &(side, i) in &unboxed {
            match b {
                None => (0..a.len())
                    .filter(|&j| j != i)
                    .for_each(|j| out.push((i.min(j), i.max(j)))),
                Some(bb) => {
                    if side == 0 {
                        (0..bb.len()).for_each(|j| out.push((i, j)));
                    } else {
                        (0..a.len()).for_each(|j| out.push((j, i)));
                    }
                }
            }
        }
        out.sort_unstable();
        out.dedup();
    }
    out
}

pub(super) fn net_box(s: &NurbsSurface<f64, 3>) -> Option<Aabb<f64, 3>> {
    let pts = s.points_weights().0;
    Aabb::of_points(pts.iter())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bx(lo: [f64; 3], hi: [f64; 3]) -> Option<Aabb<f64, 3>> {
        Aabb::of_points([lo, hi].iter())
    }

    /// The sweep lists exactly the overlapping pairs that the brute-force test lists.
    #[test]
    fn sweep_equals_brute_force() {
        let mut seed = 7u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..20 {
            let mut make = |n: usize| -> Vec<Option<Aabb<f64, 3>>> {
                (0..n)
                    .map(|_| {
                        let lo = [rnd() * 10.0, rnd() * 10.0, rnd() * 10.0];
                        let s = rnd() * 2.0;
                        bx(lo, [lo[0] + s, lo[1] + s * rnd(), lo[2] + s])
                    })
                    .collect()
            };
            let (a, b) = (make(40), make(30));
            let brute = |x: &Option<Aabb<f64, 3>>, y: &Option<Aabb<f64, 3>>| {
                x.as_ref().unwrap().overlaps(y.as_ref().unwrap())
            };
            let mut one: Vec<(usize, usize)> = Vec::new();
            for i in 0..a.len() {
                for j in i + 1..a.len() {
                    if brute(&a[i], &a[j]) {
                        one.push((i, j));
                    }
                }
            }
            assert_eq!(overlapping_pairs(&a, None, false), one);
            let mut two: Vec<(usize, usize)> = Vec::new();
            for i in 0..a.len() {
                for j in 0..b.len() {
                    if brute(&a[i], &b[j]) {
                        two.push((i, j));
                    }
                }
            }
            let mut got = overlapping_pairs(&a, Some(&b), false);
            got.sort_unstable();
            assert_eq!(got, two);
        }
        // A face without a box pairs with every face (surfaces), with none (meshes).
        let a = vec![bx([0.0; 3], [1.0; 3]), None, bx([5.0; 3], [6.0; 3])];
        assert_eq!(overlapping_pairs(&a, None, false), vec![(0, 1), (1, 2)]);
        assert!(overlapping_pairs(&a, None, true).is_empty());
    }
}
