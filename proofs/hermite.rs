//! The coverage certificate's bound for cubic pieces (`vericad::ssi::hermite::densify`): the
//! polyline of a piece's `f64` values lies within the proven distance of the exact piece,
//! both ways. Oracle: the piece evaluated exactly in rationals at rational parameters.

use crate::common::*;
use vericad::ssi::hermite::{Piece, densify};

/// The exact `H(τ)` (3D) of the piece at a rational `τ`.
fn exact(h: &Piece, t: &Q) -> Q3 {
    let (one, two, three) = (one(), qi(2), qi(3));
    let t2 = t * t;
    let t3 = &t2 * t;
    let w = [
        &two * &t3 - &three * &t2 + &one,
        &t3 - &two * &t2 + t,
        -(&two * &t3) + &three * &t2,
        &t3 - &t2,
    ];
    std::array::from_fn(|k| {
        &w[0] * q(h.p[k]) + &w[1] * q(h.dp[k]) + &w[2] * q(h.q[k]) + &w[3] * q(h.dq[k])
    })
}

/// For the chords `[v_i, v_{i+1}]` of `densify(h, delta, cap)` (every chord of up to 64,
/// else 64 spread over the piece, the first and last among them) and rational `τ` in
/// `[i/n, (i+1)/n]` (ends, and `m` interior points): the exact `H(τ)` lies within the proven
/// distance `r` of the chord point at the same parameter, `‖H(τ) − ℓ(τ)‖² ≤ r²` — so the
/// piece point is within `r` of the polyline and the chord point within `r` of the piece.
pub fn prop_densify_within_bound(h: &Piece, delta: f64, cap: usize, m: i64) {
    let (pts, r) = densify(h, delta, cap);
    let n = pts.len() - 1;
    assert!(
        n >= 1 && r.is_finite() && r > 0.0,
        "{h:?} {delta}: {n} chords, bound {r}"
    );
    let r2 = q(r) * q(r);
    let stride = n.div_ceil(64).max(1);
    for i in (0..n).step_by(stride).chain([n - 1]) {
        let (a, b) = (q3(&pts[i]), q3(&pts[i + 1]));
        for j in 0..=m {
            // ℓ at fraction s = j/m of the chord, τ = (i + s) / n.
            let s = ratio(j, m);
            let t = (qi(i as i64) + &s) / qi(n as i64);
            let l = add3(&a, &scale3(&sub3(&b, &a), &s));
            let e = sub3(&exact(h, &t), &l);
            assert!(
                dot3(&e, &e) <= r2,
                "{h:?}: chord {i}/{n} at {j}/{m} off by more than {r}"
            );
        }
    }
}

fn piece(rng: &mut Rng, scale: f64, offset: f64) -> Piece {
    let mut v = || -> [f64; 7] { std::array::from_fn(|_| offset + scale * rng.range(-1.0, 1.0)) };
    let (p, q) = (v(), v());
    let mut d = || -> [f64; 7] { std::array::from_fn(|_| 2.0 * scale * rng.range(-1.0, 1.0)) };
    Piece {
        p,
        q,
        dp: d(),
        dq: d(),
    }
}

#[test]
fn densified_pieces_are_within_their_bound() {
    let n = cases(300, 30_000);
    let mut rng = Rng::new(23);
    let mut capped = 0;
    for i in 0..n {
        // Unit pieces; pieces far from the origin (rounding of the values matters); tiny and
        // large pieces; nearly straight ones (derivatives along the chord).
        let (scale, offset) = [
            (1.0, 0.0),
            (1e-3, 1e3),
            (1e-6, 0.0),
            (1e4, 0.0),
            (0.1, -7.0),
        ][(i % 5) as usize];
        let mut h = piece(&mut rng, scale, offset);
        if i % 7 == 0 {
            let c: [f64; 7] = std::array::from_fn(|k| h.q[k] - h.p[k]);
            h.dp = c;
            h.dq = c.map(|x| x * (1.0 + 1e-9));
        }
        let delta = scale * 10f64.powf(-rng.range(1.0, 6.0));
        let cap = if i % 11 == 0 { 3 } else { 1 << 16 };
        let (_, r) = densify(&h, delta, cap);
        if r > delta {
            capped += 1;
        } else {
            assert!(r <= delta, "{r} > {delta}");
        }
        prop_densify_within_bound(&h, delta, cap, 4);
    }
    assert!(capped > 0, "the sample cap was never reached");
}
