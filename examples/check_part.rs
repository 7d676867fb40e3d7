//! Reads a CAD part (STEP, IGES, native JSON) and checks it the way a pre-processing script
//! would: its faces, which are trimmed, whether each edge lies on its faces, and a
//! self-intersection check of the whole part with its certificate.
//!
//! ```sh
//! cargo run --release --example check_part -- tests/data/public/abc-0000.step
//! ```
//! Without an argument it reads `tests/data/public/gmsh-t20_data.step`.

use std::path::PathBuf;
use vericad::{SsiParams, intersect_models, read_model};

fn main() {
    let path = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/public/gmsh-t20_data.step")
        });
    let model = match read_model(&path) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    };
    println!("{}: {} surfaces", path.display(), model.surfaces.len());
    if let Some(b) = &model.brep {
        let natural = vericad::brep::natural::natural_faces(b, &model);
        let whole = natural.iter().filter(|n| **n).count();
        println!(
            "  {} faces ({whole} bounded by their surface's whole parameter rectangle), {} edges",
            b.faces.len(),
            b.edges.len()
        );
        let e = vericad::brep::edge_check::check_edges(b, &model);
        println!(
            "  edge-face pairs: {} of {} proven within {:.1e} of their faces (largest bound {:.1e}), {} above it",
            e.proven,
            e.pairs,
            e.tolerance,
            e.largest_bound,
            e.above_tolerance()
        );
    }
    // One model: every pair of distinct faces (edges two faces share are listed as such).
    let r = match intersect_models(&model, None, &SsiParams::default(), &|_, _| {}) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    };
    let s = &r.summary;
    println!(
        "  self-intersection: {} branches ({} closed), {} face pairs coincide, certified: {}",
        s.branches, s.closed_branches, s.coincident_pairs, s.certified
    );
    for line in &s.certificate {
        println!("    - {line}");
    }
    std::process::exit(if s.certified { 0 } else { 3 });
}
