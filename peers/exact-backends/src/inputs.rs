//! The benchmark inputs, as `f64` values from a seeded xorshift64* generator. Every backend
//! lifts the same values exactly (see `crate::lift3`).

/// xorshift64* (Vigna), seeded.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed.max(1))
    }
    pub fn next_u64(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    /// Uniform in `[0, 1)` with all 53 significand bits random.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
    /// Uniform in `[lo, hi)` (rounded: a full-precision f64).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    /// A multiple of `2^-10` in `[-8, 8)`: few significant bits, so sums stay exact in f64.
    pub fn dyadic(&mut self) -> f64 {
        ((self.next_u64() >> 50) as i64 - 8192) as f64 / 1024.0
    }
    fn point(&mut self, r: f64) -> [f64; 3] {
        [self.range(-r, r), self.range(-r, r), self.range(-r, r)]
    }
}

/// Kinds of orient3d cases, in the order [`orient3d_cases`] returns them.
pub const ORIENT_RANDOM: usize = 16;
pub const ORIENT_NEAR: usize = 24;
pub const ORIENT_EXACT: usize = 8;

/// 48 quadruples `(a, b, c, d)`:
/// * 16 random points in `[-10, 10]³`;
/// * 24 nearly coplanar: `a, b, c` random, `d = a + s(b-a) + t(c-a)` evaluated in f64
///   (`s, t` random in `[0, 1)`), so `d` is off the plane only by rounding;
/// * 8 exactly coplanar: dyadic points on the plane `x + y + z = 1` (the determinant is 0).
pub fn orient3d_cases() -> Vec<[[f64; 3]; 4]> {
    let mut r = Rng::new(0x0DE1_3D0F_5EED);
    let mut out = Vec::new();
    for _ in 0..ORIENT_RANDOM {
        out.push([r.point(10.0), r.point(10.0), r.point(10.0), r.point(10.0)]);
    }
    for _ in 0..ORIENT_NEAR {
        let (a, b, c) = (r.point(10.0), r.point(10.0), r.point(10.0));
        let (s, t) = (r.unit(), r.unit());
        let d = [0, 1, 2].map(|k| a[k] + s * (b[k] - a[k]) + t * (c[k] - a[k]));
        out.push([a, b, c, d]);
    }
    for _ in 0..ORIENT_EXACT {
        let mut p = || {
            let (x, y) = (r.dyadic(), r.dyadic());
            [x, y, 1.0 - x - y]
        };
        out.push([p(), p(), p(), p()]);
    }
    out
}

/// A Bézier net of degrees `(p, q)` with `f64` coordinates, row-major as `crate::Net`.
#[derive(Clone, Debug)]
pub struct NetF64 {
    pub p: usize,
    pub q: usize,
    pub pts: Vec<[f64; 3]>,
}

/// A CAD-like patch: a jittered grid (spacing ~3.3 by ~2.7) with random heights in
/// `[-1, 1]`; every coordinate a full-precision f64.
pub fn net(r: &mut Rng, p: usize, q: usize) -> NetF64 {
    let mut pts = Vec::with_capacity((p + 1) * (q + 1));
    for i in 0..=p {
        for j in 0..=q {
            pts.push([
                i as f64 * 3.3 + r.range(-0.5, 0.5),
                j as f64 * 2.7 + r.range(-0.5, 0.5),
                r.range(-1.0, 1.0),
            ]);
        }
    }
    NetF64 { p, q, pts }
}

/// 4 bicubic nets for the half split.
pub fn bicubic_nets() -> Vec<NetF64> {
    let mut r = Rng::new(0xB1C_0B1C);
    (0..4).map(|_| net(&mut r, 3, 3)).collect()
}

/// A patch and a chord `a→b` of its domain `[0,1]²`.
#[derive(Clone, Debug)]
pub struct ChordF64 {
    pub net: NetF64,
    pub a: [f64; 2],
    pub b: [f64; 2],
}

/// 4 patches of degrees `(p, q)`, each with a random chord (end points random in `[0,1)²`).
pub fn chords(p: usize, q: usize) -> Vec<ChordF64> {
    let mut r = Rng::new(0xC0_4D00 + (p * 16 + q) as u64);
    (0..4)
        .map(|_| ChordF64 {
            net: net(&mut r, p, q),
            a: [r.unit(), r.unit()],
            b: [r.unit(), r.unit()],
        })
        .collect()
}
