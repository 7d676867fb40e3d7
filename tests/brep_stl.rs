//! CAD to STL: `vericad convert part.step out.stl` (ASCII or `--format stl-binary`) writes the
//! B-rep's faces triangulated inside their trims. For a file whose B-rep is one closed shell,
//! the STL read back (vertices welded by position) is watertight: every edge used by exactly
//! two triangles, once in each direction.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

fn public(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public")
        .join(name)
}

/// Uses of each mesh edge `(a, b)`.
type Uses = BTreeMap<(u32, u32), usize>;

/// Undirected and directed uses of each mesh edge.
fn uses(t: &[[u32; 3]]) -> (Uses, Uses) {
    let (mut und, mut dir) = (BTreeMap::new(), BTreeMap::new());
    for tri in t {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            *und.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            *dir.entry((a, b)).or_insert(0) += 1;
        }
    }
    (und, dir)
}

fn convert_and_check(file: &str, format: &str) {
    let m = vericad::io::read_model(&public(file)).unwrap();
    let b = m.brep.as_ref().unwrap();
    assert_eq!(b.shells.len(), 1, "{file}: one shell");
    assert!(b.shells[0].closed, "{file}: the shell is closed");
    let dir = std::env::temp_dir().join(format!("vericad-brep-stl-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join(format!("{file}.{format}.stl"));
    let o = Command::new(env!("CARGO_BIN_EXE_vericad"))
        .args([
            "convert",
            public(file).to_str().unwrap(),
            out.to_str().unwrap(),
            "--format",
            format,
        ])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{file}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        stdout.contains("triangulated inside their trims"),
        "{stdout}"
    );
    let back = vericad::io::stl::read(&out).unwrap();
    let t = &back.triangulations[0];
    assert!(
        t.triangles.len() > 2 * b.faces.len(),
        "{file}: {} triangles",
        t.triangles.len()
    );
    let (und, dir_uses) = uses(&t.triangles);
    let bad: Vec<_> = und.iter().filter(|(_, n)| **n != 2).collect();
    assert!(
        bad.is_empty(),
        "{file} ({format}): {} of {} edges not used twice: {:?}",
        bad.len(),
        und.len(),
        &bad[..bad.len().min(10)]
    );
    let twice: Vec<_> = dir_uses.iter().filter(|(_, n)| **n != 1).collect();
    assert!(
        twice.is_empty(),
        "{file} ({format}): inconsistent orientation {:?}",
        &twice[..twice.len().min(10)]
    );
    std::fs::remove_file(&out).ok();
}

#[test]
fn t20_converts_to_a_watertight_ascii_stl() {
    convert_and_check("gmsh-t20_data.step", "stl");
}

#[test]
fn t20_converts_to_a_watertight_binary_stl() {
    convert_and_check("gmsh-t20_data.step", "stl-binary");
}

#[test]
fn periodic_converts_to_a_watertight_binary_stl() {
    convert_and_check("gmsh-periodic_u_cst.step", "stl-binary");
}
