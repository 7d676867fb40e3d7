//! STEP parsing throughput: vericad's Part 21 parser beside foxtrot's `step` crate, on the same
//! bytes in memory, plus vericad's whole read (`read_model`: file → parse → B-rep) for
//! reference. One criterion group per input file; throughput in decimal MB/s.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use std::time::Duration;
use step_parse_peers::{
    foxtrot_counts, foxtrot_parse, inputs, label, vericad_parse, vericad_read_model,
};

fn bench(c: &mut Criterion) {
    for path in inputs() {
        let bytes = std::fs::read(&path).expect("read input");
        let name = label(&path);
        let n_vericad = vericad_parse(&bytes);
        let (n_fox, n_fox_failed) = foxtrot_counts(&bytes);
        let n_surf = vericad_read_model(&path);
        eprintln!(
            "{name}: {} bytes; vericad {n_vericad} entities, {n_surf} surfaces after read_model; \
             foxtrot {n_fox} typed, {n_fox_failed} failed to parse",
            bytes.len()
        );
        let mut g = c.benchmark_group(name.replace('/', "__"));
        g.throughput(Throughput::BytesDecimal(bytes.len() as u64));
        g.bench_function("vericad_parse", |b| {
            b.iter(|| vericad_parse(black_box(&bytes)))
        });
        g.bench_function("foxtrot_parse", |b| {
            b.iter(|| foxtrot_parse(black_box(&bytes)))
        });
        g.bench_function("vericad_read_model", |b| {
            b.iter(|| vericad_read_model(black_box(&path)))
        });
        g.finish();
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    targets = bench
}
criterion_main!(benches);
