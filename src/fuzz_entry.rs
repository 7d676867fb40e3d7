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
