//! Whole (untrimmed) surfaces of a model without a B-rep, triangulated for mesh formats: each
//! surface a grid whose lines include every knot (creases at knots stay grid lines), each
//! knot span cut into equal cells (about [`FIRST_CELLS`] a direction, at least one a span),
//! two triangles a cell, its vertices on the surface. With a chordal tolerance the cells of
//! each surface are halved until its measured deviation
//! ([`super::chordal::face_deviation`]: seven points per triangle, evidence) is at most the
//! tolerance, while a direction keeps at most [`MAX_CELLS`] cells; when asked, the final
//! grid's proven bound ([`super::bound`]) is reported beside the measure (every triangle lies
//! inside one knot span, so every triangle of a surface meshed into at most
//! [`super::bound::MAX_TRIANGLES`] has one).

use super::bound::{BoundSurface, mesh_bound};
use super::chordal::{Chordal, face_deviation, worst};
use crate::model::{Model, Triangulation};

/// Cells per direction of the first grid (as the OBJ and VTP writers sample surfaces).
pub const FIRST_CELLS: usize = 16;
/// Cells per direction at most.
pub const MAX_CELLS: usize = 1024;

/// Parameters of a grid along one direction: every distinct knot of the domain (so creases at
/// knots of full multiplicity are grid lines), each span cut into `m` equal cells.
fn lines(k: &[f64], lo: f64, hi: f64, m: usize) -> Vec<f64> {
    let mut breaks: Vec<f64> = k.iter().copied().filter(|x| *x > lo && *x < hi).collect();
    breaks.dedup();
    breaks.insert(0, lo);
    breaks.push(hi);
    let mut out = vec![lo];
    for w in breaks.windows(2) {
        out.extend((1..=m).map(|i| w[0] + (w[1] - w[0]) * i as f64 / m as f64));
    }
    out
}

/// One surface's grid (cells per knot span `m`, see [`lines`]): its points appended to `t`,
/// its triangles and the triangles' parameter corners.
fn grid(s: &crate::spline::NurbsSurface<f64, 3>, m: [usize; 2], t: &mut Triangulation) -> Cells {
    let (u0, u1, v0, v1) = s.hom.domain();
    let us = lines(s.hom.ku.knots(), u0, u1, m[0]);
    let vs = lines(s.hom.kv.knots(), v0, v1, m[1]);
    let uv = |i: usize, j: usize| [us[i], vs[j]];
    let base = t.vertices.len();
    for &u in &us {
        for &v in &vs {
            t.vertices.push(s.eval(&u, &v));
        }
    }
    let nv = vs.len();
    let id = |i: usize, j: usize| (base + i * nv + j) as u32;
    let (mut tris, mut corners) = (Vec::new(), Vec::new());
    for i in 0..us.len() - 1 {
        for j in 0..nv - 1 {
            for c in [
                [(i, j), (i + 1, j), (i + 1, j + 1)],
                [(i, j), (i + 1, j + 1), (i, j + 1)],
            ] {
                let x = c.map(|(a, b)| id(a, b));
                let p = x.map(|k| t.vertices[k as usize]);
                // A cell at a pole (a collapsed border) has two corners at one point.
                if p[0] == p[1] || p[1] == p[2] || p[0] == p[2] {
                    continue;
                }
                tris.push(x);
                corners.push(c.map(|(a, b)| uv(a, b)));
            }
        }
    }
    (tris, corners)
}

/// Knot spans of the domain in each direction.
fn spans(s: &crate::spline::NurbsSurface<f64, 3>) -> [usize; 2] {
    let (u0, u1, v0, v1) = s.hom.domain();
    [
        lines(s.hom.ku.knots(), u0, u1, 1).len() - 1,
        lines(s.hom.kv.knots(), v0, v1, 1).len() - 1,
    ]
}

/// Every surface of `model` triangulated (see the module comment); with `tol`, each surface's
/// grid refined until its measured deviation is at most `tol`, and what was reached (with a
/// proven bound when `prove`).
pub fn mesh_surfaces(
    model: &Model,
    tol: Option<f64>,
    prove: bool,
) -> (Triangulation, Option<Chordal>, Vec<String>) {
    let mut notes = Vec::new();
    let mut t = Triangulation {
        name: "surfaces".into(),
        vertices: vec![],
        triangles: vec![],
    };
    // The largest measure, the most halvings any surface needed, the first shortfall.
    let (mut measured, mut halvings, mut unmet) = (0.0_f64, 0, None);
    let (mut proven, mut unbounded) = (0.0_f64, 0);
    for surf in &model.surfaces {
        let s = &surf.nurbs;
        // About FIRST_CELLS cells a direction to start with, at least one per knot span.
        let k = spans(s);
        let mut m = k.map(|x| FIRST_CELLS.div_ceil(x).max(1));
        let mut halved = 0;
        // Trim loops that could not be triangulated once are not tried again on finer grids.
        let mut untrimmed = surf.trim_loops.is_empty();
        loop {
            let mark = t.vertices.len();
            let (tris, corners) = match (!untrimmed).then(|| trimmed(surf, m, k, &mut t)) {
                Some(Ok(x)) => x,
                Some(Err(e)) => {
                    notes.push(format!(
                        "surface {}: its trim loops could not be triangulated ({e}): written untrimmed",
                        surf.name
                    ));
                    untrimmed = true;
                    t.vertices.truncate(mark);
                    grid(s, m, &mut t)
                }
                None => grid(s, m, &mut t),
            };
            let Some(tol) = tol else {
                t.triangles.extend(tris);
                break;
            };
            let v = &t.vertices;
            let d = face_deviation(
                tris.iter().map(|x| x.map(|i| v[i as usize])),
                &corners,
                |q| s.eval(&q[0], &q[1]),
            );
            // The next grid would have twice the cells a direction.
            let most = (0..2).any(|i| 2 * m[i] * k[i] > MAX_CELLS);
            if d <= tol || most || d.is_infinite() {
                if d > tol && unmet.is_none() {
                    unmet = Some(if d.is_infinite() {
                        format!("surface {}: a point is not finite", surf.name)
                    } else {
                        format!(
                            "surface {}: {} × {} cells per knot span (the most) leave {d:.3e}",
                            surf.name, m[0], m[1]
                        )
                    });
                }
                measured = worst(measured, d);
                halvings = halvings.max(halved);
                let (u0, u1, v0, v1) = s.hom.domain();
                let bs = prove.then_some(BoundSurface {
                    s,
                    domain: [u0, u1, v0, v1],
                    periodic: [false; 2],
                });
                if let Some(bs) = bs {
                    let corners3 = tris.iter().map(|x| x.map(|i| v[i as usize]));
                    let (b, n) = mesh_bound(&bs, corners3, &corners, 2.0 * d);
                    proven = proven.max(b);
                    unbounded += n;
                }
                t.triangles.extend(tris);
                break;
            }
            t.vertices.truncate(mark);
            m = m.map(|x| 2 * x);
            halved += 1;
        }
    }
    let chordal = tol.map(|tol| Chordal {
        tol,
        measured,
        rounds: halvings + 1,
        unmet,
        proven: prove.then_some(proven),
        unbounded,
    });
    (t, chordal, notes)
}

/// A surface's triangles and the parameter points of their corners.
type Cells = (Vec<[u32; 3]>, Vec<[[f64; 2]; 3]>);

/// A surface with its own trim loops triangulated inside them ([`super::trimmed`]) at about
/// the grid's cell size (`m` cells a knot span, `k` spans a direction).
fn trimmed(
    surf: &crate::model::Surface,
    m: [usize; 2],
    k: [usize; 2],
    t: &mut Triangulation,
) -> Result<Cells, super::face::FaceError> {
    let size = super::trimmed::surface_size(surf);
    let cells = (m[0] * k[0]).max(m[1] * k[1]);
    let mut add = |p: [f64; 3]| {
        t.vertices.push(p);
        t.vertices.len() - 1
    };
    let r = super::trimmed::mesh_trimmed(surf, size, cells, &mut add);
    r.map(|f| {
        let tris = f.triangles.iter().map(|x| x.map(|i| i as u32)).collect();
        (tris, f.uv)
    })
}
