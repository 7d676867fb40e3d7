use vericad::curve_on_surface::{Params, approximate, approximate_with_progress, examples};
fn main() {
    let (s, c) = examples::table2();
    let p = Params {
        evidence_samples: 0,
        ..Params::default()
    };
    let n = 200;
    let t = std::time::Instant::now();
    let mut r = None;
    for _ in 0..n {
        r = Some(approximate(&s, &c, &p).unwrap());
    }
    let r = r.unwrap();
    println!(
        "table2: {:.3} ms/run, {} segs, {}",
        t.elapsed().as_secs_f64() * 1e3 / n as f64,
        r.num_segments,
        r.certificate.arithmetic
    );
    let t = std::time::Instant::now();
    let mut last = 0.0;
    approximate_with_progress(&s, &c, &p, &mut |step, k| {
        let e = t.elapsed().as_secs_f64() * 1e3;
        println!("  {step}: {k} (+{:.3} ms)", e - last);
        last = e;
    })
    .unwrap();
    for (name, s, c, eps_t) in [
        (
            "face17",
            examples::face_like(),
            examples::closed_curve(),
            10.0,
        ),
        ("ear19", examples::ear_like(), examples::ear_curve(), 10.0),
        (
            "face17@1",
            examples::face_like(),
            examples::closed_curve(),
            1.0,
        ),
        ("ear19@1", examples::ear_like(), examples::ear_curve(), 1.0),
    ] {
        let p = Params {
            evidence_samples: 0,
            eps_t_deg: eps_t,
            ..Params::default()
        };
        let t = std::time::Instant::now();
        let mut last = 0.0;
        let r = approximate_with_progress(&s, &c, &p, &mut |step, k| {
            let e = t.elapsed().as_secs_f64() * 1e3;
            println!("  {step}: {k} (+{:.3} ms)", e - last);
            last = e;
        })
        .unwrap();
        println!(
            "{name}: {:.3} ms, {} segs, bound {:.3e}, {}",
            t.elapsed().as_secs_f64() * 1e3,
            r.num_segments,
            r.certificate.hausdorff_bound,
            r.certificate.arithmetic
        );
    }
}
#[allow(dead_code)]
fn unused() {}
