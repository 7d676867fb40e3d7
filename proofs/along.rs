//! The bound of a curve part along an output cubic piece (`vericad::ssi::coverage::piece_bound`,
//! the `along` test of the coverage certificate's crossing search): every point of the part
//! lies within the returned `r` of the piece. Oracle: the part's point at rational `s`
//! (de Casteljau in rationals on the midpoints of its enclosed control points — a curve the
//! enclosure holds) and the piece's point at the closest parameter found in `f64`, both exact;
//! their exact distance, an upper bound of the distance to the piece, must be at most `r`.

use crate::common::*;
use vericad::scalar::Interval;
use vericad::ssi::coverage::patch::ICurve;
use vericad::ssi::coverage::piece_bound;
use vericad::ssi::hermite::Piece;

/// The exact point of the rational Bézier part (midpoints of its enclosures) at `s`.
fn part_at(c: &ICurve, s: &Q) -> Q3 {
    let mut h: Vec<[Q; 4]> =
        c.x.iter()
            .zip(&c.w)
            .map(|(x, w)| [q(x[0].mid()), q(x[1].mid()), q(x[2].mid()), q(w.mid())])
            .collect();
    let r = one() - s;
    for lev in 1..h.len() {
        for k in 0..h.len() - lev {
            h[k] = std::array::from_fn(|j| &r * &h[k][j] + s * &h[k + 1][j]);
        }
    }
    std::array::from_fn(|j| &h[0][j] / &h[0][3])
}

/// The exact point of the cubic piece at `t`: Bernstein points `p`, `p + ṗ/3`, `q − q̇/3`, `q`.
fn piece_at(h: &Piece, t: &Q) -> Q3 {
    let third = ratio(1, 3);
    let b: [Q3; 4] = [
        std::array::from_fn(|k| q(h.p[k])),
        std::array::from_fn(|k| q(h.p[k]) + q(h.dp[k]) * &third),
        std::array::from_fn(|k| q(h.q[k]) - q(h.dq[k]) * &third),
        std::array::from_fn(|k| q(h.q[k])),
    ];
    let r = one() - t;
    let w = [
        &r * &r * &r,
        qi(3) * t * &r * &r,
        qi(3) * t * t * &r,
        t * t * t,
    ];
    std::array::from_fn(|k| {
        &w[0] * &b[0][k] + &w[1] * &b[1][k] + &w[2] * &b[2][k] + &w[3] * &b[3][k]
    })
}

/// When `piece_bound(h, c, d)` gives `r`: at `m + 1` rational points of the part, the exact
/// distance to the piece point at the `f64` foot parameter is at most `r` (exactly).
/// Returns whether a bound was given.
pub fn prop_part_within_bound(h: &Piece, c: &ICurve, d: f64, m: i64) -> bool {
    let Some(r) = piece_bound(h, c, d) else {
        return false;
    };
    assert!(r.is_finite() && r >= 0.0, "bound {r}");
    let r2 = q(r) * q(r);
    for i in 0..=m {
        let s = ratio(i, m);
        let x = part_at(c, &s);
        let xf: [f64; 3] = std::array::from_fn(|k| to_f64(&x[k]));
        let t = h.foot(&xf).1;
        let e = sub3(&x, &piece_at(h, &q(t)));
        assert!(
            dot3(&e, &e) <= r2,
            "part point {i}/{m} farther than the bound {r} from the piece (d {d})"
        );
    }
    true
}

fn to_f64(x: &Q) -> f64 {
    use vericad::scalar::Scalar;
    Scalar::to_f64(x)
}

/// The cubic piece on the circle of radius `rad` from angle `a` to `b` (exact end points and
/// unit tangents, as the tracer's jets give them).
fn piece_on(rad: f64, a: f64, b: f64) -> Piece {
    let at = |t: f64| -> [f64; 7] { [rad * t.cos(), rad * t.sin(), 0.0, 0.0, 0.0, 0.0, 0.0] };
    let jet = |t: f64| -> [f64; 7] { [-t.sin(), t.cos(), 0.0, 0.0, 0.0, 0.0, 0.0] };
    Piece::cubic(&at(a), &jet(a), &at(b), &jet(b)).expect("a piece")
}

/// The rational quadratic arc of the circle of radius `rad` from angle `a` to `b`, scaled by
/// `1 + off` (so `off · rad` off the circle), tilted out of its plane by `tilt` at the
/// middle point, with control points widened by `wide` (relative).
fn arc(rad: f64, a: f64, b: f64, off: f64, tilt: f64, wide: f64) -> ICurve {
    let (m, phi) = (0.5 * (a + b), 0.5 * (b - a));
    let s = rad * (1.0 + off);
    let w = phi.cos();
    let p = [
        [s * a.cos(), s * a.sin(), 0.0],
        [s * m.cos() / w, s * m.sin() / w, tilt],
        [s * b.cos(), s * b.sin(), 0.0],
    ];
    let iv = |x: f64| {
        let e = wide * x.abs();
        Interval::new(x - e, x + e)
    };
    let ws = [1.0, w, 1.0];
    ICurve {
        x: (0..3).map(|i| p[i].map(|x| iv(x * ws[i]))).collect(),
        w: ws.iter().map(|x| iv(*x)).collect(),
    }
}

/// Circles of radius 0.5 … 100, pieces of 0.05 … 0.8 rad, parts inside them and reaching
/// their ends, on the circle and moved off it by up to 1e-5 of the radius, tilted out of the
/// plane, with point and widened control points; match distances 1e-7 … 1e-3 of the radius.
pub fn run_along_random(cases: usize) {
    let mut rng = Rng::new(0xa10e9);
    let mut bounded = 0;
    for k in 0..cases {
        let rad = [0.5, 2.0, 100.0][k % 3];
        let theta = [0.05, 0.2, 0.8][(k / 3) % 3];
        let a = rng.range(-3.0, 3.0);
        let h = piece_on(rad, a, a + theta);
        let (f0, f1) = match rng.below(3) {
            0 => (0.0, 1.0),
            1 => (rng.range(0.0, 0.4), rng.range(0.6, 1.0)),
            _ => (rng.range(0.0, 0.8), 1.0),
        };
        let off = [0.0, 1e-9, 1e-7, 1e-5][rng.below(4) as usize];
        let tilt = if rng.coin() { 0.0 } else { rad * 1e-7 };
        let wide = if rng.coin() { 0.0 } else { 1e-14 };
        let c = arc(rad, a + f0 * theta, a + f1 * theta, off, tilt, wide);
        let d = rad * [1e-7, 1e-6, 1e-5, 1e-3][rng.below(4) as usize];
        bounded += usize::from(prop_part_within_bound(&h, &c, d, 16));
    }
    assert!(
        bounded * 2 >= cases,
        "only {bounded} of {cases} parts bounded"
    );
}

#[test]
fn parts_along_pieces_are_within_their_bound() {
    run_along_random(cases(300, 30_000));
}
