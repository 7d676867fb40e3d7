//! Criterion: every kernel on every backend, the same inputs. One iteration runs a kernel
//! over all its cases (48 orient3d quadruples, 4 nets, 4 chords); `report.py` divides the
//! median by the case count. Before timing, each backend's exact results are checked
//! against num-rational's (a mismatch panics: a wrong answer is not timed).
//!
//! Clock: wall time (criterion's default), or with `EXACT_BENCH_CLOCK=cpu` the CPU time of
//! the benchmark thread (`CLOCK_THREAD_CPUTIME_ID`), which does not count the time the
//! thread waits for a core while other processes run; its groups are named `<kernel>-cpu`.

use std::hint::black_box;

use criterion::measurement::{Measurement, ValueFormatter, WallTime};
use criterion::{Criterion, Throughput};
use exact_backends::Exact;
use exact_backends::Inputs;
use exact_backends::backends::{BigRational, MalachiteRational, RBig, Ratio05, RugRational};

fn check<T: Exact>(reference: &[(&'static str, Vec<(String, String)>)]) -> Inputs<T> {
    let inp = Inputs::<T>::new();
    assert_eq!(
        inp.results(),
        reference,
        "{} differs from num-rational",
        T::NAME
    );
    inp
}

fn benches<M: Measurement>(c: &mut Criterion<M>, suffix: &str) {
    let reference = Inputs::<BigRational>::new().results();
    let nr = check::<BigRational>(&reference);
    let n5 = check::<Ratio05>(&reference);
    let rug = check::<RugRational>(&reference);
    let dashu = check::<RBig>(&reference);
    let mala = check::<MalachiteRational>(&reference);

    macro_rules! kernel {
        ($group:literal, $run:ident, $cases:ident) => {{
            let mut g = c.benchmark_group(format!("{}{suffix}", $group));
            g.throughput(Throughput::Elements(nr.$cases.len() as u64));
            g.bench_function(BigRational::NAME, |b| b.iter(|| black_box(&nr).$run()));
            g.bench_function(Ratio05::NAME, |b| b.iter(|| black_box(&n5).$run()));
            g.bench_function(RugRational::NAME, |b| b.iter(|| black_box(&rug).$run()));
            g.bench_function(RBig::NAME, |b| b.iter(|| black_box(&dashu).$run()));
            g.bench_function(MalachiteRational::NAME, |b| {
                b.iter(|| black_box(&mala).$run())
            });
            g.finish();
        }};
    }
    kernel!("orient3d", run_orient3d, orient);
    kernel!("half_split", run_half_split, nets);
    kernel!("compose6", run_compose6, chords6);
    kernel!("compose8", run_compose8, chords8);
}

/// CPU time of the calling thread, in nanoseconds.
struct ThreadCpuTime;

fn thread_cpu_ns() -> u64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid, writable timespec; the clock id is a constant Linux knows.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    assert_eq!(rc, 0, "clock_gettime(CLOCK_THREAD_CPUTIME_ID)");
    ts.tv_sec as u64 * 1_000_000_000 + ts.tv_nsec as u64
}

static WALL: WallTime = WallTime;

impl Measurement for ThreadCpuTime {
    type Intermediate = u64;
    type Value = u64;
    fn start(&self) -> u64 {
        thread_cpu_ns()
    }
    fn end(&self, start: u64) -> u64 {
        thread_cpu_ns() - start
    }
    fn add(&self, a: &u64, b: &u64) -> u64 {
        a + b
    }
    fn zero(&self) -> u64 {
        0
    }
    fn to_f64(&self, v: &u64) -> f64 {
        *v as f64
    }
    /// Nanoseconds, formatted as durations like the wall clock.
    fn formatter(&self) -> &dyn ValueFormatter {
        WALL.formatter()
    }
}

fn main() {
    if std::env::var("EXACT_BENCH_CLOCK").as_deref() == Ok("cpu") {
        let mut c = Criterion::default()
            .with_measurement(ThreadCpuTime)
            .configure_from_args();
        benches(&mut c, "-cpu");
        c.final_summary();
    } else {
        let mut c = Criterion::default().configure_from_args();
        benches(&mut c, "");
        c.final_summary();
    }
}
