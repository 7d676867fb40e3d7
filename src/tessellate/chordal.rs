//! Chordal deviation of a trimmed tessellation, and the refinement that brings it under a
//! tolerance (`vericad convert --chordal TOL`).
//!
//! **Measured** (the figure the refinement steers by; the proven bound beside it is
//! [`super::bound`]'s). Per triangle, the distance from the face's surface to the flat
//! triangle at seven parameter points: the centroid, the three edge midpoints and the points
//! `(2/3, 1/6, 1/6)` (and permutations) of the corners' parameters, each mapped by the surface
//! and measured to the triangle by its exact closest point ([`closest_point`]). Per edge
//! segment, the distance from the edge curve's point halfway (in its parameter) between two
//! samples to their chord. The largest of these is the mesh's measured deviation; between the
//! sample points the surface can lie farther from the mesh (evidence, not a bound).
//!
//! **Refinement.** An inscribed segment or triangle on a curve or surface of bounded curvature
//! deviates from it by the square of its size times half the curvature (the sagitta
//! `κ L² / 8` of a chord of length `L`), so each round scales the target edge length and the
//! largest turn per segment by `0.9 √(tol / measured)` — at least ×0.1, at most ×0.7 — and
//! meshes again, until the measured deviation is at most `tol`, the deviation stops falling
//! (the sampling's resolution limits are reached: 2,000 segments per edge, 400 grid cells
//! per face direction), [`MAX_ROUNDS`] rounds have run, or the mesh passes [`MAX_VERTICES`].
//! It does not start when the edges themselves lie more than half the tolerance off their
//! faces' surfaces ([`super::BrepMesh::floor`]: the mesh follows the edges, so the deviation
//! cannot fall below that).

use super::{BrepMesh, MeshParams, mesh_brep};
use crate::brep::Brep;
use crate::geom::triangle::closest_point;
use crate::geom::{dist, dist_to_segment};
use crate::model::Model;

/// Rounds of refinement at most.
pub const MAX_ROUNDS: usize = 8;
/// Mesh vertices past which no further round is started.
pub const MAX_VERTICES: usize = 5_000_000;

/// Barycentric weights of the points measured per triangle.
const WEIGHTS: [[f64; 3]; 7] = [
    [1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0],
    [0.5, 0.5, 0.0],
    [0.0, 0.5, 0.5],
    [0.5, 0.0, 0.5],
    [2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0],
    [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0],
    [1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0],
];

/// What the refinement reached.
#[derive(Clone, Debug, PartialEq)]
pub struct Chordal {
    /// The tolerance asked for.
    pub tol: f64,
    /// The largest measured deviation of the final mesh (see the module comment).
    pub measured: f64,
    /// Meshes made (1: the first was within `tol`).
    pub rounds: usize,
    /// `None` when `measured ≤ tol`; otherwise why the refinement stopped.
    pub unmet: Option<String>,
    /// The largest proven bound on the final mesh's deviation ([`super::bound`]: every
    /// triangle within it of its face's surface over its parameter triangle, and that surface
    /// within it of the triangle), over the triangles that have one; `None` when not asked for.
    pub proven: Option<f64>,
    /// Triangles with no proven bound (a corner on an uncertain side of a knot line where the
    /// surface is not C², past [`super::bound::MAX_CUTS`] cuts there, out of
    /// an open direction's domain, no enclosure, or on a face meshed into more than
    /// [`super::bound::MAX_TRIANGLES`]); `proven` says nothing of them.
    pub unbounded: usize,
}

/// The larger of `d` and `x`, a NaN counting as infinitely far.
pub fn worst(d: f64, x: f64) -> f64 {
    if x.is_nan() { f64::INFINITY } else { d.max(x) }
}

/// Largest measured distance of an edge's curve from its chords: `samples` the mesh points
/// along it, `halves[k]` the curve's point between samples `k` and `k + 1`.
pub fn edge_deviation(samples: &[[f64; 3]], halves: &[[f64; 3]]) -> f64 {
    samples
        .windows(2)
        .zip(halves)
        .fold(0.0, |d, (w, m)| worst(d, dist_to_segment(m, &w[0], &w[1])))
}

/// Largest measured distance of a face's surface from its triangles: `corners` the triangles'
/// mesh points, `uv` their parameter points, `eval` the surface.
pub fn face_deviation(
    corners: impl Iterator<Item = [[f64; 3]; 3]>,
    uv: &[[[f64; 2]; 3]],
    eval: impl Fn(&[f64; 2]) -> [f64; 3],
) -> f64 {
    corners.zip(uv).fold(0.0, |d, (x, q)| {
        WEIGHTS.iter().fold(d, |d, w| {
            let at = [
                w[0] * q[0][0] + w[1] * q[1][0] + w[2] * q[2][0],
                w[0] * q[0][1] + w[1] * q[1][1] + w[2] * q[2][1],
            ];
            let s = eval(&at);
            let (c, _) = closest_point(&s, &x[0], &x[1], &x[2]);
            worst(d, dist(&s, &c))
        })
    })
}

/// Triangulate `brep` ([`mesh_brep`]) finer until its measured chordal deviation is at most
/// `tol` (see the module comment); the final mesh and what was reached, with a proven bound
/// on the final mesh when `prove` ([`super::bound`]).
pub fn mesh_within(model: &Model, brep: &Brep, tol: f64, prove: bool) -> (BrepMesh, Chordal) {
    let mut params = MeshParams {
        measure: true,
        prove: false,
        ..MeshParams::default()
    };
    let mut last = f64::INFINITY;
    let mut rounds = 0;
    loop {
        let mesh = mesh_brep(model, brep, &params);
        rounds += 1;
        let measured = mesh.deviation.unwrap_or(f64::INFINITY);
        let floor = mesh.floor.unwrap_or(0.0);
        let unmet = if measured <= tol {
            None
        } else if measured.is_infinite() {
            Some("the deviation could not be measured (a surface point is not finite)".into())
        } else if floor > 0.5 * tol {
            Some(format!(
                "edges lie up to {floor:.3e} off their faces' surfaces and the mesh follows the edges: no finer sampling brings the deviation below that"
            ))
        } else if measured > 0.95 * last {
            Some(format!(
                "the deviation stopped falling ({last:e} before the last round): the sampling's limits (2,000 segments per edge, 400 grid cells per face direction) are reached"
            ))
        } else if rounds >= MAX_ROUNDS {
            Some(format!("{MAX_ROUNDS} rounds of refinement made"))
        } else if mesh.triangulation.vertices.len() > MAX_VERTICES {
            Some(format!(
                "the mesh has {} vertices (more than {MAX_VERTICES})",
                mesh.triangulation.vertices.len()
            ))
        } else {
            let f = (0.9 * (tol / measured).sqrt()).clamp(0.1, 0.7);
            params.relative_edge *= f;
            params.max_turn *= f;
            last = measured;
            continue;
        };
        // The proven bound of the final mesh, when asked for (meshed once more with it).
        let (mesh, bound) = if prove {
            let m = mesh_brep(
                model,
                brep,
                &MeshParams {
                    prove: true,
                    ..params
                },
            );
            let b = m.bound;
            (m, b)
        } else {
            (mesh, None)
        };
        let (proven, unbounded) = bound.map_or((None, 0), |(b, n)| (Some(b), n));
        let chordal = Chordal {
            tol,
            measured,
            rounds,
            unmet,
            proven,
            unbounded,
        };
        return (mesh, chordal);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A chord of a unit circle spanning angle `θ` is `1 − cos(θ/2)` from the arc's middle; a
    /// flat triangle inscribed in a unit sphere is `1 − |c|` from the sphere's point above its
    /// centroid `c` (the sphere's radial point there).
    #[test]
    fn measured_distances_of_known_chords_and_triangles() {
        let th: f64 = 0.3;
        let samples = [[1.0, 0.0, 0.0], [th.cos(), th.sin(), 0.0]];
        let halves = [[(th / 2.0).cos(), (th / 2.0).sin(), 0.0]];
        let want = 1.0 - (th / 2.0).cos();
        assert!((edge_deviation(&samples, &halves) - want).abs() <= 1e-15);
        // An octant of the unit sphere as one triangle; the surface in (u, v) by the
        // normalized barycentric point (exactly the radial projection of the flat triangle).
        let x = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let uv = [[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]];
        let eval = |q: &[f64; 2]| {
            let p = [1.0 - q[0] - q[1], q[0], q[1]];
            let n = crate::geom::norm(&p);
            p.map(|c| c / n)
        };
        // Farthest of the seven points: the centroid, 1 − 1/√3 from the plane.
        let d = face_deviation([x].into_iter(), &uv, eval);
        assert!((d - (1.0 - 1.0 / 3f64.sqrt())).abs() <= 1e-15, "{d}");
        // A NaN surface point is infinitely far, not skipped.
        let nan = |_: &[f64; 2]| [f64::NAN, 0.0, 0.0];
        assert_eq!(face_deviation([x].into_iter(), &uv, nan), f64::INFINITY);
    }
}
