//! Cooperative control of an intersection run: progress from inside one face pair, and a
//! cancel flag that stops a running pair at its next check (the result is then partial and
//! not certified), or stops the run before any pair starts.

use std::sync::atomic::Ordering;
use std::sync::{Arc, Mutex};
use vericad::model::{Model, Surface};
use vericad::spline::NurbsSurface;
use vericad::ssi::control::{Control, Stage};
use vericad::ssi::{SsiParams, intersect_models};

/// A wavy bicubic over the unit square (`n × n` control points, height ±0.05) and a plane
/// through it, tilted slightly: many closed and open branches, one face pair.
fn wavy_and_plane(n: usize) -> Model {
    let knots = |n: usize| {
        let m = n - 3;
        let mut k = vec![0.0; 4];
        k.extend((1..m).map(|i| i as f64 / m as f64));
        k.extend([1.0; 4]);
        k
    };
    let mut pts = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let (u, v) = (i as f64 / (n - 1) as f64, j as f64 / (n - 1) as f64);
            pts.push([u, v, 0.05 * (20.0 * u).sin() * (17.0 * v).cos()]);
        }
    }
    let wavy = NurbsSurface::new(knots(n), 3, knots(n), 3, n, n, pts, vec![1.0; n * n]).unwrap();
    let plane = vericad::spline::construct::bilinear(
        [0.0, 0.0, -0.01],
        [1.0, 0.0, 0.01],
        [0.0, 1.0, 0.01],
        [1.0, 1.0, -0.01],
    )
    .unwrap();
    Model {
        surfaces: vec![Surface::new("wavy", wavy), Surface::new("plane", plane)],
        ..Default::default()
    }
}

#[test]
fn progress_comes_from_inside_the_pair_and_cancel_stops_it() {
    let m = wavy_and_plane(16);
    let (mut control, flag) = Control::cancellable();
    let seen: Arc<Mutex<Vec<Stage>>> = Arc::default();
    let (seen2, flag2) = (seen.clone(), flag.clone());
    // Cancel as soon as the branch points are being certified.
    control.progress = Some(Arc::new(move |s: &Stage| {
        seen2.lock().unwrap().push(s.clone());
        if s.step == "certify branch points" {
            flag2.store(true, Ordering::Relaxed);
        }
    }));
    let prm = SsiParams {
        control,
        ..Default::default()
    };
    let r = intersect_models(&m, None, &prm, &|_, _| {}).unwrap();
    let steps: Vec<&str> = seen.lock().unwrap().iter().map(|s| s.step).collect();
    for want in [
        "triangulate",
        "tangential points",
        "candidate triangle pairs",
        "triangle intersections",
        "refine branches",
        "certify branch points",
    ] {
        assert!(steps.contains(&want), "{want} not reported: {steps:?}");
    }
    assert!(
        !steps.contains(&"coverage"),
        "coverage ran after the cancel"
    );
    assert!(
        seen.lock()
            .unwrap()
            .iter()
            .all(|s| s.pair == (1, 0) || s.pair == (0, 1))
    );
    assert_eq!(r.pairs.len(), 1);
    assert!(!r.pairs[0].complete);
    assert!(r.summary.partial && !r.summary.certified);
    assert!(
        r.summary
            .certificate
            .iter()
            .any(|c| c.contains("PARTIAL") && c.contains("cancellation")),
        "{:?}",
        r.summary.certificate
    );

    // The same run without the cancel finds branches and completes.
    let full = intersect_models(&m, None, &SsiParams::default(), &|_, _| {}).unwrap();
    assert!(full.pairs[0].complete && !full.summary.partial);
    assert!(full.summary.branches > r.summary.branches);
}

#[test]
fn a_cancelled_run_starts_no_pair() {
    let m = wavy_and_plane(8);
    let (control, flag) = Control::cancellable();
    flag.store(true, Ordering::Relaxed);
    let prm = SsiParams {
        control,
        ..Default::default()
    };
    let r = intersect_models(&m, None, &prm, &|_, _| {}).unwrap();
    assert_eq!(r.summary.pairs_not_run, 1);
    assert!(r.pairs.is_empty());
    assert!(r.summary.partial && !r.summary.certified);
}
