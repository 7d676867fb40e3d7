//! Shared oracle and input generators of the harnesses: exact rationals (`Rational`, with
//! `f64` lifted exactly by `vericad::scalar::lift`), a reproducible xorshift generator and
//! pools of adversarial `f64` values.

#![allow(dead_code)]

pub use vericad::scalar::Rational as Q;
use vericad::scalar::Scalar;
pub use vericad::scalar::{lift, ratio};

/// The exact value of a finite `f64`.
/// Cases to run: `small` by default, `large` with `VERICAD_LARGE` set.
pub fn cases<T>(small: T, large: T) -> T {
    if std::env::var("VERICAD_LARGE").is_ok() {
        large
    } else {
        small
    }
}

pub fn q(x: f64) -> Q {
    lift::<Q>(x)
}

pub fn qi(n: i64) -> Q {
    Q::from(n)
}

pub fn zero() -> Q {
    Q::ZERO
}

pub fn one() -> Q {
    Q::ONE
}

/// `x <= y` where `y` may be `+inf` / `-inf` (an extended-real end point).
pub fn le_ext(x: &Q, y: f64) -> bool {
    if y == f64::INFINITY {
        return true;
    }
    if y == f64::NEG_INFINITY || y.is_nan() {
        return false;
    }
    *x <= q(y)
}

/// `y <= x` where `y` may be infinite.
pub fn ge_ext(x: &Q, y: f64) -> bool {
    if y == f64::NEG_INFINITY {
        return true;
    }
    if y == f64::INFINITY || y.is_nan() {
        return false;
    }
    *x >= q(y)
}

/// Whether the exact `x` lies in `[lo, hi]` (extended end points).
pub fn in_ext(x: &Q, lo: f64, hi: f64) -> bool {
    ge_ext(x, lo) && le_ext(x, hi)
}

pub fn abs(x: &Q) -> Q {
    Scalar::abs(x)
}

pub type Q3 = [Q; 3];

pub fn q3(p: &[f64; 3]) -> Q3 {
    [q(p[0]), q(p[1]), q(p[2])]
}

pub fn sub3(a: &Q3, b: &Q3) -> Q3 {
    [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
}

pub fn add3(a: &Q3, b: &Q3) -> Q3 {
    [&a[0] + &b[0], &a[1] + &b[1], &a[2] + &b[2]]
}

pub fn scale3(a: &Q3, s: &Q) -> Q3 {
    [&a[0] * s, &a[1] * s, &a[2] * s]
}

pub fn dot3(a: &Q3, b: &Q3) -> Q {
    &a[0] * &b[0] + &a[1] * &b[1] + &a[2] * &b[2]
}

pub fn cross3(a: &Q3, b: &Q3) -> Q3 {
    [
        &a[1] * &b[2] - &a[2] * &b[1],
        &a[2] * &b[0] - &a[0] * &b[2],
        &a[0] * &b[1] - &a[1] * &b[0],
    ]
}

/// Exact squared distance from `c` to the segment `[p, q]` (clamped projection).
pub fn dist2_seg(c: &Q3, p: &Q3, qq: &Q3) -> Q {
    let d = sub3(qq, p);
    let e = sub3(c, p);
    let dd = dot3(&d, &d);
    let t = if dd.is_zero() {
        zero()
    } else {
        let t = dot3(&e, &d) / &dd;
        if t < zero() {
            zero()
        } else if t > one() {
            one()
        } else {
            t
        }
    };
    let r = sub3(&e, &scale3(&d, &t));
    dot3(&r, &r)
}

/// Reproducible xorshift64* generator (no dependency, same sequence on every machine).
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed.max(1))
    }
    pub fn next(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    /// Uniform in `0..n`.
    pub fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
    pub fn coin(&mut self) -> bool {
        self.next() & 1 == 1
    }
    /// Uniform in `[0, 1)` with 53 bits.
    pub fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    /// A small integer in `lo..=hi`.
    pub fn int(&mut self, lo: i64, hi: i64) -> i64 {
        lo + self.below((hi - lo + 1) as u64) as i64
    }
    /// A rational in `[0, 1]`: `k / 64`, or one of the ends, or `1/3`.
    pub fn unit_q(&mut self) -> Q {
        match self.below(8) {
            0 => zero(),
            1 => one(),
            2 => ratio(1, 3),
            _ => ratio(self.below(65) as i64, 64),
        }
    }
    /// An exact point of `[lo, hi]` (an end point or a random interior rational).
    pub fn in_interval(&mut self, lo: f64, hi: f64) -> Q {
        let t = self.unit_q();
        q(lo) + (q(hi) - q(lo)) * t
    }
    /// A random finite `f64` with any bit pattern (sign, exponent, mantissa).
    pub fn any_finite(&mut self) -> f64 {
        loop {
            let x = f64::from_bits(self.next());
            if x.is_finite() {
                return x;
            }
        }
    }
    /// A random `f64` with exponent in `[-e, e]` and a full random mantissa.
    pub fn scaled(&mut self, e: i32) -> f64 {
        let m = 1.0 + self.unit();
        let s = if self.coin() { -1.0 } else { 1.0 };
        s * m * 2f64.powi(self.int(-e as i64, e as i64) as i32)
    }
}

/// Adversarial `f64` values: signed zeros, subnormals, the normal/subnormal border, huge
/// and near-overflow values, the thresholds the interval kernel tests against (`1e±280`,
/// `1e±290`), the splitting constant of Dekker's product, values one ulp from powers of two
/// and from simple fractions.
pub fn adversarial() -> Vec<f64> {
    let mut v = vec![
        0.0,
        -0.0,
        f64::MIN_POSITIVE,
        f64::MIN_POSITIVE.next_down(),
        f64::MIN_POSITIVE.next_up(),
        5e-324,
        1e-323,
        3.0 * 2f64.powi(-1070),
        2f64.powi(-1000),
        2f64.powi(-600),
        2f64.powi(-537),
        2f64.powi(-511),
        f64::MAX,
        f64::MAX.next_down(),
        f64::MAX / 2.0,
        f64::MAX / 3.0,
        2f64.powi(1000),
        2f64.powi(1023),
        2f64.powi(600),
        2f64.powi(511),
        1e290,
        1e290f64.next_down(),
        1e290f64.next_up(),
        1e-280,
        1e-280f64.next_down(),
        1e-280f64.next_up(),
        1e-290,
        1e300,
        1e-300,
        1e145,
        1e-145,
        1.0,
        1.0f64.next_up(),
        1.0f64.next_down(),
        2.0,
        3.0,
        0.5,
        0.1,
        1.0 / 3.0,
        2.0 / 3.0,
        134217729.0,
        134217728.0,
        2f64.powi(53),
        2f64.powi(53) + 2.0,
        2f64.powi(52) + 1.0,
        2f64.powi(-53),
        2f64.powi(-54),
        (2f64.powi(27) + 1.0) * (2f64.powi(26) + 1.0),
        std::f64::consts::PI,
        1e16,
        1e-16,
    ];
    let n = v.len();
    for i in 0..n {
        v.push(-v[i]);
    }
    v
}

/// Exact homogeneous point of a Bézier patch of degrees `(p, q_)` with homogeneous net `net`
/// (row-major, `i` along u) at `(u, v)`: de Casteljau in v on every row, then in u.
pub fn eval_exact(p: usize, q_: usize, net: &[[Q; 4]], u: &Q, v: &Q) -> [Q; 4] {
    let lerp_row = |row: Vec<[Q; 4]>, t: &Q| -> [Q; 4] {
        let mut r = row;
        let n = r.len();
        for level in 1..n {
            for k in 0..n - level {
                r[k] = std::array::from_fn(|c| &r[k][c] + (&r[k + 1][c] - &r[k][c]) * t);
            }
        }
        r[0].clone()
    };
    let cols: Vec<[Q; 4]> = (0..=p)
        .map(|i| lerp_row((0..=q_).map(|j| net[i * (q_ + 1) + j].clone()).collect(), v))
        .collect();
    lerp_row(cols, u)
}
