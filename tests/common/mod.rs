//! Shared test helpers: a deterministic generator of random, nearly-degenerate, coplanar and
//! integer-grid inputs, and the case count (`VERICAD_LARGE=1` multiplies it by 20).
#![allow(dead_code)]

pub mod cli;
pub mod coons;
pub mod curves;
pub mod mesh;
pub mod reparam;
pub mod scan;
pub mod shapes;
pub mod trims;

use vericad::geom::lift_point;
use vericad::scalar::Rational;

/// SplitMix64: small, deterministic, good enough for test inputs.
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.unit()
    }
    pub fn int(&mut self, lo: i64, hi: i64) -> i64 {
        lo + (self.next_u64() % ((hi - lo + 1) as u64)) as i64
    }
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
    /// Nudge `x` by up to `k` ulps.
    pub fn nudge(&mut self, x: f64, k: i64) -> f64 {
        let mut y = x;
        let steps = self.int(-k, k);
        for _ in 0..steps.abs() {
            y = if steps > 0 {
                y.next_up()
            } else {
                y.next_down()
            };
        }
        y
    }
    pub fn p2(&mut self, s: f64) -> [f64; 2] {
        [self.range(-s, s), self.range(-s, s)]
    }
    pub fn p3(&mut self, s: f64) -> [f64; 3] {
        [self.range(-s, s), self.range(-s, s), self.range(-s, s)]
    }
    pub fn grid3(&mut self, n: i64) -> [f64; 3] {
        [
            self.int(-n, n) as f64,
            self.int(-n, n) as f64,
            self.int(-n, n) as f64,
        ]
    }
}

/// Number of cases per property: 100,000 by default, 2,000,000 with `VERICAD_LARGE=1`.
pub fn cases() -> usize {
    if std::env::var("VERICAD_LARGE").is_ok_and(|v| v == "1") {
        2_000_000
    } else {
        100_000
    }
}

pub fn q2(p: &[f64; 2]) -> [Rational; 2] {
    lift_point(p)
}
pub fn q3(p: &[f64; 3]) -> [Rational; 3] {
    lift_point(p)
}

/// Coverage budgets for tests that call `coverage` directly: match distance `d`, depths 24
/// (pairs) and 96 (crossings), 400,000 boxes, no deadline, no faces, no tubes.
pub fn coverage_params(d: f64) -> vericad::ssi::coverage::CoverageParams {
    vericad::ssi::coverage::CoverageParams {
        match_distance: d,
        max_pair_depth: 24,
        max_crossing_depth: 96,
        max_boxes: 400_000,
        deadline: None,
        cancel: None,
        outside: None,
        tubes: Default::default(),
        borders: Default::default(),
        restrict: None,
    }
}
