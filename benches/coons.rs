//! Projected Coons approximant (paper A §3): one 20 × 20 approximant over a 100-patch model
//! (10 × 10 bilinear patches of the height field z = 0.8 sin(0.3 x) cos(0.4 y) sampled at
//! the patch corners, over [0, 10]²), boundary polylines along the model's border through the
//! corner points (which lie on the patches). Results go to BENCHMARKS.md.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use vericad::approx::coons::Params;
use vericad::approx::coons::approximant::approximate;
use vericad::approx::coons::boundary::BoundarySpec;
use vericad::model::{Model, Surface};
use vericad::spline::construct::bilinear;

fn height(x: f64, y: f64) -> [f64; 3] {
    [x, y, 0.8 * (0.3 * x).sin() * (0.4 * y).cos()]
}

fn model() -> Model {
    let mut surfaces = Vec::new();
    for i in 0..10 {
        for j in 0..10 {
            let (x, y) = (i as f64, j as f64);
            let s = bilinear(
                height(x, y),
                height(x + 1.0, y),
                height(x, y + 1.0),
                height(x + 1.0, y + 1.0),
            )
            .unwrap();
            surfaces.push(Surface::new(format!("p{i}_{j}"), s));
        }
    }
    Model {
        surfaces,
        ..Default::default()
    }
}

fn boundary() -> BoundarySpec {
    let side =
        |f: &dyn Fn(f64) -> [f64; 3]| -> Vec<[f64; 3]> { (0..=10).map(|k| f(k as f64)).collect() };
    let text = serde_json::json!({"curves": [
        {"polyline": side(&|t| height(t, 0.0))},
        {"polyline": side(&|t| height(10.0, t))},
        {"polyline": side(&|t| height(10.0 - t, 10.0))},
        {"polyline": side(&|t| height(0.0, 10.0 - t))},
    ]})
    .to_string();
    BoundarySpec::parse(&text).unwrap()
}

fn bench(c: &mut Criterion) {
    let m = model();
    let b = boundary();
    let p = Params {
        tol: 1e-2,
        m: 20,
        n: 20,
        max_resolution: 20,
        ..Default::default()
    };
    let a = approximate(&m, &b, &p).unwrap();
    eprintln!(
        "20 x 20 over 100 patches: M x N {} x {}, measured error {:.3e}, {} artificial, within tol {}",
        a.report.m,
        a.report.n,
        a.report.evidence.max_error,
        a.report.fill.filled,
        a.report.within_tol
    );
    let mut g = c.benchmark_group("coons");
    g.sample_size(10);
    g.bench_function("20x20 approximant over 100 patches", |bch| {
        bch.iter(|| approximate(black_box(&m), &b, &p).unwrap())
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
