//! Closure of a surface's parameter rectangle, decided from the control net: borders that
//! collapse to a point (poles, apexes) and pairs of opposite borders that coincide (closed
//! seams).
//!
//! For a clamped knot vector the border `u = u_min` of a NURBS surface is the NURBS curve of
//! the first row of the net, which lies in the convex hull of the row's Cartesian control
//! points (positive weights). The border counts as a point when every Cartesian control point
//! of the row is within `CLOSE · scale` of the first (`scale`: the largest coordinate
//! magnitude of the net); the borders `u = u_min` and `u = u_max` count as one seam when the
//! rows' Cartesian points agree within the same bound and their weights are proportional
//! within a relative `CLOSE`. The bound is needed because control data written as Cartesian
//! points and weights is stored in homogeneous form with rounding, so a pole that is exact in
//! the file is a curve of extent ~1e-16 in the stored surface. The result is used to weld the
//! *triangulation* (an approximation whose flatness is many orders larger); every certified
//! quantity is computed on the exact stored surface. A seam or pole given with other control
//! data (possible, rare) is not detected and keeps its sides apart.

use super::NurbsSurface;
use crate::geom::Hom;

/// Relative closeness under which a border counts as collapsed or two borders as one.
pub const CLOSE: f64 = 1e-12;

/// Which borders collapse and which opposite borders coincide.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Closure {
    /// Borders `u = u_min`, `u = u_max`, `v = v_min`, `v = v_max` that are single points.
    pub degenerate: [bool; 4],
    /// `S(u_min, v) = S(u_max, v)` for every `v`.
    pub seam_u: bool,
    /// `S(u, v_min) = S(u, v_max)` for every `u`.
    pub seam_v: bool,
}

fn clamped(k: &[f64], p: usize) -> bool {
    k.len() >= 2 * (p + 1)
        && k[..=p].iter().all(|x| *x == k[0])
        && k[k.len() - 1 - p..].iter().all(|x| *x == k[k.len() - 1])
}

fn cart(h: &Hom<f64, 3>) -> [f64; 3] {
    h.wp.map(|x| x / h.w)
}

fn far(a: &[f64; 3], b: &[f64; 3], eps: f64) -> bool {
    (0..3).any(|k| (a[k] - b[k]).abs() > eps)
}

/// Whether all points of the row are one Cartesian point (within `eps`).
fn one_point(row: &[&Hom<f64, 3>], eps: f64) -> bool {
    let p0 = cart(row[0]);
    row[1..].iter().all(|h| !far(&cart(h), &p0, eps))
}

/// Whether two rows are the same curve (points within `eps`, weights proportional within a
/// relative `close`).
fn same_row(a: &[&Hom<f64, 3>], b: &[&Hom<f64, 3>], eps: f64, close: f64) -> bool {
    if a.len() != b.len() || a.is_empty() {
        return false;
    }
    let (wa0, wb0) = (a[0].w, b[0].w);
    a.iter().zip(b).all(|(x, y)| {
        let r = (x.w / wa0) / (y.w / wb0);
        !far(&cart(x), &cart(y), eps) && (r - 1.0).abs() <= close
    })
}

/// Whether the surface is closed in direction `dir` (0 = u, 1 = v) *exactly*: clamped knots
/// at both ends and the first and last rows of homogeneous control points identical, so that
/// `S(d0, ·) = S(d1, ·)` for every parameter and a proof may let the parameter run on across
/// the seam (unlike [`Closure::of`], which allows rounding and is used only for welding).
pub fn exact_seam(s: &NurbsSurface<f64, 3>, dir: usize) -> bool {
    let h = &s.hom;
    let k = if dir == 0 { &h.ku } else { &h.kv };
    if !clamped(k.knots(), k.degree()) {
        return false;
    }
    let (rows, cols) = (h.ku.n_ctrl(), h.kv.n_ctrl());
    let at = |i: usize, j: usize| &h.net[i * cols + j];
    let same = |a: &Hom<f64, 3>, b: &Hom<f64, 3>| a.wp == b.wp && a.w == b.w;
    if dir == 0 {
        (0..cols).all(|j| same(at(0, j), at(rows - 1, j)))
    } else {
        (0..rows).all(|i| same(at(i, 0), at(i, cols - 1)))
    }
}

impl Closure {
    /// The closure with [`CLOSE`] (see the module comment).
    pub fn of(s: &NurbsSurface<f64, 3>) -> Closure {
        Closure::within(s, CLOSE)
    }
    /// The closure with the relative closeness `close` in place of [`CLOSE`]: for searches
    /// that only need to know where a parameter may run on across a border (files whose
    /// closed surfaces meet themselves within a coarser rounding than [`CLOSE`]).
    pub fn within(s: &NurbsSurface<f64, 3>, close: f64) -> Closure {
        let h = &s.hom;
        let (nu, nv) = (h.ku.n_ctrl(), h.kv.n_ctrl());
        if !clamped(h.ku.knots(), h.ku.degree()) || !clamped(h.kv.knots(), h.kv.degree()) {
            return Closure::default();
        }
        let pts: Vec<[f64; 3]> = h.net.iter().map(cart).collect();
        if h.net
            .iter()
            .any(|p| p.w.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater))
            || !pts.iter().flatten().all(|x| x.is_finite())
        {
            return Closure::default();
        }
        let scale = pts.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        let eps = close * scale;
        let at = |i: usize, j: usize| &h.net[i * nv + j];
        let row_u = |i: usize| (0..nv).map(|j| at(i, j)).collect::<Vec<_>>();
        let row_v = |j: usize| (0..nu).map(|i| at(i, j)).collect::<Vec<_>>();
        let (u0, u1, v0, v1) = (row_u(0), row_u(nu - 1), row_v(0), row_v(nv - 1));
        Closure {
            degenerate: [
                one_point(&u0, eps),
                one_point(&u1, eps),
                one_point(&v0, eps),
                one_point(&v1, eps),
            ],
            seam_u: same_row(&u0, &u1, eps, close),
            seam_v: same_row(&v0, &v1, eps, close),
        }
    }
    /// The Cartesian point of a degenerate border, side `0..4` as in `degenerate` (its
    /// first control point).
    pub fn pole(s: &NurbsSurface<f64, 3>, side: usize) -> [f64; 3] {
        let h = &s.hom;
        let (nu, nv) = (h.ku.n_ctrl(), h.kv.n_ctrl());
        let c = match side {
            0 | 2 => &h.net[0],
            1 => &h.net[(nu - 1) * nv],
            _ => &h.net[nv - 1],
        };
        cart(c)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::construct::{Frame, bilinear, cylinder, sphere, torus};

    fn rotated() -> Frame {
        let (c, s) = (0.6f64, 0.8f64);
        Frame {
            o: [0.3, -1.7, 2.9],
            x: [c, s, 0.0],
            y: [-s * 0.28, c * 0.28, 0.96],
            z: [s * 0.96, -c * 0.96, 0.28],
        }
    }

    #[test]
    fn sphere_has_two_poles_and_a_seam_in_any_frame() {
        for f in [Frame::WORLD, rotated()] {
            let c = Closure::of(&sphere(&f, 2.0).unwrap());
            // revolve: u around the axis (closed), v along the profile (poles at both ends).
            assert!(c.seam_u ^ c.seam_v, "{c:?}");
            assert_eq!(c.degenerate.iter().filter(|d| **d).count(), 2, "{c:?}");
        }
    }

    #[test]
    fn torus_closed_both_ways_cylinder_one_way_plane_none() {
        let c = Closure::of(&torus(&rotated(), 3.0, 1.0).unwrap());
        assert!(c.seam_u && c.seam_v && c.degenerate == [false; 4], "{c:?}");
        let c = Closure::of(&cylinder(&rotated(), 1.0, 0.0, 2.0).unwrap());
        assert!((c.seam_u ^ c.seam_v) && c.degenerate == [false; 4], "{c:?}");
        let c = Closure::of(
            &bilinear([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]).unwrap(),
        );
        assert_eq!(c, Closure::default());
        // A triangle as a bilinear patch with one collapsed border.
        let c =
            Closure::of(&bilinear([0.0; 3], [1.0, 0.0, 0.0], [0.0; 3], [1.0, 1.0, 0.0]).unwrap());
        assert_eq!(c.degenerate, [true, false, false, false], "{c:?}");
    }
}
