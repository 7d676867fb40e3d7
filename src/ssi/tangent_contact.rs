//! Surfaces touching along a curve (measured, not proven): two cylinders lying side by side or
//! one inside the other, a ball in a cylinder. Along such a contact the surfaces are tangent
//! at every point, so no point can be certified (Krawczyk's test needs a transversal crossing),
//! the singular-point search finds a row of tangential points none of which is isolated, and
//! the mesh pipeline returns whatever its triangles happened to cross: an external contact
//! gave 2 branches and 63 tangential points, an internal one 0 branches and 62 points — the
//! same situation, told two ways. This step tells it one way.
//!
//! Test, run only for pairs whose coverage is refused with parallel normals, by its budget or
//! at a trim loop (as
//! [`super::overlap`]) and that are not coincident: a *contact point* is a point of an
//! uncertified touch point (no proven kind) or of a branch none of whose points carries a curve
//! certificate, at which the normals of both surfaces (at the point's own parameters) make an
//! angle whose sine is at most [`MAX_SIN`]. When there are at least [`MIN_POINTS`] contact
//! points spread over more than `100 · tol` (not one touching point found many times), the
//! pair gets a `tangent_contact`: the contact points chained into a polyline (nearest
//! neighbour from an extreme point), their boxes in both parameter planes, the largest sine
//! and distance measured; the touch points and the branches made only of contact points are
//! moved into it and counted. Nothing is certified by this: the coverage stays refused, the
//! run is not certified, and no point is dropped (each moved point is in the polyline).

use super::overlap::{grow, sine_and_gap};
use super::report::{PairOut, SingularKind};
use crate::spline::NurbsSurface;
use serde::Serialize;

/// Largest sine of the angle between the normals at a contact point.
pub const MAX_SIN: f64 = 1e-3;
/// Fewest contact points for a contact curve.
pub const MIN_POINTS: usize = 3;
/// Most points kept in the polyline (the rest counted).
const MAX_LISTED: usize = 5000;

/// A tangential contact along a curve (see the module comment): evidence, not proven.
#[derive(Clone, Debug, Default, Serialize)]
pub struct TangentContactOut {
    /// The contact points, chained from an extreme one by nearest neighbours.
    pub points: Vec<[f64; 3]>,
    /// Each listed point's parameters on A and on B (not in the JSON: the boxes below are).
    #[serde(skip)]
    pub params: Vec<([f64; 2], [f64; 2])>,
    /// Contact points beyond the listed ones, with their parameters on A and on B, so that a
    /// face restriction can classify every contact point, listed or not (in the JSON: their
    /// number, `points_not_listed`).
    #[serde(rename = "points_not_listed", serialize_with = "count")]
    pub unlisted: Vec<([f64; 3], [f64; 2], [f64; 2])>,
    /// Boxes `[u0, u1, v0, v1]` of the contact points' parameters on each surface.
    pub uv_a: [f64; 4],
    pub uv_b: [f64; 4],
    /// Largest sine of the normals' angle and largest distance between the surfaces' points
    /// at the contact points (f64 evaluation: measured).
    pub max_sin_angle: f64,
    pub max_gap: f64,
    /// Touch points and branches moved into the contact.
    pub touch_points_moved: usize,
    pub branches_moved: usize,
}

impl TangentContactOut {
    /// Contact points beyond the listed ones.
    pub fn points_not_listed(&self) -> usize {
        self.unlisted.len()
    }
}

/// A list written as its length.
fn count<T, S: serde::Serializer>(v: &[T], s: S) -> Result<S::Ok, S::Error> {
    s.serialize_u64(v.len() as u64)
}

/// Nearest-neighbour chain through `pts` (their indices in chain order), from the point
/// smallest along the direction in which they spread most.
fn chain(pts: &[[f64; 3]]) -> Vec<usize> {
    let ext = |k: usize| {
        let (lo, hi) = pts
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
                (l.min(p[k]), h.max(p[k]))
            });
        hi - lo
    };
    let axis = (0..3)
        .max_by(|&a, &b| ext(a).total_cmp(&ext(b)))
        .unwrap_or(0);
    let mut left: Vec<usize> = (0..pts.len()).collect();
    let Some(start) =
        (0..left.len()).min_by(|&a, &b| pts[left[a]][axis].total_cmp(&pts[left[b]][axis]))
    else {
        return Vec::new();
    };
    let mut out = vec![left.swap_remove(start)];
    while !left.is_empty() {
        let last = pts[out[out.len() - 1]];
        let d = |i: usize| crate::geom::dist(&pts[left[i]], &last);
        let k = (0..left.len())
            .min_by(|&a, &b| d(a).total_cmp(&d(b)))
            .unwrap_or(0);
        out.push(left.swap_remove(k));
    }
    out
}

/// Diagnose a tangential contact along a curve (see the module comment) and, when found, move
/// the touch points and branches that make it into `p.tangent_contact`.
pub fn diagnose(p: &mut PairOut, sa: &NurbsSurface<f64, 3>, sb: &NurbsSurface<f64, 3>, tol: f64) {
    if p.coincident.is_some() {
        return;
    }
    let contact = |ua: &[f64; 2], ub: &[f64; 2]| {
        sine_and_gap(sa, sb, ua, ub).filter(|(sin, gap)| *sin <= MAX_SIN && *gap <= tol)
    };
    let touch: Vec<Option<(f64, f64)>> = p
        .touch_points
        .iter()
        .map(|t| {
            let proven = t
                .singular
                .as_ref()
                .is_some_and(|s| s.kind != SingularKind::Uncertified);
            match (proven, t.uv_a, t.uv_b) {
                (false, Some(a), Some(b)) => contact(&a, &b),
                _ => None,
            }
        })
        .collect();
    let branch: Vec<Option<Vec<(f64, f64)>>> = p
        .branches
        .iter()
        .map(|b| {
            if b.curve_radius.iter().any(|r| r.is_some()) || b.points.is_empty() {
                return None;
            }
            b.uv_a
                .iter()
                .zip(&b.uv_b)
                .map(|(a, c)| contact(a, c))
                .collect()
        })
        .collect();
    let mut pts: Vec<[f64; 3]> = Vec::new();
    let mut uvs: Vec<([f64; 2], [f64; 2])> = Vec::new();
    let mut bx_a = [
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    let mut bx_b = bx_a;
    let (mut max_sin, mut max_gap) = (0.0f64, 0.0f64);
    let mut add = |x: [f64; 3], a: &[f64; 2], b: &[f64; 2], m: (f64, f64)| {
        pts.push(x);
        uvs.push((*a, *b));
        grow(&mut bx_a, a);
        grow(&mut bx_b, b);
        max_sin = max_sin.max(m.0);
        max_gap = max_gap.max(m.1);
    };
    for (t, m) in p.touch_points.iter().zip(&touch) {
        if let (Some(m), Some(a), Some(b)) = (m, &t.uv_a, &t.uv_b) {
            add(t.point, a, b, *m);
        }
    }
    for (br, ms) in p.branches.iter().zip(&branch) {
        for (k, m) in ms.iter().flatten().enumerate() {
            add(br.points[k], &br.uv_a[k], &br.uv_b[k], *m);
        }
    }
    let spread = {
        let lo = |k: usize| pts.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
        let hi = |k: usize| pts.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max);
        (0..3).map(|k| hi(k) - lo(k)).fold(0.0f64, f64::max)
    };
    if pts.len() < MIN_POINTS || spread.is_nan() || spread <= 100.0 * tol {
        return;
    }
    let total = pts.len();
    let listed = total.min(MAX_LISTED);
    let chained = chain(&pts[..listed]);
    let mut keep_t = touch.iter().map(|m| m.is_none());
    p.touch_points.retain(|_| keep_t.next().unwrap_or(true));
    let mut keep_b = branch.iter().map(|m| m.is_none());
    p.branches.retain(|_| keep_b.next().unwrap_or(true));
    p.tangent_contact = Some(TangentContactOut {
        unlisted: (listed..total)
            .map(|k| (pts[k], uvs[k].0, uvs[k].1))
            .collect(),
        points: chained.iter().map(|&k| pts[k]).collect(),
        params: chained.iter().map(|&k| uvs[k]).collect(),
        uv_a: bx_a,
        uv_b: bx_b,
        max_sin_angle: max_sin,
        max_gap,
        touch_points_moved: touch.iter().filter(|m| m.is_some()).count(),
        branches_moved: branch.iter().filter(|m| m.is_some()).count(),
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The chain starts at the extreme point along the widest direction and walks to the
    /// nearest point each time.
    #[test]
    fn chain_orders_points_along_a_line() {
        let pts = [
            [0.0, 0.0, 0.5],
            [0.0, 0.0, -0.25],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, 0.0],
        ];
        assert_eq!(chain(&pts), vec![1, 3, 0, 2]);
    }
}
