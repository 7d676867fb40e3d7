//! Patches of the f64 path: interval patches (hodographs, polar nets, line composition,
//! enclosed), and the midpoint–radius patch form used by the two hot steps (the local Lipschitz bound,
//! step 3, and the mapping by blossoming, step 6), with a-priori error bounds built on the
//! lerp lemma of [`super::ibez`].

use super::ibez::{I, IP, mid, mr_polar_values, polar_values};
use crate::curve_on_surface::casteljau;

/// A patch in midpoint–radius form, cached per cell for the two hot uses (the local
/// Lipschitz bound and the mapping): midpoints, the largest coordinate radius `r`, the
/// largest midpoint magnitude `mx`, and `a` ≥ the largest coordinate difference of
/// neighbouring true control points along u or v.
#[derive(Clone, Debug)]
pub struct MidPatch {
    pub p: usize,
    pub q: usize,
    pub m: Vec<[f64; 3]>,
    pub r: f64,
    pub mx: f64,
    pub a: f64,
}

/// Upper bound of the largest coordinate difference of neighbouring true control points (along
/// u or v) of a net of midpoints `m` (degrees `p × q`) with radius `r`: the f64 differences
/// round by at most `u` relatively, the true points add `2 r`.
fn neighbour_bound(m: &[[f64; 3]], p: usize, q: usize, r: f64) -> f64 {
    let mut a = 0.0f64;
    for i in 0..=p {
        for j in 0..=q {
            let x = &m[i * (q + 1) + j];
            for (di, dj) in [(1, 0), (0, 1)] {
                if i + di <= p && j + dj <= q {
                    let y = &m[(i + di) * (q + 1) + j + dj];
                    for c in 0..3 {
                        a = a.max((y[c] - x[c]).abs());
                    }
                }
            }
        }
    }
    (a * (1.0 + 1e-14) + 2.0 * r) * (1.0 + 1e-14)
}

impl MidPatch {
    pub fn new(s: &IPatch) -> MidPatch {
        let (p, q) = (s.p, s.q);
        let m: Vec<[f64; 3]> = s.net.iter().map(mid).collect();
        let (mut r, mut mx) = (0.0f64, 0.0f64);
        for x in &s.net {
            for c in x {
                r = r.max(c.radius_about_mid());
                mx = mx.max(c.mid().abs());
            }
        }
        let a = neighbour_bound(&m, p, q, r);
        MidPatch { p, q, m, r, mx, a }
    }

    /// The hodograph `∂/∂s` (`along_u`) or `∂/∂r` in local coordinates, in midpoint–radius
    /// form: control points `p (P_{i+1,j} - P_{i,j})` computed in f64 from the midpoints; the
    /// true ones differ by at most `2 p r` (the inputs) plus the rounding of one difference
    /// and one product, `≤ 2.3e-16` of the result's magnitude. `None` for degree 0.
    pub fn hodograph(&self, along_u: bool) -> Option<MidPatch> {
        let (p, q) = (self.p, self.q);
        let deg = if along_u { p } else { q };
        if deg == 0 {
            return None;
        }
        let k = deg as f64;
        let (np, nq) = if along_u { (p - 1, q) } else { (p, q - 1) };
        let mut m = Vec::with_capacity((np + 1) * (nq + 1));
        for i in 0..=np {
            for j in 0..=nq {
                let (a, b) = if along_u {
                    (self.m[i * (q + 1) + j], self.m[(i + 1) * (q + 1) + j])
                } else {
                    (self.m[i * (q + 1) + j], self.m[i * (q + 1) + j + 1])
                };
                m.push(std::array::from_fn(|c| k * (b[c] - a[c])));
            }
        }
        let mx = m
            .iter()
            .flatten()
            .fold(0.0f64, |acc: f64, x| acc.max(x.abs()));
        let r = ((2.0 * k * self.r) * (1.0 + 1e-15) + 2.3e-16 * mx + 1e-300) * (1.0 + 1e-14);
        let a = neighbour_bound(&m, np, nq, r);
        Some(MidPatch {
            p: np,
            q: nq,
            m,
            r,
            mx,
            a,
        })
    }

    /// Polar net `f(x_u^(p-i) y_u^i ; x_v^(q-j) y_v^j)` in f64 on the midpoints, with a bound
    /// on every coordinate's distance to the exact polar values of the exact patch at the
    /// exact parameters, which lie within `dt` (each) of the given ones in `[0, 1]`:
    /// the row stage is `q` de Casteljau levels and the column stage `p` (lemma of
    /// [`super::ibez`]), each parameter contributes `dt · a`.
    pub fn polar_net(&self, xu: f64, yu: f64, xv: f64, yv: f64, dt: f64) -> (Vec<[f64; 3]>, f64) {
        let mut out = vec![[0.0; 3]; (self.p + 1) * (self.q + 1)];
        let err = self.polar_net_into(xu, yu, xv, yv, dt, &mut out);
        (out, err)
    }

    /// [`MidPatch::polar_net`] into `out` (length `(p + 1)(q + 1)`), returning the bound;
    /// no allocation for nets of up to 64 points of degrees below 16.
    pub fn polar_net_into(
        &self,
        xu: f64,
        yu: f64,
        xv: f64,
        yv: f64,
        dt: f64,
        out: &mut [[f64; 3]],
    ) -> f64 {
        let (p, q) = (self.p, self.q);
        if (p + 1) * (q + 1) > 64 || p >= 16 || q >= 16 {
            let mut rows: Vec<[f64; 3]> = Vec::with_capacity((p + 1) * (q + 1));
            for i in 0..=p {
                mr_polar_values(&self.m[i * (q + 1)..(i + 1) * (q + 1)], xv, yv, &mut rows);
            }
            let mut vals: Vec<[f64; 3]> = Vec::with_capacity(p + 1);
            for j in 0..=q {
                let col: Vec<[f64; 3]> = (0..=p).map(|i| rows[i * (q + 1) + j]).collect();
                vals.clear();
                mr_polar_values(&col, xu, yu, &mut vals);
                for (i, v) in vals.iter().enumerate() {
                    out[i * (q + 1) + j] = *v;
                }
            }
        } else if casteljau::polar_net(&self.m, p + 1, q + 1, [xu, yu, xv, yv], out).is_some() {
        } else {
            let mut rows = [[0.0; 3]; 64];
            for i in 0..=p {
                casteljau::polar_values(
                    &self.m[i * (q + 1)..(i + 1) * (q + 1)],
                    xv,
                    yv,
                    &mut rows[i * (q + 1)..(i + 1) * (q + 1)],
                );
            }
            let mut col = [[0.0; 3]; 16];
            let mut vals = [[0.0; 3]; 16];
            for j in 0..=q {
                for i in 0..=p {
                    col[i] = rows[i * (q + 1) + j];
                }
                casteljau::polar_values(&col[..=p], xu, yu, &mut vals[..=p]);
                for i in 0..=p {
                    out[i * (q + 1) + j] = vals[i];
                }
            }
        }
        let levels = (p + q) as f64;
        (self.r + levels * dt * self.a + levels * (3.4e-16 * self.mx * (1.0 + 1e-12) + 1e-300))
            * (1.0 + 1e-14)
    }

    /// Upper bound of `sup |S|` over the local rectangle `[x_u, y_u] × [x_v, y_v]` (this patch
    /// being a hodograph): the largest norm of the restricted control points (convex hull),
    /// each enlarged by the error bound in every coordinate.
    pub fn sup_norm_hi(&self, rect: [f64; 4]) -> f64 {
        let mut buf = [[0.0; 3]; 64];
        let mut heap = Vec::new();
        let n = (self.p + 1) * (self.q + 1);
        let net: &mut [[f64; 3]] = if n <= 64 {
            &mut buf[..n]
        } else {
            heap.resize(n, [0.0; 3]);
            &mut heap
        };
        let err = self.polar_net_into(rect[0], rect[1], rect[2], rect[3], 0.0, net);
        let m2 = net
            .iter()
            .map(|x| {
                let n = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
                // sqrt and the sum round by a few ulps: 1e-15 relatively covers them.
                n * (1.0 + 1e-15)
            })
            .fold(0.0, f64::max);
        ((m2 + 3f64.sqrt() * 1.000001 * err) * (1.0 + 1e-15)).next_up()
    }

    /// The image of the local segment `a → b` (exact local coordinates within `dt` of the
    /// given ones, all in `[0, 1]`): the degree `p + q` Bézier control points in f64 and a
    /// bound on every coordinate's distance to the exact ones. The binomial combination
    /// `Σ C(p,i) C(q,j) / C(p+q,k) h_ij` has weights summing to 1, each computed as
    /// `fl(fl(C(p,i) C(q,j)) / fl(C(p+q,k)))` from exact integers: within `3u` relatively of
    /// the exact weight (one rounding each for the product and the conversion of `C(p+q,k)`
    /// when they exceed `2^53`, one for the division; all exact below that). With at most 32
    /// terms the rounding (weights, products and sum) is within `(terms + 4) · 1.2e-16 · max |h|`.
    pub fn compose_line(&self, a: [f64; 2], b: [f64; 2], dt: f64) -> (Vec<[f64; 3]>, f64) {
        let (p, q) = (self.p, self.q);
        let mut buf = [[0.0; 3]; 64];
        let mut heap = Vec::new();
        let n = (p + 1) * (q + 1);
        let h: &mut [[f64; 3]] = if n <= 64 {
            &mut buf[..n]
        } else {
            heap.resize(n, [0.0; 3]);
            &mut heap
        };
        let eh = self.polar_net_into(a[0], b[0], a[1], b[1], dt, h);
        let mut mh = 0.0f64;
        for x in h.iter() {
            for c in x {
                mh = mh.max(c.abs());
            }
        }
        let binom = |n: usize, k: usize| crate::scalar::BINOMIAL[n][k] as f64;
        let mut bp = [0.0; 64];
        let mut bq = [0.0; 64];
        let mut bpq = [0.0; 64];
        for (i, b) in bp.iter_mut().enumerate().take(p + 1) {
            *b = binom(p, i);
        }
        for (j, b) in bq.iter_mut().enumerate().take(q + 1) {
            *b = binom(q, j);
        }
        for (k, b) in bpq.iter_mut().enumerate().take(p + q + 1) {
            *b = binom(p + q, k);
        }
        let out: Vec<[f64; 3]> = (0..=p + q)
            .map(|k| {
                let mut acc = [0.0; 3];
                for i in k.saturating_sub(q)..=k.min(p) {
                    let j = k - i;
                    let w = bp[i] * bq[j] / bpq[k];
                    let v = &h[i * (q + 1) + j];
                    for c in 0..3 {
                        acc[c] += w * v[c];
                    }
                }
                acc
            })
            .collect();
        let terms = (p.min(q) + 1) as f64;
        let err =
            (eh + (terms + 4.0) * 1.2e-16 * (mh + eh) * (1.0 + 1e-14) + 1e-300) * (1.0 + 1e-14);
        (out, err)
    }
}

/// A tensor-product Bézier patch with interval control points, `net[i * (q + 1) + j]`
/// (`i` along u).
#[derive(Clone, Debug)]
pub struct IPatch {
    pub p: usize,
    pub q: usize,
    pub net: Vec<IP<3>>,
}

impl IPatch {
    pub fn at(&self, i: usize, j: usize) -> &IP<3> {
        &self.net[i * (self.q + 1) + j]
    }

    /// `∂/∂s` in local coordinates: degree `(p - 1, q)`, control points `p (P_{i+1,j} - P_{i,j})`.
    pub fn hodograph_u(&self) -> Option<IPatch> {
        if self.p == 0 {
            return None;
        }
        let m = I::point(self.p as f64);
        let mut net = Vec::with_capacity(self.p * (self.q + 1));
        for i in 0..self.p {
            for j in 0..=self.q {
                let (a, b) = (self.at(i, j), self.at(i + 1, j));
                net.push(std::array::from_fn(|c| m * (b[c] - a[c])));
            }
        }
        Some(IPatch {
            p: self.p - 1,
            q: self.q,
            net,
        })
    }

    /// `∂/∂r` in local coordinates: degree `(p, q - 1)`.
    pub fn hodograph_v(&self) -> Option<IPatch> {
        if self.q == 0 {
            return None;
        }
        let n = I::point(self.q as f64);
        let mut net = Vec::with_capacity((self.p + 1) * self.q);
        for i in 0..=self.p {
            for j in 0..self.q {
                let (a, b) = (self.at(i, j), self.at(i, j + 1));
                net.push(std::array::from_fn(|c| n * (b[c] - a[c])));
            }
        }
        Some(IPatch {
            p: self.p,
            q: self.q - 1,
            net,
        })
    }

    /// Polar values `f(x_u^(p-i) y_u^i ; x_v^(q-j) y_v^j)` for all `i, j`, row-major: the
    /// patch restricted to `[x_u, y_u] × [x_v, y_v]` (tensor-product blossom, rows first).
    pub fn polar_net(&self, xu: I, yu: I, xv: I, yv: I) -> Vec<IP<3>> {
        let (p, q) = (self.p, self.q);
        let rows: Vec<Vec<IP<3>>> = (0..=p)
            .map(|i| polar_values(&self.net[i * (q + 1)..(i + 1) * (q + 1)], xv, yv))
            .collect();
        let mut out = vec![[I::point(0.0); 3]; (p + 1) * (q + 1)];
        let mut col: Vec<IP<3>> = Vec::with_capacity(p + 1);
        for j in 0..=q {
            col.clear();
            col.extend(rows.iter().map(|r| r[j]));
            for (i, v) in polar_values(&col, xu, yu).into_iter().enumerate() {
                out[i * (q + 1) + j] = v;
            }
        }
        out
    }

    /// Enclosure of the image `S(a + t (b - a))` of a local segment: the Bézier curve of
    /// degree `p + q` from the blossom (the interval counterpart of
    /// `spline::compose::compose_line`).
    ///
    /// The caller guarantees that the exact local coordinates lie in `[0, 1]` (the chord is in
    /// the patch), so the enclosures are intersected with `[0, 1]`.
    pub fn compose_line(&self, a: &IP<2>, b: &IP<2>) -> Vec<IP<3>> {
        let (p, q) = (self.p, self.q);
        let unit = |x: I| I::new(x.lo.max(0.0), x.hi.min(1.0));
        let (a, b) = ([unit(a[0]), unit(a[1])], [unit(b[0]), unit(b[1])]);
        let h = self.polar_net(a[0], b[0], a[1], b[1]);
        let binom = |n: usize, k: usize| crate::scalar::binomial_i64(n, k) as f64;
        (0..=p + q)
            .map(|k| {
                let den = I::point(binom(p + q, k));
                let mut acc = [I::point(0.0); 3];
                for i in k.saturating_sub(q)..=k.min(p) {
                    let j = k - i;
                    let w = I::point(binom(p, i) * binom(q, j))
                        .checked_div(den)
                        .expect("binomial coefficients are positive");
                    let v = &h[i * (q + 1) + j];
                    for c in 0..3 {
                        acc[c] = acc[c] + w * v[c];
                    }
                }
                acc
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve_on_surface::float::ibez::ip;
    use crate::curve_on_surface::float::ibez::tests::{q_, rng};
    use crate::scalar::{Rational, Scalar};
    use crate::spline::BezierSurface;

    #[test]
    fn mid_patch_compose_and_sup_are_within_their_bounds() {
        let mut r = rng(11);
        for trial in 0..60 {
            let (p, q) = (1 + trial % 4, 1 + (trial / 4) % 3);
            let net: Vec<[f64; 3]> = (0..(p + 1) * (q + 1)).map(|_| [r(), r(), r()]).collect();
            let exact = BezierSurface::new(
                p,
                q,
                net.iter()
                    .map(crate::geom::lift_point::<Rational, 3>)
                    .collect(),
            )
            .unwrap();
            let ipatch = IPatch {
                p,
                q,
                net: net.iter().map(ip).collect(),
            };
            let mp = MidPatch::new(&ipatch);
            let (a, b) = (
                [r().abs().min(1.0), r().abs().min(1.0)],
                [r().abs().min(1.0), 1.0],
            );
            let want = crate::spline::compose::compose_line(
                &exact,
                &crate::geom::lift_point(&a),
                &crate::geom::lift_point(&b),
            );
            let (got, err) = mp.compose_line(a, b, 0.0);
            for (g, w) in got.iter().zip(&want.control) {
                for c in 0..3 {
                    assert!((q_(g[c]) - w[c].clone()).abs() <= q_(err), "trial {trial}");
                }
            }
            // Hodographs in midpoint–radius form against the exact ones.
            for (along_u, ex) in [(true, exact.hodograph_u()), (false, exact.hodograph_v())] {
                if let (Some(h), Some(ex)) = (mp.hodograph(along_u), ex) {
                    for (g, w) in h.m.iter().zip(&ex.net) {
                        for c in 0..3 {
                            assert!((q_(g[c]) - w[c].clone()).abs() <= q_(h.r), "trial {trial}");
                        }
                    }
                }
            }
            // sup over a sub-rectangle: at least every exact point of the restricted net.
            let rect = [0.25, 0.5, 0.0, 0.75];
            let sup = mp.sup_norm_hi(rect);
            let sub = exact.sub_patch(&q_(0.25), &q_(0.5), &q_(0.0), &q_(0.75));
            for x in &sub.net {
                let n2 = crate::geom::norm2(x);
                assert!(n2 <= q_(sup) * q_(sup), "trial {trial}");
            }
        }
    }
}
