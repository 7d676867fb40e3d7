//! A surface's own trim loops (JSON `trim_loops`, IGES 144 faces not sewn into a B-rep)
//! triangulated inside them as a B-rep face is ([`super::face::mesh_face`]): each loop's
//! curves sampled at equal parameter steps (at least [`SAMPLES_PER_CURVE`], as the outline
//! the SSI face restriction uses, more for finer meshes), the loop's winding around a periodic direction taken from its ends, the face on the
//! left of its loops about its normal (holes only: the domain minus them,
//! [`super::outline`]), the polygons checked not to cross.

use super::domain::{BoundaryPoint, FaceSurface, Ring};
use super::face::{FaceError, FaceMesh, triangulate};
use super::outline::Sense;
use crate::geom::Aabb;
use crate::geom::dist;
use crate::model::Surface;

/// The diagonal of the box of `surf`'s control points (0 when not finite).
pub fn surface_size(surf: &Surface) -> f64 {
    let pts = surf.nurbs.points_weights().0;
    let d = Aabb::of_points(&pts).map_or(0.0, |b| dist(&b.min, &b.max));
    if d.is_finite() { d } else { 0.0 }
}

/// Samples per trim curve at least (the curves' start points exactly).
pub const SAMPLES_PER_CURVE: usize = 64;

/// The loops of `surf` as rings of `n` sample points per curve (vertices from `add`).
fn rings(
    fs: &FaceSurface,
    surf: &Surface,
    n: usize,
    add: &mut dyn FnMut([f64; 3]) -> usize,
) -> Vec<Ring> {
    surf.trim_loops
        .iter()
        .filter_map(|l| {
            let last = l.curves.last()?;
            // The samples and the loop's end, unwrapped across seams (a step of more than
            // half a period is a jump across the seam).
            let mut uvs: Vec<[f64; 2]> = l
                .curves
                .iter()
                .flat_map(|c| {
                    let (t0, t1) = c.hom.domain();
                    (0..n).map(move |k| c.eval(&(t0 + (t1 - t0) * k as f64 / n as f64)))
                })
                .collect();
            uvs.push(last.eval(&last.hom.domain().1));
            for d in 0..2 {
                let Some(p) = fs.period[d] else { continue };
                let mut offset = 0.0;
                for k in 1..uvs.len() {
                    let step = uvs[k][d] + offset - uvs[k - 1][d];
                    offset -= (step / p).round() * p;
                    uvs[k][d] += offset;
                }
            }
            let (start, end) = (uvs[0], uvs.pop()?);
            let winding = [0, 1]
                .map(|d| fs.period[d].map_or(0, |p| ((end[d] - start[d]) / p).round() as i64));
            let points = uvs
                .into_iter()
                .map(|uv| BoundaryPoint::straight(uv, add(fs.eval(&uv))))
                .collect();
            Some(Ring { points, winding })
        })
        .collect()
}

/// The closed parameter-plane polygons of `surf`'s own trim loops
/// ([`super::polygons::face_polygons`]), `n` samples per curve, cuts and frame sized for edge
/// length `h` and turn `max_turn`. A loop that does not wind around the surface is taken as
/// declared — an outer loop counter-clockwise about the face's normal, a hole clockwise —
/// whatever its direction: with no outer loop the face is the domain minus the holes (IGES
/// 144 with no outer boundary).
pub fn trim_polygons(
    surf: &Surface,
    size: f64,
    n: usize,
    (h, max_turn): (f64, f64),
    add: &mut dyn FnMut([f64; 3]) -> usize,
) -> Result<Vec<Vec<BoundaryPoint>>, FaceError> {
    let fs = FaceSurface::new(&surf.nurbs, size);
    let sense = Sense {
        same_sense: !surf.reversed,
        declared_outer: surf.trim_loops.iter().any(|l| l.outer),
    };
    let mut rings = rings(&fs, surf, n, add);
    for (r, l) in rings
        .iter_mut()
        .zip(surf.trim_loops.iter().filter(|l| !l.curves.is_empty()))
    {
        if r.winding == [0, 0] && (sense.area(&r.points) > 0.0) != l.outer {
            r.points.reverse();
        }
    }
    super::polygons::face_polygons(&fs, rings, None, sense, h, max_turn, add)
}

/// Triangulate `surf` inside its own trim loops with about `cells` grid cells across (target
/// edge length `size / cells`, a turn of at most `3 pi / (4 cells)` per segment) and `4 cells`
/// samples per trim curve (at least [`SAMPLES_PER_CURVE`]); `size`: the surface's size.
pub fn mesh_trimmed(
    surf: &Surface,
    size: f64,
    cells: usize,
    add: &mut dyn FnMut([f64; 3]) -> usize,
) -> Result<FaceMesh, FaceError> {
    let n = (4 * cells).clamp(SAMPLES_PER_CURVE, 4096);
    let (h, max_turn) = (
        size / cells as f64,
        std::f64::consts::PI / (0.75 * cells as f64),
    );
    let polys = trim_polygons(surf, size, n, (h, max_turn), add)?;
    let fs = FaceSurface::new(&surf.nurbs, size);
    triangulate(&fs, &polys, !surf.reversed, h, max_turn, add)
}
