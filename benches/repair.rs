//! Repair pipeline on grids of biquadratic patches with small gaps (steps 1–4: connectivity,
//! T-junction search, verification, features, averaging). The target: 10,000 patches
//! in under 10 s. Results go to BENCHMARKS.md.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use vericad::repair::{RepairParams, repair};
use vericad::spline::NurbsSurface;

fn grid(n: usize) -> Vec<NurbsSurface<f64, 3>> {
    let mut seed = 12345u64;
    let mut rnd = move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let mut out = Vec::with_capacity(n * n);
    for a in 0..n {
        for b in 0..n {
            let mut pts = Vec::new();
            for i in 0..3 {
                for j in 0..3 {
                    let (x, y) = (a as f64 + i as f64 / 2.0, b as f64 + j as f64 / 2.0);
                    pts.push([
                        x + 1e-5 * rnd(),
                        y + 1e-5 * rnd(),
                        0.1 * (x * 0.3).sin() * (y * 0.2).cos(),
                    ]);
                }
            }
            let k = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
            out.push(NurbsSurface::new(k.clone(), 2, k, 2, 3, 3, pts, vec![1.0; 9]).unwrap());
        }
    }
    out
}

fn bench(c: &mut Criterion) {
    let prm = RepairParams {
        u1: 1e-3,
        u2: 1e-3,
        ..Default::default()
    };
    let mut g = c.benchmark_group("repair");
    g.sample_size(10);
    for n in [50usize, 100] {
        let patches = grid(n);
        g.bench_function(format!("{} patches", n * n), |b| {
            b.iter(|| {
                repair(
                    black_box(patches.clone()),
                    &prm,
                    &Default::default(),
                    &|_| {},
                )
                .unwrap()
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
