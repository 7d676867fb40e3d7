//! Bodies of the fuzz targets in `fuzz/`, kept in the library so that `cargo test` runs the
//! same code over seed corpora and random inputs (`tests/fuzz_entries.rs`). Each body feeds
//! arbitrary bytes to an entry point and checks the invariants that must hold for every
//! input: no panic, a typed error for bad input, and the result's own consistency.

use crate::model::json;
use crate::predicates::tri_tri::{TriTriContact, construct, tri_tri};
use crate::predicates::{Sidedness, single_sided};

/// Finite `f64`s read 8 bytes at a time; non-finite values are mapped to 0 so every byte
/// string yields valid geometry (non-finite input is rejected earlier, at the model layer).
fn floats(data: &[u8]) -> Vec<f64> {
    data.chunks_exact(8)
        .map(|c| {
            let x = f64::from_le_bytes(c.try_into().unwrap_or([0; 8]));
            if x.is_finite() { x } else { 0.0 }
        })
        .collect()
}

/// Model text: parsing never panics; an accepted model survives a round trip exactly.
pub fn model_json(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match json::from_str(text, "fuzz") {
        Ok(m) => {
            if let Err(e) = m.validate() {
                panic!("the JSON reader accepted geometry that is not finite: {e}");
            }
            let again =
                json::from_str(&json::to_string(&m), "fuzz-rt").expect("re-read of written model");
            assert_eq!(m, again, "round trip changed the model");
        }
        Err(e) => assert!(!e.reason.is_empty()),
    }
}

/// Single-sided test: total on any finite control points (2 to 8 of them); a double-sided
/// verdict comes with at least one isolated crossing.
pub fn single_sided_test(data: &[u8]) {
    let f = floats(data);
    let pts: Vec<[f64; 2]> = f.chunks_exact(2).take(8).map(|c| [c[0], c[1]]).collect();
    if pts.len() < 2 {
        return;
    }
    match single_sided(&pts) {
        Sidedness::DoubleSided { crossings } => {
            assert!(crossings >= 1);
            assert_eq!(
                crate::predicates::single_sided::split_parameters(&pts, 1e-3).len(),
                crossings
            );
        }
        Sidedness::SingleSided { .. } | Sidedness::DegenerateChord => {}
    }
}

/// Triangle–triangle: total, symmetric in kind, and every constructed end point carries a
/// finite error bound.
pub fn tri_tri_test(data: &[u8]) {
    let f = floats(data);
    if f.len() < 18 {
        return;
    }
    let t = |o: usize| -> [[f64; 3]; 3] {
        std::array::from_fn(|i| std::array::from_fn(|j| f[o + 3 * i + j]))
    };
    let (a, b) = (t(0), t(9));
    let ab = tri_tri(&a, &b);
    let ba = tri_tri(&b, &a);
    assert_eq!(
        std::mem::discriminant(&ab),
        std::mem::discriminant(&ba),
        "{ab:?} vs {ba:?}"
    );
    if let TriTriContact::Crossing(p, q) | TriTriContact::TouchEdge(p, q) = ab {
        for cp in [p, q] {
            let c = construct(&a, &b, cp);
            assert!(c.err >= 0.0 && !c.err.is_nan());
        }
    }
}

/// Curve on surface: a random quadratic domain curve on the Table 2 surface, tolerance from
/// the bytes (kept ≥ 1e-2 so a run is short): either a typed error or a result whose proven
/// bound is within the tolerance and whose evidence does not exceed the bound.
pub fn curve_on_surface(data: &[u8]) {
    use crate::curve_on_surface::{Params, approximate};
    let f = floats(data);
    if f.len() < 7 {
        return;
    }
    let Ok(m) = json::from_str(crate::demo::DEFAULT_MODEL, "embedded") else {
        return;
    };
    let squash = |x: f64| (x.abs() % 1.5) - 0.25;
    let pts = vec![
        [squash(f[0]), squash(f[1])],
        [squash(f[2]), squash(f[3])],
        [squash(f[4]), squash(f[5])],
    ];
    let Ok(c) = crate::spline::NurbsCurve::new(vec![0., 0., 0., 1., 1., 1.], 2, pts, vec![1.0; 3])
    else {
        return;
    };
    let eps = 1e-2 + (f[6].abs() % 1.0);
    if let Ok(r) = approximate(
        &m.surfaces[0].nurbs,
        &c,
        &Params {
            eps_d: eps,
            evidence_samples: 4,
            ..Params::default()
        },
    ) {
        assert!(r.certificate.hausdorff_bound <= eps);
        assert!(
            r.evidence.max_distance_sampled <= r.certificate.hausdorff_bound * (1.0 + 1e-9) + 1e-12
        );
        assert!(r.bspline.joints_exact);
    }
}

/// STEP, IGES and STL readers: any bytes give a model or a located error, never a panic;
/// everything an accepted model holds is finite (knots, spans, control points, weights,
/// `w·p`, vertices) and its surfaces evaluate to points that are not NaN; its accounts
/// balance (per kind, read = converted + used + unsupported + invalid) and the converted
/// free curves are the model's curves (STEP `B_SPLINE_CURVE_WITH_KNOTS`, IGES 126), the
/// converted IGES faces and surfaces its surfaces. STEP and IGES are read twice: refusing a
/// file with an invalid face, and skipping such faces (`ReadOptions::skip_invalid_faces`).
/// A B-rep read is also written and read back, and repaired by the faces repair, whose
/// result must pass its own invariants ([`crate::repair::faces::FacesResult::check`]).
pub fn readers(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    let accounted = |m: &crate::model::Model, curve_kind: &str| {
        if let Err(e) = m.accounts.check() {
            panic!("a reader's accounts do not balance: {e}");
        }
        let converted = m.accounts.kinds.get(curve_kind).map_or(0, |a| a.converted);
        assert_eq!(converted, m.curves.len(), "converted {curve_kind} curves");
    };
    let check = |m: crate::model::Model| {
        if let Err(e) = m.validate() {
            panic!("a reader accepted geometry that is not finite: {e}");
        }
        for s in &m.surfaces {
            let (u0, _, v0, _) = s.nurbs.hom.domain();
            let p = s.nurbs.eval(&u0, &v0);
            assert!(p.iter().all(|x| !x.is_nan()), "{}", s.name);
        }
        // What was read is written (a B-rep in every form, seams made explicit) and read
        // back: the writers never panic and their output is readable.
        if m.brep.is_some() {
            use crate::io::iges::write::{BrepForm, write_with};
            for form in [BrepForm::BrepEntities, BrepForm::TrimmedSurfaces] {
                let (text, _) = write_with(&m, "fuzz", form);
                if let Err(e) = crate::io::iges::from_str(&text, "written.igs") {
                    panic!("vericad's IGES ({form:?}) does not read back: {e}");
                }
            }
            let (text, _) = crate::io::step::write::write(&m, "fuzz");
            if let Err(e) = crate::io::step::from_str(&text, "written.step") {
                panic!("vericad's STEP does not read back: {e}");
            }
            // The faces repair (sewing within a thousandth of the model's size) gives a
            // B-rep and a report that agree (small B-reps: the verification projects every
            // edge onto its faces).
            if m.brep.as_ref().is_some_and(|b| b.faces.len() <= 8) {
                let size = m.brep.as_ref().map_or(1.0, |b| b.extent());
                let tol = if size.is_finite() && size > 0.0 {
                    1e-3 * size
                } else {
                    1e-3
                };
                let prm = crate::repair::RepairParams {
                    u1: tol,
                    u2: tol,
                    ..Default::default()
                };
                if let Ok(r) = crate::repair::faces::repair_faces(&m, &prm, &|_| {}) {
                    let faults = r.check();
                    assert!(faults.is_empty(), "faces repair: {faults:?}");
                }
            }
        }
    };
    // Both ways of treating an invalid face: refuse the file, or skip and account it.
    for skip_invalid_faces in [false, true] {
        let opt = crate::io::ReadOptions { skip_invalid_faces };
        match crate::io::step::from_str_with(&text, "fuzz.step", opt) {
            Ok(m) => {
                accounted(&m, "B_SPLINE_CURVE_WITH_KNOTS");
                check(m)
            }
            Err(e) => assert!(!e.reason.is_empty()),
        }
        match crate::io::iges::from_str_with(&text, "fuzz.igs", opt) {
            Ok(m) => {
                accounted(&m, "126");
                let faces: usize = (m.accounts.kinds.iter())
                    .filter(|(k, _)| *k != "126")
                    .map(|(_, a)| a.converted)
                    .sum();
                assert_eq!(faces, m.surfaces.len(), "converted IGES faces and surfaces");
                check(m)
            }
            Err(e) => assert!(!e.reason.is_empty()),
        }
    }
    match crate::io::stl::from_bytes(data, "fuzz.stl") {
        Ok(m) => {
            assert!(m.accounts.is_empty(), "an STL model has no entity accounts");
            check(m)
        }
        Err(e) => assert!(!e.reason.is_empty()),
    }
}

/// A small grid triangulation from bytes: `n × n` vertices on integer (x, y) with integer
/// heights in `-2..=2` (so many exact coincidences and coplanarities), in the frame given by
/// `axes` (a permutation of the coordinates).
fn byte_grid(data: &[u8], n: usize, axes: [usize; 3], shift: f64) -> crate::model::Triangulation {
    let mut vertices = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let h = data.get(i * n + j).map_or(0, |b| (*b % 5) as i32 - 2) as f64;
            let local = [i as f64 - shift, j as f64 - shift, h * 0.5];
            let mut p = [0.0; 3];
            for k in 0..3 {
                p[axes[k]] = local[k];
            }
            vertices.push(p);
        }
    }
    let mut triangles = Vec::new();
    for i in 0..n - 1 {
        for j in 0..n - 1 {
            let v = |a: usize, b: usize| (a * n + b) as u32;
            let flip = data.get(n * n + i * n + j).is_some_and(|b| b & 1 == 1);
            if flip {
                triangles.push([v(i, j), v(i + 1, j), v(i + 1, j + 1)]);
                triangles.push([v(i, j), v(i + 1, j + 1), v(i, j + 1)]);
            } else {
                triangles.push([v(i, j), v(i + 1, j), v(i, j + 1)]);
                triangles.push([v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)]);
            }
        }
    }
    crate::model::Triangulation {
        name: "fuzz".into(),
        vertices,
        triangles,
    }
}

/// SSI topology on degenerate meshes: two byte-defined grids (integer coordinates, so
/// vertices lie exactly in other triangles' planes and edges cross exactly) intersect in mesh
/// mode without error; every triangle pair is consistent under the symbolic perturbation;
/// the loop invariants hold (checked inside) and every segment is in exactly one branch (its
/// ends listed, or merged with the point before at an edge-on-edge contact).
/// Returns the number of segments found.
pub fn ssi_meshes(data: &[u8]) -> usize {
    let n = 4;
    let a = byte_grid(data, n, [0, 1, 2], 0.0);
    let b = byte_grid(data.get(2 * n * n..).unwrap_or(&[]), n, [0, 2, 1], 0.5);
    let r = crate::ssi::mesh::intersect_meshes(&a, &b, (0, 1));
    let r = match r {
        Ok(r) => r,
        Err(e) => panic!("mesh intersection failed: {e}"),
    };
    assert_eq!(r.stats.inconsistent_triangle_pairs, 0, "{:?}", r.stats);
    let in_branches: usize = r
        .branches
        .iter()
        .map(|b| b.points.len() - usize::from(!b.closed))
        .sum();
    assert_eq!(
        in_branches + r.stats.merged_points,
        r.stats.segments,
        "{:?}",
        r.stats
    );
    r.stats.segments
}

/// Repair on random patch soups: bilinear patches with small-integer corners from the bytes
/// (so duplicates, shared corners, collapsed edges, many patches at a corner and T-junctions
/// all occur). Never a panic; every input patch accounted for in the output.
pub fn repair_soup(data: &[u8]) -> usize {
    let mut patches = Vec::new();
    for chunk in data.chunks(12).take(12) {
        if chunk.len() < 12 {
            break;
        }
        let c =
            |k: usize| -> [f64; 3] { std::array::from_fn(|d| (chunk[3 * k + d] % 5) as f64 * 0.5) };
        if let Ok(s) = crate::spline::construct::bilinear(c(0), c(1), c(3), c(2)) {
            patches.push(s);
        }
    }
    if patches.is_empty() {
        return 0;
    }
    let n = patches.len();
    let prm = crate::repair::RepairParams {
        u1: 0.1,
        u2: 0.1,
        ..Default::default()
    };
    let none = |_: &str| {};
    match crate::repair::repair(patches, &prm, &Default::default(), &none) {
        Ok(r) => {
            let mut seen = vec![false; n];
            for o in r.report.patch_origin.iter().flatten() {
                seen[*o] = true;
            }
            assert!(seen.iter().all(|s| *s), "a patch was lost");
            assert_eq!(r.patches.len(), r.report.patches_out);
            r.report.edges_connected
        }
        Err(e) => panic!("repair refused valid patches: {e}"),
    }
}

/// SSI of two byte-defined biquadratic patches (small-integer control points, weights 1–4):
/// coincidences, touching, crossings at knot lines and degenerate nets all occur. Never a
/// panic; the coverage classes add up; a certified run has no uncertified region and every
/// point proven within tol of the curve; every proven radius is finite. Returns the number of
/// branches. The text report and the JSON of the whole result are built too.
pub fn ssi_surfaces(data: &[u8]) -> usize {
    use crate::spline::NurbsSurface;
    let byte = |k: usize| data.get(k).copied().unwrap_or(0);
    let patch = |off: usize, rational: bool| {
        let pts: Vec<[f64; 3]> = (0..9)
            .map(|i| {
                let (u, v) = ((i / 3) as f64, (i % 3) as f64);
                let h = f64::from(byte(off + i) % 7) - 3.0;
                [u, v, h * 0.5]
            })
            .collect();
        let w: Vec<f64> = (0..9)
            .map(|i| {
                if rational {
                    f64::from(byte(off + 9 + i) % 4 + 1)
                } else {
                    1.0
                }
            })
            .collect();
        let k = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
        NurbsSurface::new(k.clone(), 2, k, 2, 3, 3, pts, w)
    };
    let (Ok(a), Ok(mut b)) = (patch(0, byte(40) & 1 == 1), patch(18, byte(40) & 2 == 2)) else {
        return 0;
    };
    // Turn B a quarter about the z axis and shift it by half a cell, so the patches cross.
    for h in &mut b.hom.net {
        let (x, y) = (h.wp[0], h.wp[1]);
        h.wp[0] = y + 0.5 * h.w;
        h.wp[1] = 2.0 * h.w - x;
    }
    let prm = crate::ssi::SsiParams {
        tol: 1e-6,
        coverage_max_boxes: 20_000,
        ..Default::default()
    };
    // Through the whole job (two one-face models), so the summary and the report that a
    // user reads are built from every result too (a report once indexed an empty polyline).
    let model = |s: NurbsSurface<f64, 3>| crate::model::Model {
        surfaces: vec![crate::model::Surface::new("patch", s)],
        ..Default::default()
    };
    let (ma, mb) = (model(a), model(b));
    let all = match crate::ssi::intersect_models(&ma, Some(&mb), &prm, &|_, _| {}) {
        Ok(r) => r,
        Err(e) => panic!("ssi failed on valid patches: {e}"),
    };
    assert!(!all.to_string().is_empty());
    if let Err(e) = serde_json::to_string(&all) {
        panic!("the result does not serialize: {e}");
    }
    let Some(r) = all.pairs.into_iter().next() else {
        return 0;
    };
    if let Some(c) = &r.coverage {
        assert_eq!(
            c.free
                + c.near_output
                + c.near_shared_edges
                + c.transversal
                + c.branch_point_regions
                + c.uncertified,
            c.pairs
        );
        assert_eq!(c.no_missed_branches, c.uncertified == 0, "{c:?}");
        assert!(
            c.free_pairs_with_branch_points.is_none_or(|n| n == 0),
            "{c:?}"
        );
    }
    for br in &r.branches {
        assert_eq!(br.curve_radius.len(), br.points.len());
        for x in br.curve_radius.iter().flatten() {
            assert!(x.is_finite() && *x >= 0.0, "radius {x}");
        }
        assert_eq!(
            br.curve_uncertified_points,
            br.curve_radius.iter().filter(|x| x.is_none()).count()
        );
    }
    r.branches.len()
}

/// Coons boundary files: any text is a boundary file or a typed error; an accepted one over
/// a fixed plane gives an approximant (or a typed error) with finite control points that
/// interpolates its grid points.
pub fn coons_boundary(data: &[u8]) {
    use crate::approx::coons::{Params, approximate, boundary::BoundarySpec};
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(spec) = BoundarySpec::parse(text) else {
        return;
    };
    let Ok(plane) = crate::spline::construct::bilinear(
        [-1.0, -1.0, 0.0],
        [2.0, -1.0, 0.0],
        [-1.0, 2.0, 0.0],
        [2.0, 2.0, 0.0],
    ) else {
        return;
    };
    let mut model = crate::model::Model::default();
    model
        .surfaces
        .push(crate::model::Surface::new("plane", plane));
    let params = Params {
        m: 4,
        n: 4,
        max_resolution: 8,
        ..Default::default()
    };
    if let Ok(ap) = approximate(&model, &spec, &params) {
        let (pts, _) = ap.surface.points_weights();
        assert!(pts.iter().flatten().all(|c| c.is_finite()));
        assert!(ap.report.proven.interpolates_grid_points);
    }
}
