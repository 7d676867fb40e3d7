//! Many approximants joined along shared boundary curves (`vericad approximate`): shared
//! boundary control rows identical bit for bit, each approximant within tolerance, the
//! topology checks. Truth from the construction: the analytic distance to the unit sphere,
//! and for a bicubic graph `z = f(x, y)` the vertical distance (which bounds the true one).

mod common;

use common::coons::dense_max;
use std::process::Command;
use vericad::approx::coons::layout::{Layout, LayoutError, topology};
use vericad::approx::coons::layout_job::approximate_layout;
use vericad::approx::coons::{Approximant, Params};
use vericad::geom::{cross, norm};
use vericad::model::{Curve, CurveGeometry, Model, Surface};
use vericad::spline::construct::{Frame, arc, revolve_curve_range};
use vericad::spline::{NurbsCurve, NurbsSurface};

/// The unit sphere between longitudes `a0..a1` and latitudes ±0.6.
fn sphere_piece(a0: f64, a1: f64) -> NurbsSurface<f64, 3> {
    let meridian_plane = Frame {
        o: [0.0; 3],
        x: [1.0, 0.0, 0.0],
        y: [0.0, 0.0, 1.0],
        z: [0.0, -1.0, 0.0],
    };
    let profile = arc(&meridian_plane, 1.0, -0.6, 0.6).unwrap();
    revolve_curve_range(&[0.0; 3], &[0.0, 0.0, 1.0], &profile, a0, a1).unwrap()
}

fn latitude(phi: f64, a0: f64, a1: f64) -> NurbsCurve<f64, 3> {
    let f = Frame {
        o: [0.0, 0.0, phi.sin()],
        ..Frame::WORLD
    };
    arc(&f, phi.cos(), a0, a1).unwrap()
}

fn meridian(a: f64, p0: f64, p1: f64) -> NurbsCurve<f64, 3> {
    let x = [a.cos(), a.sin(), 0.0];
    let y = [0.0, 0.0, 1.0];
    let f = Frame {
        o: [0.0; 3],
        x,
        y,
        z: cross(&x, &y),
    };
    arc(&f, 1.0, p0, p1).unwrap()
}

fn curve(name: &str, c: NurbsCurve<f64, 3>) -> Curve {
    Curve {
        name: name.into(),
        geometry: CurveGeometry::Space(c),
    }
}

/// The control net of an approximant as rows `I = 0..=3M` of `3N + 1` points.
fn net(ap: &Approximant) -> Vec<Vec<[f64; 3]>> {
    let (pts, _) = ap.surface.points_weights();
    let cv = 3 * ap.report.n + 1;
    pts.chunks(cv).map(|c| c.to_vec()).collect()
}

/// Two sphere pieces with a gap between longitudes 0.65 and 0.85, covered by two
/// approximants that share the meridian at 0.75 (in the gap).
#[test]
fn two_sphere_pieces_joined_along_a_shared_curve() {
    let mut model = Model::default();
    for (k, (a0, a1)) in [(0.0, 0.65), (0.85, 1.6)].iter().enumerate() {
        model
            .surfaces
            .push(Surface::new(format!("piece {k}"), sphere_piece(*a0, *a1)));
    }
    model.curves = vec![
        curve("south west", latitude(-0.4, 0.2, 0.75)),
        curve("south east", latitude(-0.4, 0.75, 1.3)),
        curve("north west", latitude(0.4, 0.2, 0.75)),
        curve("north east", latitude(0.4, 0.75, 1.3)),
        curve("west", meridian(0.2, -0.4, 0.4)),
        curve("middle", meridian(0.75, -0.4, 0.4)),
        curve("east", meridian(1.3, -0.4, 0.4)),
    ];
    let layout = Layout::parse(
        r#"{"curves": {"sw": {"curve": 0}, "se": {"curve": "south east"}, "nw": {"curve": 2},
            "ne": {"curve": 3}, "w": {"curve": 4}, "mid": {"curve": 5}, "e": {"curve": 6}},
           "approximants": [
             {"name": "left", "n": 16, "sides": [{"curve": "sw"}, {"curve": "mid"}, {"curve": "nw"}, {"curve": "w"}]},
             {"name": "right", "sides": [{"curve": "se"}, {"curve": "e"}, {"curve": "ne"}, {"curve": "mid"}]}
           ]}"#,
    )
    .unwrap();
    let params = Params {
        tol: 1e-4,
        ..Default::default()
    };
    let r = approximate_layout(&model, &layout, &params, &mut |_, _| {}).unwrap();
    let (aps, shared, topo, rebuilds) = (r.approximants, r.shared, r.topology, r.rebuilds);
    eprintln!("sphere layout: shared {shared:?}, rebuilds {rebuilds}");
    assert_eq!(topo.open.len(), 6);
    assert_eq!(shared.len(), 1);
    assert!(shared[0].identical);
    let (l, r) = (&aps[0], &aps[1]);
    assert_eq!(
        l.report.n, r.report.n,
        "equal counts along the shared curve"
    );
    // Independent check of bit-identity: the left's side I = M against the right's side
    // I = 0 (in one of the two orders), every coordinate bit for bit.
    let (nl, nr) = (net(l), net(r));
    let a = nl.last().unwrap().clone();
    let b = nr[0].clone();
    let mut b_rev = b.clone();
    b_rev.reverse();
    let bits = |p: &[[f64; 3]]| -> Vec<u64> { p.iter().flatten().map(|c| c.to_bits()).collect() };
    assert!(
        bits(&a) == bits(&b) || bits(&a) == bits(&b_rev),
        "shared boundary rows differ"
    );
    // Each approximant within tol away from the gap (dense, analytic sphere distance).
    for ap in &aps {
        assert!(ap.report.within_tol, "{}", ap.report.reason);
        let h = 0.55 / ap.report.m as f64;
        let away = |p: &[f64; 3]| {
            let a = p[1].atan2(p[0]);
            a < 0.65 - h || a > 0.85 + h
        };
        let d = dense_max(&ap.surface, 100, |p| (norm(p) - 1.0).abs(), away);
        eprintln!(
            "sphere layout: M×N {}×{}, measured {:.3e}, dense away from the gap {d:.3e}",
            ap.report.m, ap.report.n, ap.report.evidence.max_error
        );
        assert!(d <= params.tol, "{d}");
    }
}

#[test]
fn a_curve_used_by_three_approximants_is_refused() {
    let side = |c: &str| format!(r#"{{"curve": "{c}"}}"#);
    let ap = |n: &str, s: [&str; 4]| {
        format!(
            r#"{{"name": "{n}", "sides": [{}]}}"#,
            s.map(side).join(", ")
        )
    };
    let curves: Vec<String> = ["a", "b", "c", "d", "e", "f", "g", "h", "x"]
        .iter()
        .map(|c| format!(r#""{c}": {{"curve": 0}}"#))
        .collect();
    let text = format!(
        r#"{{"curves": {{{}}}, "approximants": [{}, {}, {}]}}"#,
        curves.join(", "),
        ap("p", ["a", "b", "x", "c"]),
        ap("q", ["d", "x", "e", "f"]),
        ap("r", ["x", "g", "h", "a"])
    );
    let layout = Layout::parse(&text).unwrap();
    match topology(&layout) {
        Err(LayoutError::Overused { curve, users }) => {
            assert_eq!(curve, "x");
            assert_eq!(users, ["p", "q", "r"]);
        }
        other => panic!("expected Overused, got {other:?}"),
    }
    // An unknown curve and a wrong side count are typed errors too.
    let bad = text.replace(r#""curve": "h""#, r#""curve": "nowhere""#);
    assert!(matches!(
        topology(&Layout::parse(&bad).unwrap()),
        Err(LayoutError::UnknownCurve { .. })
    ));
}

const Z: [[f64; 4]; 4] = [
    [0.0, 0.1, -0.05, 0.0],
    [0.1, 0.2, 0.1, -0.1],
    [0.0, -0.1, 0.15, 0.05],
    [0.05, 0.0, 0.1, 0.0],
];

fn bernstein(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t]
}

/// The graph `z = f(x, y)` of the bicubic Bézier patch over `[0, 2]²` (control points at
/// `x = 2i/3`, `y = 2j/3`, so `x = 2u`, `y = 2v`).
fn f(x: f64, y: f64) -> f64 {
    let (bu, bv) = (bernstein(x / 2.0), bernstein(y / 2.0));
    (0..4)
        .map(|i| (0..4).map(|j| bu[i] * bv[j] * Z[i][j]).sum::<f64>())
        .sum()
}

fn bicubic_model() -> Model {
    let mut pts = Vec::new();
    for (i, row) in Z.iter().enumerate() {
        for (j, z) in row.iter().enumerate() {
            pts.push([2.0 * i as f64 / 3.0, 2.0 * j as f64 / 3.0, *z]);
        }
    }
    let k = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    let s = NurbsSurface::new(k.clone(), 3, k, 3, 4, 4, pts, vec![1.0; 16]).unwrap();
    Model {
        surfaces: vec![Surface::new("bicubic", s)],
        ..Default::default()
    }
}

/// The 2×2 layout over `[0.2, 1.8]²` split at 1: polylines on the graph (64 segments).
fn grid_layout() -> String {
    let line = |a: [f64; 2], b: [f64; 2]| {
        let pts: Vec<String> = (0..=64)
            .map(|k| {
                let t = k as f64 / 64.0;
                let (x, y) = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]));
                format!("[{x:?}, {y:?}, {:?}]", f(x, y))
            })
            .collect();
        format!(r#"{{"polyline": [{}]}}"#, pts.join(", "))
    };
    let xs = [0.2, 1.0, 1.8];
    let mut curves = Vec::new();
    for (r, y) in xs.iter().enumerate() {
        for c in 0..2 {
            curves.push(format!(
                r#""h{r}{c}": {}"#,
                line([xs[c], *y], [xs[c + 1], *y])
            ));
        }
    }
    for (c, x) in xs.iter().enumerate() {
        for r in 0..2 {
            curves.push(format!(
                r#""v{c}{r}": {}"#,
                line([*x, xs[r]], [*x, xs[r + 1]])
            ));
        }
    }
    let mut aps = Vec::new();
    for r in 0..2 {
        for c in 0..2 {
            aps.push(format!(
                r#"{{"name": "q{r}{c}", "sides": [{{"curve": "h{r}{c}"}}, {{"curve": "v{}{r}"}}, {{"curve": "h{}{c}"}}, {{"curve": "v{c}{r}"}}]}}"#,
                c + 1,
                r + 1
            ));
        }
    }
    format!(
        r#"{{"curves": {{{}}}, "approximants": [{}]}}"#,
        curves.join(", "),
        aps.join(", ")
    )
}

#[test]
fn two_by_two_layout_reproduces_a_bicubic_patch() {
    let model = bicubic_model();
    let layout = Layout::parse(&grid_layout()).unwrap();
    let params = Params {
        tol: 1e-4,
        ..Default::default()
    };
    let r = approximate_layout(&model, &layout, &params, &mut |_, _| {}).unwrap();
    let (aps, shared, topo) = (r.approximants, r.shared, r.topology);
    assert_eq!(shared.len(), 4);
    assert_eq!(topo.open.len(), 8);
    for s in &shared {
        eprintln!(
            "2×2: {} {} gap {:.3e} moved {:.3e}",
            s.curve, s.status, s.gap, s.moved
        );
        assert!(s.identical);
    }
    for ap in &aps {
        let d = dense_max(&ap.surface, 80, |p| (p[2] - f(p[0], p[1])).abs(), |_| true);
        eprintln!(
            "2×2: M×N {}×{}, measured {:.3e}, dense vertical {d:.3e}",
            ap.report.m, ap.report.n, ap.report.evidence.max_error
        );
        assert!(ap.report.within_tol, "{}", ap.report.reason);
        assert!(d <= params.tol, "{d}");
    }
    // The interior corner (1, 1) is one point: the net corner of every approximant nearest
    // it is the same bit for bit.
    let corners: Vec<[f64; 3]> = aps
        .iter()
        .map(|ap| {
            let n = net(ap);
            let last = n.len() - 1;
            let cs = [
                n[0][0],
                n[0][n[0].len() - 1],
                n[last][0],
                n[last][n[0].len() - 1],
            ];
            *cs.iter()
                .min_by(|a, b| {
                    let d = |p: &[f64; 3]| (p[0] - 1.0).powi(2) + (p[1] - 1.0).powi(2);
                    d(a).total_cmp(&d(b))
                })
                .unwrap()
        })
        .collect();
    eprintln!("2×2: interior corners {corners:?}");
    assert!(
        corners
            .iter()
            .all(|c| c.map(f64::to_bits) == corners[0].map(f64::to_bits))
    );
    assert!((corners[0][0] - 1.0).abs() < 1e-9 && (corners[0][1] - 1.0).abs() < 1e-9);
}

#[test]
fn the_approximate_command() {
    let dir = std::env::temp_dir().join(format!("vericad-approximate-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join("model.json");
    vericad::io::write_model(&model, &bicubic_model()).unwrap();
    let layout = dir.join("layout.json");
    std::fs::write(&layout, grid_layout()).unwrap();
    let (out, report) = (dir.join("surfaces.igs"), dir.join("report.json"));
    let vtk = dir.join("view.vtp");
    let run = |extra: &[&str]| {
        let mut args: Vec<std::ffi::OsString> = vec![
            "approximate".into(),
            model.clone().into(),
            "--layout".into(),
            layout.clone().into(),
        ];
        args.extend(extra.iter().map(Into::into));
        Command::new(env!("CARGO_BIN_EXE_vericad"))
            .args(args)
            .output()
            .unwrap()
    };
    let o = run(&[
        "--tol",
        "1e-3",
        "--out",
        out.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
        "--vtk",
        vtk.to_str().unwrap(),
    ]);
    eprintln!("{}", String::from_utf8_lossy(&o.stdout));
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let back = vericad::io::read_model(&out).unwrap();
    assert_eq!(back.surfaces.len(), 4);
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(r["shell"]["shared_edges"], 4);
    assert_eq!(r["shell"]["free_edges"], 8);
    // The files hold the shell: read back (IGES 514/510 and STEP open shell), every shared
    // curve is one edge used by two faces, every open curve an edge of one face, the nine
    // grid corners its vertices.
    let step = dir.join("surfaces.step");
    let o = run(&["--tol", "1e-3", "--out", step.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0));
    for file in [&out, &step] {
        let m = vericad::io::read_model(file).unwrap();
        let b = m.brep.as_ref().expect("a B-rep");
        assert_eq!((b.shells.len(), b.faces.len()), (1, 4), "{file:?}");
        assert!(!b.shells[0].closed);
        assert_eq!((b.edges.len(), b.vertices.len()), (12, 9), "{file:?}");
        let mut uses = vec![0usize; b.edges.len()];
        for f in &b.faces {
            for l in &f.loops {
                if let vericad::brep::LoopKind::Edges(es) = &l.kind {
                    for e in es {
                        uses[e.edge] += 1;
                    }
                }
            }
        }
        assert_eq!(uses.iter().filter(|&&u| u == 2).count(), 4, "{file:?}");
        assert_eq!(uses.iter().filter(|&&u| u == 1).count(), 8, "{file:?}");
    }
    assert!(std::fs::read_to_string(&vtk).unwrap().contains("VTKFile"));
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(r["approximants"].as_array().unwrap().len(), 4);
    assert_eq!(r["shared"].as_array().unwrap().len(), 4);
    let o = run(&["--tol", "1e-7", "--max-resolution", "8"]);
    assert_eq!(
        o.status.code(),
        Some(3),
        "not within tol at the maximum resolution"
    );
    for bad in [["--m", "-1"], ["--tol", "-1"], ["--k", "0"]] {
        assert_eq!(run(&bad).status.code(), Some(2), "{bad:?}");
    }
    let mut l = grid_layout();
    l = l.replace(r#""curve": "v01""#, r#""curve": "v11""#);
    std::fs::write(&layout, l).unwrap();
    assert_eq!(
        run(&[]).status.code(),
        Some(2),
        "a curve used twice by one approximant"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A tighter tolerance: some approximants refine and some do not, so neighbours end with
/// different counts along a shared curve and are rebuilt; afterwards the counts agree.
#[test]
fn unequal_refinement_is_rebuilt_to_equal_counts() {
    let model = bicubic_model();
    let layout = Layout::parse(&grid_layout()).unwrap();
    let params = Params {
        tol: 3e-5,
        ..Default::default()
    };
    let r = approximate_layout(&model, &layout, &params, &mut |_, _| {}).unwrap();
    let mn: Vec<(usize, usize)> = r
        .approximants
        .iter()
        .map(|ap| (ap.report.m, ap.report.n))
        .collect();
    eprintln!("rebuilds {}, M×N {mn:?}", r.rebuilds);
    assert!(r.rebuilds >= 1, "the rebuild path is exercised");
    for (s, (_, [p, q])) in r.shared.iter().zip(&r.topology.shared) {
        let count = |u: &vericad::approx::coons::layout::Use| {
            let (m, n) = mn[u.approximant];
            if u.side.is_multiple_of(2) { m } else { n }
        };
        assert_eq!(count(p), count(q), "curve {}", s.curve);
        assert!(s.identical, "curve {}", s.curve);
    }
    for ap in &r.approximants {
        let d = dense_max(&ap.surface, 80, |p| (p[2] - f(p[0], p[1])).abs(), |_| true);
        eprintln!(
            "tight: M×N {}×{}, measured {:.3e}, dense vertical {d:.3e}, {}",
            ap.report.m, ap.report.n, ap.report.evidence.max_error, ap.report.reason
        );
        assert!(ap.report.within_tol, "{}", ap.report.reason);
        assert!(d <= params.tol, "{d}");
    }
}
