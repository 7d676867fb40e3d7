//! The parameter-space region of a trimmed face: its loops' sample points projected onto the
//! surface, unwrapped across seams (periodic surfaces), poles expanded into lines, and loops
//! that wind around a periodic direction closed into one polygon — two winding loops (a band)
//! joined by a cut, one winding loop joined to the pole line it encloses. The cut and pole
//! points get their own mesh vertices, each shared by the two copies of the cut, so the face's
//! triangulation closes across the seam.

use crate::geom::{Point, dist};
use crate::spline::NurbsSurface;
use crate::spline::closure::Closure;
use crate::spline::project::{descend, project};

/// A boundary point of a face: where it lies in the (unwrapped) parameter plane, which mesh
/// vertex it is, and, when the boundary segment to the next point follows an edge, the
/// parameter point of the edge's middle between the two (for the area between chord and
/// curve).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundaryPoint {
    pub uv: [f64; 2],
    pub vertex: usize,
    pub mid: Option<[f64; 2]>,
}

impl BoundaryPoint {
    /// A point on a cut or pole line (straight in the parameter plane: no middle point).
    pub fn straight(uv: [f64; 2], vertex: usize) -> Self {
        BoundaryPoint {
            uv,
            vertex,
            mid: None,
        }
    }
    /// Moved by `s` in parameter direction `d` (with its middle point).
    pub fn shifted(mut self, d: usize, s: f64) -> Self {
        self.uv[d] += s;
        if let Some(m) = &mut self.mid {
            m[d] += s;
        }
        self
    }
}

/// The surface of a face with what the domain construction needs of it.
pub struct FaceSurface<'a> {
    pub s: &'a NurbsSurface<f64, 3>,
    pub closure: Closure,
    /// `[u0, u1, v0, v1]`.
    pub domain: [f64; 4],
    /// Period of each parameter (`None` when the surface is not closed in it).
    pub period: [Option<f64>; 2],
    /// Distances below this count as zero (model size × 1e-9).
    pub eps: f64,
}

impl<'a> FaceSurface<'a> {
    pub fn new(s: &'a NurbsSurface<f64, 3>, size: f64) -> Self {
        let closure = Closure::of(s);
        let (u0, u1, v0, v1) = s.hom.domain();
        FaceSurface {
            s,
            closure,
            domain: [u0, u1, v0, v1],
            period: [
                closure.seam_u.then_some(u1 - u0),
                closure.seam_v.then_some(v1 - v0),
            ],
            eps: size * 1e-9,
        }
    }
    /// `S(u, v)` with periodic parameters reduced into the domain and the others clamped.
    pub fn eval(&self, uv: &[f64; 2]) -> [f64; 3] {
        let mut p = *uv;
        for d in 0..2 {
            let (lo, hi) = (self.domain[2 * d], self.domain[2 * d + 1]);
            p[d] = match self.period[d] {
                Some(per) => (lo + (p[d] - lo).rem_euclid(per)).min(hi),
                None => p[d].clamp(lo, hi),
            };
        }
        self.s.eval(&p[0], &p[1])
    }
    /// Parameters of `x`, searched first from `near`.
    fn project(&self, x: &[f64; 3], near: Option<[f64; 2]>) -> [f64; 2] {
        if let Some(n) = near {
            let (uv, e2) = descend(self.s, x, n, &self.domain);
            if e2.sqrt() <= self.eps * 1e3 {
                return uv;
            }
        }
        project(self.s, x)
    }
    /// The parameter left free at `x` when it is the pole of a degenerate border (`Some(d)`:
    /// coordinate `d` is undefined there).
    fn free_at(&self, x: &[f64; 3]) -> Option<usize> {
        (0..4).find_map(|side| {
            (self.closure.degenerate[side]
                && dist(&Closure::pole(self.s, side), x) <= self.eps * 1e3)
                .then_some(if side < 2 { 1 } else { 0 })
        })
    }
    /// The degenerate border on side `side` (0: u=u0, 1: u=u1, 2: v=v0, 3: v=v1), if a pole.
    pub fn pole(&self, side: usize) -> Option<[f64; 3]> {
        self.closure.degenerate[side].then(|| Closure::pole(self.s, side))
    }
}

/// A loop in the parameter plane and how many times it winds around each periodic direction.
#[derive(Clone, Debug)]
pub struct Ring {
    pub points: Vec<BoundaryPoint>,
    pub winding: [i64; 2],
}

impl Ring {
    /// The same loop starting at its point `i` (the points before it follow, moved on by the
    /// loop's winding times the periods: the loop stays unwrapped).
    pub fn starting_at(&self, i: usize, period: [Option<f64>; 2]) -> Ring {
        let i = i % self.points.len().max(1);
        let mut points = self.points[i..].to_vec();
        points.extend(self.points[..i].iter().map(|p| {
            let mut q = *p;
            for d in 0..2 {
                q = q.shifted(d, self.winding[d] as f64 * period[d].unwrap_or(0.0));
            }
            q
        }));
        Ring {
            points,
            winding: self.winding,
        }
    }
}

/// Project a loop's points `(vertex, point)` (closed: the last joins the first), unwrap
/// across seams and expand pole points into pole lines. `breaks[i]`: point `i` begins the
/// second traversal of a seam edge of the face, whose copy lies one period from the first:
/// there the parameter jumps by a period (the sign that brings the loop's winding towards
/// zero) instead of continuing.
///
/// `mids[i]`: the edge's point halfway (in its parameter) between points `i` and `i + 1`.
pub fn ring(
    fs: &FaceSurface,
    pts: &[(usize, [f64; 3])],
    mids: &[Option<[f64; 3]>],
    breaks: &[bool],
) -> Ring {
    let mut raw: Vec<(usize, [f64; 2], Option<usize>)> = Vec::with_capacity(pts.len());
    let mut prev = None;
    for (v, x) in pts {
        let uv = fs.project(x, prev);
        let free = fs.free_at(x);
        if free.is_none() {
            prev = Some(uv);
        }
        raw.push((*v, uv, free));
    }
    let mut winding = [0i64; 2];
    for d in 0..2 {
        let Some(per) = fs.period[d] else { continue };
        // Continuous unwrapping, remembering where the breaks are.
        let unwrap = |raw: &mut Vec<(usize, [f64; 2], Option<usize>)>, jumps: &[(usize, f64)]| {
            let mut last: Option<f64> = None;
            let mut first: Option<f64> = None;
            let mut pending = false;
            let mut at_break = Vec::new();
            for (i, (_, uv, free)) in raw.iter_mut().enumerate() {
                pending |= breaks.get(i).copied().unwrap_or(false);
                if *free == Some(d) {
                    continue;
                }
                if let Some(l) = last {
                    uv[d] += ((l - uv[d]) / per).round() * per;
                }
                if pending {
                    at_break.push(i);
                    pending = false;
                }
                if let Some((_, j)) = jumps.iter().find(|(k, _)| *k == i) {
                    uv[d] += j;
                }
                last = Some(uv[d]);
                first.get_or_insert(uv[d]);
            }
            let w = match (first, last) {
                (Some(f), Some(l)) => ((l - f) / per).round() as i64,
                _ => 0,
            };
            (w, at_break)
        };
        let saved = raw.clone();
        let (w0, at_break) = unwrap(&mut raw, &[]);
        winding[d] = w0;
        if w0 != 0 && !at_break.is_empty() {
            // Each break jumps one period against the remaining winding.
            let mut left = w0;
            let mut jumps = Vec::new();
            for i in at_break {
                if left == 0 {
                    break;
                }
                jumps.push((i, -(left.signum() as f64) * per));
                left -= left.signum();
            }
            let continuous = std::mem::replace(&mut raw, saved);
            winding[d] = unwrap(&mut raw, &jumps).0;
            // A loop through a pole where `d` is free can close through the pole line
            // instead: a cap bounded by a seam traversed up and back and a circle between
            // the traversals needs no jump (the circle already puts the copies a period
            // apart), while one whose traversals meet at the pole does. Of the two, the
            // jumps that lay the seam's copies on top of each other give a polygon of no
            // area: the larger one is kept.
            if raw.iter().any(|r| r.2 == Some(d)) {
                let area = |r: &[(usize, [f64; 2], Option<usize>)]| {
                    let q: Vec<[f64; 2]> =
                        r.iter().filter(|x| x.2.is_none()).map(|x| x.1).collect();
                    let n = q.len();
                    (0..n)
                        .map(|i| {
                            let (a, b) = (q[i], q[(i + 1) % n]);
                            a[0] * b[1] - a[1] * b[0]
                        })
                        .sum::<f64>()
                        .abs()
                };
                if area(&continuous) > area(&raw) {
                    raw = continuous;
                    winding[d] = 0;
                }
            }
        }
    }
    // Middle points, projected near their segment and unwrapped next to its start.
    let n = raw.len();
    let mid_uv = |i: usize| -> Option<[f64; 2]> {
        let x = mids.get(i).copied().flatten()?;
        let (a, b) = (raw[i].1, raw[(i + 1) % n].1);
        let start = if raw[i].2.is_some() { b } else { a };
        let mut m = fs.project(&x, Some(start));
        for d in 0..2 {
            if let Some(per) = fs.period[d] {
                m[d] += ((start[d] - m[d]) / per).round() * per;
            }
        }
        // A middle point is only used where it sits between its ends (not across a pole).
        let spread = (a[0] - b[0]).abs().max((a[1] - b[1]).abs());
        let off = (m[0] - (a[0] + b[0]) / 2.0)
            .abs()
            .max((m[1] - (a[1] + b[1]) / 2.0).abs());
        (raw[i].2.is_none() && raw[(i + 1) % n].2.is_none() && off <= spread).then_some(m)
    };
    // Pole points: the free coordinate runs from the previous point's to the next one's.
    let mut points = Vec::with_capacity(n + 4);
    for i in 0..n {
        let (v, uv, free) = raw[i];
        let Some(d) = free else {
            points.push(BoundaryPoint {
                uv,
                vertex: v,
                mid: mid_uv(i),
            });
            continue;
        };
        let find = |step: isize| {
            (1..n).find_map(|k| {
                let j = (i as isize + step * k as isize).rem_euclid(n as isize) as usize;
                (raw[j].2 != Some(d)).then_some(raw[j].1[d])
            })
        };
        let (a, b) = (find(-1).unwrap_or(uv[d]), find(1).unwrap_or(uv[d]));
        let mut p = uv;
        p[d] = a;
        points.push(BoundaryPoint::straight(p, v));
        if b != a {
            p[d] = b;
            points.push(BoundaryPoint::straight(p, v));
        }
    }
    Ring { points, winding }
}

/// Signed area of a closed polygon (positive counter-clockwise).
pub fn signed_area(p: &[BoundaryPoint]) -> f64 {
    let n = p.len();
    (0..n)
        .map(|i| {
            let (a, b) = (p[i].uv, p[(i + 1) % n].uv);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
        / 2.0
}

/// `count` points strictly between `a` and `b` on the parameter-plane segment, each a new mesh
/// vertex at its surface point (`add` makes the vertex).
pub fn cut_points(
    fs: &FaceSurface,
    a: [f64; 2],
    b: [f64; 2],
    count: usize,
    add: &mut dyn FnMut([f64; 3]) -> usize,
) -> Vec<BoundaryPoint> {
    (1..=count)
        .map(|i| {
            let t = i as f64 / (count + 1) as f64;
            let uv = [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t];
            BoundaryPoint::straight(uv, add(fs.eval(&uv)))
        })
        .collect()
}

/// A band: `a` winds once around direction `d`, `b` the other way; joined into one polygon by
/// a cut from `a`'s first point to the nearest point of `b` (the cut's two copies, one period
/// apart, share their vertices). `cuts` interior points on the cut.
pub fn join_band(
    fs: &FaceSurface,
    d: usize,
    a: &Ring,
    b: &Ring,
    cuts: usize,
    add: &mut dyn FnMut([f64; 3]) -> usize,
) -> Vec<BoundaryPoint> {
    let per = fs.period[d].unwrap_or(0.0);
    let kb = b.winding[d] as f64;
    let a0 = a.points[0];
    let mut a_end = BoundaryPoint::straight(a0.uv, a0.vertex);
    a_end.uv[d] += a.winding[d] as f64 * per;
    // The point of b nearest (in d, modulo the period) to a's closing copy, shifted there.
    let (j, shift) = b
        .points
        .iter()
        .enumerate()
        .map(|(j, p)| {
            let s = ((a_end.uv[d] - p.uv[d]) / per).round() * per;
            (
                j,
                s,
                (p.uv[d] + s - a_end.uv[d]).abs() + 1e-3 * (p.uv[1 - d] - a_end.uv[1 - d]).abs(),
            )
        })
        .min_by(|x, y| x.2.total_cmp(&y.2))
        .map(|(j, s, _)| (j, s))
        .unwrap_or((0, 0.0));
    let nb = b.points.len();
    let mut out: Vec<BoundaryPoint> = a.points.clone();
    out.push(a_end);
    let bj = b.points[j].shifted(d, shift);
    let cut = cut_points(fs, a_end.uv, bj.uv, cuts, add);
    out.extend(cut.iter().copied());
    // Around b from j back to j (one period on), then the cut's copy back to a's start.
    let mut unwrap = 0.0;
    for k in 0..=nb {
        let i = (j + k) % nb;
        if k > 0 && i == 0 {
            unwrap = kb * per;
        }
        let mut p = b.points[i].shifted(d, shift + unwrap);
        if k == nb {
            p = BoundaryPoint::straight(bj.uv, bj.vertex).shifted(d, kb * per);
        }
        out.push(p);
    }
    let back = out.last().map_or(bj.uv, |p| p.uv);
    for c in cut.iter().rev() {
        let t = [c.uv[0] - bj.uv[0] + back[0], c.uv[1] - bj.uv[1] + back[1]];
        out.push(BoundaryPoint::straight(t, c.vertex));
    }
    out
}

/// One loop winding around direction `d`, the region on its left closed by the pole line on
/// border `side`: loop, meridian to the pole, pole line back one period, meridian down. The
/// meridian's two copies share vertices; the pole points are all `pole_vertex`.
pub fn join_pole(
    fs: &FaceSurface,
    d: usize,
    a: &Ring,
    side: usize,
    pole_vertex: usize,
    cuts: usize,
    add: &mut dyn FnMut([f64; 3]) -> usize,
) -> Vec<BoundaryPoint> {
    let per = fs.period[d].unwrap_or(0.0);
    let a0 = a.points[0];
    let mut a_end = BoundaryPoint::straight(a0.uv, a0.vertex);
    a_end.uv[d] += a.winding[d] as f64 * per;
    let pole_coord = fs.domain[side];
    let mut p_end = a_end.uv;
    p_end[1 - d] = pole_coord;
    let mut out = a.points.clone();
    out.push(a_end);
    let cut = cut_points(fs, a_end.uv, p_end, cuts, add);
    out.extend(cut.iter().copied());
    // The pole line, sampled like the cut so the fan at the pole is not one sliver.
    let steps = cuts.max(2) + 1;
    for i in 0..=steps {
        let t = i as f64 / steps as f64;
        let mut uv = p_end;
        uv[d] = a_end.uv[d] + (a0.uv[d] - a_end.uv[d]) * t;
        out.push(BoundaryPoint::straight(uv, pole_vertex));
    }
    for c in cut.iter().rev() {
        let mut uv = c.uv;
        uv[d] -= a.winding[d] as f64 * per;
        out.push(BoundaryPoint::straight(uv, c.vertex));
    }
    out
}

/// Even-odd test of `x` against closed polygons.
pub fn inside(polys: &[Vec<BoundaryPoint>], x: &[f64; 2]) -> bool {
    let mut c = false;
    for p in polys {
        let n = p.len();
        for i in 0..n {
            let (a, b) = (p[i].uv, p[(i + 1) % n].uv);
            if (a[1] > x[1]) != (b[1] > x[1]) {
                let t = (x[1] - a[1]) / (b[1] - a[1]);
                if x[0] < a[0] + t * (b[0] - a[0]) {
                    c = !c;
                }
            }
        }
    }
    c
}

/// Shift a non-winding ring by whole periods so that its lowest point lies in `[lo, lo + per)`
/// in each periodic direction (a ring whose range does not hold `lo` modulo the period then
/// lies between `lo` and `lo + per`, where a band's cut lines are).
pub fn shift_into(fs: &FaceSurface, r: &mut [BoundaryPoint], lo: [f64; 2]) {
    for d in 0..2 {
        if let Some(per) = fs.period[d] {
            let min = r.iter().map(|p| p.uv[d]).fold(f64::INFINITY, f64::min);
            if !min.is_finite() {
                continue;
            }
            let s = ((min - lo[d]) / per).floor() * per;
            for p in r.iter_mut() {
                *p = p.shifted(d, -s);
            }
        }
    }
}

/// Distance from `x` to the segment `a b` in the plane.
pub fn seg_dist(x: &[f64; 2], a: &[f64; 2], b: &[f64; 2]) -> f64 {
    let ab = b.sub(a);
    let l2 = ab[0] * ab[0] + ab[1] * ab[1];
    let t = if l2 > 0.0 {
        (((x[0] - a[0]) * ab[0] + (x[1] - a[1]) * ab[1]) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let q = [a[0] + t * ab[0], a[1] + t * ab[1]];
    ((x[0] - q[0]).powi(2) + (x[1] - q[1]).powi(2)).sqrt()
}
