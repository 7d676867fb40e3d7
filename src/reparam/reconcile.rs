//! Step 2 of the RCA parametrization (§2, "Finding an interpolating surface"): the
//! interpolation points of two opposite boundary curves, as fractions of each curve's arc
//! length, are reconciled into one sequence. For every fraction present on one curve and
//! absent (within a tolerance) on the other, an auxiliary point is inserted on the other:
//! the result is the union of the two sets, with fractions closer than the tolerance merged
//! into one (their mean; 0 and 1 stay fixed).
//!
//! The merged sequence is the parameter sequence of the new surface in that direction
//! (`ξ_i` from `v = v0` and `v = v1`, `η_j` from `u = u0` and `u = u1`): each boundary point
//! sits at the arc-length fraction equal to its parameter, so both curves are chord-length
//! (arc-length) parametrized by construction (docs/papers.md §A, property (1)), with one knot
//! vector by averaging ([`knots`], The NURBS Book eq. 9.8).

/// Union of the fraction sets `a` and `b` (each ascending from 0 to 1), fractions closer
/// than `merge` times the smallest gap of either set merged. A set is `None` for a border
/// that is a point (a pole): the other set alone is taken. `None` when both are.
pub fn reconcile(a: Option<&[f64]>, b: Option<&[f64]>, merge: f64) -> Option<Vec<f64>> {
    let min_gap = |f: &[f64]| {
        f.windows(2)
            .map(|w| w[1] - w[0])
            .fold(f64::INFINITY, f64::min)
    };
    let sets: Vec<&[f64]> = [a, b].into_iter().flatten().collect();
    if sets.is_empty() {
        return None;
    }
    let gap = sets
        .iter()
        .map(|f| min_gap(f))
        .fold(f64::INFINITY, f64::min);
    let tol = merge * gap;
    let mut all: Vec<f64> = sets.iter().flat_map(|f| f.iter().copied()).collect();
    all.sort_by(f64::total_cmp);
    // Clusters of consecutive fractions closer than `tol`.
    let mut out: Vec<f64> = Vec::new();
    let mut cluster: Vec<f64> = Vec::new();
    let flush = |cluster: &mut Vec<f64>, out: &mut Vec<f64>| {
        if cluster.is_empty() {
            return;
        }
        let v = if cluster.contains(&0.0) {
            0.0
        } else if cluster.contains(&1.0) {
            1.0
        } else {
            cluster.iter().sum::<f64>() / cluster.len() as f64
        };
        if out.last().is_none_or(|&l| v > l) {
            out.push(v);
        }
        cluster.clear();
    };
    for x in all {
        if let Some(&last) = cluster.last()
            && x - last > tol
        {
            flush(&mut cluster, &mut out);
        }
        cluster.push(x);
    }
    flush(&mut cluster, &mut out);
    if out.first() != Some(&0.0) {
        out.insert(0, 0.0);
    }
    if out.last() != Some(&1.0) {
        out.push(1.0);
    }
    Some(out)
}

/// Cubic knots by averaging (The NURBS Book eq. 9.8) for the parameters `t`.
pub fn knots(t: &[f64]) -> Vec<f64> {
    crate::spline::interpolate::averaged_knots(t, 3.min(t.len() - 1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn union_with_auxiliary_points_and_merging() {
        let a = [0.0, 0.25, 0.5, 0.75, 1.0];
        let b = [0.0, 0.35, 0.51, 1.0];
        // Smallest gap 0.16; merge below 0.048: 0.5 and 0.51 become 0.505.
        let r = reconcile(Some(&a), Some(&b), 0.3).unwrap();
        assert_eq!(r.len(), 6);
        assert_eq!(r[0], 0.0);
        assert_eq!(r[5], 1.0);
        assert!((r[3] - 0.505).abs() < 1e-15);
        assert!((r[1] - 0.25).abs() < 1e-15 && (r[2] - 0.35).abs() < 1e-15);
        // A pole side: the other set alone.
        assert_eq!(reconcile(None, Some(&b), 0.3).unwrap(), b.to_vec());
        assert!(reconcile(None, None, 0.3).is_none());
    }
}
