//! Conversion of IGES curve and surface entities into NURBS in model space, each entity's
//! transformation (124) applied: the rational B-spline surface (128), the surface of
//! revolution (120), the tabulated cylinder (122) and the analytic surfaces; the rational
//! B-spline curve (126), the line (110), the circular arc (100) and the composite curve (102).

use super::{EXPANSION_BASE, EXPANSION_PER_ENTITY, R, Reader, analytic};
use crate::geom::Point;
use crate::model::SurfaceKind;
use crate::spline::{NurbsCurve, NurbsSurface, construct};

impl Reader<'_> {
    fn b128(&self, de: usize) -> R<NurbsSurface<f64, 3>> {
        let h = self.nums(de, 1, 4)?;
        let (k1, k2, m1, m2) = (h[0] as usize, h[1] as usize, h[2] as usize, h[3] as usize);
        if k1 > 10_000 || k2 > 10_000 || m1 > 64 || m2 > 64 {
            return self.err(de, "implausible control-net size or degree");
        }
        let (nu, nv) = (k1 + 1, k2 + 1);
        let mut i = 10;
        let ku = self.nums(de, i, k1 + m1 + 2)?;
        i += k1 + m1 + 2;
        let kv = self.nums(de, i, k2 + m2 + 2)?;
        i += k2 + m2 + 2;
        let w = self.nums(de, i, nu * nv)?;
        i += nu * nv;
        let c = self.nums(de, i, 3 * nu * nv)?;
        let mut pts: Vec<[f64; 3]> = vec![[0.0; 3]; nu * nv];
        let mut ws = vec![0.0; nu * nv];
        for jv in 0..nv {
            for iu in 0..nu {
                let k = iu + jv * nu;
                pts[iu * nv + jv] = [c[3 * k], c[3 * k + 1], c[3 * k + 2]];
                ws[iu * nv + jv] = w[k];
            }
        }
        self.apply(de, &mut pts)?;
        NurbsSurface::new(ku, m1, kv, m2, nu, nv, pts, ws).or_else(|e| self.err(de, e.to_string()))
    }
    /// A curve entity (126, 110, 100) as a NURBS curve in model space.
    pub(super) fn curve(&self, de: usize) -> R<Option<NurbsCurve<f64, 3>>> {
        let e = &self.e[&de];
        let c = match e.etype {
            126 => {
                let h = self.nums(de, 1, 2)?;
                let (k, m) = (h[0] as usize, h[1] as usize);
                if k > 100_000 || m > 64 {
                    return self.err(de, "implausible curve size or degree");
                }
                let knots = self.nums(de, 7, k + m + 2)?;
                let w = self.nums(de, 7 + k + m + 2, k + 1)?;
                let c = self.nums(de, 7 + k + m + 2 + k + 1, 3 * (k + 1))?;
                let mut pts: Vec<[f64; 3]> = c.chunks(3).map(|p| [p[0], p[1], p[2]]).collect();
                self.apply(de, &mut pts)?;
                NurbsCurve::new(knots, m, pts, w).or_else(|e| self.err(de, e.to_string()))?
            }
            110 => {
                let v = self.nums(de, 1, 6)?;
                let mut pts = vec![[v[0], v[1], v[2]], [v[3], v[4], v[5]]];
                self.apply(de, &mut pts)?;
                NurbsCurve::new(vec![0.0, 0.0, 1.0, 1.0], 1, pts, vec![1.0, 1.0])
                    .or_else(|e| self.err(de, e.to_string()))?
            }
            100 => {
                let v = self.nums(de, 1, 7)?;
                let (zt, c, st, en) = (v[0], [v[1], v[2]], [v[3], v[4]], [v[5], v[6]]);
                let r = ((st[0] - c[0]).powi(2) + (st[1] - c[1]).powi(2)).sqrt();
                if r.is_nan() || r <= 0.0 {
                    return self.err(de, "arc of zero radius");
                }
                let a0 = (st[1] - c[1]).atan2(st[0] - c[0]);
                let mut a1 = (en[1] - c[1]).atan2(en[0] - c[0]);
                while a1 <= a0 + 1e-15 {
                    a1 += std::f64::consts::TAU;
                }
                let f = construct::Frame {
                    o: [c[0], c[1], zt],
                    x: [1.0, 0.0, 0.0],
                    y: [0.0, 1.0, 0.0],
                    z: [0.0, 0.0, 1.0],
                };
                let mut arc =
                    construct::arc(&f, r, a0, a1).or_else(|e| self.err(de, e.to_string()))?;
                let (mut pts, w) = arc.points_weights();
                self.apply(de, &mut pts)?;
                arc = NurbsCurve::new(arc.hom.knots.knots().to_vec(), 2, pts, w)
                    .or_else(|e| self.err(de, e.to_string()))?;
                arc
            }
            _ => return Ok(None),
        };
        Ok(Some(c))
    }
    /// A curve or composite curve (102) as its list of segments; `None` for unsupported
    /// members.
    pub(super) fn segments(&self, de: usize, depth: usize) -> R<Option<Vec<NurbsCurve<f64, 3>>>> {
        if depth > 16 {
            return self.err(de, "composite curves nested too deeply");
        }
        match self.budget.get().checked_sub(1) {
            Some(b) => self.budget.set(b),
            None => {
                return self.err(
                    de,
                    format!(
                        "composite curves expand to more curve segments than the file's expansion budget ({} + {} per entity = {}): members are shared too often",
                        EXPANSION_BASE,
                        EXPANSION_PER_ENTITY,
                        EXPANSION_BASE + EXPANSION_PER_ENTITY * self.e.len()
                    ),
                );
            }
        }
        if self.e[&de].etype == 102 {
            let n = self.nums(de, 1, 1)?[0] as usize;
            let mut out = Vec::new();
            for k in 0..n.min(100_000) {
                match self.segments(self.ptr(de, 2 + k)?, depth + 1)? {
                    Some(v) => out.extend(v),
                    None => return Ok(None),
                }
            }
            return Ok(Some(out));
        }
        Ok(self.curve(de)?.map(|c| vec![c]))
    }
    /// `s` (built in the definition space of entity `de` from its member curves) moved by
    /// `de`'s own transformation (124) into model space: the control points mapped, exact
    /// for NURBS (affine invariance).
    fn placed(&self, de: usize, s: NurbsSurface<f64, 3>) -> R<NurbsSurface<f64, 3>> {
        if self.e[&de].transform == 0 {
            return Ok(s);
        }
        let (mut pts, w) = s.points_weights();
        self.apply(de, &mut pts)?;
        let h = &s.hom;
        NurbsSurface::new(
            h.ku.knots().to_vec(),
            h.ku.degree(),
            h.kv.knots().to_vec(),
            h.kv.degree(),
            h.ku.n_ctrl(),
            h.kv.n_ctrl(),
            pts,
            w,
        )
        .or_else(|e| self.err(de, e.to_string()))
    }
    /// The NURBS form of surface entity `de`; `face`: the face using it (unbounded analytic
    /// surfaces span its points).
    pub(super) fn surface(
        &self,
        de: usize,
        face: usize,
    ) -> R<Option<(NurbsSurface<f64, 3>, SurfaceKind)>> {
        if analytic::ANALYTIC.contains(&self.e[&de].etype) {
            let pts = match self.e[&face].etype {
                _ if face == de => vec![],
                510 => self.face_points(face),
                143 | 144 => self
                    .space_loops(face, None, &mut Default::default())?
                    .into_iter()
                    .flatten()
                    .flat_map(|l| l.curves)
                    .flat_map(|(_, c)| c.points_weights().0)
                    .collect(),
                _ => vec![],
            };
            return self.analytic(de, &pts);
        }
        match self.e[&de].etype {
            128 => Ok(Some((self.b128(de)?, SurfaceKind::BSpline))),
            120 => {
                let axis = self.ptr(de, 1)?;
                let generatrix = self.ptr(de, 2)?;
                let (Some(a), Some(g)) = (self.curve(axis)?, self.curve(generatrix)?) else {
                    return Ok(None);
                };
                let (ap, _) = a.points_weights();
                let d = ap[ap.len() - 1].sub(&ap[0]);
                let l = crate::geom::norm(&d);
                if l == 0.0 || !l.is_finite() {
                    return self.err(
                        de,
                        format!("axis DE {axis} has length {l:e}: not a usable direction"),
                    );
                }
                // SA, TA (parameters 3, 4 of the 120): the angular range, radians.
                let sa = self.nums(de, 3, 2)?;
                let (sa, ta) = (
                    sa[0],
                    if sa[1] > sa[0] {
                        sa[1]
                    } else {
                        sa[0] + std::f64::consts::TAU
                    },
                );
                let s = construct::revolve_curve_range(&ap[0], &d.scale(&(1.0 / l)), &g, sa, ta)
                    .or_else(|e| self.err(de, e.to_string()))?;
                Ok(Some((self.placed(de, s)?, SurfaceKind::Revolution)))
            }
            122 => {
                let dir = self.ptr(de, 1)?;
                let Some(c) = self.curve(dir)? else {
                    return Ok(None);
                };
                let end = self.nums(de, 2, 3)?;
                let start = c.eval(&c.hom.domain().0);
                let s = construct::extrude(
                    &c,
                    &[end[0] - start[0], end[1] - start[1], end[2] - start[2]],
                )
                .or_else(|e| self.err(de, e.to_string()))?;
                Ok(Some((self.placed(de, s)?, SurfaceKind::Extrusion)))
            }
            _ => Ok(None),
        }
    }
}
