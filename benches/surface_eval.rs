//! Bicubic B-spline surface point and first-derivative evaluation, 10×10 and 50×50 nets with
//! random non-uniform knots, vericad (f64) side by side with truck-geometry in one run.
//! Results, as ratios with the machine named, go to BENCHMARKS.md.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use truck_geometry::prelude::{BSplineSurface as TruckSurface, KnotVec, ParametricSurface, Point3};
use vericad::spline::BSplineSurface;

struct Rng(u64);
impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn knots(r: &mut Rng, n: usize, p: usize) -> Vec<f64> {
    let mut inner: Vec<f64> = (0..n - p - 1).map(|_| r.unit()).collect();
    inner.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let mut k = vec![0.0; p + 1];
    k.extend(inner);
    k.extend(vec![1.0; p + 1]);
    k
}

type Case = (
    BSplineSurface<[f64; 3]>,
    TruckSurface<Point3>,
    Vec<(f64, f64)>,
);

fn setup(n: usize) -> Case {
    let mut r = Rng(n as u64);
    let (ku, kv) = (knots(&mut r, n, 3), knots(&mut r, n, 3));
    let net: Vec<[f64; 3]> = (0..n * n)
        .map(|k| [(k / n) as f64, (k % n) as f64, r.unit()])
        .collect();
    let ours = BSplineSurface::new(ku.clone(), 3, kv.clone(), 3, n, n, net.clone()).unwrap();
    let rows: Vec<Vec<Point3>> = (0..n)
        .map(|i| (0..n).map(|j| Point3::from(net[i * n + j])).collect())
        .collect();
    let truck = TruckSurface::new((KnotVec::from(ku), KnotVec::from(kv)), rows);
    let params = (0..1000).map(|_| (r.unit(), r.unit())).collect();
    (ours, truck, params)
}

fn bench(c: &mut Criterion) {
    for n in [10usize, 50] {
        let (ours, truck, params) = setup(n);
        // Same surface: the two evaluators agree.
        for &(u, v) in params.iter().take(20) {
            let a = ours.eval(&u, &v);
            let b = truck.subs(u, v);
            assert!((a[0] - b.x).abs() + (a[1] - b.y).abs() + (a[2] - b.z).abs() < 1e-9);
        }
        let mut g = c.benchmark_group(format!("bicubic_{n}x{n}"));
        g.bench_function(BenchmarkId::new("point", "vericad"), |b| {
            b.iter(|| {
                for &(u, v) in &params {
                    black_box(ours.eval(black_box(&u), black_box(&v)));
                }
            })
        });
        g.bench_function(BenchmarkId::new("point", "truck"), |b| {
            b.iter(|| {
                for &(u, v) in &params {
                    black_box(truck.subs(black_box(u), black_box(v)));
                }
            })
        });
        g.bench_function(BenchmarkId::new("point+derivs", "vericad"), |b| {
            b.iter(|| {
                for &(u, v) in &params {
                    black_box(ours.eval_d1(black_box(&u), black_box(&v)));
                }
            })
        });
        g.bench_function(BenchmarkId::new("point+derivs", "truck"), |b| {
            b.iter(|| {
                for &(u, v) in &params {
                    let (u, v) = (black_box(u), black_box(v));
                    black_box((truck.subs(u, v), truck.uder(u, v), truck.vder(u, v)));
                }
            })
        });
        g.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
