//! Plot3D surface-grid reader: ASCII and binary (little-endian), single- and multi-block,
//! single and double precision, with and without Fortran record markers, with or without
//! iblank. Each block becomes the degree-1 B-spline surface through its grid points — the
//! exact piecewise-bilinear surface of the grid (knots at the grid indices).
//!
//! Layout per block: dimensions `ni nj [nk=1]`, then all x, all y, all z (i fastest),
//! then optionally `ni·nj` iblank integers. Variants are recognized by size consistency;
//! an input that fits none is an error saying what was expected.

use crate::model::{Model, Surface};
use crate::spline::NurbsSurface;

/// A fault in a Plot3D file.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{file}: {reason}")]
pub struct Plot3dError {
    pub file: String,
    pub reason: String,
}

struct Block {
    ni: usize,
    nj: usize,
    xyz: Vec<f64>,
}

fn surfaces(blocks: Vec<Block>, file: &str) -> Result<Model, Plot3dError> {
    let mut m = Model::default();
    for (b, bl) in blocks.into_iter().enumerate() {
        let (ni, nj) = (bl.ni, bl.nj);
        let n = ni * nj;
        if ni < 2 || nj < 2 {
            return Err(Plot3dError {
                file: file.into(),
                reason: format!(
                    "block {b}: a surface grid needs at least 2×2 points, got {ni}×{nj}"
                ),
            });
        }
        if bl.xyz.iter().any(|x| !x.is_finite()) {
            return Err(Plot3dError {
                file: file.into(),
                reason: format!("block {b}: non-finite coordinate"),
            });
        }
        // net[i * nj + j] = point (i, j); file order has i fastest.
        let mut pts = Vec::with_capacity(n);
        for i in 0..ni {
            for j in 0..nj {
                let k = i + j * ni;
                pts.push([bl.xyz[k], bl.xyz[n + k], bl.xyz[2 * n + k]]);
            }
        }
        let knots = |c: usize| {
            let mut k = vec![0.0];
            k.extend((0..c).map(|x| x as f64));
            k.push((c - 1) as f64);
            k
        };
        let s = NurbsSurface::new(knots(ni), 1, knots(nj), 1, ni, nj, pts, vec![1.0; n]).map_err(
            |e| Plot3dError {
                file: file.into(),
                reason: format!("block {b}: {e}"),
            },
        )?;
        m.surfaces.push(Surface {
            source: Some(format!("block {b}")),
            ..Surface::new(format!("block {b}"), s)
        });
    }
    Ok(m)
}

/// Interpret a flat list of numbers as blocks, trying the given layouts (multi-block or
/// not, 3 or 2 dimensions per block).
fn from_numbers(v: &[f64], layouts: &[(bool, usize)]) -> Option<Vec<Block>> {
    let as_count = |x: f64| (x >= 1.0 && x.fract() == 0.0 && x < 1e8).then_some(x as usize);
    for &(multi, d) in layouts {
        {
            let (nb, mut at) = if multi {
                (as_count(*v.first()?)?, 1)
            } else {
                (1, 0)
            };
            if nb > 100_000 || at + nb * d > v.len() {
                continue;
            }
            let mut dims = Vec::with_capacity(nb);
            let mut ok = true;
            for b in 0..nb {
                let ds: Option<Vec<usize>> = (0..d).map(|k| as_count(v[at + b * d + k])).collect();
                match ds {
                    Some(ds) if d == 2 || ds[2] == 1 => dims.push((ds[0], ds[1])),
                    _ => ok = false,
                }
            }
            if !ok {
                continue;
            }
            at += nb * d;
            let need: usize = dims.iter().map(|(a, b)| 3 * a * b).sum();
            let iblank: usize = dims.iter().map(|(a, b)| a * b).sum();
            let rest = v.len() - at;
            if rest != need && rest != need + iblank {
                continue;
            }
            let with_iblank = rest == need + iblank;
            let mut blocks = Vec::new();
            for (ni, nj) in dims {
                let n = ni * nj;
                blocks.push(Block {
                    ni,
                    nj,
                    xyz: v[at..at + 3 * n].to_vec(),
                });
                at += 3 * n + if with_iblank { n } else { 0 };
            }
            return Some(blocks);
        }
    }
    None
}

/// Read Plot3D bytes.
pub fn from_bytes(b: &[u8], file: &str) -> Result<Model, Plot3dError> {
    let fail = |reason: &str| Plot3dError {
        file: file.into(),
        reason: reason.into(),
    };
    // ASCII: every token a number.
    if let Ok(text) = std::str::from_utf8(b) {
        let toks: Option<Vec<f64>> = text
            .split_whitespace()
            .map(|t| t.replace(['D', 'd'], "E").parse::<f64>().ok())
            .collect();
        if let Some(v) = toks.filter(|v| !v.is_empty()) {
            return match from_numbers(&v, &[(true, 3), (true, 2), (false, 3), (false, 2)]) {
                Some(bl) => surfaces(bl, file),
                None => Err(fail(
                    "ASCII numbers do not match any Plot3D surface-grid layout (counts and dimensions disagree)",
                )),
            };
        }
    }
    let i32_at = |o: usize| {
        b.get(o..o + 4)
            .map(|s| i32::from_le_bytes([s[0], s[1], s[2], s[3]]))
    };
    // Fortran records: [len][payload][len]...
    let records = || -> Option<Vec<&[u8]>> {
        let mut out = Vec::new();
        let mut o = 0;
        while o < b.len() {
            let n = usize::try_from(i32_at(o)?).ok()?;
            let payload = b.get(o + 4..o + 4 + n)?;
            if i32_at(o + 4 + n)? as usize != n {
                return None;
            }
            out.push(payload);
            o += 8 + n;
        }
        Some(out)
    };
    // Candidate streams of (ints, reals): header ints then reals of one precision.
    let decode = |payload: &[u8], header_ints: usize, real: usize| -> Option<Vec<f64>> {
        let mut v = Vec::new();
        let (h, r) = payload.split_at((4 * header_ints).min(payload.len()));
        for c in h.chunks_exact(4) {
            v.push(i32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64);
        }
        if r.len() % real != 0 {
            return None;
        }
        for c in r.chunks_exact(real) {
            v.push(if real == 4 {
                f32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64
            } else {
                f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]])
            });
        }
        Some(v)
    };
    let streams: Vec<Vec<u8>> = match records() {
        Some(r) if !r.is_empty() => vec![r.concat()],
        _ => vec![],
    };
    for data in streams
        .iter()
        .map(|v| v.as_slice())
        .chain(std::iter::once(b))
    {
        for real in [8usize, 4] {
            for multi in [true, false] {
                for d in [3usize, 2] {
                    let nb = if multi {
                        match i32_at_slice(data, 0) {
                            Some(n) if (1..100_000).contains(&n) => n as usize,
                            _ => continue,
                        }
                    } else {
                        1
                    };
                    let header = usize::from(multi) + nb * d;
                    let Some(v) = decode(data, header, real) else {
                        continue;
                    };
                    if let Some(bl) = from_numbers(&v, &[(multi, d)])
                        && bl
                            .iter()
                            .all(|x| x.xyz.iter().all(|c| c.is_finite() && c.abs() < 1e30))
                    {
                        return surfaces(bl, file);
                    }
                }
            }
        }
    }
    Err(fail(
        "binary data does not match any Plot3D surface-grid layout (tried f64/f32, single/multi-block, with/without record markers)",
    ))
}

fn i32_at_slice(b: &[u8], o: usize) -> Option<i32> {
    b.get(o..o + 4)
        .map(|s| i32::from_le_bytes([s[0], s[1], s[2], s[3]]))
}

/// Read a Plot3D file (`.xyz`, `.p3d`, `.x`).
pub fn read(path: &std::path::Path) -> Result<Model, Plot3dError> {
    let name = path.display().to_string();
    let b = std::fs::read(path).map_err(|e| Plot3dError {
        file: name.clone(),
        reason: e.to_string(),
    })?;
    from_bytes(&b, &name)
}
