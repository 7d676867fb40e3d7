//! The two triangulations of a pair (paper §4, step 1): each surface meshed to a flatness,
//! refined where the meshes come close at a small angle (near tangency).

use super::SsiParams;
use super::coverage::Suspects;
use super::pair::{net_diagonal, tree, tri, unit_normal};
use super::report::PairStats;
use super::triangulate::{
    CellKey, Evaluations, SurfaceMesh, TriangulateParams, triangulate_cached,
};
use crate::geom::{Point, cross, dot, norm2, spread_triple};
use crate::spline::NurbsSurface;
use rustc_hash::FxHashSet as HashSet;

/// The unit normal of every triangle of `m` (`None` for a degenerate one).
pub(crate) fn unit_normals(m: &SurfaceMesh) -> Vec<Option<[f64; 3]>> {
    (0..m.triangles.len() as u32)
        .map(|t| unit_normal(&tri(m, t)))
        .collect()
}

/// Whether every control point of `s` lies within 1e-12 of the net's size from one plane
/// (through a well-spread triple of them, [`spread_triple`]). A scheduling test for the mesh
/// only: nothing is claimed from it.
fn planar(s: &NurbsSurface<f64, 3>) -> bool {
    let (pts, _) = s.points_weights();
    let Some([p0, a, b]) = spread_triple(&pts) else {
        return false;
    };
    let e = a.sub(&p0);
    let n = cross(&e, &b.sub(&p0));
    let (r2, c2) = (norm2(&e), norm2(&n));
    // Collinear (or a single point): no plane to speak of.
    if !r2.is_finite() || r2 <= 0.0 || c2.is_nan() || c2 <= 1e-12 * r2 * r2 {
        return false;
    }
    let (len, size) = (c2.sqrt(), r2.sqrt());
    pts.iter()
        .all(|p| (dot(&p.sub(&p0), &n) / len).abs() <= 1e-12 * size)
}

/// Triangulate both surfaces, refining cells where the meshes come close at a small angle
/// (near tangency), up to `rounds` times — none when `transversal` (no tangential point,
/// proven: planes at a small angle get no finer mesh than planes at a large one), and only
/// cells meeting the `suspects` (the parameter boxes where a tangential point may lie,
/// `coverage::apart`) when those are known.
pub(crate) fn meshes(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    prm: &SsiParams,
    transversal: bool,
    suspects: Option<&Suspects>,
    stats: &mut PairStats,
) -> (SurfaceMesh, SurfaceMesh) {
    let diag = net_diagonal(&[sa, sb]).max(f64::MIN_POSITIVE);
    let tp = TriangulateParams {
        flatness: prm.flatness.unwrap_or(diag * 2e-3),
        max_edge: diag / prm.min_cells_per_diagonal.max(1) as f64,
        max_depth: prm.max_depth,
    };
    // Where the normals are proven never parallel, a planar surface is meshed by its
    // flatness alone: its cells are flat whatever their size, and more triangles there only
    // multiply the candidate pairs. (Near a tangency the fine mesh of both surfaces is what
    // lets the tracer resolve a branch point.)
    let own = |s: &NurbsSurface<f64, 3>| TriangulateParams {
        max_edge: if transversal && planar(s) {
            f64::INFINITY
        } else {
            tp.max_edge
        },
        ..tp
    };
    let (ta, tb) = (own(sa), own(sb));
    let (mut fa, mut fb) = (HashSet::<CellKey>::default(), HashSet::<CellKey>::default());
    let cos_t = prm.tangent_angle_deg.to_radians().cos();
    let (mut ca, mut cb) = (Evaluations::default(), Evaluations::default());
    let mut ma = triangulate_cached(sa, &ta, &fa, &mut ca);
    let mut mb = triangulate_cached(sb, &tb, &fb, &mut cb);
    let rounds = if transversal { 0 } else { prm.tangency_rounds };
    for _ in 0..rounds {
        let pairs = tree(&ma).overlapping_pairs(&tree(&mb));
        let (na, nb) = (fa.len(), fb.len());
        let (ua, ub) = (unit_normals(&ma), unit_normals(&mb));
        for (ta, tb) in pairs {
            if let (Some(x), Some(y)) = (ua[ta as usize], ub[tb as usize]) {
                let c = (x[0] * y[0] + x[1] * y[1] + x[2] * y[2]).abs();
                // Only where a tangential point may lie (`coverage::apart`), when known.
                if c > cos_t && suspects.is_none_or(|s| s.meets(&ma.uv_box(ta), &mb.uv_box(tb))) {
                    fa.insert(ma.cells[ma.tri_cell[ta as usize] as usize]);
                    fb.insert(mb.cells[mb.tri_cell[tb as usize] as usize]);
                }
            }
        }
        if fa.len() == na && fb.len() == nb {
            break;
        }
        stats.tangency_refinement_rounds += 1;
        ma = triangulate_cached(sa, &ta, &fa, &mut ca);
        mb = triangulate_cached(sb, &tb, &fb, &mut cb);
    }
    (ma, mb)
}
