//! Property tests of the curve-on-surface algorithm (issue: "random surfaces, degrees 1–3
//! each way, non-uniform knots, interior knots of multiplicity up to the degree, random domain
//! curves"): the proven bound and the measured distance stay within ε_D, junction angles
//! within ε_T except at junctions the result reports as unresolved (which must sit on a C0
//! knot line of S, where the exact image itself has a corner), and every output control point
//! is the exact blossom of S on its chord — exactly (exact arithmetic) or within the proven
//! rounding bound (f64 path, checked in exact arithmetic).
//!
//! proptest drives the f64 path; quickcheck drives the exact path on smaller cases.

use proptest::prelude::*;
use vericad::curve_on_surface::cells::Cells;
use vericad::curve_on_surface::{Arithmetic, CurveOnSurface, Params, approximate};
use vericad::scalar::{Rational, Scalar, lift};
use vericad::spline::compose::compose_line;
use vericad::spline::{BSplineSurface, NurbsCurve, NurbsSurface};

type Q = Rational;

/// Clamped knots on [0, 1] for `n` control points of degree `p`: interior knots from
/// `cuts` (sorted, distinct, in (0, 1)) with multiplicities from `mults` (1..=p), trimmed so
/// the count fits `n`.
fn knots(p: usize, interior: &[(f64, usize)]) -> Vec<f64> {
    let mut k = vec![0.0; p + 1];
    for &(x, m) in interior {
        k.extend(std::iter::repeat_n(x, m.clamp(1, p)));
    }
    k.extend(std::iter::repeat_n(1.0, p + 1));
    k
}

/// A random surface: degrees, interior knots (sorted distinct parameters with
/// multiplicities), control net heights.
#[derive(Clone, Debug)]
struct SurfaceSpec {
    p: usize,
    q: usize,
    ku: Vec<(f64, usize)>,
    kv: Vec<(f64, usize)>,
    seed: u64,
}

fn interior(cuts: Vec<(u32, usize)>) -> Vec<(f64, usize)> {
    let mut v: Vec<(f64, usize)> = cuts
        .into_iter()
        .map(|(c, m)| (f64::from(c % 15 + 1) / 16.0 + f64::from(c % 7) / 1024.0, m))
        .collect();
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    v.dedup_by(|a, b| a.0 == b.0);
    v
}

fn surface(spec: &SurfaceSpec) -> NurbsSurface<f64, 3> {
    let (ku, kv) = (knots(spec.p, &spec.ku), knots(spec.q, &spec.kv));
    let (nu, nv) = (ku.len() - spec.p - 1, kv.len() - spec.q - 1);
    let mut state = spec.seed | 1;
    let mut rnd = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let mut pts = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            let (x, y) = (i as f64 / (nu - 1) as f64, j as f64 / (nv - 1) as f64);
            pts.push([x + 0.1 * rnd(), y + 0.1 * rnd(), 0.4 * rnd()]);
        }
    }
    NurbsSurface::new(ku, spec.p, kv, spec.q, nu, nv, pts, vec![1.0; nu * nv]).unwrap()
}

/// A random C1 domain curve (degree 2 or 3, simple interior knots), control points in
/// [0.05, 0.95]² so the curve stays in the domain (convex hull).
fn curve(deg: usize, pts: Vec<(f64, f64)>) -> NurbsCurve<f64, 2> {
    let n = pts.len().max(deg + 1);
    let mut ctrl: Vec<[f64; 2]> = pts
        .iter()
        .map(|&(x, y)| [0.05 + 0.9 * x, 0.05 + 0.9 * y])
        .collect();
    while ctrl.len() < n {
        ctrl.push([0.5, 0.5]);
    }
    let inner: Vec<(f64, usize)> = (1..n - deg)
        .map(|i| (i as f64 / (n - deg) as f64, 1))
        .collect();
    NurbsCurve::new(knots(deg, &inner), deg, ctrl, vec![1.0; n]).unwrap()
}

fn bspline(s: &NurbsSurface<f64, 3>) -> BSplineSurface<[f64; 3]> {
    let (net, _) = s.points_weights();
    BSplineSurface {
        ku: s.hom.ku.clone(),
        kv: s.hom.kv.clone(),
        net,
    }
}

/// Check everything the issue asks of one result; returns a description of the first failure.
fn check(s: &NurbsSurface<f64, 3>, r: &CurveOnSurface, prm: &Params) -> Result<(), String> {
    let c = &r.certificate;
    if c.hausdorff_bound > prm.eps_d {
        return Err(format!("bound {} > eps {}", c.hausdorff_bound, prm.eps_d));
    }
    if r.evidence.max_distance_sampled > prm.eps_d {
        return Err(format!(
            "measured {} > eps",
            r.evidence.max_distance_sampled
        ));
    }
    let bs = bspline(s);
    let ku = bs.ku.clone();
    let kv = bs.kv.clone();
    let c0 = |k: &vericad::spline::KnotVector<f64>, x: f64| {
        let p = k.degree();
        x > k.domain().0 && x < k.domain().1 && k.multiplicity(&x) >= p
    };
    // Junction angles: above eps_t only where the vertex is on a C0 knot line.
    let (pdeg, qdeg) = bs.degrees();
    let mut above = 0;
    for w in r.segments.windows(2) {
        let t0 = tangent(&w[0].control_points, true);
        let t1 = tangent(&w[1].control_points, false);
        if let Some(a) = angle(&t0, &t1)
            && a > prm.eps_t_deg + 1e-6
        {
            let v = w[0].domain[1];
            if !(c0(&ku, v[0]) || c0(&kv, v[1])) {
                return Err(format!("angle {a} > eps_t at {v:?}, not on a C0 knot line"));
            }
            above += 1;
        }
    }
    if above > c.unresolved_junctions {
        return Err(format!(
            "{above} junctions above eps_t but {} reported",
            c.unresolved_junctions
        ));
    }
    // Every control point is the exact blossom of S on the chord.
    let cells = Cells::new(&bs, None, prm.eps_d).unwrap();
    let round = c.control_point_rounding;
    if round.is_nan() || round >= 1e-12 {
        return Err(format!("rounding bound {round}"));
    }
    for seg in &r.segments {
        if seg.degree != pdeg + qdeg {
            return Err(format!("degree {}", seg.degree));
        }
        let [a, b] = seg.domain;
        let mid: [Q; 2] = [
            (lift::<Q>(a[0]) + lift::<Q>(b[0])) / Q::from(2),
            (lift::<Q>(a[1]) + lift::<Q>(b[1])) / Q::from(2),
        ];
        let cell = cells.locate(&mid).ok_or("chord outside the domain")?;
        let exact = compose_line(
            &cells.cells[cell].patch,
            &cells.local(cell, &a),
            &cells.local(cell, &b),
        );
        for (p, e) in seg.control_points.iter().zip(&exact.control) {
            for i in 0..3 {
                let d = (lift::<Q>(p[i]) - e[i].clone()).abs();
                if d > lift::<Q>(round) {
                    return Err(format!(
                        "control point off the exact blossom by {}",
                        Scalar::to_f64(&d)
                    ));
                }
            }
        }
    }
    Ok(())
}

fn tangent(cps: &[[f64; 3]], at_end: bool) -> [f64; 3] {
    let n = cps.len() - 1;
    let (a, b) = if at_end {
        (cps[n - 1], cps[n])
    } else {
        (cps[0], cps[1])
    };
    [b[0] - a[0], b[1] - a[1], b[2] - a[2]]
}

fn angle(a: &[f64; 3], b: &[f64; 3]) -> Option<f64> {
    let na = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    let nb = (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]).sqrt();
    if na < 1e-12 || nb < 1e-12 {
        return None;
    }
    let c = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (na * nb);
    Some(c.clamp(-1.0, 1.0).acos().to_degrees())
}

fn surface_strategy() -> impl Strategy<Value = SurfaceSpec> {
    (
        1usize..=3,
        1usize..=3,
        proptest::collection::vec((0u32..1000, 1usize..=3), 0..3),
        proptest::collection::vec((0u32..1000, 1usize..=3), 0..3),
        any::<u64>(),
    )
        .prop_map(|(p, q, ku, kv, seed)| SurfaceSpec {
            p,
            q,
            ku: interior(ku),
            kv: interior(kv),
            seed,
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, .. ProptestConfig::default() })]

    /// f64 path.
    #[test]
    fn float_path_meets_its_certificate(
        spec in surface_strategy(),
        deg in 2usize..=3,
        pts in proptest::collection::vec((0.0f64..1.0, 0.0f64..1.0), 3..7),
        eps in prop_oneof![Just(1e-2), Just(1e-3)],
        eps_t in 10.0f64..30.0,
    ) {
        let s = surface(&spec);
        let c = curve(deg, pts);
        let prm = Params { eps_d: eps, eps_t_deg: eps_t, evidence_samples: 8, ..Params::default() };
        let r = approximate(&s, &c, &prm).map_err(|e| TestCaseError::fail(e.to_string()))?;
        check(&s, &r, &prm).map_err(TestCaseError::fail)?;
    }
}

/// Exact path (quickcheck): smaller cases, ε_D = 1e-2.
#[test]
fn exact_path_meets_its_certificate() {
    fn prop(p: u8, q: u8, cut: u16, mult: u8, seed: u64, pts: Vec<(u16, u16)>) -> bool {
        let spec = SurfaceSpec {
            p: usize::from(p % 3) + 1,
            q: usize::from(q % 3) + 1,
            ku: interior(vec![(u32::from(cut), usize::from(mult % 3) + 1)]),
            kv: vec![],
            seed,
        };
        let pts: Vec<(f64, f64)> = pts
            .iter()
            .take(5)
            .map(|&(x, y)| (f64::from(x) / 65535.0, f64::from(y) / 65535.0))
            .collect();
        if pts.len() < 3 {
            return true;
        }
        let s = surface(&spec);
        let c = curve(2, pts);
        let prm = Params {
            eps_d: 1e-2,
            eps_t_deg: 20.0,
            evidence_samples: 8,
            arithmetic: Arithmetic::Exact,
            ..Params::default()
        };
        match approximate(&s, &c, &prm) {
            Ok(r) => match check(&s, &r, &prm) {
                Ok(()) => r.certificate.control_point_rounding <= f64::EPSILON,
                Err(e) => {
                    eprintln!("{spec:?}: {e}");
                    false
                }
            },
            Err(e) => {
                eprintln!("{spec:?}: {e}");
                false
            }
        }
    }
    quickcheck::QuickCheck::new()
        .tests(12)
        .quickcheck(prop as fn(u8, u8, u16, u8, u64, Vec<(u16, u16)>) -> bool);
}
