//! Curve on surface (Yang et al. §6): the Table 2 example, the 17 × 17 face-like case and
//! the 19 × 19 ear-like case with a 20-segment cubic, at the paper's tolerances (ε_D = 1e-3;
//! ε_T = 10°, and 1° as in the paper's last columns), in the f64 path (the default) and, for
//! Table 2, the exact path. Evidence sampling is off: the time is the algorithm with its
//! certificate. Paper: 15 ms, 79 ms (196 ms at 1°), 121 ms (308 ms at 1°), Pentium IV 2 GHz.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use vericad::curve_on_surface::{Arithmetic, Params, approximate, examples};

fn cases(c: &mut Criterion) {
    let (s2, c2) = examples::table2();
    let face = (examples::face_like(), examples::closed_curve());
    let ear = (examples::ear_like(), examples::ear_curve());
    let p = |eps_t: f64, arithmetic: Arithmetic| Params {
        eps_d: 1e-3,
        eps_t_deg: eps_t,
        evidence_samples: 0,
        arithmetic,
        ..Params::default()
    };
    let mut g = c.benchmark_group("curve_on_surface");
    g.sample_size(20);
    for (name, s, d, eps_t) in [
        ("table2", &s2, &c2, 10.0),
        ("face17", &face.0, &face.1, 10.0),
        ("ear19", &ear.0, &ear.1, 10.0),
        ("face17_1deg", &face.0, &face.1, 1.0),
        ("ear19_1deg", &ear.0, &ear.1, 1.0),
    ] {
        let prm = p(eps_t, Arithmetic::Float);
        let r = approximate(s, d, &prm).expect("certified");
        eprintln!(
            "{name}: {} segments, bound {:.3e}, arithmetic {}",
            r.num_segments, r.certificate.hausdorff_bound, r.certificate.arithmetic
        );
        g.bench_function(format!("{name}/f64"), |b| {
            b.iter(|| approximate(black_box(s), black_box(d), &prm).unwrap())
        });
    }
    let prm = p(10.0, Arithmetic::Exact);
    g.bench_function("table2/exact", |b| {
        b.iter(|| approximate(black_box(&s2), black_box(&c2), &prm).unwrap())
    });
    g.finish();
}

criterion_group!(benches, cases);
criterion_main!(benches);
