//! Wavefront OBJ writer: surfaces tessellated on a parameter grid (one group per surface)
//! and triangulations.

use std::fmt::Write;

/// A model as OBJ text.
pub fn model_to_obj(m: &crate::model::Model, grid: usize) -> String {
    let mut s = String::from("# vericad OBJ export\n");
    let mut base = 1usize;
    for (k, surf) in m.surfaces.iter().enumerate() {
        let _ = writeln!(s, "g surface_{k}");
        let (u0, u1, v0, v1) = surf.nurbs.hom.domain();
        for i in 0..=grid {
            for j in 0..=grid {
                let p = surf.nurbs.eval(
                    &(u0 + (u1 - u0) * i as f64 / grid as f64),
                    &(v0 + (v1 - v0) * j as f64 / grid as f64),
                );
                let _ = writeln!(s, "v {:?} {:?} {:?}", p[0], p[1], p[2]);
            }
        }
        let id = |i: usize, j: usize| base + i * (grid + 1) + j;
        for i in 0..grid {
            for j in 0..grid {
                let _ = writeln!(
                    s,
                    "f {} {} {} {}",
                    id(i, j),
                    id(i + 1, j),
                    id(i + 1, j + 1),
                    id(i, j + 1)
                );
            }
        }
        base += (grid + 1) * (grid + 1);
    }
    for t in &m.triangulations {
        let _ = writeln!(
            s,
            "g {}",
            if t.name.is_empty() {
                "triangulation"
            } else {
                &t.name
            }
        );
        for v in &t.vertices {
            let _ = writeln!(s, "v {:?} {:?} {:?}", v[0], v[1], v[2]);
        }
        for tri in &t.triangles {
            let _ = writeln!(
                s,
                "f {} {} {}",
                base + tri[0] as usize,
                base + tri[1] as usize,
                base + tri[2] as usize
            );
        }
        base += t.vertices.len();
    }
    s
}
