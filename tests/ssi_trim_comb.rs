//! A floor trimmed to a comb of 40 teeth 0.0005 wide under a curved wall: the faces meet in
//! 40 short pieces inside the teeth, between traced points outside them. The run must not be
//! certified with any of them absent from the output (the coverage once decided the pair
//! transversal on border crossings near output kept outside the teeth).
mod common;
use vericad::model::TrimLoop;
use vericad::spline::NurbsSurface;
use vericad::spline::construct::bilinear;
use vericad::ssi::{SsiParams, intersect_models};

use common::trims::{model, poly, seg_dist};

fn run(wall_y: f64, teeth: &[f64], w: f64, swap: bool) {
    run_s(1.0, wall_y, teeth, w, swap)
}
fn run_s(sc: f64, wall_y: f64, teeth: &[f64], w: f64, swap: bool) {
    let wall = bilinear(
        [0.0, wall_y * sc, -0.5],
        [sc, wall_y * sc, -0.5],
        [0.0, wall_y * sc, 0.5],
        [sc, wall_y * sc, 0.5],
    )
    .unwrap();
    run_g(sc, wall, &|_x| wall_y, (0.4, 0.6), teeth, w, swap)
}
fn run_g(
    sc: f64,
    wall: NurbsSurface<f64, 3>,
    yof: &dyn Fn(f64) -> f64,
    (y0, y1): (f64, f64),
    teeth: &[f64],
    w: f64,
    swap: bool,
) {
    let floor = bilinear(
        [0.0, 0.0, 0.0],
        [sc, 0.0, 0.0],
        [0.0, sc, 0.0],
        [sc, sc, 0.0],
    )
    .unwrap();
    // Comb: bottom bar y <= 0.4, end teeth x <= 0.05 and x >= 0.95, thin teeth up to y = 0.6.
    let mut p = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.95, 1.0], [0.95, y0]];
    for &xc in teeth.iter().rev() {
        p.extend([[xc + w, y0], [xc + w, y1], [xc, y1], [xc, y0]]);
    }
    p.extend([[0.05, y0], [0.05, 1.0], [0.0, 1.0]]);
    let mut m = if swap {
        model(vec![wall, floor])
    } else {
        model(vec![floor, wall])
    };
    let fi = if swap { 1 } else { 0 };
    m.surfaces[fi].trim_loops = vec![TrimLoop {
        outer: true,
        curves: poly(&p),
    }];
    let r = intersect_models(&m, None, &SsiParams::default(), &|_, _| {}).expect("runs");
    let mut pts = Vec::new();
    let mut segs = Vec::new();
    for pr in &r.pairs {
        for b in &pr.branches {
            eprintln!(
                "branch pair ({},{}) n={} closed={} xs={:?}",
                pr.a,
                pr.b,
                b.points.len(),
                b.closed,
                b.points
                    .iter()
                    .map(|q| (q[0] * 1e4).round() / 1e4)
                    .collect::<Vec<_>>()
            );
            pts.extend(b.points.iter().copied());
            segs.extend(b.points.windows(2).map(|w| (w[0], w[1])));
        }
        pts.extend(pr.touch_points.iter().map(|t| t.point));
        for c in &pr.common_borders {
            pts.extend(c.points.iter().copied());
        }
        eprintln!(
            "coverage: {:?}",
            pr.coverage.as_ref().map(|c| (
                c.uncertified,
                c.no_missed_branches,
                c.transversal,
                c.near_output,
                c.outside_faces
            ))
        );
        eprintln!("faces: {:?}", pr.faces);
    }
    eprintln!(
        "certified={} no_missed={}",
        r.summary.certified, r.summary.no_missed_branches
    );
    for &xc in teeth {
        let xm = xc + w / 2.0;
        let q = [xm * sc, yof(xm) * sc, 0.0];
        let dp = pts
            .iter()
            .map(|x| seg_dist(q, *x, *x))
            .fold(f64::INFINITY, f64::min);
        let ds = segs
            .iter()
            .map(|(a, b)| seg_dist(q, *a, *b))
            .fold(f64::INFINITY, f64::min);
        eprintln!(
            "tooth {xc}: nearest output point {dp:.3e}, nearest chord {ds:.3e}{}",
            if r.summary.certified && dp > 1e-5 {
                "  <-- CERTIFIED BUT MISSED"
            } else {
                ""
            }
        );
    }
}

#[test]
fn comb_floor() {
    let teeth: Vec<f64> = (0..8).map(|k| 0.113 + 0.1037 * k as f64).collect();
    run(0.5, &teeth, 0.002, false);
    run(0.5, &teeth, 0.002, true);
}
#[test]
fn comb_scaled() {
    let teeth: Vec<f64> = (0..8).map(|k| 0.113 + 0.1037 * k as f64).collect();
    for sc in [10.0, 100.0] {
        eprintln!("== scale {sc}");
        run_s(sc, 0.5, &teeth, 0.002, false);
    }
}

#[test]
fn comb_curved() {
    let (xs, ys) = ([0.0, 0.5, 1.0], [0.3, 0.7, 0.3]);
    let pts: Vec<[f64; 3]> = (0..2)
        .flat_map(|i| (0..3).map(move |j| [xs[j], ys[j], -0.5 + i as f64]))
        .collect();
    let wall = NurbsSurface::new(
        vec![0.0, 0.0, 1.0, 1.0],
        1,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        2,
        2,
        3,
        pts,
        vec![1.0; 6],
    )
    .unwrap();
    let teeth: Vec<f64> = (0..40).map(|k| 0.0713 + 0.02137 * k as f64).collect();
    let yof = |x: f64| 0.3 + 0.8 * x * (1.0 - x);
    run_g(1.0, wall.clone(), &yof, (0.25, 0.55), &teeth, 0.0005, false);
    eprintln!("== swapped");
    run_g(1.0, wall, &yof, (0.25, 0.55), &teeth, 0.0005, true);
}
