//! The sign-change certificate (`ssi/sign_change.rs`): where it returns a radius `r` for a
//! point `p` (as a certificate, or refused as above tol), a true common point of both faces
//! lies within `r` of `p`.
//!
//! The constructions make the truth exact: `A` is the graph `z = f(x, y)` of a biquadratic
//! Bézier patch over `[−1, 1]²` (`x = 2u − 1`, `y = 2v − 1`), `B` the plane `z = 0` over the
//! same square. A common point is `(x, y, 0)` with `f(x, y) = 0`, and `f` at rational
//! parameters is evaluated exactly from the control values (Bernstein sums in rationals, not
//! the kernel's evaluator). `f = a (x − x0)² ∓ b (y − y0)² + c` with dyadic coefficients
//! (control values from the polar form, exact in `f64`):
//! * a saddle (`−`): two crossing lines at `c = 0` — a branch point, where the certificate is
//!   used — and hyperbolas at `c ≠ 0`, from `±2⁻⁴⁸` (the rounding level of an evaluation
//!   near the branch point; the smallest `c` that keeps every control value exact) to `±2⁻¹⁰`;
//! * an elliptic cup (`+`): one touching point at `c = 0`, no common point at all for `c > 0`
//!   (from `2⁻⁴⁸` to `2⁻²⁰`), where every claim is false.
//!
//! **The oracle.** A claimed radius `r` about `p` is confirmed by a *witness*: two rational
//! points `w₁`, `w₂` of the plane with `f(w₁) ≥ 0 ≥ f(w₂)`, both within the disc
//! `{(x, y) : (x − p_x)² + (y − p_y)² ≤ r² − p_z²}`. The segment `w₁w₂` lies in that disc
//! (it is convex), `f` has a zero on it (intermediate value theorem), and that zero `(x*, y*)`
//! gives the common point `(x*, y*, 0)` within `r` of `p`. Witnesses are looked for at the
//! corners of the certificate's own parameter box (mapped to the plane), then on a grid and a
//! circle of samples across the disc. For the cup with `c > 0` no witness can exist (`f ≥ c`
//! exactly), and for `c = 0` the touching point must lie in the disc, decided exactly.

use crate::common::{Q, Rng, cases, q, qi, ratio};
use vericad::spline::NurbsSurface;
use vericad::ssi::certify::ExactSurface;
use vericad::ssi::sign_change::{SignChangeFail, certify_by_sign_change};

/// `f = a (x − x0)² + s b (y − y0)² + c` (`s = −1` saddle, `+1` cup), dyadic coefficients.
#[derive(Clone, Copy, Debug)]
pub struct Quadric {
    pub a: f64,
    pub b: f64,
    pub s: f64,
    pub x0: f64,
    pub y0: f64,
    pub c: f64,
}

impl Quadric {
    /// The biquadratic Bézier control values of `f` over `[−1, 1]²`: the polar form of
    /// `(x − x0)²` at the end parameters `x(0) = −1`, `x(1) = 1` gives
    /// `(−1 − x0)², (−1 − x0)(1 − x0), (1 − x0)²`.
    fn control(&self) -> Vec<[f64; 3]> {
        let polar = |x0: f64| {
            [
                (-1.0 - x0) * (-1.0 - x0),
                (-1.0 - x0) * (1.0 - x0),
                (1.0 - x0) * (1.0 - x0),
            ]
        };
        let (px, py) = (polar(self.x0), polar(self.y0));
        let mut pts = Vec::new();
        for (i, pxi) in px.iter().enumerate() {
            for (j, pyj) in py.iter().enumerate() {
                let z = self.a * pxi + self.s * self.b * pyj + self.c;
                pts.push([i as f64 - 1.0, j as f64 - 1.0, z]);
            }
        }
        pts
    }
    pub fn surface(&self) -> NurbsSurface<f64, 3> {
        let k = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
        NurbsSurface::new(k.clone(), 2, k, 2, 3, 3, self.control(), vec![1.0; 9])
            .expect("a valid patch")
    }
    /// `f(x, y)` exactly: the Bernstein sum of the control values at `u = (x + 1)/2`,
    /// `v = (y + 1)/2` (rational; independent of the kernel's evaluation).
    fn f(&self, x: &Q, y: &Q) -> Q {
        let two = qi(2);
        let (u, v) = ((x + qi(1)) / &two, (y + qi(1)) / &two);
        let bern = |t: &Q| {
            let s = qi(1) - t;
            [&s * &s, &two * t * &s, t * t]
        };
        let (bu, bv) = (bern(&u), bern(&v));
        let pts = self.control();
        let mut z = Q::ZERO;
        for i in 0..3 {
            for j in 0..3 {
                z += &bu[i] * &bv[j] * q(pts[i * 3 + j][2]);
            }
        }
        z
    }
    /// The exact check that the stored control values are the quadric (no rounding in their
    /// construction): both forms agree at a few rational points.
    fn reproduces(&self) -> bool {
        [(-1, 1), (0, 1), (1, 3), (-3, 4), (5, 8)]
            .iter()
            .all(|&(n, d)| {
                let x = ratio(n, d);
                let y = ratio(-n, d + 1);
                let dx = &x - q(self.x0);
                let dy = &y - q(self.y0);
                let direct = q(self.a) * &dx * &dx + q(self.s * self.b) * &dy * &dy + q(self.c);
                self.f(&x, &y) == direct
            })
    }
}

pub fn plane() -> NurbsSurface<f64, 3> {
    let k = vec![0.0, 0.0, 1.0, 1.0];
    let pts = vec![
        [-1.0, -1.0, 0.0],
        [-1.0, 1.0, 0.0],
        [1.0, -1.0, 0.0],
        [1.0, 1.0, 0.0],
    ];
    NurbsSurface::new(k.clone(), 1, k, 1, 2, 2, pts, vec![1.0; 4]).expect("a valid plane")
}

/// What the oracle decided about one claim.
#[derive(Debug, PartialEq, Eq)]
pub enum Verdict {
    /// A witness pair was found: the claim holds.
    Confirmed,
    /// No common point can lie in the ball (the cup above the plane, or the touching point
    /// outside it): the claim is false.
    Refuted,
    /// Neither (the oracle's samples found no sign change).
    Open,
}

/// The oracle for the claim "a common point lies within `r` of `p`" (module comment).
pub fn judge(f: &Quadric, p: &[f64; 3], r: f64, corners: &[[f64; 2]]) -> Verdict {
    let rho2 = q(r) * q(r) - q(p[2]) * q(p[2]);
    if rho2 < Q::ZERO {
        return Verdict::Refuted;
    }
    let (px, py) = (q(p[0]), q(p[1]));
    let inside = |x: &Q, y: &Q| {
        let (dx, dy) = (x - &px, y - &py);
        &dx * &dx + &dy * &dy <= rho2
    };
    if f.s > 0.0 {
        // f ≥ c everywhere; for c = 0 the only zero is (x0, y0).
        if f.c > 0.0 {
            return Verdict::Refuted;
        }
        if f.c == 0.0 {
            return if inside(&q(f.x0), &q(f.y0)) {
                Verdict::Confirmed
            } else {
                Verdict::Refuted
            };
        }
    }
    // Samples: the given corners, then a grid over the disc's inscribed square and a circle
    // just inside the disc (rational points; those outside the disc are dropped).
    let mut pts: Vec<(Q, Q)> = corners.iter().map(|c| (q(c[0]), q(c[1]))).collect();
    let rho = rho2.to_f64_lossy().sqrt();
    let n = 24;
    for i in 0..=n {
        for j in 0..=n {
            let t = |k: i32| q(0.7 * rho * (2.0 * k as f64 / n as f64 - 1.0));
            pts.push((&px + t(i), &py + t(j)));
        }
    }
    for k in 0..96 {
        let ang = k as f64 * std::f64::consts::TAU / 96.0;
        pts.push((
            &px + q(0.999 * rho * ang.cos()),
            &py + q(0.999 * rho * ang.sin()),
        ));
    }
    let (mut pos, mut neg) = (false, false);
    for (x, y) in &pts {
        if !inside(x, y) {
            continue;
        }
        let z = f.f(x, y);
        pos |= z >= Q::ZERO;
        neg |= z <= Q::ZERO;
        if pos && neg {
            return Verdict::Confirmed;
        }
    }
    Verdict::Open
}

trait Lossy {
    fn to_f64_lossy(&self) -> f64;
}

impl Lossy for Q {
    fn to_f64_lossy(&self) -> f64 {
        vericad::scalar::Scalar::to_f64(self)
    }
}

/// One case: the certificate for `p` (parameters from the plane's mapping, both orders of
/// the surfaces), each radius it states — a certificate or "above tol" — judged.
/// Returns the number of claims made and confirmed.
pub fn prop_sign_change_claims(f: &Quadric, p: &[f64; 3], tol: f64) -> (usize, usize) {
    assert!(
        f.reproduces(),
        "{f:?}: the control values are not the quadric"
    );
    let (sa, sb) = (f.surface(), plane());
    let (ea, eb) = (ExactSurface::new(&sa), ExactSurface::new(&sb));
    let uv = [(p[0] + 1.0) / 2.0, (p[1] + 1.0) / 2.0];
    let (mut made, mut confirmed) = (0, 0);
    for swap in [false, true] {
        let res = if swap {
            certify_by_sign_change(&sb, &sa, &eb, &ea, p, &uv, &uv, tol)
        } else {
            certify_by_sign_change(&sa, &sb, &ea, &eb, p, &uv, &uv, tol)
        };
        let (r, corners) = match res {
            Ok(c) => {
                let b = c.params;
                let to_xy = |u: f64, v: f64| [2.0 * u - 1.0, 2.0 * v - 1.0];
                let corners = vec![
                    to_xy(b[0].lo, b[1].lo),
                    to_xy(b[0].lo, b[1].hi),
                    to_xy(b[0].hi, b[1].lo),
                    to_xy(b[0].hi, b[1].hi),
                ];
                (c.radius, corners)
            }
            Err(SignChangeFail::AboveTol(r)) => (r, Vec::new()),
            Err(SignChangeFail::NoSignChange) => continue,
        };
        made += 1;
        match judge(f, p, r, &corners) {
            Verdict::Confirmed => confirmed += 1,
            Verdict::Refuted => panic!("{f:?}, p = {p:?}, swap {swap}: false claim r = {r:e}"),
            Verdict::Open => {}
        }
    }
    (made, confirmed)
}

/// The quadrics and points of the harness: branch points (saddles at `c = 0`) and points on
/// the crossing lines at distances `1e-7 … 1e-2`, offset by `0 … 1e-6`; hyperbolas close to
/// the branch point; cups touching or floating above the plane by `2⁻⁴⁸ … 2⁻²⁰`.
pub fn cases_of(rng: &mut Rng, n: usize) -> Vec<(Quadric, [f64; 3])> {
    let mut out = Vec::new();
    for k in 0..n {
        // Dyadic: few bits, so every control value is exact.
        let dy = |rng: &mut Rng, lo: i64, hi: i64, e: i32| rng.int(lo, hi) as f64 * 2f64.powi(e);
        let x0 = dy(rng, -8, 8, -5);
        let y0 = dy(rng, -8, 8, -5);
        let m = [1.0, 0.5, 2.0, 0.75][rng.below(4) as usize];
        let b = dy(rng, 1, 8, -2);
        let a = b * m * m;
        let cup = k % 4 == 3;
        let c = if cup {
            [0.0, 2f64.powi(-48), 2f64.powi(-40), 2f64.powi(-20)][rng.below(4) as usize]
        } else if k % 4 == 0 {
            0.0
        } else {
            let e = [-48, -40, -20, -10][rng.below(4) as usize];
            if rng.coin() {
                2f64.powi(e)
            } else {
                -(2f64.powi(e))
            }
        };
        let f = Quadric {
            a,
            b,
            s: if cup { 1.0 } else { -1.0 },
            x0,
            y0,
            c,
        };
        let d = [1e-7, 1e-5, 1e-3, 1e-2][rng.below(4) as usize];
        let ang = rng.range(0.0, std::f64::consts::TAU);
        let (x, y) = if cup {
            (x0 + d * ang.cos(), y0 + d * ang.sin())
        } else {
            // On the zero set, in f64: y − y0 = ±√((a (x − x0)² + c) / b).
            let sx = if rng.coin() { 1.0 } else { -1.0 };
            let x = x0 + sx * d;
            let w = (a * (x - x0) * (x - x0) + c) / b;
            let sy = if rng.coin() { 1.0 } else { -1.0 };
            (x, y0 + sy * w.max(0.0).sqrt())
        };
        let off = [0.0, 1e-12, 1e-9, 1e-6][rng.below(4) as usize];
        let p = [
            x + off * rng.range(-1.0, 1.0),
            y + off * rng.range(-1.0, 1.0),
            off * rng.range(-1.0, 1.0),
        ];
        if p[0].abs() < 0.99 && p[1].abs() < 0.99 {
            out.push((f, p));
        }
    }
    out
}

#[test]
fn sign_change_claims_hold() {
    let mut rng = Rng::new(0x5167_c4a6_e000_0001);
    let n = cases(48, 2_000);
    let (mut made, mut confirmed, mut false_cup) = (0, 0, 0);
    for (f, p) in cases_of(&mut rng, n) {
        let (m, c) = prop_sign_change_claims(&f, &p, 1e-2);
        made += m;
        confirmed += c;
        false_cup += usize::from(f.s > 0.0 && f.c > 0.0 && m > 0);
    }
    println!("sign-change claims: {made} made, {confirmed} confirmed by a witness");
    // Not vacuous: claims are made, and the oracle confirms most of them.
    assert!(made >= n / 4, "{made} claims in {n} cases");
    assert!(
        confirmed * 10 >= made * 9,
        "{confirmed} of {made} confirmed"
    );
    assert_eq!(false_cup, 0);
}

/// The oracle itself: it confirms a true claim, refutes claims on a floating cup and a
/// touching point outside the ball, and leaves a ball far from the zero set open.
#[test]
fn the_oracle_tells_true_from_false() {
    let saddle = Quadric {
        a: 1.0,
        b: 1.0,
        s: -1.0,
        x0: 0.0,
        y0: 0.0,
        c: 0.0,
    };
    assert!(saddle.reproduces());
    assert_eq!(
        judge(&saddle, &[0.25, 0.25, 0.0], 1e-3, &[]),
        Verdict::Confirmed
    );
    assert_eq!(judge(&saddle, &[0.25, 0.0, 0.0], 1e-3, &[]), Verdict::Open);
    assert_eq!(
        judge(&saddle, &[0.25, 0.25, 2e-3], 1e-3, &[]),
        Verdict::Refuted
    );
    let cup = Quadric {
        s: 1.0,
        c: 2f64.powi(-48),
        ..saddle
    };
    assert_eq!(judge(&cup, &[0.0, 0.0, 0.0], 1.0, &[]), Verdict::Refuted);
    let touch = Quadric { c: 0.0, ..cup };
    assert_eq!(
        judge(&touch, &[1e-3, 0.0, 0.0], 1e-3, &[]),
        Verdict::Confirmed
    );
    assert_eq!(
        judge(&touch, &[1e-3, 0.0, 0.0], 0.999e-3, &[]),
        Verdict::Refuted
    );
}
