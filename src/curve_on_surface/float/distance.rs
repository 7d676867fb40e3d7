//! Steps 3–4, f64 path — the certified Hausdorff bound of each segment and the subdivision
//! at the farthest point until `K · h ≤ ε_D`.
//!
//! For segment `i` (chord `[a, b]`, curve piece `D[t_0, t_1]`, f64 parameters):
//! * `h ≤ max_j dist(Q_j, [a, b]) + max(e_a, e_b)`, where `Q_j` are enclosures of the exact
//!   control points of `D[t_0, t_1]` (blossoms; subdivided up to `2^HULL_LEVELS` times to
//!   tighten) — distance to a segment is convex, so the curve is within the largest control
//!   point distance of the chord (convex hull property); the curve's clamped projection onto
//!   the chord runs continuously from within `e_a` of `a` to within `e_b` of `b` (`e` = proven
//!   distance of a vertex from the curve point `D(t)` it stands for), so every chord point is
//!   within `max_j dist + max(e)` of the curve;
//! * `K` bounds the Lipschitz constant of S on the rectangle `R` that holds the enclosures
//!   and the chord (intersected with the domain, which holds the exact curve and chord):
//!   eq. (12) or the local hodograph bound, on every cell `R` meets;
//! * then `|S(x) - S(y)| ≤ K |x - y|` on the convex `R` gives Hausdorff
//!   `(S(chord), S(D[t_0, t_1])) ≤ K · h` (eq. 11).
//!
//! The union over segments covers `S(D)` and the output curve, so the largest `K · h` bounds
//! the Hausdorff distance of the whole curve.

use super::cells::FCells;
use super::ibez::{I, dist_to_segment_mr, mid, mr_levels_error, mr_polar_values};
use super::{FSeg, FloatError, Piece};
use crate::curve_on_surface::CosInternal;
use crate::curve_on_surface::{Bound, CosError};

/// Subdivision levels used to tighten the hull bound.
pub const HULL_LEVELS: u32 = 3;

/// The control points of `D[t_0, t_1]` of a segment in midpoint–radius form: every exact
/// control point lies within `r` of its midpoint in every coordinate; `mx` bounds the
/// midpoints' magnitude.
#[derive(Clone, Debug)]
pub struct SubCurve {
    pub m: Vec<[f64; 2]>,
    pub r: f64,
    pub mx: f64,
}

/// [`SubCurve`] of a segment: polar values of its piece at `t_0`, `t_1` (exact f64 in
/// `[0, 1]`), `n` de Casteljau levels on the piece's midpoints.
pub fn sub_curve(s: &FSeg, pieces: &[Piece]) -> SubCurve {
    let mut c = SubCurve {
        m: Vec::new(),
        r: 0.0,
        mx: 0.0,
    };
    sub_curve_into(s, pieces, &mut c);
    c
}

/// [`sub_curve`] into `c`, reusing its storage.
pub fn sub_curve_into(s: &FSeg, pieces: &[Piece], c: &mut SubCurve) {
    let p = &pieces[s.piece];
    let n = p.ctrl_f64.len() - 1;
    c.m.clear();
    mr_polar_values(&p.ctrl_f64, s.t0, s.t1, &mut c.m);
    c.r = mr_levels_error(p.ctrl_r, n, p.ctrl_mx);
    c.mx = p.ctrl_mx * (1.0 + 1e-13);
}

/// De Casteljau halves at 1/2 in f64 of `c` (the caller adds `n` levels of error), appended
/// to `out` (left then right); `w` is scratch.
fn halves_f64(c: &[[f64; 2]], w: &mut Vec<[f64; 2]>, out: &mut Vec<[f64; 2]>) {
    let n = c.len() - 1;
    w.clear();
    w.extend_from_slice(c);
    let start = out.len();
    out.resize(start + 2 * (n + 1), c[n]);
    out[start] = w[0];
    for r in 1..=n {
        for i in 0..=n - r {
            for k in 0..2 {
                w[i][k] = 0.5 * w[i][k] + 0.5 * w[i + 1][k];
            }
        }
        out[start + r] = w[0];
        out[start + n + 1 + n - r] = w[n - r];
    }
}

/// Scratch storage of `hull_bound`, kept across segments.
#[derive(Default)]
pub struct HullScratch {
    parts: Vec<[f64; 2]>,
    next: Vec<[f64; 2]>,
    w: Vec<[f64; 2]>,
}

/// Certified `h` (stopping once `≤ target`) for the curve piece `c` and the chord: the
/// halving levels run in f64 on midpoints, each adding the error of `n` de Casteljau levels
/// (values stay within the hull, so `mx` bounds them).
fn hull_bound(
    c: &SubCurve,
    a: &[f64; 2],
    b: &[f64; 2],
    e: f64,
    target: f64,
    scratch: &mut HullScratch,
) -> f64 {
    let n1 = c.m.len();
    let n = n1 - 1;
    let HullScratch { parts, next, w } = scratch;
    parts.clear();
    parts.extend_from_slice(&c.m);
    let mut r = c.r;
    let mut best = f64::INFINITY;
    for level in 0..=HULL_LEVELS {
        let m = parts
            .iter()
            .map(|q| dist_to_segment_mr(q, r, a, b))
            .fold(0.0, f64::max);
        best = best.min((m + e).next_up());
        if best <= target || level == HULL_LEVELS {
            break;
        }
        next.clear();
        for p in parts.chunks_exact(n1) {
            halves_f64(p, w, next);
        }
        std::mem::swap(parts, next);
        r = mr_levels_error(r, n, c.mx * (1.0 + 1e-12));
    }
    best
}

/// The rectangle holding the curve piece (its control points' boxes) and the chord, within
/// the domain.
fn region(c: &SubCurve, s: &FSeg, dom: [f64; 4]) -> [f64; 4] {
    let mut r = [
        s.a[0].min(s.b[0]),
        s.a[0].max(s.b[0]),
        s.a[1].min(s.b[1]),
        s.a[1].max(s.b[1]),
    ];
    for q in &c.m {
        r[0] = r[0].min((q[0] - c.r).next_down());
        r[1] = r[1].max((q[0] + c.r).next_up());
        r[2] = r[2].min((q[1] - c.r).next_down());
        r[3] = r[3].max((q[1] + c.r).next_up());
    }
    [
        r[0].max(dom[0]),
        r[1].min(dom[1]),
        r[2].max(dom[2]),
        r[3].min(dom[3]),
    ]
}

/// `K` on the rectangle `r`.
fn lipschitz(r: [f64; 4], cells: &FCells, bound: Bound) -> Result<f64, FloatError> {
    cells
        .lipschitz_on(r, bound == Bound::Local)
        .map_err(FloatError::from)
}

/// Whether rectangle `inner` lies in `outer`.
fn within(inner: &[f64; 4], outer: &[f64; 4]) -> bool {
    outer[0] <= inner[0] && inner[1] <= outer[1] && outer[2] <= inner[2] && inner[3] <= outer[3]
}

/// Certify segment `s` (its `h`, and a `K` valid on a rectangle holding its curve piece and
/// chord): the inherited `K` is used when its region holds the segment's and it suffices;
/// otherwise the segment's own (tighter) `K` is computed.
/// Returns `false` without certifying when the f64 estimate `h_est` (from below) already
/// shows that `K · h > ε_D` with the segment's own `K`: the segment must be split.
fn certify(
    s: &mut FSeg,
    c: &SubCurve,
    h_est: f64,
    cells: &FCells,
    (eps_d, bound): (f64, Bound),
    scratch: &mut HullScratch,
) -> Result<bool, FloatError> {
    let r = region(c, s, cells.domain());
    if !(s.k.is_finite() && within(&r, &s.k_region)) {
        s.k = lipschitz(r, cells, bound)?;
        s.k_region = r;
        s.k_own = true;
    }
    let hopeless = |k: f64| k * h_est > eps_d * (1.0 + 1e-9);
    // An inherited bound far above what is needed: the segment's own bound (on a smaller
    // region) is rarely less than half of it, so split without computing it (a choice of
    // where to refine, never a certificate).
    if !s.k_own && s.k * h_est > 2.0 * eps_d {
        return Ok(false);
    }
    if hopeless(s.k) && !s.k_own {
        s.k = lipschitz(r, cells, bound)?;
        s.k_region = r;
        s.k_own = true;
    }
    if hopeless(s.k) {
        return Ok(false);
    }
    let d = crate::curve_on_surface::tolerance::tolerance_2d(eps_d, s.k);
    s.h = hull_bound(c, &s.a, &s.b, s.ea.max(s.eb), d, scratch);
    if (s.k * s.h).next_up() > eps_d && !s.k_own {
        s.k = lipschitz(r, cells, bound)?;
        s.k_region = r;
        s.k_own = true;
        // `hull_bound` stopped at a smaller target or ran all its levels: its value stands.
    }
    Ok(true)
}

/// The parameter in `(0, 1)` of the point of the piece (f64 control points) farthest from
/// its chord's line: roots of `f'(t)` (eq. 15: tangent parallel to the chord), bracketed on
/// 64 samples and bisected in f64, the one with the largest `|f|`; `1/2` when none. A choice
/// of where to split, not a claim.
pub fn farthest_parameter(c: &[[f64; 2]]) -> f64 {
    farthest(c).0
}

/// [`farthest_parameter`] and the distance of that point from the chord's line (f64, an
/// estimate from below of the piece's distance from its chord: used only to decide that a
/// segment must be split, never to certify one).
pub fn farthest(c: &[[f64; 2]]) -> (f64, f64) {
    let n = c.len() - 1;
    if n < 2 {
        return (0.5, 0.0);
    }
    let chord = [c[n][0] - c[0][0], c[n][1] - c[0][1]];
    let (mut b_buf, mut b_heap) = ([0.0; 32], Vec::new());
    let b = small_buf(&mut b_buf, &mut b_heap, n + 1);
    for (bi, p) in b.iter_mut().zip(c) {
        *bi = (p[0] - c[0][0]) * chord[1] - (p[1] - c[0][1]) * chord[0];
    }
    let (mut db_buf, mut db_heap) = ([0.0; 32], Vec::new());
    let db = small_buf(&mut db_buf, &mut db_heap, n);
    for (d, w) in db.iter_mut().zip(b.windows(2)) {
        *d = w[1] - w[0];
    }
    let (b, db) = (&*b, &*db);
    let bern = |coef: &[f64], t: f64| {
        let (mut buf, mut heap) = ([0.0; 32], Vec::new());
        let w = small_buf(&mut buf, &mut heap, coef.len());
        w.copy_from_slice(coef);
        for r in 1..w.len() {
            for i in 0..w.len() - r {
                w[i] = (1.0 - t) * w[i] + t * w[i + 1];
            }
        }
        w[0]
    };
    let mut best = (-1.0, 0.5);
    if n == 2 || n == 3 {
        // f' has degree ≤ 2: its roots in closed form (power basis from Bernstein).
        let (c0, c1, c2) = if n == 2 {
            (db[0], db[1] - db[0], 0.0)
        } else {
            (db[0], 2.0 * (db[1] - db[0]), db[0] - 2.0 * db[1] + db[2])
        };
        let mut roots: arrayvec::ArrayVec<f64, 2> = arrayvec::ArrayVec::new();
        if c2 == 0.0 {
            if c1 != 0.0 {
                roots.push(-c0 / c1);
            }
        } else {
            let disc = c1 * c1 - 4.0 * c2 * c0;
            if disc >= 0.0 {
                let sq = disc.sqrt();
                let q = -0.5 * (c1 + c1.signum() * sq);
                roots.push(q / c2);
                if q != 0.0 {
                    roots.push(c0 / q);
                }
            }
        }
        for t in roots {
            if t > 0.0 && t < 1.0 {
                let f = bern(b, t).abs();
                if f > best.0 {
                    best = (f, t);
                }
            }
        }
        let len = (chord[0] * chord[0] + chord[1] * chord[1]).sqrt();
        let dist = if len > 0.0 {
            best.0.max(0.0) / len
        } else {
            0.0
        };
        return (best.1.clamp(1.0 / 64.0, 63.0 / 64.0), dist);
    }
    let k = 64;
    let mut prev = bern(db, 0.0);
    for i in 1..=k {
        let t1 = i as f64 / k as f64;
        let cur = bern(db, t1);
        if prev == 0.0 || prev.signum() != cur.signum() {
            let (mut lo, mut hi) = ((i - 1) as f64 / k as f64, t1);
            let slo = prev.signum();
            for _ in 0..60 {
                let m = 0.5 * (lo + hi);
                if bern(db, m).signum() == slo {
                    lo = m;
                } else {
                    hi = m;
                }
            }
            let t = 0.5 * (lo + hi);
            let f = bern(b, t).abs();
            if t > 0.0 && t < 1.0 && f > best.0 {
                best = (f, t);
            }
        }
        prev = cur;
    }
    let len = (chord[0] * chord[0] + chord[1] * chord[1]).sqrt();
    let dist = if len > 0.0 {
        best.0.max(0.0) / len
    } else {
        0.0
    };
    (best.1.clamp(1.0 / 64.0, 63.0 / 64.0), dist)
}

/// `n` zeros in `buf` when they fit, else in `heap`.
fn small_buf<'a>(buf: &'a mut [f64; 32], heap: &'a mut Vec<f64>, n: usize) -> &'a mut [f64] {
    if n <= buf.len() {
        &mut buf[..n]
    } else {
        heap.resize(n, 0.0);
        heap
    }
}

/// Split a segment at local parameter `s`; the new vertex is the midpoint of the enclosure
/// of the curve point, kept in the segment's cell, with its proven offset.
pub fn split_at(seg: &FSeg, s: f64, pieces: &[Piece], cells: &FCells) -> Option<(FSeg, FSeg)> {
    let t = seg.t0 + (seg.t1 - seg.t0) * s;
    if !(t > seg.t0 && t < seg.t1) {
        return None;
    }
    let e = super::ibez::eval(&pieces[seg.piece].ctrl, I::point(t));
    let v = cells.clamp(seg.cell, &mid(&e));
    let off = super::ibez::dist_hi(&e, &v);
    // The children keep the parent's `K` (and the region it holds on) until they need a
    // tighter one of their own.
    let left = FSeg {
        t1: t,
        b: v,
        eb: off,
        h: f64::INFINITY,
        k_own: false,
        ..*seg
    };
    let right = FSeg {
        t0: t,
        a: v,
        ea: off,
        h: f64::INFINITY,
        k_own: false,
        ..*seg
    };
    Some((left, right))
}

/// Compute `h`, `K` for every segment whose bound is unknown; split those with
/// `K · h > ε_D` at their farthest point.
pub fn enforce_distance(
    mut segs: Vec<FSeg>,
    pieces: &[Piece],
    cells: &FCells,
    eps_d: f64,
    bound: Bound,
    max_segments: usize,
) -> Result<Vec<FSeg>, FloatError> {
    let mut c = SubCurve {
        m: Vec::new(),
        r: 0.0,
        mx: 0.0,
    };
    let mut scratch = HullScratch::default();
    loop {
        let mut out = Vec::with_capacity(segs.len() * 2);
        let mut changed = false;
        for mut s in segs {
            if !s.h.is_infinite() && (s.k * s.h).next_up() <= eps_d {
                out.push(s);
                continue;
            }
            sub_curve_into(&s, pieces, &mut c);
            let (t_far, h_est) = farthest(&c.m);
            if s.h.is_infinite()
                && !certify(&mut s, &c, h_est, cells, (eps_d, bound), &mut scratch)?
            {
                s.h = f64::INFINITY;
            }
            if (s.k * s.h).next_up() <= eps_d {
                out.push(s);
                continue;
            }
            changed = true;
            let (l, r) = split_at(&s, t_far, pieces, cells).ok_or_else(|| {
                FloatError::Cos(
                    CosInternal::Unsplittable {
                        t: [s.t0, s.t1],
                        bound: s.k * s.h,
                    }
                    .into(),
                )
            })?;
            out.push(l);
            out.push(r);
        }
        if out.len() > max_segments {
            return Err(FloatError::Cos(CosError::TooManySegments(max_segments)));
        }
        segs = out;
        if !changed {
            return Ok(segs);
        }
    }
}
