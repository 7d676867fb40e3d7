//! Step 9b, the curve certificate: the system `F(u, v, s, t) = (S_A(u, v) − S_B(s, t), g)`
//! that Krawczyk's test is run on (see the parent module's comment for the theorem), with `F`
//! and its Jacobian in `f64` for Newton, the enclosure of `F` at a point, the interval
//! Jacobian over a box (mean-value form), and the Krawczyk operator `K(X)`.

use super::M4;
use crate::geom::dot;
use crate::scalar::Interval;
use crate::spline::NurbsSurface;
use crate::ssi::enclose::{Jet, enclose_jet, enclose_point};
use crate::ssi::jet_cache::JetCache;
use crate::ssi::refine::point_d1;

/// A surface point and its first partial derivatives, in `f64`.
pub(super) type Eval = ([f64; 3], [f64; 3], [f64; 3]);

#[derive(Clone, Copy, Debug)]
pub(super) enum Fourth {
    /// `n · (S_A(u, v) − p) = 0`.
    Plane { n: [f64; 3], p: [f64; 3] },
    /// `z_k − c = 0`.
    Hold { k: usize, c: f64 },
}

pub(super) struct System<'a> {
    pub(super) sa: &'a NurbsSurface<f64, 3>,
    pub(super) sb: &'a NurbsSurface<f64, 3>,
    /// Enclosures over a box shared with nearby points, used for every box it holds.
    pub(super) cache: Option<&'a JetCache>,
    pub(super) e: Fourth,
    /// The point certified.
    pub(super) p: [f64; 3],
    /// Domain bounds of `(u, v, s, t)`.
    pub(super) lo: [f64; 4],
    pub(super) hi: [f64; 4],
}

pub(super) fn pt(x: f64) -> Interval {
    Interval::point(x)
}

impl System<'_> {
    /// `F` and its Jacobian in `f64` (approximations: they only steer).
    pub(super) fn eval_f64(&self, z: &[f64; 4]) -> ([f64; 4], M4) {
        self.assemble(
            z,
            point_d1(self.sa, z[0], z[1]),
            point_d1(self.sb, z[2], z[3]),
        )
    }

    /// `F` and its Jacobian from the surfaces' points and first derivatives at `z`.
    pub(super) fn assemble(&self, z: &[f64; 4], ea: Eval, eb: Eval) -> ([f64; 4], M4) {
        let ((a, au, av), (b, bs, bt)) = (ea, eb);
        let mut f = [0.0; 4];
        let mut j = [[0.0; 4]; 4];
        for k in 0..3 {
            f[k] = a[k] - b[k];
            j[k] = [au[k], av[k], -bs[k], -bt[k]];
        }
        match self.e {
            Fourth::Plane { n, p } => {
                f[3] = dot(&n, &[a[0] - p[0], a[1] - p[1], a[2] - p[2]]);
                j[3] = [dot(&n, &au), dot(&n, &av), 0.0, 0.0];
            }
            Fourth::Hold { k, c } => {
                f[3] = z[k] - c;
                j[3] = [0.0; 4];
                j[3][k] = 1.0;
            }
        }
        (f, j)
    }

    /// Enclosure of `F(y)` at the point `y`, with those of `S_A(y_uv)` and `S_B(y_st)`.
    pub(super) fn f_at(&self, y: &[f64; 4]) -> Option<([Interval; 4], [[Interval; 3]; 2])> {
        let a = enclose_point(self.sa, pt(y[0]), pt(y[1]))?;
        let b = enclose_point(self.sb, pt(y[2]), pt(y[3]))?;
        let g = match self.e {
            Fourth::Plane { n, p } => {
                (0..3).fold(pt(0.0), |acc, k| acc + pt(n[k]) * (a[k] - pt(p[k])))
            }
            Fourth::Hold { k, c } => pt(y[k]) - pt(c),
        };
        Some(([a[0] - b[0], a[1] - b[1], a[2] - b[2], g], [a, b]))
    }

    /// Interval Jacobian over the box `x` (mean-value form, see the module comment).
    fn jacobian(&self, x: &[Interval; 4]) -> Option<([[Interval; 4]; 4], [Jet; 2])> {
        let (ja, jb) = match self.cache {
            Some(c) if c.covers(x) => (c.jets[0], c.jets[1]),
            _ => (
                enclose_jet(self.sa, x[0], x[1])?,
                enclose_jet(self.sb, x[2], x[3])?,
            ),
        };
        let mut j = [[pt(0.0); 4]; 4];
        for k in 0..3 {
            j[k] = [ja.su[k], ja.sv[k], -jb.su[k], -jb.sv[k]];
        }
        match self.e {
            Fourth::Plane { n, .. } => {
                let d = |v: &[Interval; 3]| (0..3).fold(pt(0.0), |acc, k| acc + pt(n[k]) * v[k]);
                j[3] = [d(&ja.su), d(&ja.sv), pt(0.0), pt(0.0)];
            }
            Fourth::Hold { k, .. } => j[3][k] = pt(1.0),
        }
        Some((j, [ja, jb]))
    }

    /// `K(X)` for centre `y`, preconditioner `yinv`, enclosure `fy` of `F(y)`; with the
    /// surfaces' derivative enclosures over `X`.
    pub(super) fn krawczyk(
        &self,
        y: &[f64; 4],
        x: &[Interval; 4],
        yinv: &M4,
        fy: &[Interval; 4],
    ) -> Option<([Interval; 4], [Jet; 2])> {
        let (j, jets) = self.jacobian(x)?;
        let mut k = [pt(0.0); 4];
        for i in 0..4 {
            let mut acc = pt(y[i]);
            for l in 0..4 {
                acc = acc - pt(yinv[i][l]) * fy[l];
            }
            for c in 0..4 {
                // (I − Y J)_{ic}
                let mut cij = pt(if i == c { 1.0 } else { 0.0 });
                for l in 0..4 {
                    cij = cij - pt(yinv[i][l]) * j[l][c];
                }
                acc = acc + cij * (x[c] - pt(y[c]));
            }
            k[i] = acc;
        }
        Some((k, jets))
    }
}
