//! Faces given by their own trim loops (JSON, IGES 144 without a B-rep), end to end through
//! `intersect_models`: a face with only a hole loop is the domain minus the hole (IGES 144
//! with no outer boundary), and a face on a closed surface is periodic across its seam, as a
//! B-rep face's region is. Ground truth from the construction, decided with this file's own
//! closed even-odd test; a run that says certified must have every point of the faces'
//! intersection within its match distance of the output.
mod common;
use vericad::model::{Model, TrimLoop};
use vericad::spline::construct::{Frame, bilinear, cylinder};
use vericad::ssi::{SsiParams, intersect_models};

use common::trims::{crossing_loops, model, poly, seg_dist};

/// Even-odd (crossing number) test of my own, closed: points on an edge count inside.
fn in_polys(polys: &[Vec<[f64; 2]>], p: [f64; 2]) -> bool {
    let mut odd = false;
    for poly in polys {
        let n = poly.len();
        for k in 0..n {
            let (a, b) = (poly[k], poly[(k + 1) % n]);
            // on-edge (tolerant to exactness: use exact-ish cross product)
            let cr = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
            if cr == 0.0
                && p[0] >= a[0].min(b[0])
                && p[0] <= a[0].max(b[0])
                && p[1] >= a[1].min(b[1])
                && p[1] <= a[1].max(b[1])
            {
                return true;
            }
            if (a[1] > p[1]) != (b[1] > p[1]) {
                let x = a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
                if p[0] < x {
                    odd = !odd;
                }
            }
        }
    }
    odd
}

struct Res {
    certified: bool,
    d: f64,
    segs: Vec<([f64; 3], [f64; 3])>,
    nbranches: usize,
}

fn run(m: &Model, prm: &SsiParams) -> Res {
    let r = intersect_models(m, None, prm, &|_, _| {}).expect("runs");
    let mut segs = Vec::new();
    let mut d = f64::INFINITY;
    let mut nb = 0;
    for pr in &r.pairs {
        for b in &pr.branches {
            nb += 1;
            let n = b.points.len();
            if n == 1 {
                segs.push((b.points[0], b.points[0]));
            }
            for k in 0..n.saturating_sub(1) {
                segs.push((b.points[k], b.points[k + 1]));
            }
            if b.closed && n > 1 {
                segs.push((b.points[n - 1], b.points[0]));
            }
        }
        for t in &pr.touch_points {
            segs.push((t.point, t.point));
        }
        for c in &pr.common_borders {
            for w in c.points.windows(2) {
                segs.push((w[0], w[1]));
            }
        }
        if let Some(c) = &pr.coverage {
            d = d.min(c.match_distance);
            eprintln!(
                "pair ({},{}) branches {} cov: uncert {} nomiss {} transv {} near {} outside {} trim_edge_searches {} faces {:?}",
                pr.a,
                pr.b,
                pr.branches.len(),
                c.uncertified,
                c.no_missed_branches,
                c.transversal,
                c.near_output,
                c.outside_faces,
                c.trim_edge_searches,
                pr.faces
                    .as_ref()
                    .map(|f| (f.points_outside, f.chord_ends_outside))
            );
        } else {
            eprintln!("pair ({},{}) no coverage", pr.a, pr.b);
        }
    }
    eprintln!(
        "certified={} no_missed={}",
        r.summary.certified, r.summary.no_missed_branches
    );
    Res {
        certified: r.summary.certified,
        d,
        segs,
        nbranches: nb,
    }
}

/// Largest distance from the ground-truth points (already restricted to the faces) to the output.
fn worst(res: &Res, gt: &[[f64; 3]]) -> (f64, [f64; 3]) {
    let mut w = (0.0, [0.0; 3]);
    for q in gt {
        let dd = res
            .segs
            .iter()
            .map(|(a, b)| seg_dist(*q, *a, *b))
            .fold(f64::INFINITY, f64::min);
        if dd > w.0 {
            w = (dd, *q);
        }
    }
    w
}

/// Every ground-truth point within `d` of the output when the run says certified; the worst
/// distance.
fn check(name: &str, res: &Res, gt: &[[f64; 3]]) -> f64 {
    assert!(gt.len() > 10, "{name}: ground truth empty");
    let (w, q) = worst(res, gt);
    assert!(
        !res.certified || w <= res.d,
        "{name}: FALSE CERTIFICATE: {q:?} is {w:.3e} from the output (d = {:.1e}, {} branches)",
        res.d,
        res.nbranches
    );
    w
}

/// A floor over [0, 1]² with only a hole loop ([0.4, 0.6]²) under the wall x = 0.2: the
/// faces meet in the whole segment x = 0.2, y ∈ [0, 1], z = 0 (the hole is elsewhere). Before,
/// the face was taken as the hole's inside: 0 branches, certified.
#[test]
fn a_face_with_only_a_hole_is_the_domain_minus_the_hole() {
    let floor = bilinear(
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
    )
    .unwrap();
    let wall = bilinear(
        [0.2, 0.0, -1.0],
        [0.2, 1.0, -1.0],
        [0.2, 0.0, 1.0],
        [0.2, 1.0, 1.0],
    )
    .unwrap();
    let mut m = model(vec![floor, wall]);
    let hole = vec![[0.4, 0.4], [0.6, 0.4], [0.6, 0.6], [0.4, 0.6]];
    m.surfaces[0].trim_loops = vec![TrimLoop {
        outer: false,
        curves: poly(&hole),
    }];
    let res = run(&m, &SsiParams::default());
    let gt: Vec<[f64; 3]> = (0..=1000)
        .map(|k| k as f64 / 1000.0)
        .filter(|&y| !in_polys(std::slice::from_ref(&hole), [0.2, y]))
        .map(|y| [0.2, y, 0.0])
        .collect();
    check("hole only", &res, &gt);
    assert!(
        res.nbranches > 0 && res.certified,
        "the segment found and certified"
    );
}

/// A cylinder (axis z, radius 1, height 1) trimmed to a band across its seam, u ∈ [0.9, 1.1]
/// (or [−0.1, 0.1]), v ∈ [0.2, 0.8], cut by the plane z = 0.5: the faces meet in the arc of
/// the circle whose u (mod 1) is within 0.1 of the seam. Before, loops of a face's own were
/// taken literally in the domain: half the arc was absent and the run certified.
#[test]
fn a_band_across_a_seam_is_periodic() {
    for band in [[0.9, 1.1], [-0.1, 0.1]] {
        let cyl = cylinder(&Frame::WORLD, 1.0, 0.0, 1.0).unwrap();
        let h = 0.5;
        let plane = bilinear(
            [-2.0, -2.0, h],
            [2.0, -2.0, h],
            [-2.0, 2.0, h],
            [2.0, 2.0, h],
        )
        .unwrap();
        let mut m = model(vec![cyl.clone(), plane]);
        let poly_uv = vec![
            [band[0], 0.2],
            [band[1], 0.2],
            [band[1], 0.8],
            [band[0], 0.8],
        ];
        m.surfaces[0].trim_loops = vec![TrimLoop {
            outer: true,
            curves: poly(&poly_uv),
        }];
        let (u0, u1, _, _) = cyl.hom.domain();
        let per = u1 - u0;
        let res = run(&m, &SsiParams::default());
        let polys = vec![poly_uv.clone()];
        let n = 20_000;
        let gt: Vec<[f64; 3]> = (0..n)
            .map(|k| u0 + per * k as f64 / n as f64)
            .filter(|&u| {
                [0.0, per, -per]
                    .iter()
                    .any(|s| in_polys(&polys, [u + s, h]))
            })
            .map(|u| {
                let p = cyl.eval(&u, &h);
                assert!((p[2] - h).abs() < 1e-12, "v is the height");
                p
            })
            .collect();
        check(&format!("band {band:?}"), &res, &gt);
        assert!(res.certified, "band {band:?}: the arc found and certified");
    }
}

/// A face whose own trim loops cross (an outer square and a "hole" square straddling its
/// edge): the even-odd rule would take the overlap for the complement of the face. The loops
/// are refused — the surface is not clipped — and the run says so and is not certified.
#[test]
fn crossing_trim_loops_are_not_outlined_and_not_certified() {
    let mut m = model(vec![
        bilinear([0., 0., 0.], [10., 0., 0.], [0., 10., 0.], [10., 10., 0.]).unwrap(),
        bilinear([5., 5., -5.], [5., 5., 5.], [5., 15., -5.], [5., 15., 5.]).unwrap(),
    ]);
    m.surfaces[0].trim_loops = crossing_loops();
    let r = intersect_models(&m, None, &SsiParams::default(), &|_, _| {}).expect("runs");
    assert!(!r.summary.certified);
    assert!(
        r.summary
            .certificate
            .iter()
            .any(|c| c.contains("NOT restricted") && c.contains("trim loops are not outlined")),
        "{:?}",
        r.summary.certificate
    );
}
