//! The four border curves of a clamped NURBS surface, exactly. With end knots of multiplicity
//! `p + 1` only the first (last) basis function is non-zero at the domain's end (The NURBS
//! Book, eq. (2.5) and P2.3), so `S(u_min, v) = Σ_j N_j(v) w_0j P_0j / Σ_j N_j(v) w_0j`: the
//! border is the NURBS curve of the border row of the control net, with the other direction's
//! knots and the row's weights — the same homogeneous points, so no arithmetic is done.

use super::NurbsSurface;
use super::bspline_curve::BSplineCurve;
use super::nurbs::NurbsCurve;

fn clamped(k: &[f64], p: usize) -> bool {
    k.len() >= 2 * (p + 1)
        && k[..=p].iter().all(|x| *x == k[0])
        && k[k.len() - 1 - p..].iter().all(|x| *x == k[k.len() - 1])
}

/// Which border of a parameter rectangle: the parameter held fixed (`0`: `u`, `1`: `v`) and
/// whether at its largest value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Border {
    pub fixed: usize,
    pub at_max: bool,
}

impl Border {
    /// `u_min`, `u_max`, `v_min` or `v_max`.
    pub fn label(&self) -> &'static str {
        match (self.fixed, self.at_max) {
            (0, false) => "u_min",
            (0, true) => "u_max",
            (_, false) => "v_min",
            (_, true) => "v_max",
        }
    }
    /// The parameter point of the border at `t` (the running parameter) on a surface with
    /// domain `(u0, u1, v0, v1)`.
    pub fn at(&self, t: f64, d: (f64, f64, f64, f64)) -> [f64; 2] {
        match (self.fixed, self.at_max) {
            (0, false) => [d.0, t],
            (0, true) => [d.1, t],
            (_, false) => [t, d.2],
            (_, true) => [t, d.3],
        }
    }
}

/// The four borders of `s`, each as the NURBS curve of its border row in the direction of
/// the running parameter (not reversed: the knots are the surface's own), in the order
/// `v_min`, `v_max`, `u_min`, `u_max`. `None` unless both knot vectors are clamped.
pub fn borders(s: &NurbsSurface<f64, 3>) -> Option<[(Border, NurbsCurve<f64, 3>); 4]> {
    let h = &s.hom;
    let (p, q) = (h.ku.degree(), h.kv.degree());
    if !clamped(h.ku.knots(), p) || !clamped(h.kv.knots(), q) {
        return None;
    }
    let (nu, nv) = (h.ku.n_ctrl(), h.kv.n_ctrl());
    let at = |i: usize, j: usize| h.net[i * nv + j].clone();
    let along_u = |j: usize| -> Option<NurbsCurve<f64, 3>> {
        let row = (0..nu).map(|i| at(i, j)).collect();
        Some(NurbsCurve {
            hom: BSplineCurve::new(h.ku.knots().to_vec(), p, row).ok()?,
        })
    };
    let along_v = |i: usize| -> Option<NurbsCurve<f64, 3>> {
        let col = (0..nv).map(|j| at(i, j)).collect();
        Some(NurbsCurve {
            hom: BSplineCurve::new(h.kv.knots().to_vec(), q, col).ok()?,
        })
    };
    let b = |fixed, at_max| Border { fixed, at_max };
    Some([
        (b(1, false), along_u(0)?),
        (b(1, true), along_u(nv - 1)?),
        (b(0, false), along_v(0)?),
        (b(0, true), along_v(nu - 1)?),
    ])
}

/// The borders of `s` as a loop counterclockwise in the parameter plane: `v = v_min` in
/// increasing `u`, `u = u_max` in increasing `v`, `v = v_max` in decreasing `u`, `u = u_min`
/// in decreasing `v` (consecutive curves meet at the corners exactly: they share the corner's
/// control point). `None` unless both knot vectors are clamped.
pub fn sides(s: &NurbsSurface<f64, 3>) -> Option<[NurbsCurve<f64, 3>; 4]> {
    let [(_, v_min), (_, v_max), (_, u_min), (_, u_max)] = borders(s)?;
    Some([v_min, u_max, v_max.reversed(), u_min.reversed()])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::construct::{Frame, torus};

    /// Each side equals the surface along its border (sampled, f64 evaluation of both), and
    /// the loop closes at the corners bit for bit.
    #[test]
    fn sides_are_the_borders() {
        let f = Frame {
            o: [0.1, -0.2, 0.3],
            x: [1.0, 0.0, 0.0],
            y: [0.0, 0.6, 0.8],
            z: [0.0, -0.8, 0.6],
        };
        let s = torus(&f, 2.0, 0.7).unwrap();
        let c = sides(&s).unwrap();
        let (u0, u1, v0, v1) = s.hom.domain();
        for k in 0..=20 {
            let t = k as f64 / 20.0;
            let (u, v) = (u0 + (u1 - u0) * t, v0 + (v1 - v0) * t);
            let (ur, vr) = (u1 - (u1 - u0) * t, v1 - (v1 - v0) * t);
            let pairs = [
                (c[0].eval(&u), s.eval(&u, &v0)),
                (c[1].eval(&v), s.eval(&u1, &v)),
                (c[2].eval(&(u0 + u1 - ur)), s.eval(&ur, &v1)),
                (c[3].eval(&(v0 + v1 - vr)), s.eval(&u0, &vr)),
            ];
            for (a, b) in pairs {
                for i in 0..3 {
                    assert!((a[i] - b[i]).abs() <= 1e-14, "{a:?} {b:?}");
                }
            }
        }
        for i in 0..4 {
            let (_, e) = c[i].hom.domain();
            let (s1, _) = c[(i + 1) % 4].hom.domain();
            assert_eq!(c[i].eval(&e), c[(i + 1) % 4].eval(&s1));
        }
    }

    /// An unclamped knot vector has no border rows.
    #[test]
    fn unclamped_is_refused() {
        let pts = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 1.0],
        ];
        let s = NurbsSurface::new(
            vec![0.0, 0.5, 1.0, 1.5],
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            1,
            2,
            2,
            pts,
            vec![1.0; 4],
        )
        .unwrap();
        assert!(sides(&s).is_none());
    }
}
