//! A face's closed parameter-plane polygons ([`face_polygons`]): winding loops closed into
//! bands and pole caps ([`super::domain`]), on the face's side of its loops
//! ([`super::outline`]), holes placed between the cuts, and checked not to cross
//! ([`super::simple`]).

use super::domain::{self, BoundaryPoint, FaceSurface, Ring};
use super::face::{FaceError, resolution};
use super::outline::{self, Sense};
use super::simple;

/// The closed parameter-plane polygons of a face (even-odd: the face is inside an odd number
/// of them): winding loops closed into bands or pole caps on the face's side of them (the
/// left about its normal, [`super::outline`]), the other loops shifted by periods into the
/// range of the first, and when every loop is a hole ([`outline::holes_only`]) the domain's
/// frame around them ([`outline::frame`]). Arguments as [`super::face::mesh_face`]; cut, pole and frame
/// points get vertices from `add`.
pub fn face_polygons(
    fs: &FaceSurface,
    rings: Vec<Ring>,
    vertex_loop: Option<usize>,
    sense: Sense,
    h: f64,
    max_turn: f64,
    add: &mut dyn FnMut([f64; 3]) -> usize,
) -> Result<Vec<Vec<BoundaryPoint>>, FaceError> {
    // The cuts start where the winding loops start; where they cross a loop (one folding
    // back, a hole across the seam) the loops are tried from other points. The vertices of an
    // attempt are provisional until it succeeds.
    // Loops winding around both periodic directions (a torus band between Villarceau circles)
    // would be closed into bands one direction at a time, which outlines another region.
    if rings.iter().any(|r| r.winding[0] != 0 && r.winding[1] != 0) {
        return Err(FaceError::BothDirections);
    }
    const TRIES: usize = 8;
    const PROVISIONAL: usize = usize::MAX / 2;
    let mut last = FaceError::Empty;
    for k in 0..TRIES {
        let tried: Vec<Ring> = rings
            .iter()
            .map(|r| match r.winding {
                [0, 0] => r.clone(),
                _ => r.starting_at(k * r.points.len() / TRIES, fs.period),
            })
            .collect();
        let mut made: Vec<[f64; 3]> = Vec::new();
        let mut record = |p: [f64; 3]| {
            made.push(p);
            PROVISIONAL + made.len() - 1
        };
        let once = polygons_once(fs, tried, vertex_loop, sense, h, max_turn, &mut record);
        match once {
            Ok(mut polys) => {
                let real: Vec<usize> = made.into_iter().map(&mut *add).collect();
                for b in polys.iter_mut().flatten() {
                    if b.vertex >= PROVISIONAL {
                        b.vertex = real[b.vertex - PROVISIONAL];
                    }
                }
                return Ok(polys);
            }
            Err(e @ FaceError::Crossing(_)) if rings.iter().any(|r| r.winding != [0, 0]) => {
                last = e
            }
            Err(e) => return Err(e),
        }
    }
    Err(last)
}

/// [`face_polygons`] with the winding loops' cuts where they start.
fn polygons_once(
    fs: &FaceSurface,
    mut rings: Vec<Ring>,
    vertex_loop: Option<usize>,
    sense: Sense,
    h: f64,
    max_turn: f64,
    add: &mut dyn FnMut([f64; 3]) -> usize,
) -> Result<Vec<Vec<BoundaryPoint>>, FaceError> {
    // Loops winding around a periodic direction, closed into polygons.
    let mut polys: Vec<Vec<BoundaryPoint>> = Vec::new();
    for d in 0..2 {
        let winding: Vec<usize> = (0..rings.len())
            .filter(|&i| rings[i].winding[d] != 0)
            .collect();
        if winding.is_empty() {
            continue;
        }
        let name = if d == 0 { 'u' } else { 'v' };
        let box_of = |r: &Ring| {
            let mut lo = [f64::INFINITY; 2];
            let mut hi = [f64::NEG_INFINITY; 2];
            for p in &r.points {
                for k in 0..2 {
                    lo[k] = lo[k].min(p.uv[k]);
                    hi[k] = hi[k].max(p.uv[k]);
                }
            }
            (lo, hi)
        };
        let (lo, hi) = box_of(&rings[winding[0]]);
        let cuts = |span: f64, lo: [f64; 2], hi: [f64; 2]| {
            let n = resolution(fs, lo, hi, 1 - d, h, max_turn) as f64;
            ((span.abs() / (hi[1 - d] - lo[1 - d]).max(1e-300) * n).ceil() as usize).clamp(1, 400)
        };
        match winding.len() {
            2 => {
                let (a, b) = (&rings[winding[0]], &rings[winding[1]]);
                if a.winding[d].abs() != 1 || a.winding[d] != -b.winding[d] {
                    return Err(FaceError::Winding(2, name));
                }
                // The loops bound two strips when the other direction is periodic too (a
                // torus): the face's is on its side of `a` (positive area about the normal).
                let trial = domain::join_band(fs, d, a, b, 0, add);
                let other;
                let b = if sense.area(&trial) >= 0.0 {
                    b
                } else {
                    let Some(pv) = fs.period[1 - d] else {
                        return Err(FaceError::BandSide(name));
                    };
                    let s = if b.points[0].uv[1 - d] > a.points[0].uv[1 - d] {
                        -pv
                    } else {
                        pv
                    };
                    other = Ring {
                        points: b.points.iter().map(|p| p.shifted(1 - d, s)).collect(),
                        winding: b.winding,
                    };
                    &other
                };
                let span = a.points[0].uv[1 - d] - b.points[0].uv[1 - d];
                let (blo, bhi) = box_of(b);
                let l = [lo[0].min(blo[0]), lo[1].min(blo[1])];
                let u = [hi[0].max(bhi[0]), hi[1].max(bhi[1])];
                let n = cuts(span, l, u);
                polys.push(domain::join_band(fs, d, a, b, n, add));
            }
            1 => {
                let a = &rings[winding[0]];
                if a.winding[d].abs() != 1 {
                    return Err(FaceError::Winding(1, name));
                }
                // The region lies left of the loop (right when the face is reversed).
                let up = (a.winding[d] > 0) == sense.same_sense;
                let side = match (d, up) {
                    (0, true) => 3,
                    (0, false) => 2,
                    (_, true) => 0,
                    (_, false) => 1,
                };
                let Some(pole) = fs.pole(side) else {
                    return Err(FaceError::OpenBorder);
                };
                let pv = vertex_loop.unwrap_or_else(|| add(pole));
                let span = a.points[0].uv[1 - d] - fs.domain[side];
                let mut l = lo;
                let mut u = hi;
                l[1 - d] = l[1 - d].min(fs.domain[side]);
                u[1 - d] = u[1 - d].max(fs.domain[side]);
                let n = cuts(span, l, u);
                polys.push(domain::join_pole(fs, d, a, side, pv, n, add));
            }
            k => return Err(FaceError::Winding(k, name)),
        }
        rings.retain(|r| r.winding[d] == 0);
    }
    // Non-winding loops: the largest first, the others shifted by periods into its range.
    rings.sort_by(|a, b| {
        domain::signed_area(&b.points)
            .abs()
            .total_cmp(&domain::signed_area(&a.points).abs())
    });
    let anchor = polys
        .first()
        .or_else(|| rings.first().map(|r| &r.points))
        .map(|p| {
            let mut lo = [f64::INFINITY; 2];
            for q in p {
                lo[0] = lo[0].min(q.uv[0]);
                lo[1] = lo[1].min(q.uv[1]);
            }
            lo
        });
    let Some(anchor) = anchor else {
        return Err(FaceError::Empty);
    };
    for (i, r) in rings.into_iter().enumerate() {
        let mut pts = r.points;
        if i > 0 || !polys.is_empty() {
            domain::shift_into(fs, &mut pts, anchor);
        }
        polys.push(pts);
    }
    if outline::holes_only(fs, &polys, sense) {
        let (lo, hi) = ([fs.domain[0], fs.domain[2]], [fs.domain[1], fs.domain[3]]);
        let n = [0, 1].map(|d| resolution(fs, lo, hi, d, h, max_turn).clamp(1, 400));
        let frame = outline::frame(fs, &mut polys, sense, n, add)?;
        polys.insert(0, frame);
    }
    let on_pole = |a: &[f64; 2], b: &[f64; 2]| {
        (0..4).any(|side| {
            let (d, at) = (side / 2, fs.domain[side]);
            fs.closure.degenerate[side] && a[d] == at && b[d] == at
        })
    };
    if let Some((e, _)) = simple::first_crossing(&polys, &on_pole) {
        return Err(FaceError::Crossing(format!("{:?}", polys[e.0][e.1].uv)));
    }
    Ok(polys)
}
