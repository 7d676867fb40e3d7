//! STL reader (ASCII and binary) into a triangulation with welded vertices (bit-identical
//! coordinates merged), and an ASCII writer.

use crate::model::{Model, Triangulation};
use std::collections::HashMap;

/// A fault in an STL file.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{file}: {location}: {reason}")]
pub struct StlError {
    pub file: String,
    pub location: String,
    pub reason: String,
}

fn weld(tris: Vec<[[f64; 3]; 3]>, name: String) -> Triangulation {
    let mut index: HashMap<[u64; 3], u32> = HashMap::new();
    let mut vertices = Vec::new();
    let mut triangles = Vec::with_capacity(tris.len());
    for t in tris {
        let ids = t.map(|p| {
            let key = p.map(|x| (if x == 0.0 { 0.0 } else { x }).to_bits());
            *index.entry(key).or_insert_with(|| {
                vertices.push(p);
                (vertices.len() - 1) as u32
            })
        });
        triangles.push(ids);
    }
    Triangulation {
        name,
        vertices,
        triangles,
    }
}

/// Read STL bytes (binary when the size matches the binary layout, ASCII otherwise).
pub fn from_bytes(b: &[u8], file: &str) -> Result<Model, StlError> {
    let err = |location: String, reason: String| StlError {
        file: file.into(),
        location,
        reason,
    };
    let binary = b.len() >= 84 && {
        let n = u32::from_le_bytes([b[80], b[81], b[82], b[83]]) as usize;
        b.len() == 84 + 50 * n
    };
    let mut tris = Vec::new();
    let name;
    if binary {
        name = String::from_utf8_lossy(&b[..80])
            .trim_matches(char::from(0))
            .trim()
            .to_string();
        let n = u32::from_le_bytes([b[80], b[81], b[82], b[83]]) as usize;
        for k in 0..n {
            let o = 84 + 50 * k + 12;
            let f = |i: usize| {
                f32::from_le_bytes([
                    b[o + 4 * i],
                    b[o + 4 * i + 1],
                    b[o + 4 * i + 2],
                    b[o + 4 * i + 3],
                ]) as f64
            };
            let t: [[f64; 3]; 3] = std::array::from_fn(|v| std::array::from_fn(|c| f(3 * v + c)));
            if t.iter().flatten().any(|x| !x.is_finite()) {
                return Err(err(format!("triangle {k}"), "non-finite coordinate".into()));
            }
            tris.push(t);
        }
    } else {
        let text = String::from_utf8_lossy(b);
        let mut lines = text.lines().enumerate();
        name = match lines.next() {
            Some((_, l)) if l.trim_start().starts_with("solid") => {
                l.trim_start()[5..].trim().to_string()
            }
            _ => {
                return Err(err(
                    "line 1".into(),
                    "neither binary STL nor ASCII 'solid'".into(),
                ));
            }
        };
        let mut cur: Vec<[f64; 3]> = Vec::new();
        for (n, l) in lines {
            let w: Vec<&str> = l.split_whitespace().collect();
            match w.first() {
                Some(&"vertex") => {
                    let c: Result<Vec<f64>, _> = w[1..].iter().map(|x| x.parse::<f64>()).collect();
                    match c {
                        Ok(c) if c.len() == 3 && c.iter().all(|x| x.is_finite()) => {
                            cur.push([c[0], c[1], c[2]])
                        }
                        _ => {
                            return Err(err(
                                format!("line {}", n + 1),
                                format!("bad vertex '{}'", l.trim()),
                            ));
                        }
                    }
                }
                Some(&"endfacet") => {
                    if cur.len() != 3 {
                        return Err(err(
                            format!("line {}", n + 1),
                            format!("facet with {} vertices", cur.len()),
                        ));
                    }
                    tris.push([cur[0], cur[1], cur[2]]);
                    cur.clear();
                }
                _ => {}
            }
        }
    }
    Ok(Model {
        triangulations: vec![weld(tris, name)],
        ..Model::default()
    })
}

/// Read an STL file.
pub fn read(path: &std::path::Path) -> Result<Model, StlError> {
    let name = path.display().to_string();
    let b = std::fs::read(path).map_err(|e| StlError {
        file: name.clone(),
        location: "(file)".into(),
        reason: e.to_string(),
    })?;
    from_bytes(&b, &name)
}

/// ASCII STL of a triangulation.
pub fn to_string(t: &Triangulation) -> String {
    let mut s = format!("solid {}\n", t.name);
    for tri in &t.triangles {
        s += "  facet normal 0 0 0\n    outer loop\n";
        for &v in tri {
            let p = t.vertices[v as usize];
            s += &format!("      vertex {:?} {:?} {:?}\n", p[0], p[1], p[2]);
        }
        s += "    endloop\n  endfacet\n";
    }
    s += &format!("endsolid {}\n", t.name);
    s
}

/// Binary STL of a triangulation (normals from the vertices, single precision as the format
/// prescribes: coordinates are rounded to f32).
pub fn to_binary(t: &Triangulation) -> Vec<u8> {
    let mut b = vec![0u8; 80];
    let name = t.name.as_bytes();
    b[..name.len().min(80)].copy_from_slice(&name[..name.len().min(80)]);
    b.extend((t.triangles.len() as u32).to_le_bytes());
    for tri in &t.triangles {
        let p = tri.map(|v| t.vertices[v as usize]);
        let e1 = [p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]];
        let e2 = [p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]];
        let n = crate::geom::cross(&e1, &e2);
        let l = crate::geom::norm(&n);
        let n = if l > 0.0 {
            [n[0] / l, n[1] / l, n[2] / l]
        } else {
            [0.0; 3]
        };
        for x in n.iter().chain(p.iter().flatten()) {
            b.extend((*x as f32).to_le_bytes());
        }
        b.extend([0u8, 0u8]);
    }
    b
}
