//! Step 1a, f64 path — the Bézier patches of S, enclosed in interval arithmetic and built
//! only for the cells the curve visits, with the Lipschitz bounds of step 3: eq. (12) per
//! patch scaled to its spans (derivation in [`crate::curve_on_surface::tolerance`]), and the
//! local refinement on a sub-rectangle (hodograph hulls, Cauchy–Schwarz). Every bound is
//! computed upward from enclosures of the exact patch, so it holds for the exact surface.

use super::ibez::{I, IP};
use super::midpatch::{IPatch, MidPatch};
use super::rational::RationalCell;
use super::span::bspline_span_bezier_f64_into;
use crate::curve_on_surface::g1::{mapped_tangent_with, rational_tangent};
use crate::spline::{BSplineSurface, BezierSurface};
use std::cell::OnceCell;

/// One Bézier patch of S.
#[derive(Clone, Debug)]
pub struct FCell {
    pub u0: f64,
    pub u1: f64,
    pub v0: f64,
    pub v1: f64,
    /// Enclosures of the exact patch control points.
    pub patch: IPatch,
    /// The hodographs of their midpoints (for tangents in the ε_T pass, computed in f64).
    pub hodo_f64: crate::curve_on_surface::g1::Hodographs,
    /// Midpoint–radius forms of the patch and its hodographs (the fast path).
    pub mpatch: MidPatch,
    pub mhodo_u: Option<MidPatch>,
    pub mhodo_v: Option<MidPatch>,
    /// Lower bounds of the span widths.
    pub du_lo: f64,
    pub dv_lo: f64,
    /// Eq. (12) Lipschitz bound in global parameters, rounded up (for a rational surface:
    /// the bound of [`RationalCell::lipschitz`] from eq. (12) of `Q` and `W`).
    pub eq12: f64,
    /// For a rational surface: the weight patch and the centring (then `patch`, `mpatch`
    /// and the hodographs are those of the centred numerator `Q`, see [`super::rational`]).
    pub rational: Option<RationalCell>,
}

/// The patch grid of S, built lazily.
pub struct FCells<'a> {
    s: &'a BSplineSurface<[f64; 3]>,
    ku: Vec<f64>,
    kv: Vec<f64>,
    pub u_breaks: Vec<f64>,
    pub v_breaks: Vec<f64>,
    cells: Vec<OnceCell<FCell>>,
    /// The weights in coordinate 0 when S is rational (then `s` holds the homogeneous
    /// points `w·P`).
    w: Option<Vec<[f64; 3]>>,
}

/// Why a cell could not be built, with its rectangle `[u0, u1, v0, v1]`.
#[derive(Debug)]
pub enum CellError {
    /// An invalid knot vector (the only cause for a polynomial surface).
    Knots([f64; 4]),
    /// A weight of the rational patch not proven positive.
    Weight([f64; 4]),
}

impl From<CellError> for crate::curve_on_surface::CosError {
    fn from(e: CellError) -> Self {
        match e {
            CellError::Knots(cell) => {
                crate::curve_on_surface::CosInternal::CellKnots { cell }.into()
            }
            CellError::Weight(cell) => crate::curve_on_surface::CosError::Weight { cell },
        }
    }
}

impl<'a> FCells<'a> {
    pub fn new(s: &'a BSplineSurface<[f64; 3]>) -> FCells<'a> {
        let u_breaks = s.ku.breakpoints();
        let v_breaks = s.kv.breakpoints();
        let n = (u_breaks.len() - 1) * (v_breaks.len() - 1);
        FCells {
            ku: s.ku.knots().to_vec(),
            kv: s.kv.knots().to_vec(),
            s,
            u_breaks,
            v_breaks,
            cells: (0..n).map(|_| OnceCell::new()).collect(),
            w: None,
        }
    }

    /// The cells of a rational surface: `s` holds the homogeneous points `w·P` (as the
    /// surface stores them) and `weights` the weights, row-major like `s.net`.
    pub fn rational(s: &'a BSplineSurface<[f64; 3]>, weights: &[f64]) -> FCells<'a> {
        FCells {
            w: Some(weights.iter().map(|w| [*w, 0.0, 0.0]).collect()),
            ..FCells::new(s)
        }
    }

    pub fn count(&self) -> usize {
        self.cells.len()
    }

    /// Number of cells built so far.
    pub fn built(&self) -> usize {
        self.cells.iter().filter(|c| c.get().is_some()).count()
    }

    fn nv_cells(&self) -> usize {
        self.v_breaks.len() - 1
    }

    /// Cell `c` (row-major over `u_breaks × v_breaks`), built on first use.
    pub fn get(&self, c: usize) -> Result<&FCell, CellError> {
        if let Some(x) = self.cells[c].get() {
            return Ok(x);
        }
        let built = self.build(c)?;
        Ok(self.cells[c].get_or_init(|| built))
    }

    fn build(&self, c: usize) -> Result<FCell, CellError> {
        let (i, j) = (c / self.nv_cells(), c % self.nv_cells());
        let (u0, u1) = (self.u_breaks[i], self.u_breaks[i + 1]);
        let (v0, v1) = (self.v_breaks[j], self.v_breaks[j + 1]);
        let rect = [u0, u1, v0, v1];
        let x = self.extract(rect, &self.s.net)?;
        let (patch, rational) = match &self.w {
            None => (x, None),
            Some(w) => {
                let w = self.extract(rect, w)?;
                let (q, r) = RationalCell::new(&x, &w).map_err(|_| CellError::Weight(rect))?;
                (q, Some(r))
            }
        };
        let du_lo = (I::point(u1) - I::point(u0)).lo;
        let dv_lo = (I::point(v1) - I::point(v0)).lo;
        let mpatch = MidPatch::new(&patch);
        let eq12 = eq12_bound(&mpatch, du_lo, dv_lo);
        let eq12 = match &rational {
            None => eq12,
            Some(r) => r.lipschitz(eq12, eq12_bound(&r.w, du_lo, dv_lo)),
        };
        let (mhodo_u, mhodo_v) = (mpatch.hodograph(true), mpatch.hodograph(false));
        // The tangents of the ε_T pass use the hodographs' midpoints (computed in f64 from
        // the patch's midpoints as `k (P_{i+1} - P_i)`).
        let bezier_of = |h: &MidPatch| BezierSurface {
            p: h.p,
            q: h.q,
            net: h.m.clone(),
        };
        Ok(FCell {
            u0,
            u1,
            v0,
            v1,
            hodo_f64: (
                mhodo_u.as_ref().map(bezier_of),
                mhodo_v.as_ref().map(bezier_of),
            ),
            mhodo_u,
            mhodo_v,
            mpatch,
            patch,
            du_lo,
            dv_lo,
            eq12,
            rational,
        })
    }

    /// The enclosed Bézier patch of the net `net` (the surface's, or its weights in
    /// coordinate 0) on the cell `rect`.
    fn extract(&self, rect: [f64; 4], net: &[[f64; 3]]) -> Result<IPatch, CellError> {
        let [u0, _, v0, _] = rect;
        let (p, q) = self.s.degrees();
        let su = self.s.ku.find_span(&u0);
        let sv = self.s.kv.find_span(&v0);
        let nv = self.s.nv();
        let err = || CellError::Knots(rect);
        // Rows (fixed u index) → Bézier in v; then columns → Bézier in u (f64 with the
        // error bound of `bspline_span_bezier_f64`, applied twice).
        let mut rows: Vec<[f64; 3]> = Vec::with_capacity((p + 1) * (q + 1));
        let mut e_rows = 0.0f64;
        for r in su - p..=su {
            let row = &net[r * nv..(r + 1) * nv];
            let e = bspline_span_bezier_f64_into(&self.kv, q, row, 0.0, sv, &mut rows)
                .ok_or_else(err)?;
            e_rows = e_rows.max(e);
        }
        let mut m = vec![[0.0; 3]; (p + 1) * (q + 1)];
        let mut e_net = 0.0f64;
        // The columns as the span's `p + 1` points, indexed from `su - p` (the knots are
        // shifted alike, so span `p` of the shifted knots is span `su`).
        let mut col = vec![[0.0; 3]; p + 1];
        let mut pts = Vec::with_capacity(p + 1);
        for l in 0..=q {
            for (k, x) in col.iter_mut().enumerate() {
                *x = rows[k * (q + 1) + l];
            }
            pts.clear();
            let e = bspline_span_bezier_f64_into(&self.ku[su - p..], p, &col, e_rows, p, &mut pts)
                .ok_or_else(err)?;
            e_net = e_net.max(e);
            for (k, x) in pts.iter().enumerate() {
                m[k * (q + 1) + l] = *x;
            }
        }
        let net: Vec<IP<3>> = m
            .iter()
            .map(|x| {
                std::array::from_fn(|c| {
                    I::new((x[c] - e_net).next_down(), (x[c] + e_net).next_up())
                })
            })
            .collect();
        Ok(IPatch { p, q, net })
    }

    /// The cell whose closed rectangle holds `p` (first match), `None` outside the domain.
    pub fn locate(&self, p: &[f64; 2]) -> Option<usize> {
        let find = |br: &[f64], x: f64| (0..br.len() - 1).find(|&i| br[i] <= x && x <= br[i + 1]);
        Some(find(&self.u_breaks, p[0])? * self.nv_cells() + find(&self.v_breaks, p[1])?)
    }

    /// Clamp `p` into cell `c`'s rectangle.
    pub fn clamp(&self, c: usize, p: &[f64; 2]) -> [f64; 2] {
        let (i, j) = (c / self.nv_cells(), c % self.nv_cells());
        [
            p[0].clamp(self.u_breaks[i], self.u_breaks[i + 1]),
            p[1].clamp(self.v_breaks[j], self.v_breaks[j + 1]),
        ]
    }

    /// The domain rectangle `[u_min, u_max] × [v_min, v_max]`.
    pub fn domain(&self) -> [f64; 4] {
        [
            self.u_breaks[0],
            *self.u_breaks.last().expect("two breaks"),
            self.v_breaks[0],
            *self.v_breaks.last().expect("two breaks"),
        ]
    }

    /// Upper bound `K` of the Lipschitz constant of S on the rectangle `r = [u0,u1]×[v0,v1]`
    /// (inside the domain): the largest over the cells `r` meets of the bound on their
    /// common part — eq. (12) of the cell, or (`local`) the smaller of it and the local
    /// common part (S is continuous and piecewise C¹, and `r` is convex, so the segment between
    /// two points crosses finitely many cells and the bounds chain).
    pub fn lipschitz_on(&self, r: [f64; 4], local: bool) -> Result<f64, CellError> {
        // The cells whose open span meets `[lo, hi]`'s interior — or, for a degenerate
        // `lo == hi`, the first closed span holding it: the convex `r` lies in the union of
        // those closed cells, and on each closed cell S is its patch's polynomial, so a cell
        // touching `r` only along its edge adds nothing (edges snapped onto knot lines are
        // common, and would build the neighbour for nothing).
        let range = |br: &[f64], lo: f64, hi: f64| {
            let n = br.len() - 1;
            let first = (0..n).find(|&i| br[i + 1] > lo).unwrap_or(n - 1);
            let last = (0..n).rev().find(|&i| br[i] < hi).unwrap_or(0);
            if lo < hi && first <= last {
                first..=last
            } else {
                let c = (0..n)
                    .find(|&i| br[i] <= lo && lo <= br[i + 1])
                    .unwrap_or(first);
                c..=c
            }
        };
        let mut k = 0.0f64;
        for i in range(&self.u_breaks, r[0], r[1]) {
            for j in range(&self.v_breaks, r[2], r[3]) {
                let c = self.get(i * self.nv_cells() + j)?;
                let to_local = |x: f64, a: f64, b: f64, up: bool| {
                    let y = (I::point(x.clamp(a, b)) - I::point(a))
                        .checked_div(I::point(b) - I::point(a));
                    match y {
                        Some(y) if up => y.hi.min(1.0),
                        Some(y) => y.lo.max(0.0),
                        None => {
                            if up {
                                1.0
                            } else {
                                0.0
                            }
                        }
                    }
                };
                let rect = [
                    to_local(r[0], c.u0, c.u1, false),
                    to_local(r[1], c.u0, c.u1, true),
                    to_local(r[2], c.v0, c.v1, false),
                    to_local(r[3], c.v0, c.v1, true),
                ];
                k = k.max(if local {
                    local_bound(c, rect).min(c.eq12)
                } else {
                    c.eq12
                });
            }
        }
        Ok(k)
    }
}

/// Eq. (12), scaled: `n · A_v / (e - c) + m · A_u / (b - a)`, upward. The maxima are taken
/// over the midpoints in f64 (a Euclidean norm of a difference rounds by a few ulps: `1e-15`
/// relatively covers it) plus `2 √3 r` for the true points' offsets.
fn eq12_bound(s: &MidPatch, du_lo: f64, dv_lo: f64) -> f64 {
    let (m, n) = (s.p, s.q);
    let at = |i: usize, j: usize| &s.m[i * (n + 1) + j];
    let norm = |a: &[f64; 3], b: &[f64; 3]| {
        let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
    };
    let mut au = 0.0f64;
    for i in 0..m {
        for h in 0..=n {
            for k in 0..=n {
                au = au.max(norm(at(i + 1, h), at(i, k)));
            }
        }
    }
    let mut av = 0.0f64;
    for i in 0..n {
        for h in 0..=m {
            for k in 0..=m {
                av = av.max(norm(at(h, i + 1), at(k, i)));
            }
        }
    }
    let slack = 2.0 * 3f64.sqrt() * 1.000001 * s.r;
    let (au, av) = (
        (au * (1.0 + 1e-15) + slack) * (1.0 + 1e-15),
        (av * (1.0 + 1e-15) + slack) * (1.0 + 1e-15),
    );
    let ku = if m == 0 {
        0.0
    } else {
        ((m as f64 * au).next_up() / du_lo).next_up()
    };
    let kv = if n == 0 {
        0.0
    } else {
        ((n as f64 * av).next_up() / dv_lo).next_up()
    };
    (ku + kv).next_up()
}

/// The local bound on the local sub-rectangle `rect = [s0,s1]×[r0,r1]` of a cell:
/// `sqrt(L_u² + L_v²)` with `L_u`, `L_v` bounded by the hodographs' control points
/// restricted to `rect` (convex hull property), scaled to global parameters.
/// For a rational surface, the bound of [`RationalCell::lipschitz`] from the local bounds of
/// `Q` and `W`.
fn local_bound(c: &FCell, rect: [f64; 4]) -> f64 {
    let k = |hu: Option<&MidPatch>, hv: Option<&MidPatch>| {
        let sup = |h: Option<&MidPatch>| h.map(|h| h.sup_norm_hi(rect)).unwrap_or(0.0);
        let lu = (sup(hu) / c.du_lo).next_up();
        let lv = (sup(hv) / c.dv_lo).next_up();
        ((lu * lu).next_up() + (lv * lv).next_up())
            .next_up()
            .sqrt()
            .next_up()
    };
    let kq = k(c.mhodo_u.as_ref(), c.mhodo_v.as_ref());
    match &c.rational {
        None => kq,
        Some(r) => r.lipschitz(kq, k(r.w_hodo_u.as_ref(), r.w_hodo_v.as_ref())),
    }
}

impl FCell {
    /// Start (or end, `at_end`) tangent of the image of the chord `a → b` (global
    /// parameters, inside the cell), computed in f64 (eq. 20; for a rational surface the
    /// quotient rule of [`crate::curve_on_surface::g1::rational_tangent`]).
    pub fn tangent(&self, a: &[f64; 2], b: &[f64; 2], at_end: bool) -> [f64; 3] {
        let rect = [self.u0, self.u1, self.v0, self.v1];
        match &self.rational {
            None => mapped_tangent_with(&self.hodo_f64, rect, a, b, at_end),
            Some(r) => rational_tangent(&r.q_f64, &r.w_f64, rect, a, b, at_end),
        }
    }
}
