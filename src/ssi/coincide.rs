//! Coincident surfaces: pairs whose intersection is not a set of curves but a region. Two
//! cases are decided exactly, before any triangulation:
//!
//! * **identical** — the same knots, degrees, homogeneous control points and weights, bit for
//!   bit: the surfaces are one surface, and their intersection is all of it.
//! * **coplanar** — every Cartesian control point of both surfaces (`X/w`, exactly, in
//!   rationals) lies in one plane (exact `orient3d` against three non-collinear control
//!   points). A NURBS surface with positive weights lies in the convex hull of its control
//!   points, so both surfaces lie in that plane, and wherever their images overlap they
//!   coincide: the intersection is a planar region (possibly empty), not curves.
//!
//! Other coincidences (a surface and a reparametrization or a piece of it, overlapping
//! curved surfaces) are not proven here; the curve pipeline then runs, its certificates
//! refuse where the normals are parallel, and [`super::overlap`] measures the overlap.

use crate::predicates::orient::orient3d;
use crate::scalar::{Rational, Scalar, Sign, lift};
use crate::spline::NurbsSurface;
use serde::Serialize;

type Q = Rational;

/// How two faces coincide.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CoincidenceKind {
    Identical,
    Coplanar,
    /// Overlapping curved surfaces, measured ([`super::overlap`]): evidence, not proven.
    Overlap,
}

/// Where two surfaces were measured to overlap ([`super::overlap`]).
#[derive(Clone, Debug, Serialize)]
pub struct OverlapOut {
    /// Boxes `[u0, u1, v0, v1]` of the overlap samples in each parameter plane.
    pub uv_a: [f64; 4],
    pub uv_b: [f64; 4],
    /// Grid points found on the other surface with parallel normals, in 2×2 blocks.
    pub samples: usize,
    /// Their largest distance to the other surface (local search: evidence).
    pub max_distance: f64,
    /// Branches and touch points of the curve pipeline inside the overlap, removed.
    pub branches_removed: usize,
    pub touch_points_removed: usize,
}

/// A coincidence, reported instead of intersection curves: proven (identical, coplanar) or
/// measured (overlap).
#[derive(Clone, Debug, Serialize)]
pub struct CoincidenceOut {
    pub kind: CoincidenceKind,
    /// A point of the common plane and a normal (coplanar; for identical surfaces: none).
    pub plane_point: Option<[f64; 3]>,
    pub plane_normal: Option<[f64; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub overlap: Option<OverlapOut>,
}

fn cartesian_exact(s: &NurbsSurface<f64, 3>) -> Option<Vec<[Q; 3]>> {
    s.hom
        .net
        .iter()
        .map(|h| {
            let w = lift::<Q>(h.w);
            if h.w.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater)
                || !h.wp.iter().all(|x| x.is_finite())
            {
                return None;
            }
            Some(h.wp.map(|x| lift::<Q>(x) / &w))
        })
        .collect()
}

/// A fast exact refusal of the coplanar case: four control points of weight 1 (their
/// Cartesian points are the `f64` values themselves, exactly) with a nonzero orientation
/// (adaptive exact predicate) show the two nets are not coplanar. `false` says nothing (the
/// exact test decides).
fn proven_not_coplanar(sa: &NurbsSurface<f64, 3>, sb: &NurbsSurface<f64, 3>) -> bool {
    let pts: Vec<[f64; 3]> = sa
        .hom
        .net
        .iter()
        .chain(&sb.hom.net)
        .filter(|h| h.w == 1.0 && h.wp.iter().all(|x| x.is_finite()))
        .map(|h| h.wp)
        .collect();
    // A well-spread triple (any triple is sound: a collinear one only makes every test zero).
    let Some([p0, p1, p2]) = crate::geom::spread_triple(&pts) else {
        return false;
    };
    pts.iter()
        .any(|p| orient3d::<f64>(&p0, &p1, &p2, p) != Sign::Zero)
}

fn sub(a: &[Q; 3], b: &[Q; 3]) -> [Q; 3] {
    std::array::from_fn(|k| &a[k] - &b[k])
}

fn cross(a: &[Q; 3], b: &[Q; 3]) -> [Q; 3] {
    [
        &a[1] * &b[2] - &a[2] * &b[1],
        &a[2] * &b[0] - &a[0] * &b[2],
        &a[0] * &b[1] - &a[1] * &b[0],
    ]
}

/// Whether the two surfaces are proven to coincide (see the module comment).
pub fn coincidence(sa: &NurbsSurface<f64, 3>, sb: &NurbsSurface<f64, 3>) -> Option<CoincidenceOut> {
    let same = {
        let (a, b) = (&sa.hom, &sb.hom);
        a.ku.degree() == b.ku.degree()
            && a.kv.degree() == b.kv.degree()
            && a.ku.knots() == b.ku.knots()
            && a.kv.knots() == b.kv.knots()
            && a.net.len() == b.net.len()
            && a.net
                .iter()
                .zip(&b.net)
                .all(|(x, y)| x.wp == y.wp && x.w == y.w)
    };
    if same {
        return Some(CoincidenceOut {
            kind: CoincidenceKind::Identical,
            plane_point: None,
            plane_normal: None,
            overlap: None,
        });
    }
    if proven_not_coplanar(sa, sb) {
        return None;
    }
    let pa = cartesian_exact(sa)?;
    let pb = cartesian_exact(sb)?;
    let p0 = pa[0].clone();
    let p1 = pa.iter().find(|p| **p != p0)?.clone();
    let zero = Q::ZERO;
    let p2 = pa
        .iter()
        .find(|p| {
            cross(&sub(&p1, &p0), &sub(p, &p0))
                .iter()
                .any(|c| *c != zero)
        })?
        .clone();
    let flat = pa
        .iter()
        .chain(&pb)
        .all(|p| orient3d::<Q>(&p0, &p1, &p2, p) == Sign::Zero);
    if !flat {
        return None;
    }
    let n = cross(&sub(&p1, &p0), &sub(&p2, &p0));
    let nf: [f64; 3] = std::array::from_fn(|k| Scalar::to_f64(&n[k]));
    let l = (nf[0] * nf[0] + nf[1] * nf[1] + nf[2] * nf[2]).sqrt();
    Some(CoincidenceOut {
        kind: CoincidenceKind::Coplanar,
        plane_point: Some(std::array::from_fn(|k| Scalar::to_f64(&p0[k]))),
        plane_normal: (l > 0.0 && l.is_finite()).then(|| nf.map(|c| c / l)),
        overlap: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::construct::{Frame, bilinear, sphere};

    #[test]
    fn identical_and_coplanar_are_proven_others_not() {
        let f = Frame {
            o: [0.3, -1.0, 2.0],
            x: [0.6, 0.8, 0.0],
            y: [-0.8, 0.6, 0.0],
            z: [0.0, 0.0, 1.0],
        };
        let s = sphere(&f, 2.0).unwrap();
        assert_eq!(
            coincidence(&s, &s).unwrap().kind,
            CoincidenceKind::Identical
        );
        // Two squares in the plane z = x + 2y (exact in binary), overlapping.
        let z = |x: f64, y: f64| [x, y, x + 2.0 * y];
        let a = bilinear(z(0.0, 0.0), z(1.0, 0.0), z(0.0, 1.0), z(1.0, 1.0)).unwrap();
        let b = bilinear(z(0.5, 0.5), z(1.5, 0.5), z(0.5, 1.5), z(1.5, 1.5)).unwrap();
        let c = coincidence(&a, &b).unwrap();
        assert_eq!(c.kind, CoincidenceKind::Coplanar);
        // Lifted by one ulp at one corner: not coplanar.
        let mut q = z(1.5, 1.5);
        q[2] = q[2].next_up();
        let b2 = bilinear(z(0.5, 0.5), z(1.5, 0.5), z(0.5, 1.5), q).unwrap();
        assert!(coincidence(&a, &b2).is_none());
        // The sphere against a plane through its centre: no coincidence.
        assert!(coincidence(&s, &a).is_none());
        let s2 = sphere(&f, 2.0 + 1e-15).unwrap();
        assert!(coincidence(&s, &s2).is_none());
        // The fast refusal says nothing on the coplanar pair, and refuses the lifted one.
        assert!(!proven_not_coplanar(&a, &b));
        assert!(proven_not_coplanar(&a, &b2));
    }

    /// The fast refusal never contradicts the exact test: on small-integer nets, coplanar by
    /// construction (z = αx + βy + γ) or with one point moved by 0 … 2 units, whenever it
    /// refuses, the exact decision is "not coplanar" too; and it refuses every moved net.
    #[test]
    fn fast_refusal_agrees_with_the_exact_test() {
        let mut seed = 12345u64;
        let mut next = |m: u64| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 33) % m) as f64
        };
        for case in 0..300 {
            let (al, be, ga) = (next(7) - 3.0, next(7) - 3.0, next(9) - 4.0);
            let mut corners: Vec<[f64; 3]> = (0..8)
                .map(|_| {
                    let (x, y) = (next(11) - 5.0, next(11) - 5.0);
                    [x, y, al * x + be * y + ga]
                })
                .collect();
            let moved = next(3);
            corners[(case % 8) as usize][2] += moved;
            let c = &corners;
            let (a, b) = (
                bilinear(c[0], c[1], c[2], c[3]).unwrap(),
                bilinear(c[4], c[5], c[6], c[7]).unwrap(),
            );
            let exact_flat = coincidence(&a, &b).is_some();
            if proven_not_coplanar(&a, &b) {
                assert!(!exact_flat, "case {case}: refused a coplanar pair");
            }
            if moved > 0.0 && !exact_flat {
                assert!(proven_not_coplanar(&a, &b), "case {case}: not refused");
            }
        }
    }
}
