//! Chord-length reparametrization (RCA, paper §2): one face of the gmsh t20 STEP file and a
//! badly parametrized 50 × 50 control net (a gently curved sheet with clustered knots and
//! non-uniform weights). Results go to BENCHMARKS.md.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use vericad::reparam::{Params, reparametrize};
use vericad::spline::NurbsSurface;

/// A bicubic sheet over a 50 × 50 net: knots clustered towards the low ends (t²), weights
/// varying between 0.5 and 2, heights a smooth bump.
fn net50() -> NurbsSurface<f64, 3> {
    let n = 50;
    let inner = n - 3;
    let mut k = vec![0.0; 4];
    for i in 1..inner {
        let t = i as f64 / inner as f64;
        k.push(t * t);
    }
    k.extend([1.0; 4]);
    let mut pts = vec![];
    let mut w = vec![];
    for i in 0..n {
        for j in 0..n {
            let (a, b) = (i as f64 / (n - 1) as f64, j as f64 / (n - 1) as f64);
            pts.push([10.0 * a, 8.0 * b, 0.8 * (3.0 * a).sin() * (2.0 * b).cos()]);
            w.push(1.25 + 0.75 * (7.0 * a + 5.0 * b).sin());
        }
    }
    NurbsSurface::new(k.clone(), 3, k, 3, n, n, pts, w).unwrap()
}

fn bench(c: &mut Criterion) {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/public/gmsh-t20_data.step"
    );
    let m = vericad::io::read_model(std::path::Path::new(path)).unwrap();
    let face = m.surfaces[3].nurbs.clone();
    let p = Params::default();
    let off = Params {
        prove_bound: false,
        ..Params::default()
    };
    let mut g = c.benchmark_group("reparam");
    g.sample_size(10);
    g.bench_function("t20 face 3 (eps 1e-4)", |b| {
        b.iter(|| reparametrize(black_box(&face), &p).unwrap())
    });
    g.bench_function("t20 face 3 (eps 1e-4), no proven bound", |b| {
        b.iter(|| reparametrize(black_box(&face), &off).unwrap())
    });
    // The proven bound alone where it succeeds (face 1: 2.3e-5 ≤ ε).
    let f1 = m.surfaces[1].nurbs.clone();
    let r1 = reparametrize(&f1, &off).unwrap();
    g.bench_function("t20 face 1 proven bound (eps 1e-4)", |b| {
        b.iter(|| {
            vericad::reparam::bound::prove(black_box(&f1), &r1.surface, &r1.grid, 2.3e-5, 20_000)
        })
    });
    let s = net50();
    let p3 = Params {
        tol: 1e-3,
        ..Params::default()
    };
    g.bench_function("50x50 net (eps 1e-3)", |b| {
        b.iter(|| reparametrize(black_box(&s), &p3).unwrap())
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
