//! STEP assemblies (tests/data/public/occt-written/occt-assembly-*.step, written by Open
//! CASCADE 8.0.1 with make_assemblies.py there): every occurrence of a part is its own placed
//! solid, nested occurrences compose their placements, and the un-placed part does not appear.
//! Oracles: what Open CASCADE reads from the same files (solids, each solid's area and tight
//! bounding box, printed by make_assemblies.py --read-only), and the placements the files were
//! built with (rotations about given axes by given angles, Rodrigues' formula, applied to the
//! parts' known corners).

use std::path::Path;
use vericad::brep::Brep;
use vericad::model::Model;
use vericad::spline::NurbsCurve;

fn path(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public/occt-written")
        .join(name)
}

fn text(name: &str) -> String {
    std::fs::read_to_string(path(name)).unwrap()
}

fn read(name: &str, text: &str) -> (Model, Brep) {
    let m = vericad::io::step::from_str(text, name).unwrap_or_else(|e| panic!("{name}: {e}"));
    let b = m.brep.clone().expect("a B-rep");
    (m, b)
}

/// Per solid: area (mm²) and bounding box `[xmin, ymin, zmin, xmax, ymax, zmax]`, as Open
/// CASCADE 8.0.1 reads the file (`BRepGProp` surface properties at 1e-9, `BRepBndLib::AddOptimal`).
type Occt = (f64, [f64; 6]);
const BOXES: [Occt; 2] = [
    (2200.0, [80.0, 0.0, 0.0, 100.0, 10.0, 30.0]),
    (
        2200.0,
        [
            0.0,
            39.393398282,
            6.464466094,
            21.276474699,
            69.330127019,
            43.051829925,
        ],
    ),
];
const NESTED: [Occt; 4] = [
    (3100.0, [0.0, -5.0, 0.0, 40.0, 0.0, 30.0]),
    (
        450.0,
        [6.464466094, -25.0, 10.0, 13.535533906, -5.0, 17.071067812],
    ),
    (
        3100.0,
        [
            196.938137822,
            -24.494897428,
            50.0,
            238.371173071,
            23.75,
            85.744897428,
        ],
    ),
    (
        450.0,
        [
            195.814413465,
            2.626275643,
            61.092544324,
            212.391989197,
            12.929576502,
            80.422671343,
        ],
    ),
];
const CYLINDER: [Occt; 1] = [(
    1407.433508808,
    [
        -1.971323526,
        -36.537912211,
        0.091237112,
        14.231922973,
        -13.601582480,
        28.648163441,
    ],
)];

/// Largest value of `f` along the curve: the best of 400 samples, refined by golden-section
/// search between its neighbours.
fn curve_max(c: &NurbsCurve<f64, 3>, f: impl Fn(&[f64; 3]) -> f64) -> f64 {
    let (t0, t1) = (c.hom.knots.knots()[0], *c.hom.knots.knots().last().unwrap());
    let n = 400;
    let at = |i: usize| t0 + (t1 - t0) * i as f64 / n as f64;
    let g = |t: f64| f(&c.eval(&t));
    let best = (0..=n)
        .max_by(|&a, &b| g(at(a)).total_cmp(&g(at(b))))
        .unwrap();
    let (mut a, mut b) = (at(best.saturating_sub(1)), at((best + 1).min(n)));
    let r = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..100 {
        let (x, y) = (b - r * (b - a), a + r * (b - a));
        if g(x) < g(y) {
            a = x;
        } else {
            b = y;
        }
    }
    g(at(best)).max(g(0.5 * (a + b)))
}

/// Per solid of the B-rep: the sum of its faces' trimmed areas and the bounding box of its
/// edges (the box of a solid bounded by planes and cylinders is reached on its edges).
fn solids(m: &Model, b: &Brep) -> Vec<Occt> {
    let areas = vericad::tessellate::face_areas(m, b);
    b.solids
        .iter()
        .map(|s| {
            let sh = &b.shells[s.outer];
            let area: f64 = sh.faces.iter().map(|f| areas[f.0].area.unwrap()).sum();
            let mut bx = [f64::INFINITY, f64::INFINITY, f64::INFINITY, 0.0, 0.0, 0.0];
            bx[3..].fill(f64::NEG_INFINITY);
            for &(f, _) in &sh.faces {
                for l in &b.faces[f].loops {
                    let vericad::brep::LoopKind::Edges(es) = &l.kind else {
                        continue;
                    };
                    for oe in es {
                        let c = &b.edges[oe.edge].curve.as_ref().unwrap().nurbs;
                        for k in 0..3 {
                            bx[k] = bx[k].min(-curve_max(c, |p| -p[k]));
                            bx[k + 3] = bx[k + 3].max(curve_max(c, |p| p[k]));
                        }
                    }
                }
            }
            (area, bx)
        })
        .collect()
}

/// Each of Open CASCADE's solids matches exactly one of vericad's: area within 1e-9
/// (relative) and box within 1e-6 mm.
fn check(name: &str, got: &[Occt], occt: &[Occt]) {
    assert_eq!(got.len(), occt.len(), "{name}: solids");
    let mut used = vec![false; got.len()];
    for (area, bx) in occt {
        let hits: Vec<usize> = (0..got.len())
            .filter(|&i| (0..6).all(|k| (got[i].1[k] - bx[k]).abs() < 1e-6))
            .collect();
        assert_eq!(hits.len(), 1, "{name}: box {bx:?} among {got:?}");
        let i = hits[0];
        assert!(!used[i]);
        used[i] = true;
        assert!(
            ((got[i].0 - area) / area).abs() < 1e-9,
            "{name}: area {} vs Open CASCADE {area}",
            got[i].0
        );
    }
}

#[test]
fn solids_areas_and_boxes_equal_open_cascade() {
    for (name, occt) in [
        ("occt-assembly-boxes.step", &BOXES[..]),
        ("occt-assembly-nested.step", &NESTED[..]),
        ("occt-assembly-cylinder.step", &CYLINDER[..]),
    ] {
        let (m, b) = read(name, &text(name));
        check(name, &solids(&m, &b), occt);
        // One model surface per placed face; no face outside the placed solids.
        let faces: usize = b.solids.iter().map(|s| b.shells[s.outer].faces.len()).sum();
        assert_eq!(b.faces.len(), faces, "{name}");
        assert_eq!(m.surfaces.len(), faces, "{name}");
        assert!(
            !m.warnings.iter().any(|w| w.contains("assembly")),
            "{name}: {:?}",
            m.warnings
        );
    }
}

/// Rotation by `deg` degrees about `axis` (Rodrigues), then translation `t`.
fn motion(axis: [f64; 3], deg: f64, t: [f64; 3]) -> impl Fn([f64; 3]) -> [f64; 3] {
    let l = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
    let k = axis.map(|x| x / l);
    let (s, c) = deg.to_radians().sin_cos();
    move |p: [f64; 3]| {
        let kxp = [
            k[1] * p[2] - k[2] * p[1],
            k[2] * p[0] - k[0] * p[2],
            k[0] * p[1] - k[1] * p[0],
        ];
        let kp = k[0] * p[0] + k[1] * p[1] + k[2] * p[2];
        [0, 1, 2].map(|i| p[i] * c + kxp[i] * s + k[i] * kp * (1.0 - c) + t[i])
    }
}

fn corners(d: [f64; 3]) -> Vec<[f64; 3]> {
    (0..8)
        .map(|i| [0, 1, 2].map(|k| if i >> k & 1 == 1 { d[k] } else { 0.0 }))
        .collect()
}

/// The vertices of solid `s` are exactly `expected` (as sets, within `tol`).
fn vertices_are(b: &Brep, s: usize, expected: &[[f64; 3]], tol: f64) {
    let mut vs = std::collections::BTreeSet::new();
    for &(f, _) in &b.shells[b.solids[s].outer].faces {
        for l in &b.faces[f].loops {
            if let vericad::brep::LoopKind::Edges(es) = &l.kind {
                for oe in es {
                    vs.insert(b.edges[oe.edge].start);
                    vs.insert(b.edges[oe.edge].end);
                }
            }
        }
    }
    assert_eq!(vs.len(), expected.len());
    for e in expected {
        let hit = vs.iter().any(|&v| {
            let p = b.vertices[v].point;
            (0..3).all(|k| (p[k] - e[k]).abs() < tol)
        });
        assert!(hit, "solid {s}: no vertex at {e:?}");
    }
}

#[test]
fn placements_equal_the_construction_and_nest() {
    let (_, b) = read("boxes", &text("occt-assembly-boxes.step"));
    let bx = corners([10.0, 20.0, 30.0]);
    let m1 = motion([0.0, 0.0, 1.0], 90.0, [100.0, 0.0, 0.0]);
    let m2 = motion([1.0, 1.0, 0.0], 30.0, [0.0, 50.0, 10.0]);
    // The file holds directions to 12 significant digits.
    vertices_are(&b, 0, &bx.iter().map(|&p| m1(p)).collect::<Vec<_>>(), 1e-9);
    vertices_are(&b, 1, &bx.iter().map(|&p| m2(p)).collect::<Vec<_>>(), 1e-9);
    let names: Vec<(&str, &str, usize)> = b
        .occurrences
        .iter()
        .map(|o| (o.source.as_str(), o.product.as_str(), o.solids.len()))
        .collect();
    assert_eq!(
        names,
        [
            ("#5", "two boxes", 0),
            ("#376", "box", 1),
            ("#382", "box", 1)
        ]
    );

    // Nested: the pair (plate, peg) placed twice; the peg's placement composes with the pair's.
    let (_, b) = read("nested", &text("occt-assembly-nested.step"));
    let tree: Vec<(usize, &str, &str)> = b
        .occurrences
        .iter()
        .map(|o| (o.depth, o.path.as_str(), o.product.as_str()))
        .collect();
    assert_eq!(
        tree,
        [
            (0, "#5", "two pairs"),
            (1, "#54", "pair"),
            (2, "#54/#403", "plate"),
            (2, "#54/#752", "peg"),
            (1, "#758", "pair"),
            (2, "#758/#403", "plate"),
            (2, "#758/#752", "peg"),
        ]
    );
    let peg = motion([0.0, 0.0, 1.0], 45.0, [10.0, 10.0, 5.0]);
    let top = [
        motion([1.0, 0.0, 0.0], 90.0, [0.0; 3]),
        motion([0.0, 1.0, 1.0], -60.0, [200.0, 0.0, 50.0]),
    ];
    let (plate_c, peg_c) = (corners([40.0, 30.0, 5.0]), corners([5.0, 5.0, 20.0]));
    for (k, o) in [2usize, 3, 5, 6].iter().enumerate() {
        let occ = &b.occurrences[*o];
        let t = &top[k / 2];
        let expect: Vec<[f64; 3]> = if k % 2 == 0 {
            plate_c.iter().map(|&p| t(p)).collect()
        } else {
            peg_c.iter().map(|&p| t(peg(p))).collect()
        };
        vertices_are(&b, occ.solids[0], &expect, 1e-9);
    }
}

#[test]
fn reversed_relationship_and_mapped_item_place_alike() {
    // The relationship written parent-first (rep_1 the assembly's, items swapped): the
    // inverse of its transformation places the child, as Open CASCADE reads it.
    let t = text("occt-assembly-boxes.step")
        .replace("RELATIONSHIP('','',#36,#10)", "RELATIONSHIP('','',#10,#36)")
        .replace(
            "ITEM_DEFINED_TRANSFORMATION('','',#11,#15)",
            "ITEM_DEFINED_TRANSFORMATION('','',#15,#11)",
        )
        .replace(
            "ITEM_DEFINED_TRANSFORMATION('','',#11,#19)",
            "ITEM_DEFINED_TRANSFORMATION('','',#19,#11)",
        );
    let (m, b) = read("reversed", &t);
    check("reversed", &solids(&m, &b), &BOXES);

    // The cylinder placed by a MAPPED_ITEM of its representation instead of an occurrence.
    let t = text("occt-assembly-cylinder.step");
    let cut = (t.find("#136 = ").unwrap(), t.find("#141 = ").unwrap());
    let t = format!("{}{}", &t[..cut.0], &t[cut.1..])
        .replace("#25 = SHAPE_DEFINITION_REPRESENTATION(#26,#32);", "")
        .replace(
            "#10 = SHAPE_REPRESENTATION('',(#11,#15),#19);",
            "#10 = SHAPE_REPRESENTATION('',(#11,#900),#19);\n#900 = MAPPED_ITEM('',#901,#15);\n#901 = REPRESENTATION_MAP(#11,#32);",
        );
    let (m, b) = read("mapped", &t);
    check("mapped", &solids(&m, &b), &CYLINDER);
}

#[test]
fn faults_in_the_product_structure_are_reported() {
    // A dangling placement and a cycle (the part used in itself): named, no panic.
    let t = text("occt-assembly-boxes.step")
        .replace(
            "ITEM_DEFINED_TRANSFORMATION('','',#11,#19)",
            "ITEM_DEFINED_TRANSFORMATION('','',#11,#9999)",
        )
        .replace(
            "#382 = NEXT_ASSEMBLY_USAGE_OCCURRENCE('2','=>[0:1:1:1]','',#5,#31,$);",
            "#382 = NEXT_ASSEMBLY_USAGE_OCCURRENCE('2','=>[0:1:1:1]','',#5,#31,$);\n#383 = NEXT_ASSEMBLY_USAGE_OCCURRENCE('3','','',#31,#31,$);",
        );
    let (m, b) = read("faulty", &t);
    let w = m.warnings.join("\n");
    assert!(w.contains("#380") && w.contains("#382"), "{w}");
    assert!(w.contains("#383") && w.contains("own ancestor"), "{w}");
    // The part still appears at both occurrences (one without its motion).
    assert_eq!(b.solids.len(), 2);
}

#[test]
fn info_convert_and_ssi_work_on_assemblies() {
    let bin = env!("CARGO_BIN_EXE_vericad");
    let run = |args: &[&str]| {
        let o = std::process::Command::new(bin).args(args).output().unwrap();
        let out = String::from_utf8_lossy(&o.stdout).to_string();
        assert!(o.status.success(), "{args:?}: {out}");
        out
    };
    let nested = path("occt-assembly-nested.step");
    let nested = nested.to_str().unwrap();
    let info = run(&["info", nested]);
    assert!(info.contains("assembly: 7 occurrence(s)"), "{info}");
    for line in ["#54 'pair' (#31)", "#752 'peg' (#407)", "#758 'pair' (#31)"] {
        assert!(info.contains(line), "{line}: {info}");
    }
    // Written as STEP (each placed solid its own MANIFOLD_SOLID_BREP) and read back.
    let dir = std::env::temp_dir().join(format!("vericad-asm-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("nested.step");
    run(&["convert", nested, out.to_str().unwrap()]);
    let m = vericad::io::read_model(&out).unwrap();
    let b = m.brep.clone().unwrap();
    check("nested written", &solids(&m, &b), &NESTED);
    let stl = dir.join("nested.stl");
    let said = run(&["convert", nested, stl.to_str().unwrap()]);
    assert!(said.contains("24 B-rep faces"), "{said}");
    // The two boxes are apart: no branch.
    let boxes = path("occt-assembly-boxes.step");
    // (Exit 3: finished, coverage not certified everywhere along the boxes' shared edges.)
    let o = std::process::Command::new(bin)
        .args(["ssi", boxes.to_str().unwrap()])
        .output()
        .unwrap();
    let ssi = String::from_utf8_lossy(&o.stdout);
    assert!(matches!(o.status.code(), Some(0 | 3)), "{ssi}");
    assert!(
        ssi.contains("faces: 12 x 0") && ssi.contains("branches: 0 "),
        "{ssi}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Signed volume enclosed by the B-rep's triangulation (divergence theorem; positive when
/// the triangles face outward): the oracle for the faces' orientation after a mirroring.
fn mesh_volume(m: &Model, b: &Brep) -> f64 {
    let mesh = vericad::tessellate::mesh_brep(m, b, &vericad::tessellate::MeshParams::default());
    assert!(mesh.issues(b).is_empty(), "{:?}", mesh.issues(b));
    let t = &mesh.triangulation;
    t.triangles
        .iter()
        .map(|tri| {
            let [a, b, c] = tri.map(|i| t.vertices[i as usize]);
            vericad::geom::dot(&a, &vericad::geom::cross(&b, &c)) / 6.0
        })
        .sum()
}

#[test]
fn cartesian_transformation_operators_scale_and_mirror() {
    // The first box placed by an operator with scale 2 (the standard's 7-attribute form, the
    // axes of the file's own frame #15); the second by a mirroring operator (6-attribute
    // form: axis1 = y, axis2 = x, axis3 unset, so T p = (p_y, p_x, p_z)) at (100, 0, 0).
    let t = text("occt-assembly-boxes.step")
        .replace(
            "#374 = ITEM_DEFINED_TRANSFORMATION('','',#11,#15);",
            "#374 = CARTESIAN_TRANSFORMATION_OPERATOR_3D('','',#18,#9001,#16,2.,#17);\n#9001 = DIRECTION('',(-1.,0.,0.));",
        )
        .replace(
            "#380 = ITEM_DEFINED_TRANSFORMATION('','',#11,#19);",
            "#380 = CARTESIAN_TRANSFORMATION_OPERATOR_3D('',#9002,#9003,#16,$,$);\n#9002 = DIRECTION('',(0.,1.,0.));\n#9003 = DIRECTION('',(1.,0.,0.));",
        );
    let (m, b) = read("operators", &t);
    let w = m.warnings.join("\n");
    assert!(!w.contains("assembly"), "{w}");
    let bx = corners([10.0, 20.0, 30.0]);
    let m1 = motion([0.0, 0.0, 1.0], 90.0, [100.0, 0.0, 0.0]);
    let scaled: Vec<[f64; 3]> = bx.iter().map(|&p| m1(p.map(|x| 2.0 * x))).collect();
    let mirrored: Vec<[f64; 3]> = bx.iter().map(|p| [p[1] + 100.0, p[0], p[2]]).collect();
    vertices_are(&b, 0, &scaled, 1e-9);
    vertices_are(&b, 1, &mirrored, 1e-9);
    // Areas scale by 4; the mirrored box keeps its area, and both enclose their volume
    // with the faces outward.
    let got = solids(&m, &b);
    assert!((got[0].0 - 4.0 * 2200.0).abs() < 1e-6, "{got:?}");
    assert!((got[1].0 - 2200.0).abs() < 1e-6, "{got:?}");
    // Every face meshed: 8 · 6000 + 6000 (a mirrored box facing inward would give 42000).
    let v = mesh_volume(&m, &b);
    assert!((v - 54000.0).abs() < 1e-6 * 54000.0, "{v}");
    // ISO 10303-42: each bound, taken with its orientation, runs counter-clockwise about the
    // face's outward normal (the face on its left). For a box the outward normal of a face
    // points from the box's centre to the face's centre.
    for (k, centre) in [(0, m1([10.0, 20.0, 30.0])), (1, [110.0, 5.0, 15.0])] {
        for &(f, _) in &b.shells[b.solids[k].outer].faces {
            for l in &b.faces[f].loops {
                let vericad::brep::LoopKind::Edges(es) = &l.kind else {
                    panic!("a box face bounded by edges")
                };
                let pts: Vec<[f64; 3]> = es
                    .iter()
                    .map(|oe| {
                        let e = &b.edges[oe.edge];
                        b.vertices[if oe.forward { e.start } else { e.end }].point
                    })
                    .collect();
                let n = pts.len() as f64;
                let mid = [0, 1, 2].map(|i| pts.iter().map(|p| p[i]).sum::<f64>() / n);
                let mut newell = [0.0; 3];
                for (i, p) in pts.iter().enumerate() {
                    let q = pts[(i + 1) % pts.len()];
                    let c = vericad::geom::cross(p, &q);
                    (0..3).for_each(|j| newell[j] += c[j]);
                }
                let out = [0, 1, 2].map(|i| mid[i] - centre[i]);
                let turn =
                    vericad::geom::dot(&newell, &out) * if l.orientation { 1.0 } else { -1.0 };
                assert!(
                    turn > 0.0,
                    "solid {k}, face {}: bound {} runs clockwise",
                    b.faces[f].source,
                    l.source
                );
            }
        }
    }

    // Reversed (the parent as rep_1): the inverse of the scaled operator places the child.
    let r = t.replace(
        "( REPRESENTATION_RELATIONSHIP('','',#36,#10)",
        "( REPRESENTATION_RELATIONSHIP('','',#10,#36)",
    );
    let (m, b) = read("operators reversed", &r);
    assert!(!m.warnings.join("\n").contains("assembly"));
    let inv = |p: [f64; 3]| [p[1] / 2.0, (100.0 - p[0]) / 2.0, p[2] / 2.0];
    vertices_are(&b, 0, &bx.iter().map(|&p| inv(p)).collect::<Vec<_>>(), 1e-9);

    // An operator as a MAPPED_ITEM's target (mapping origin the world frame #11): the
    // identity operator and one with scale 3 and origin (1, 2, 3) place the cylinder part at
    // S and at 3 S + (1, 2, 3).
    let t = text("occt-assembly-cylinder.step");
    let cut = (t.find("#136 = ").unwrap(), t.find("#141 = ").unwrap());
    let mapped = |scale: &str, o: &str| {
        let t = format!("{}{}", &t[..cut.0], &t[cut.1..])
            .replace("#25 = SHAPE_DEFINITION_REPRESENTATION(#26,#32);", "")
            .replace(
                "#10 = SHAPE_REPRESENTATION('',(#11,#15),#19);",
                &format!("#10 = SHAPE_REPRESENTATION('',(#11,#900),#19);\n#900 = MAPPED_ITEM('',#901,#902);\n#901 = REPRESENTATION_MAP(#11,#32);\n#902 = CARTESIAN_TRANSFORMATION_OPERATOR_3D('',$,$,#903,{scale},$);\n#903 = CARTESIAN_POINT('',({o}));"),
            );
        let (m, b) = read("mapped operator", &t);
        assert!(!m.warnings.join("\n").contains("assembly"));
        solids(&m, &b)[0]
    };
    let (a1, b1) = mapped("$", "0.,0.,0.");
    let (a3, b3) = mapped("3.", "1.,2.,3.");
    assert!((a3 - 9.0 * a1).abs() < 1e-9 * a3, "{a1} {a3}");
    for k in 0..6 {
        let want = 3.0 * b1[k] + [1.0, 2.0, 3.0][k % 3];
        assert!((b3[k] - want).abs() < 1e-6, "{b1:?} {b3:?}");
    }
}

#[test]
fn faulty_operators_are_reported() {
    for (op, says) in [
        (
            "CARTESIAN_TRANSFORMATION_OPERATOR_3D('',#17,$,#16,$,#17)",
            "do not span",
        ),
        (
            "CARTESIAN_TRANSFORMATION_OPERATOR_3D('',$,$,#16,-1.,$)",
            "scale",
        ),
        (
            "CARTESIAN_TRANSFORMATION_OPERATOR_3D('',$,$,#16)",
            "attributes",
        ),
        (
            "CARTESIAN_TRANSFORMATION_OPERATOR_3D('',$,$,#9999,$,$)",
            "#9999",
        ),
    ] {
        let t = text("occt-assembly-boxes.step").replace(
            "#374 = ITEM_DEFINED_TRANSFORMATION('','',#11,#15);",
            &format!("#374 = {op};"),
        );
        let (m, b) = read("faulty operator", &t);
        let w = m.warnings.join("\n");
        assert!(w.contains("#376") && w.contains(says), "{op}: {w}");
        assert_eq!(b.solids.len(), 2);
    }
}

#[test]
fn parts_in_another_length_unit_are_scaled_into_the_assemblys() {
    // The box part's context in inches (a conversion-based unit of 25.4 mm), the assembly's
    // in millimetres: the model is in mm, the boxes are 254 × 508 × 762 mm, placed by the
    // file's motions (their translations are the assembly's, in mm).
    let t = text("occt-assembly-boxes.step").replace(
        "#368 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );",
        "#368 = ( CONVERSION_BASED_UNIT('INCH',#9020) LENGTH_UNIT() NAMED_UNIT(#9021) );\n#9020 = LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4),#24);\n#9021 = DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.);",
    );
    let (m, b) = read("inch part", &t);
    assert_eq!(m.unit.as_deref(), Some("mm"));
    let w = m.warnings.join("\n");
    assert!(w.contains("#36 ") && w.contains("scaled by 25.4"), "{w}");
    let bx = corners([254.0, 508.0, 762.0]);
    let m1 = motion([0.0, 0.0, 1.0], 90.0, [100.0, 0.0, 0.0]);
    let m2 = motion([1.0, 1.0, 0.0], 30.0, [0.0, 50.0, 10.0]);
    vertices_are(
        &b,
        0,
        &bx.iter().map(|&p| m1(p)).collect::<Vec<_>>(),
        1e-9 * 762.0,
    );
    vertices_are(
        &b,
        1,
        &bx.iter().map(|&p| m2(p)).collect::<Vec<_>>(),
        1e-9 * 762.0,
    );
    // Open CASCADE 8.0.1 reads the same file (it converts every unit to mm) as these two
    // solids: area 1419352 mm² each, boxes printed to 1e-6 mm.
    let occt: [Occt; 2] = [
        (1419352.0, [-408.0, 0.0, 0.0, 100.0, 254.0, 762.0]),
        (
            1419352.0,
            [
                0.0,
                -219.407684,
                -79.802561,
                540.422457,
                540.985226,
                849.51648,
            ],
        ),
    ];
    check("inch part", &solids(&m, &b), &occt);
    // The child's frame of the first placement moved to (1, 2, 3) in the part (inches): it is
    // 25.4 · (1, 2, 3) mm in the model, and the motion maps it onto the assembly's frame.
    let t2 = t
        .replace(
            "#374 = ITEM_DEFINED_TRANSFORMATION('','',#11,#15);",
            "#374 = ITEM_DEFINED_TRANSFORMATION('','',#9030,#15);\n#9030 = AXIS2_PLACEMENT_3D('',#9031,#13,#14);\n#9031 = CARTESIAN_POINT('',(1.,2.,3.));",
        )
        .replace("#36 = ADVANCED_BREP_SHAPE_REPRESENTATION('',(#11,#37),#367);", "#36 = ADVANCED_BREP_SHAPE_REPRESENTATION('',(#11,#37,#9030),#367);");
    assert_ne!(t2, t);
    let (_, b) = read("inch part, moved frame", &t2);
    let shifted: Vec<[f64; 3]> = bx
        .iter()
        .map(|&p| m1([p[0] - 25.4, p[1] - 50.8, p[2] - 76.2]))
        .collect();
    vertices_are(&b, 0, &shifted, 1e-9 * 762.0);

    // Without the occurrences nothing says how the two units relate: a warning, not a guess.
    let lines: Vec<&str> = t
        .lines()
        .filter(|l| !l.contains("NEXT_ASSEMBLY_USAGE_OCCURRENCE"))
        .collect();
    let (m, _) = read("inch part, no structure", &lines.join("\n"));
    let w = m.warnings.join("\n");
    assert!(w.contains("use 2 length units (1e-3, 2.54e-2 m)"), "{w}");

    // The same part in metres (SI, no prefix) and the assembly in mm: scaled by 1000.
    let t = text("occt-assembly-boxes.step").replace(
        "#368 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );",
        "#368 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT($,.METRE.) );",
    );
    let (m, b) = read("metre part", &t);
    let bx = corners([10000.0, 20000.0, 30000.0]);
    vertices_are(
        &b,
        0,
        &bx.iter().map(|&p| m1(p)).collect::<Vec<_>>(),
        1e-9 * 30000.0,
    );
    assert_eq!(m.unit.as_deref(), Some("mm"));
}
