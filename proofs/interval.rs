//! Enclosure of the outward-rounded interval operations (`vericad::scalar::Interval`).
//!
//! Every certificate that carries an error bound (constructed crossing points, curve-on-
//! surface bounds, the coverage certificate's hulls, cones and distances) rests on one lemma:
//! *for reals `a ∈ x`, `b ∈ y`, the exact `a ∘ b` lies in `x ∘ y`*. Here it is checked
//! against exact rational arithmetic.

use crate::common::*;
use vericad::scalar::Interval;

/// Number of random interior points per operand pair.
const INTERIOR: usize = 1;

fn check(name: &str, x: Interval, y: Interval, r: Interval, exact: &Q) {
    assert!(
        !r.lo.is_nan() && !r.hi.is_nan() && r.lo <= r.hi,
        "{name}: {x:?} {y:?} gives the invalid interval {r:?}"
    );
    assert!(
        in_ext(exact, r.lo, r.hi),
        "{name}: {x:?} {y:?} -> {r:?} misses the exact value {}",
        exact.to_string().chars().take(80).collect::<String>()
    );
}

/// The property: for `a` at the ends of `x` and at random interior rationals of `x`, and `b`
/// likewise in `y`, the exact `a + b`, `a − b`, `a · b`, `a / b` (when `checked_div` gives a
/// quotient), `a²` and `−a` lie in the computed intervals; `x.hull(y)` holds `a` and `b`;
/// `radius_about_mid` bounds `|a − mid|`. Operands: finite end points, `lo <= hi`.
pub fn prop_interval_ops_enclose(x: Interval, y: Interval, rng: &mut Rng) {
    assert!(x.lo <= x.hi && y.lo <= y.hi);
    let (add, sub, mul, div) = (x + y, x - y, x * y, x.checked_div(y));
    let (sqr, neg, hull) = (x.sqr(), -x, x.hull(y));
    if x.checked_div(y).is_none() {
        assert!(y.contains_zero(), "checked_div refused {x:?} / {y:?}");
    }
    let mut xs = vec![q(x.lo), q(x.hi)];
    let mut ys = vec![q(y.lo), q(y.hi)];
    if x.lo == x.hi {
        xs.pop();
    } else {
        for _ in 0..INTERIOR {
            xs.push(rng.in_interval(x.lo, x.hi));
        }
    }
    if y.lo == y.hi {
        ys.pop();
    } else {
        for _ in 0..INTERIOR {
            ys.push(rng.in_interval(y.lo, y.hi));
        }
    }
    for a in &xs {
        check("sqr", x, x, sqr, &(a * a));
        check("neg", x, x, neg, &(-a.clone()));
        check("hull", x, y, hull, a);
        if x.is_finite() {
            let m = q(x.mid());
            let r = x.radius_about_mid();
            assert!(le_ext(&abs(&(a - &m)), r), "radius_about_mid of {x:?}: {r}");
        }
        for b in &ys {
            check("add", x, y, add, &(a + b));
            check("sub", x, y, sub, &(a - b));
            check("mul", x, y, mul, &(a * b));
            if let Some(d) = div {
                check("div", x, y, d, &(a / b));
            }
        }
    }
    for b in &ys {
        check("hull", x, y, hull, b);
    }
}

/// Regression (found by the harness above, fixed): `checked_div` on two points took the
/// quotient `q = a / b` as exact when Dekker's product gave `q·b = a` with zero error, but
/// near underflow the error term itself underflows to zero: `2^-1022 / (2^-1022 − 2^-1074)`
/// returned the point `1 + 2^-52`, while the exact quotient is `2^52 / (2^52 − 1)`. The
/// shortcut now requires every operand above `1e-280` in magnitude, as the product does.
#[test]
fn checked_div_exact_point_shortcut_near_underflow() {
    for (a, b) in [
        (f64::MIN_POSITIVE, f64::MIN_POSITIVE.next_down()),
        (-2.225073858507202e-308, -4.1823696442276423e-305),
    ] {
        let (x, y) = (Interval::point(a), Interval::point(b));
        let r = x.checked_div(y).unwrap();
        check("div", x, y, r, &(q(a) / q(b)));
    }
}

/// Operand intervals built from a value: the point, a few ulps wide, and spans to other
/// values.
fn operands(a: f64, b: f64, rng: &mut Rng) -> Vec<Interval> {
    let mut v = vec![Interval::point(a)];
    let mut hi = a;
    for _ in 0..1 + rng.below(3) {
        hi = hi.next_up();
    }
    if hi.is_finite() {
        v.push(Interval::new(a, hi));
    }
    v.push(Interval::new(a.min(b), a.max(b)));
    v
}

/// Exhaustive over point operands from the adversarial pool (every ordered pair: exact
/// sums and products, ties, cancellation, subnormals, overflow and the kernel's
/// thresholds), plus intervals spanning pool values.
#[test]
fn interval_ops_enclose_adversarial_pairs() {
    let pool = adversarial();
    let mut rng = Rng::new(1);
    for &a in &pool {
        for &b in &pool {
            prop_interval_ops_enclose(Interval::point(a), Interval::point(b), &mut rng);
        }
    }
    for (i, &a) in pool.iter().enumerate() {
        let b = pool[(i * 7 + 3) % pool.len()];
        let c = pool[(i * 13 + 5) % pool.len()];
        for x in operands(a, b, &mut rng) {
            for y in operands(c, a, &mut rng) {
                prop_interval_ops_enclose(x, y, &mut rng);
            }
        }
    }
}

/// Random operands: any bit pattern; values of moderate exponent (so that sums and
/// products are mostly inexact and in range); exact cancellations (`a` and `−a·(1+ε)`);
/// products near the Dekker range limits; and operands one ulp apart.
#[test]
fn interval_ops_enclose_random() {
    let n = cases(4_000, 400_000);
    let mut rng = Rng::new(0x5eed_1234);
    let pool = adversarial();
    for i in 0..n {
        let (a, b) = match i % 6 {
            0 => (rng.any_finite(), rng.any_finite()),
            1 => (rng.scaled(60), rng.scaled(60)),
            2 => {
                let a = rng.scaled(1000);
                let mut b = -a;
                for _ in 0..rng.below(4) {
                    b = b.next_up();
                }
                (a, b)
            }
            3 => {
                // Products straddling the 1e±280 / 1e±290 thresholds and overflow.
                let e = [930, 965, 1020, -930, -965, -1020][rng.below(6) as usize];
                let a = rng.scaled(8) * 2f64.powi(e / 2);
                (a, rng.scaled(8) * 2f64.powi(e - e / 2))
            }
            4 => {
                let a = pool[rng.below(pool.len() as u64) as usize];
                let t = rng.scaled(30);
                (a, if rng.coin() { a * t } else { a + t })
            }
            _ => {
                let a = rng.scaled(300);
                (a, a * (1.0 + rng.scaled(1) * 2f64.powi(-50)))
            }
        };
        let (c, d) = (rng.scaled(60), rng.scaled(1000));
        let x = Interval::new(a.min(b), a.max(b));
        let y = if rng.coin() {
            Interval::point(c)
        } else {
            Interval::new(c.min(d), c.max(d))
        };
        if ![a, b, c, d].iter().all(|v| v.is_finite()) {
            continue;
        }
        let px = Interval::point(a);
        let py = Interval::point(b);
        prop_interval_ops_enclose(px, py, &mut rng);
        prop_interval_ops_enclose(x, y, &mut rng);
        prop_interval_ops_enclose(px, y, &mut rng);
    }
}
