//! The coverage certificate: both parameter domains are cut into boxes (every Bézier patch,
//! extracted exactly in rationals, then halved `depth` times in u and v in outward-rounded
//! interval arithmetic, so every control point of every piece is *enclosed*, not
//! approximated), and every pair of boxes is classified:
//!
//! * **free** — the axis-aligned boxes of the two exact control nets are disjoint. A NURBS
//!   patch with positive weights lies in the convex hull of its Cartesian control points, so
//!   the two pieces cannot meet. (Boxes are rounded outward to `f64` before comparing.)
//! * **loop-free** — the normal cones of the two pieces contain no parallel vectors, so the
//!   intersection inside the pair contains no closed loop (Sederberg & Meyers 1988, the
//!   loop-detection criterion). The normal of a piece is a non-negative combination of the
//!   cross products `A_kr × B_ls` of the Bernstein coefficients of `A ∝ S_u` and `B ∝ S_v`
//!   (`A = w X_u − w_u X`, `B = w X_v − w_v X` for homogeneous `(X, w)`, products taken in
//!   Bernstein form; the hodographs for polynomial patches). "No parallel vectors" is shown by
//!   exhibiting vectors `m`, `m'` with `m·a > 0 > m·b` and `m'·a > 0, m'·b > 0` for every
//!   generator `a` of one cone and `b` of the other; generators are interval enclosures and a
//!   sign counts only when the whole interval has it.
//! * **on a branch** — a refined point of a traced branch has its parameters in both boxes.
//! * **uncertified** — none of the above: a small closed loop could hide there. Listed.
//!
//! What this proves: no closed intersection loop exists outside the listed uncertified box
//! pairs and the box pairs crossed by a branch that are not loop-free. It does not prove that
//! no *open* piece was missed (one would have to cross a box border, which is not checked).

use super::report::BranchOut;
use crate::geom::{Hom, lift_point};
use crate::scalar::{Interval, Scalar, binomial_i64, lift};
use crate::spline::NurbsSurface;
use num_rational::BigRational;
use serde::Serialize;

type Q = BigRational;
type V = [Interval; 3];

/// One box of a domain with what is known about its piece.
struct Cell {
    uv: [f64; 4],
    lo: [f64; 3],
    hi: [f64; 3],
    patch: IPatch,
    polynomial: bool,
    /// Generators of the normal cone, computed on first use (empty when a generator may
    /// vanish: no cone claimed).
    normals: std::cell::OnceCell<Vec<V>>,
}

impl Cell {
    fn normals(&self) -> &[V] {
        self.normals
            .get_or_init(|| normal_generators(&self.patch, self.polynomial))
    }
}

/// A pair of parameter boxes that could not be certified.
#[derive(Clone, Debug, Serialize)]
pub struct RegionOut {
    pub uv_a: [f64; 4],
    pub uv_b: [f64; 4],
    pub on_branch: bool,
}

/// Counts of box pairs by class, and the uncertified ones (first 100).
#[derive(Clone, Debug, Default, Serialize)]
pub struct CoverageOut {
    pub boxes_a: usize,
    pub boxes_b: usize,
    pub pairs: usize,
    pub free: usize,
    pub loop_free: usize,
    pub on_branch: usize,
    pub on_branch_loop_free: usize,
    pub uncertified: usize,
    /// Whether every pair is free, loop-free, or on a branch and loop-free: then no closed
    /// loop was missed.
    pub no_missed_loops: bool,
    pub uncertified_regions: Vec<RegionOut>,
    /// Box pairs proven free that nevertheless hold a branch point (a contradiction: must be
    /// 0; kept as a self-check of the certificate, tested).
    pub free_pairs_with_branch_points: usize,
    pub seconds: f64,
}

fn outward(lo: &Q, hi: &Q) -> (f64, f64) {
    let (mut a, mut b) = (lo.to_f64(), hi.to_f64());
    if lift::<Q>(a) > *lo {
        a = a.next_down();
    }
    if lift::<Q>(b) < *hi {
        b = b.next_up();
    }
    (a, b)
}

fn iv0() -> Interval {
    Interval::point(0.0)
}

/// A Bézier piece with interval control points: homogeneous `(X, w)`, row-major.
#[derive(Clone)]
struct IPatch {
    p: usize,
    q: usize,
    x: Vec<V>,
    w: Vec<Interval>,
}

impl IPatch {
    fn at(&self, i: usize, j: usize) -> usize {
        i * (self.q + 1) + j
    }
    /// de Casteljau at 1/2 along u (`along_u`) or v; returns the two halves.
    fn halve(&self, along_u: bool) -> (IPatch, IPatch) {
        let half = Interval::point(0.5);
        let (n, m) = if along_u {
            (self.p, self.q)
        } else {
            (self.q, self.p)
        };
        let mut l = self.clone();
        let mut r = self.clone();
        for line in 0..=m {
            let idx = |k: usize| {
                if along_u {
                    self.at(k, line)
                } else {
                    self.at(line, k)
                }
            };
            let mut xs: Vec<V> = (0..=n).map(|k| self.x[idx(k)]).collect();
            let mut ws: Vec<Interval> = (0..=n).map(|k| self.w[idx(k)]).collect();
            l.x[idx(0)] = xs[0];
            l.w[idx(0)] = ws[0];
            r.x[idx(n)] = xs[n];
            r.w[idx(n)] = ws[n];
            for level in 1..=n {
                for k in 0..=n - level {
                    xs[k] = std::array::from_fn(|c| (xs[k][c] + xs[k + 1][c]) * half);
                    ws[k] = (ws[k] + ws[k + 1]) * half;
                }
                l.x[idx(level)] = xs[0];
                l.w[idx(level)] = ws[0];
                r.x[idx(n - level)] = xs[n - level];
                r.w[idx(n - level)] = ws[n - level];
            }
        }
        (l, r)
    }
    /// Hodograph in u or v (degree one less), as homogeneous `(X', w')`.
    fn hodograph(&self, along_u: bool) -> Option<IPatch> {
        let (p, q) = if along_u {
            (self.p.checked_sub(1)?, self.q)
        } else {
            (self.p, self.q.checked_sub(1)?)
        };
        let deg = Interval::point(if along_u { self.p } else { self.q } as f64);
        let mut h = IPatch {
            p,
            q,
            x: Vec::new(),
            w: Vec::new(),
        };
        for i in 0..=p {
            for j in 0..=q {
                let (a, b) = if along_u {
                    (self.at(i + 1, j), self.at(i, j))
                } else {
                    (self.at(i, j + 1), self.at(i, j))
                };
                h.x.push(std::array::from_fn(|c| (self.x[a][c] - self.x[b][c]) * deg));
                h.w.push((self.w[a] - self.w[b]) * deg);
            }
        }
        Some(h)
    }
}

fn cross(a: &V, b: &V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Bernstein product of scalar grid `f` (`fp × fq`) and vector grid `g` (`gp × gq`).
fn product(f: &[Interval], fp: usize, fq: usize, g: &[V], gp: usize, gq: usize) -> Vec<V> {
    let (p, q) = (fp + gp, fq + gq);
    let mut net = vec![[iv0(); 3]; (p + 1) * (q + 1)];
    for k in 0..=fp {
        for r in 0..=fq {
            for l in 0..=gp {
                for s in 0..=gq {
                    let num = (binomial_i64(fp, k)
                        * binomial_i64(gp, l)
                        * binomial_i64(fq, r)
                        * binomial_i64(gq, s)) as f64;
                    let den = (binomial_i64(p, k + l) * binomial_i64(q, r + s)) as f64;
                    let c = Interval::point(num)
                        .checked_div(Interval::point(den))
                        .unwrap_or(Interval {
                            lo: f64::NEG_INFINITY,
                            hi: f64::INFINITY,
                        })
                        * f[k * (fq + 1) + r];
                    let idx = (k + l) * (q + 1) + (r + s);
                    let gv = g[l * (gq + 1) + s];
                    net[idx] = std::array::from_fn(|c2| net[idx][c2] + gv[c2] * c);
                }
            }
        }
    }
    net
}

/// Normal-cone generators of a piece; empty if one may vanish.
fn normal_generators(h: &IPatch, polynomial: bool) -> Vec<V> {
    let (Some(hu), Some(hv)) = (h.hodograph(true), h.hodograph(false)) else {
        return Vec::new();
    };
    let (a, b) = if polynomial {
        (hu.x.clone(), hv.x.clone())
    } else {
        let wxu = product(&h.w, h.p, h.q, &hu.x, hu.p, hu.q);
        let wux = product(&hu.w, hu.p, hu.q, &h.x, h.p, h.q);
        let wxv = product(&h.w, h.p, h.q, &hv.x, hv.p, hv.q);
        let wvx = product(&hv.w, hv.p, hv.q, &h.x, h.p, h.q);
        let diff = |s: Vec<V>, t: Vec<V>| -> Vec<V> {
            s.iter()
                .zip(&t)
                .map(|(x, y)| std::array::from_fn(|c| x[c] - y[c]))
                .collect()
        };
        (diff(wxu, wux), diff(wxv, wvx))
    };
    let mut out = Vec::with_capacity(a.len() * b.len());
    for x in &a {
        for y in &b {
            let c = cross(x, y);
            if c.iter().all(|v| v.contains_zero()) || !c.iter().all(|v| v.is_finite()) {
                return Vec::new();
            }
            out.push(c);
        }
    }
    out
}

/// Interval enclosure of a rational, outward.
fn enclose(x: &Q) -> Interval {
    let (lo, hi) = outward(x, x);
    Interval { lo, hi }
}

fn cells_of(s: &NurbsSurface<f64, 3>, depth: u32) -> Vec<Cell> {
    let exact = s.hom.map(
        |k| lift::<Q>(*k),
        |h| Hom {
            wp: lift_point(&h.wp),
            w: lift(h.w),
        },
    );
    let polynomial = s.is_polynomial();
    let mut out = Vec::new();
    for bp in exact.bezier_patches() {
        let root = IPatch {
            p: bp.patch.p,
            q: bp.patch.q,
            x: bp
                .patch
                .net
                .iter()
                .map(|h| std::array::from_fn(|c| enclose(&h.wp[c])))
                .collect(),
            w: bp.patch.net.iter().map(|h| enclose(&h.w)).collect(),
        };
        let (u0, u1, v0, v1) = (
            bp.u0.to_f64(),
            bp.u1.to_f64(),
            bp.v0.to_f64(),
            bp.v1.to_f64(),
        );
        let mut pieces = vec![(root, [u0, u1, v0, v1])];
        for _ in 0..depth {
            let mut next = Vec::with_capacity(pieces.len() * 4);
            for (p, [a0, a1, b0, b1]) in pieces {
                let (am, bm) = (0.5 * (a0 + a1), 0.5 * (b0 + b1));
                let (l, r) = p.halve(true);
                for (piece, x0, x1) in [(l, a0, am), (r, am, a1)] {
                    let (d, t) = piece.halve(false);
                    next.push((d, [x0, x1, b0, bm]));
                    next.push((t, [x0, x1, bm, b1]));
                }
            }
            pieces = next;
        }
        for (p, uv) in pieces {
            let mut lo = [f64::INFINITY; 3];
            let mut hi = [f64::NEG_INFINITY; 3];
            for (x, w) in p.x.iter().zip(&p.w) {
                for k in 0..3 {
                    let c = x[k].checked_div(*w).unwrap_or(Interval {
                        lo: f64::NEG_INFINITY,
                        hi: f64::INFINITY,
                    });
                    lo[k] = lo[k].min(c.lo);
                    hi[k] = hi[k].max(c.hi);
                }
            }
            out.push(Cell {
                uv,
                lo,
                hi,
                patch: p,
                polynomial,
                normals: std::cell::OnceCell::new(),
            });
        }
    }
    out
}

fn dot(m: &[f64; 3], v: &V) -> Interval {
    let m: V = m.map(Interval::point);
    m[0] * v[0] + m[1] * v[1] + m[2] * v[2]
}

fn unit_mean(v: &[V]) -> [f64; 3] {
    let mut s = [0.0; 3];
    for x in v {
        let f: [f64; 3] = std::array::from_fn(|k| x[k].mid());
        let l = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
        if l > 0.0 {
            for k in 0..3 {
                s[k] += f[k] / l;
            }
        }
    }
    s
}

/// Whether the two cones are proven to hold no parallel vectors (see the module comment).
fn cones_separated(a: &[V], b: &[V]) -> bool {
    if a.is_empty() || b.is_empty() {
        return false;
    }
    let (ma, mb) = (unit_mean(a), unit_mean(b));
    let na = (ma[0] * ma[0] + ma[1] * ma[1] + ma[2] * ma[2]).sqrt();
    let nb = (mb[0] * mb[0] + mb[1] * mb[1] + mb[2] * mb[2]).sqrt();
    if !(na > 0.0 && nb > 0.0) {
        return false;
    }
    let (ua, ub) = (ma.map(|c| c / na), mb.map(|c| c / nb));
    let m: [f64; 3] = std::array::from_fn(|k| ua[k] - ub[k]);
    let m2: [f64; 3] = std::array::from_fn(|k| ua[k] + ub[k]);
    let pos = |i: Interval| i.lo > 0.0;
    let neg = |i: Interval| i.hi < 0.0;
    a.iter().all(|x| pos(dot(&m, x)) && pos(dot(&m2, x)))
        && b.iter().all(|y| neg(dot(&m, y)) && pos(dot(&m2, y)))
}

fn inside(uv: &[f64; 2], c: &[f64; 4]) -> bool {
    c[0] <= uv[0] && uv[0] <= c[1] && c[2] <= uv[1] && uv[1] <= c[3]
}

/// Classify every box pair of the two surfaces.
pub fn coverage(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    depth: u32,
    branches: &[BranchOut],
) -> CoverageOut {
    let t0 = std::time::Instant::now();
    let (ca, cb) = (cells_of(sa, depth), cells_of(sb, depth));
    let mut out = CoverageOut {
        boxes_a: ca.len(),
        boxes_b: cb.len(),
        pairs: ca.len() * cb.len(),
        ..Default::default()
    };
    let mut on_branch = std::collections::HashSet::new();
    for br in branches {
        for (x, y) in br.uv_a.iter().zip(&br.uv_b) {
            for (i, c) in ca.iter().enumerate().filter(|(_, c)| inside(x, &c.uv)) {
                let _ = c;
                for (j, _) in cb.iter().enumerate().filter(|(_, d)| inside(y, &d.uv)) {
                    on_branch.insert((i, j));
                }
            }
        }
    }
    for (i, x) in ca.iter().enumerate() {
        for (j, y) in cb.iter().enumerate() {
            let disjoint = (0..3).any(|k| x.hi[k] < y.lo[k] || y.hi[k] < x.lo[k]);
            if disjoint {
                out.free += 1;
                out.free_pairs_with_branch_points += usize::from(on_branch.contains(&(i, j)));
                continue;
            }
            let loop_free = cones_separated(x.normals(), y.normals());
            let crossed = on_branch.contains(&(i, j));
            match (crossed, loop_free) {
                (true, true) => out.on_branch_loop_free += 1,
                (true, false) => out.on_branch += 1,
                (false, true) => out.loop_free += 1,
                (false, false) => out.uncertified += 1,
            }
            if !loop_free && out.uncertified_regions.len() < 100 {
                out.uncertified_regions.push(RegionOut {
                    uv_a: x.uv,
                    uv_b: y.uv,
                    on_branch: crossed,
                });
            }
        }
    }
    out.no_missed_loops = out.uncertified == 0 && out.on_branch == 0;
    out.seconds = t0.elapsed().as_secs_f64();
    out
}
