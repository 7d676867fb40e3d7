//! Jets over a parameter box from the Bernstein form (`vericad::spline::enclose2::bezier_jet`),
//! on which the regions of proven branch points rest (`vericad::ssi::singular::BranchRegion`):
//! at rational parameters inside the box, the exact point and first and second partial
//! derivatives of the exact rational Bézier patch lie in the enclosures. Oracle: the Bernstein
//! basis and its derivatives (`n (B^{n−1}_{i−1} − B^{n−1}_i)`, applied twice) evaluated in
//! exact rationals at the point, and the quotient rule in rationals.

use crate::common::*;
use vericad::scalar::Interval;
use vericad::spline::enclose2::bezier_jet;
use vericad::spline::enclosed_bezier::EnclosedPatch;

/// `B^n_i(σ)` exactly (0 outside `0..=n`).
fn bern(n: i64, i: i64, s: &Q) -> Q {
    if i < 0 || i > n {
        return zero();
    }
    let mut c = one();
    for k in 0..i {
        c = c * qi(n - k) / qi(k + 1);
    }
    let mut v = c;
    for _ in 0..i {
        v *= s;
    }
    let r = one() - s;
    for _ in 0..(n - i) {
        v *= &r;
    }
    v
}

/// `d^k/dσ^k B^n_i(σ)` for `k ≤ 2`, exactly.
fn dbern(n: i64, i: i64, k: u32, s: &Q) -> Q {
    match k {
        0 => bern(n, i, s),
        1 if n >= 1 => qi(n) * (bern(n - 1, i - 1, s) - bern(n - 1, i, s)),
        2 if n >= 2 => {
            qi(n * (n - 1))
                * (bern(n - 2, i - 2, s) - qi(2) * bern(n - 2, i - 1, s) + bern(n - 2, i, s))
        }
        _ => zero(),
    }
}

/// The exact homogeneous `∂^{a+b} X / ∂u^a ∂v^b` (4 components, the last the weight) of the
/// patch with f64 net `net` on the span `uv`, at `(u, v)`.
fn exact_d(
    net: &[[f64; 4]],
    (p, qd): (usize, usize),
    uv: &[f64; 4],
    (u, v): (&Q, &Q),
    (a, b): (u32, u32),
) -> [Q; 4] {
    let (du, dv) = (q(uv[1]) - q(uv[0]), q(uv[3]) - q(uv[2]));
    let s = (u - q(uv[0])) / &du;
    let t = (v - q(uv[2])) / &dv;
    let mut out: [Q; 4] = std::array::from_fn(|_| zero());
    for i in 0..=p {
        let bu = dbern(p as i64, i as i64, a, &s);
        for j in 0..=qd {
            let bv = dbern(qd as i64, j as i64, b, &t);
            let c = &bu * &bv;
            for m in 0..4 {
                out[m] = &out[m] + &c * q(net[i * (qd + 1) + j][m]);
            }
        }
    }
    // Chain rule: d/du = (1/du) d/dσ.
    let mut scale = one();
    for _ in 0..a {
        scale /= &du;
    }
    for _ in 0..b {
        scale /= &dv;
    }
    out.map(|x| x * &scale)
}

/// For the patch `(p, q, net)` on the span `uv` and the box `[u0, u1] × [v0, v1]` inside it:
/// `bezier_jet` returns a jet, and at `m × m` rational points of the box (ends included) the
/// exact `S`, `S_u`, `S_v`, `S_uu`, `S_uv`, `S_vv` lie in it.
pub fn prop_bezier_jet_encloses(
    p: usize,
    qd: usize,
    net: &[[f64; 4]],
    uv: [f64; 4],
    bx: [f64; 4],
    m: i64,
) {
    let e = EnclosedPatch {
        uv,
        p,
        q: qd,
        net: net.iter().map(|h| h.map(Interval::point)).collect(),
    };
    let j = bezier_jet(&e, Interval::new(bx[0], bx[1]), Interval::new(bx[2], bx[3]))
        .unwrap_or_else(|| panic!("no jet: p {p} q {qd} uv {uv:?} box {bx:?}"));
    for a in 0..=m {
        for b in 0..=m {
            let u = q(bx[0]) + (q(bx[1]) - q(bx[0])) * ratio(a, m);
            let v = q(bx[2]) + (q(bx[3]) - q(bx[2])) * ratio(b, m);
            let x = |da: u32, db: u32| exact_d(net, (p, qd), &uv, (&u, &v), (da, db));
            let (x0, xu, xv, xuu, xuv, xvv) =
                (x(0, 0), x(1, 0), x(0, 1), x(2, 0), x(1, 1), x(0, 2));
            let w = &x0[3];
            for c in 0..3 {
                let s = &x0[c] / w;
                let su = (&xu[c] - &xu[3] * &s) / w;
                let sv = (&xv[c] - &xv[3] * &s) / w;
                let suu = (&xuu[c] - qi(2) * &xu[3] * &su - &xuu[3] * &s) / w;
                let suv = (&xuv[c] - &xu[3] * &sv - &xv[3] * &su - &xuv[3] * &s) / w;
                let svv = (&xvv[c] - qi(2) * &xv[3] * &sv - &xvv[3] * &s) / w;
                for (name, val, enc) in [
                    ("S", &s, j.s[c]),
                    ("S_u", &su, j.su[c]),
                    ("S_v", &sv, j.sv[c]),
                    ("S_uu", &suu, j.suu[c]),
                    ("S_uv", &suv, j.suv[c]),
                    ("S_vv", &svv, j.svv[c]),
                ] {
                    assert!(
                        in_ext(val, enc.lo, enc.hi),
                        "{name}[{c}] at ({a}/{m}, {b}/{m}) of box {bx:?} not in {enc:?} (p {p} q {qd} uv {uv:?})"
                    );
                }
            }
        }
    }
}

/// Random patches of degree 1–4 × 1–4, polynomial and rational (weights 0.3–3), control
/// points in [−2, 2]³, spans of f64 knots (`[0, 1]`, and random ends such as `[0.1, 0.35]`),
/// boxes of relative width 1, ½, 1e-2, 1e-6 at random places, and boxes touching the span's
/// ends.
pub fn run_bezier_jet_random(cases: usize) {
    let mut r = Rng::new(0xbe21e7);
    for k in 0..cases {
        let (p, qd) = (r.int(1, 4) as usize, r.int(1, 4) as usize);
        let rational = k % 2 == 1;
        let net: Vec<[f64; 4]> = (0..(p + 1) * (qd + 1))
            .map(|_| {
                let w = if rational { r.range(0.3, 3.0) } else { 1.0 };
                [
                    r.range(-2.0, 2.0) * w,
                    r.range(-2.0, 2.0) * w,
                    r.range(-2.0, 2.0) * w,
                    w,
                ]
            })
            .collect();
        let uv = if k % 3 == 0 {
            [0.0, 1.0, 0.0, 1.0]
        } else {
            let (a, b) = (r.range(-1.0, 1.0), r.range(-1.0, 1.0));
            [a, a + r.range(0.01, 2.0), b, b + r.range(0.01, 2.0)]
        };
        let frac = [1.0, 0.5, 1e-2, 1e-6][k % 4];
        let pick = |r: &mut Rng, lo: f64, hi: f64| -> (f64, f64) {
            let w = frac * (hi - lo);
            match r.below(4) {
                0 => (lo, lo + w),
                1 => (hi - w, hi),
                _ => {
                    let a = lo + r.unit() * (hi - lo - w);
                    (a, (a + w).min(hi))
                }
            }
        };
        let (u0, u1) = pick(&mut r, uv[0], uv[1]);
        let (v0, v1) = pick(&mut r, uv[2], uv[3]);
        if u0 >= u1 || v0 >= v1 {
            continue;
        }
        prop_bezier_jet_encloses(p, qd, &net, uv, [u0, u1, v0, v1], 3);
    }
}

#[test]
fn bezier_jets_enclose_the_exact_derivatives() {
    run_bezier_jet_random(cases(400, 40_000));
}
