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

/// Triangles welded as they are read: vertices with bit-identical coordinates merged (`-0.0`
/// as `0.0`), so the file's triangles are never held a second time as coordinates.
struct Welder {
    index: HashMap<[u64; 3], u32>,
    vertices: Vec<[f64; 3]>,
    triangles: Vec<[u32; 3]>,
}

impl Welder {
    /// For about `n` triangles (a closed mesh has about half as many vertices: sized up
    /// front, the table is never rebuilt while it grows).
    fn with_capacity(n: usize) -> Welder {
        Welder {
            index: HashMap::with_capacity(n / 2 + 16),
            vertices: Vec::with_capacity(n / 2 + 16),
            triangles: Vec::with_capacity(n),
        }
    }
    fn push(&mut self, t: [[f64; 3]; 3]) {
        let ids = t.map(|p| {
            let key = p.map(|x| (if x == 0.0 { 0.0 } else { x }).to_bits());
            *self.index.entry(key).or_insert_with(|| {
                self.vertices.push(p);
                (self.vertices.len() - 1) as u32
            })
        });
        self.triangles.push(ids);
    }
    fn len(&self) -> usize {
        self.triangles.len()
    }
    fn finish(self, name: String) -> Triangulation {
        Triangulation {
            name,
            vertices: self.vertices,
            triangles: self.triangles,
        }
    }
}

/// Whether the bytes are plain text (printable ASCII and whitespace): an ASCII STL. A
/// binary STL whose 80-byte header happens to start with `solid` fails this on its
/// triangle data.
fn is_text(b: &[u8]) -> bool {
    b.iter()
        .all(|&c| c == b'\n' || c == b'\r' || c == b'\t' || (0x20..0x7f).contains(&c))
}

/// Read STL bytes. Binary when the size matches the binary layout (`84 + 50 n` bytes for
/// the `n` triangles the header claims), also when only whitespace or NUL bytes follow the
/// triangles (reported in the warnings); ASCII when the file is text starting with `solid`.
/// Anything else is an error that says which size was expected: never an empty model.
pub fn from_bytes(b: &[u8], file: &str) -> Result<Model, StlError> {
    let err = |location: String, reason: String| StlError {
        file: file.into(),
        location,
        reason,
    };
    let claimed = (b.len() >= 84).then(|| u32::from_le_bytes([b[80], b[81], b[82], b[83]]) as u64);
    let needed = claimed.map(|n| 84 + 50 * n);
    let solid = b
        .iter()
        .position(|c| !c.is_ascii_whitespace())
        .is_some_and(|i| b[i..].starts_with(b"solid"));
    let mut warnings = Vec::new();
    let binary = match needed {
        Some(need) if b.len() as u64 == need => true,
        _ if solid && is_text(b) => false,
        Some(need) if (b.len() as u64) > need => {
            let extra = &b[need as usize..];
            if extra.iter().all(|c| c.is_ascii_whitespace() || *c == 0) {
                warnings.push(format!(
                    "{} byte(s) of padding after the {} triangles of the binary STL ignored",
                    extra.len(),
                    claimed.unwrap_or(0)
                ));
                true
            } else {
                return Err(err(
                    "(file)".into(),
                    format!(
                        "not ASCII STL (not text starting with 'solid'), and not binary STL: the header claims {} triangles ({need} bytes) but the file has {} bytes, {} more that are not padding",
                        claimed.unwrap_or(0),
                        b.len(),
                        b.len() as u64 - need
                    ),
                ));
            }
        }
        Some(need) => {
            return Err(err(
                "(file)".into(),
                format!(
                    "not ASCII STL (not text starting with 'solid'), and not binary STL: the header claims {} triangles ({need} bytes) but the file has only {} bytes (truncated?)",
                    claimed.unwrap_or(0),
                    b.len()
                ),
            ));
        }
        None if solid && is_text(b) => false,
        None => {
            return Err(err(
                "(file)".into(),
                format!(
                    "neither binary STL (shorter than its 84-byte header: {} bytes) nor ASCII 'solid'",
                    b.len()
                ),
            ));
        }
    };
    let mut tris = Welder::with_capacity(if binary {
        claimed.unwrap_or(0) as usize
    } else {
        0
    });
    let name;
    if binary {
        name = String::from_utf8_lossy(&b[..80])
            .trim_matches(char::from(0))
            .trim()
            .to_string();
        // The count was checked against the file size above.
        let n = claimed.unwrap_or(0) as usize;
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
        let mut lines = text
            .lines()
            .enumerate()
            .skip_while(|(_, l)| l.trim().is_empty());
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
        // Line of the open `facet`, if any; whether the last solid was closed.
        let mut open: Option<usize> = None;
        let mut ended = false;
        for (n, l) in lines {
            let w: Vec<&str> = l.split_whitespace().collect();
            match w.first() {
                Some(&"facet") => {
                    if let Some(o) = open {
                        return Err(err(
                            format!("line {}", n + 1),
                            format!(
                                "facet begins before the facet of line {} ended (no 'endfacet')",
                                o
                            ),
                        ));
                    }
                    open = Some(n + 1);
                    ended = false;
                }
                Some(&"vertex") => {
                    if open.is_none() {
                        return Err(err(
                            format!("line {}", n + 1),
                            "vertex outside a facet".into(),
                        ));
                    }
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
                    if cur.len() != 3 || open.is_none() {
                        return Err(err(
                            format!("line {}", n + 1),
                            format!("facet with {} vertices", cur.len()),
                        ));
                    }
                    tris.push([cur[0], cur[1], cur[2]]);
                    cur.clear();
                    open = None;
                }
                Some(&"endsolid") => {
                    if let Some(o) = open {
                        return Err(err(
                            format!("line {}", n + 1),
                            format!("'endsolid' inside the facet of line {o}"),
                        ));
                    }
                    ended = true;
                }
                Some(&"solid") => ended = false,
                _ => {}
            }
        }
        if let Some(o) = open {
            return Err(err(
                format!("line {o}"),
                format!(
                    "the file ends inside the facet that begins here (no 'endfacet'): truncated after {} complete triangles",
                    tris.len()
                ),
            ));
        }
        if !ended {
            warnings.push(format!(
                "ASCII STL without a final 'endsolid': the file may be truncated; {} complete triangles read",
                tris.len()
            ));
        }
    }
    Ok(Model {
        triangulations: vec![tris.finish(name)],
        warnings,
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
/// prescribes: coordinates are rounded to f32). A coordinate beyond the `f32` range (it
/// would be written as infinity) is refused: the vertex index and value are returned.
pub fn to_binary(t: &Triangulation) -> Result<Vec<u8>, (usize, f64)> {
    for (k, v) in t.vertices.iter().enumerate() {
        if let Some(x) = v.iter().find(|x| x.is_nan() || x.abs() > f32::MAX as f64) {
            return Err((k, *x));
        }
    }
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
        let n = if l > 0.0 && l.is_finite() {
            [n[0] / l, n[1] / l, n[2] / l]
        } else {
            [0.0; 3]
        };
        for x in n.iter().chain(p.iter().flatten()) {
            b.extend((*x as f32).to_le_bytes());
        }
        b.extend([0u8, 0u8]);
    }
    Ok(b)
}
