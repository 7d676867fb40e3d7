//! Repair of faulty patch sets: the paper's cube (Plate 2) cut into 3×3 patches per face with
//! gaps and perturbations below u1/u2, a T-junction, a flipped patch, and bad input.

mod common;
use common::Rng;
use vericad::repair::features::FeatureOverrides;
use vericad::repair::{RepairParams, repair};
use vericad::spline::NurbsSurface;
use vericad::spline::construct::bilinear;

/// A biquadratic patch over a planar quad (so it has interior boundary control points), with
/// its corners and edge midpoints moved by up to `noise`.
fn patch(c: [[f64; 3]; 4], noise: f64, r: &mut Rng) -> NurbsSurface<f64, 3> {
    let lerp = |a: [f64; 3], b: [f64; 3], t: f64| -> [f64; 3] {
        std::array::from_fn(|k| a[k] + t * (b[k] - a[k]))
    };
    let mut pts = Vec::new();
    for i in 0..3 {
        for j in 0..3 {
            let (s, t) = (i as f64 / 2.0, j as f64 / 2.0);
            let p = lerp(lerp(c[0], c[1], s), lerp(c[3], c[2], s), t);
            pts.push(std::array::from_fn(|k| {
                p[k] + noise * (2.0 * r.unit() - 1.0)
            }));
        }
    }
    let k = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    NurbsSurface::new(k.clone(), 2, k, 2, 3, 3, pts, vec![1.0; 9]).unwrap()
}

/// The unit cube's six faces, each 3×3 patches, outward normals (S_u × S_v points out).
fn cube(noise: f64, seed: u64) -> Vec<NurbsSurface<f64, 3>> {
    let mut r = Rng(seed);
    // Faces as (origin, du, dv) with du × dv outward.
    let faces: [([f64; 3], [f64; 3], [f64; 3]); 6] = [
        ([0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]), // z = 0, normal -z
        ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]), // z = 1, +z
        ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]), // y = 0, -y
        ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]), // y = 1, +y
        ([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]), // x = 0, -x
        ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]), // x = 1, +x
    ];
    let mut out = Vec::new();
    for (o, du, dv) in faces {
        for i in 0..3 {
            for j in 0..3 {
                let at = |a: f64, b: f64| -> [f64; 3] {
                    std::array::from_fn(|k| o[k] + a / 3.0 * du[k] + b / 3.0 * dv[k])
                };
                let (a, b) = (i as f64, j as f64);
                out.push(patch(
                    [
                        at(a, b),
                        at(a + 1.0, b),
                        at(a + 1.0, b + 1.0),
                        at(a, b + 1.0),
                    ],
                    noise,
                    &mut r,
                ));
            }
        }
    }
    out
}

fn none(_: &str) {}

/// Reverse a patch's u direction (a flipped patch).
fn flip_u(s: &mut NurbsSurface<f64, 3>) {
    let f = &mut s.hom;
    let (nu, nv) = (f.nu(), f.nv());
    let old = f.net.clone();
    for i in 0..nu {
        for j in 0..nv {
            f.net[i * nv + j] = old[(nu - 1 - i) * nv + j].clone();
        }
    }
}

/// The cube of Plate 2 with 1e-4 noise, repaired at u1 = u2 = 1e-2, feature angle 30°.
fn repaired_cube() -> vericad::repair::RepairResult {
    let prm = RepairParams {
        u1: 1e-2,
        u2: 1e-2,
        feature_angle_deg: 30.0,
        ..Default::default()
    };
    repair(cube(1e-4, 7), &prm, &FeatureOverrides::default(), &none).unwrap()
}

/// The picture of the repaired cube: six patches (one border each), the 36 feature edges
/// drawn over them, the legend counting both; no gaps left, so no red.
#[test]
fn cube_picture_shows_patches_and_feature_edges() {
    let r = repaired_cube();
    let svg = vericad::repair::picture::picture(&r, Some("mm"), &Default::default());
    let group = |id: &str| -> Vec<&str> {
        svg.lines()
            .skip_while(|l| !l.starts_with(&format!("<g id=\"{id}\"")))
            .skip(1)
            .take_while(|l| !l.starts_with("</g>"))
            .collect()
    };
    assert_eq!(group("outlines").len(), 6);
    let curves = group("curves");
    assert_eq!(curves.len(), r.report.feature_edges);
    assert!(curves.iter().all(|l| l.contains("stroke=\"#141414\"")));
    // 6 patches × 12² quads × 2 triangles.
    assert_eq!(group("faces").len(), 6 * 144 * 2);
    assert!(svg.contains("output patches (6), one colour each"));
    assert!(svg.contains("feature edges (36)"));
    assert!(!svg.contains("gaps left above u2 ("));
    assert!(
        svg.contains(" mm</text>"),
        "the scale bar in the file's unit"
    );
}

#[test]
fn cube_plate2_connectivity_features_and_averaging() {
    let r = repaired_cube();
    let rep = &r.report;
    assert_eq!(rep.patches_in, 54);
    // Algorithm 2 stops at the feature lines: one 3 × 3 group per face, six merged patches.
    assert_eq!(rep.patches_out, 6, "{rep}");
    assert_eq!(rep.groups, Some(6));
    assert!(
        rep.group_sizes.iter().all(|s| *s == (3, 3)),
        "{:?}",
        rep.group_sizes
    );
    assert!(
        rep.max_merge_deviation.unwrap() < 1e-12,
        "{:?}",
        rep.max_merge_deviation
    );
    // Each merged patch is one face of the unit cube (independent check by sampling).
    let mut faces = std::collections::BTreeSet::new();
    for s in &r.patches {
        let (u0, u1, v0, v1) = s.hom.domain();
        let pts: Vec<[f64; 3]> = (0..=8)
            .flat_map(|a| (0..=8).map(move |b| (a, b)))
            .map(|(a, b)| {
                s.eval(
                    &(u0 + (u1 - u0) * a as f64 / 8.0),
                    &(v0 + (v1 - v0) * b as f64 / 8.0),
                )
            })
            .collect();
        let axis = (0..3)
            .find(|&k| pts.iter().all(|p| (p[k] - pts[0][k]).abs() < 1e-3))
            .expect("planar face");
        faces.insert((axis, (pts[0][axis]).round() as i32));
    }
    assert_eq!(faces.len(), 6, "{faces:?}");
    // 6 faces × 12 interior patch edges + 12 cube edges × 3 patch edges.
    assert_eq!(rep.edges_connected, 6 * 12 + 12 * 3, "{rep}");
    assert!(rep.non_manifold.is_empty() && rep.gaps_left.is_empty());
    assert_eq!(rep.flipped_pairs, 0);
    // The 12 cube edges (36 patch-edge pairs) are feature edges; nothing else.
    assert_eq!(rep.feature_edges, 36, "{rep}");
    for e in &rep.edges {
        if e.feature {
            assert!((e.max_angle_deg - 90.0).abs() < 1.0, "{e:?}");
        } else {
            assert!(e.max_angle_deg < 1.0, "{e:?}");
        }
    }
    // Gaps before are the perturbation; after averaging every shared edge is identical.
    assert!(rep.gap_max_before > 1e-5 && rep.gap_max_before < 1e-3);
    assert_eq!(rep.shared_edges_identical, rep.edges_connected);
    assert!(rep.gap_max_after < 1e-12, "{}", rep.gap_max_after);
}

#[test]
fn gaps_above_u2_are_reported_not_merged() {
    let mut ps = cube(0.0, 1);
    // Pull one patch's middle row away by 0.05 (corners stay): an interior gap (Fig. 6b).
    let h = &mut ps[4].hom;
    for j in 0..3 {
        let nv = h.nv();
        h.net[nv + j].wp[2] += 0.05;
    }
    let prm = RepairParams {
        u1: 1e-3,
        u2: 1e-3,
        ..Default::default()
    };
    let rep = repair(ps, &prm, &FeatureOverrides::default(), &none)
        .unwrap()
        .report;
    assert!(!rep.gaps_left.is_empty());
    assert!(
        rep.gaps_left
            .iter()
            .all(|g| g.gap >= 1e-3 && (g.connection.p == 4 || g.connection.q == 4))
    );
}

#[test]
fn t_junction_is_split_and_flipped_patch_found() {
    let mut ps = cube(0.0, 2);
    // Face z = 1 (patches 9..18, cells (i, j) at 9 + 3i + j): replace cells (0,0) and (1,0)
    // by one patch spanning both: its edge then has a T at the corner of cell (0,1)/(1,1).
    let big = bilinear(
        [0.0, 0.0, 1.0],
        [2.0 / 3.0, 0.0, 1.0],
        [0.0, 1.0 / 3.0, 1.0],
        [2.0 / 3.0, 1.0 / 3.0, 1.0],
    )
    .unwrap();
    ps[9] = big;
    ps.remove(12);
    // Flip one patch of face y = 0 (reverse its u direction).
    flip_u(&mut ps[18]);
    let n_in = ps.len();
    let prm = RepairParams {
        u1: 1e-3,
        u2: 1e-3,
        ..Default::default()
    };
    let rep = repair(ps, &prm, &FeatureOverrides::default(), &none)
        .unwrap()
        .report;
    assert!(rep.t_junctions >= 1, "{rep}");
    assert_eq!(rep.patch_origin.len(), rep.patches_out);
    // Every output patch comes from an input patch; every input patch is present.
    let mut seen = vec![false; n_in];
    for o in rep.patch_origin.iter().flatten() {
        seen[*o] = true;
    }
    assert!(seen.iter().all(|s| *s));
    assert!(rep.flipped_pairs >= 2, "{rep}");
    assert!(rep.non_manifold.is_empty());
}

#[test]
fn feature_overrides_add_and_remove() {
    let prm = RepairParams {
        u1: 1e-3,
        u2: 1e-3,
        ..Default::default()
    };
    let base = repair(cube(0.0, 3), &prm, &FeatureOverrides::default(), &none)
        .unwrap()
        .report;
    let f = base.edges.iter().find(|e| e.feature).unwrap();
    let n = base.edges.iter().find(|e| !e.feature).unwrap();
    let ov = FeatureOverrides {
        add: vec![(n.p, n.ep)],
        remove: vec![(f.p, f.ep)],
    };
    let r = repair(cube(0.0, 3), &prm, &ov, &none).unwrap().report;
    assert_eq!(r.feature_edges, base.feature_edges);
    assert_eq!(r.features_overridden, 2);
}

#[test]
fn bad_input_is_a_typed_error() {
    let mut ps = cube(0.0, 4);
    ps[3].hom.net[4].wp[1] = f64::NAN;
    let e = repair(
        ps,
        &RepairParams::default(),
        &FeatureOverrides::default(),
        &none,
    )
    .err()
    .unwrap();
    assert!(e.to_string().contains("patch 3"), "{e}");
    for (u1, u2, a) in [
        (0.0, 1e-3, 30.0),
        (1e-3, f64::NAN, 30.0),
        (1e-3, 1e-3, 0.0),
        (1e-3, 1e-3, 180.0),
    ] {
        let prm = RepairParams {
            u1,
            u2,
            feature_angle_deg: a,
            ..Default::default()
        };
        assert!(repair(cube(0.0, 4), &prm, &FeatureOverrides::default(), &none).is_err());
    }
    assert!(
        repair(
            Vec::new(),
            &RepairParams::default(),
            &FeatureOverrides::default(),
            &none
        )
        .is_err()
    );
    // A triangular patch (one collapsed edge) is handled.
    let mut ps = cube(0.0, 5);
    let t = bilinear(
        [2.0, 2.0, 2.0],
        [3.0, 2.0, 2.0],
        [2.0, 2.0, 2.0],
        [3.0, 3.0, 2.0],
    )
    .unwrap();
    ps.push(t);
    let rep = repair(
        ps,
        &RepairParams::default(),
        &FeatureOverrides::default(),
        &none,
    )
    .unwrap()
    .report;
    assert_eq!(rep.collapsed_edges, 1);
}

#[test]
fn real_patch_sets_repair_without_error() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/public");
    for f in ["occt-bug28366_fuselage.stp", "gmsh-t20_data.step"] {
        let out =
            std::env::temp_dir().join(format!("vericad-repair-{}-{f}.json", std::process::id()));
        let rep = vericad::repair::job::run(
            &dir.join(f),
            &RepairParams::default(),
            None,
            vericad::repair::job::Outputs {
                report: Some(&out),
                ..Default::default()
            },
        )
        .unwrap();
        assert!(rep.edges_connected > 0, "{f}");
        assert_eq!(rep.patch_origin.len(), rep.patches_out);
        assert!(rep.patches_out <= rep.patches_in + rep.t_junctions);
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
        for k in [
            "patches_in",
            "patches_out",
            "edges_connected",
            "t_junctions",
            "gap_max_before",
            "gap_max_after",
            "gaps_left",
            "feature_edges",
            "groups",
            "max_merge_deviation",
        ] {
            assert!(v.get(k).is_some(), "{f}: report lacks {k}");
        }
        std::fs::remove_file(&out).ok();
    }
}

/// Fig. 1-like: 54 patches on a smooth closed body (the cube's patches pushed onto the unit
/// sphere), with gaps, one T-junction and one flipped patch → a handful of patches, and the
/// output is C0: recomputed from scratch on the output at 1e-9, every edge has a partner and
/// no gap is left.
#[test]
fn smooth_body_with_gaps_t_junction_and_flip() {
    let mut ps = cube(0.0, 9);
    let mut r = Rng(99);
    for s in &mut ps {
        for h in &mut s.hom.net {
            let c: [f64; 3] = std::array::from_fn(|k| h.wp[k] / h.w - 0.5);
            let l = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
            let p: [f64; 3] = std::array::from_fn(|k| c[k] / l + 1e-4 * (2.0 * r.unit() - 1.0));
            h.wp = p.map(|x| x * h.w);
        }
    }
    // T-junction: on face z = 1 (patches 9..18), replace cells (0,0) and (1,0) by one patch
    // covering both exactly (knots 0,0,0,½,½,1,1,1 in u: the two nets joined at a C0 break).
    let (a, b) = (ps[9].clone(), ps[12].clone());
    let mut pts = Vec::new();
    for i in 0..5 {
        for j in 0..3 {
            let h = if i < 3 {
                a.hom.at(i, j)
            } else {
                b.hom.at(i - 2, j)
            };
            pts.push(h.wp.map(|x| x / h.w));
        }
    }
    let ku = vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0];
    let kv = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    ps[9] = NurbsSurface::new(ku, 2, kv, 2, 5, 3, pts, vec![1.0; 15]).unwrap();
    ps.remove(12);
    // Flip one patch (reverse u) on face x = 1.
    flip_u(&mut ps[50]);
    assert_eq!(ps.len(), 53);
    let prm = RepairParams {
        u1: 5e-2,
        u2: 5e-2,
        feature_angle_deg: 30.0,
        ..Default::default()
    };
    let res = repair(ps, &prm, &FeatureOverrides::default(), &none).unwrap();
    let rep = &res.report;
    assert!(rep.t_junctions >= 1, "{rep}");
    assert!(rep.flipped_pairs >= 1, "{rep}");
    assert_eq!(rep.feature_edges, 0, "smooth body: no feature lines");
    assert!(rep.patches_out <= 12, "a handful: {rep}");
    assert!(rep.gaps_left.is_empty(), "{rep}");
    // C0 (watertight): every sample on every output patch boundary lies on another output
    // patch's boundary (independent check: samples and closest points on all other edges).
    use vericad::repair::edges::{arc_length_samples, closest_on_curve, edge_curve};
    let mut worst = 0.0f64;
    for (i, s) in res.patches.iter().enumerate() {
        for e in 0..4 {
            for (_, x) in arc_length_samples(&edge_curve(s, e), 16) {
                let d = res
                    .patches
                    .iter()
                    .enumerate()
                    .filter(|(j, _)| *j != i)
                    .flat_map(|(_, t)| {
                        (0..4).map(move |f| closest_on_curve(&edge_curve(t, f), &x).2)
                    })
                    .fold(f64::INFINITY, f64::min);
                worst = worst.max(d);
            }
        }
    }
    assert!(
        worst < 1e-9,
        "largest boundary gap of the output: {worst}\n{rep}"
    );
    assert!(rep.averaging.edges_incompatible.is_empty());
}
