//! §3.6: the discrete error (17) and what is proven about the approximant.
//!
//! The error samples are `e_{I,J} = s((ξ_I+ξ_{I+1})/2, η_J)`, `f_{I,J} = s(ξ_I,
//! (η_J+η_{J+1})/2)` and `g_{I,J} = s((ξ_I+ξ_{I+1})/2, (η_J+η_{J+1})/2)`. A sample whose
//! neighbouring grid points (two for `e`, `f`, four for `g`) include an artificial
//! projection lies over a gap and is skipped (counted). For every other sample the
//! distance to the original surfaces is measured by projection: the nearest triangle of the
//! triangulation gives the surface and a start `(u, v)`, damped Gauss–Newton
//! ([`crate::spline::project::descend`]) finds the foot. These distances are **evidence**
//! (samples and a local search), not a bound.
//!
//! Proven (see `docs/coons.md`): (i) the approximant interpolates the grid points —
//! `d_{3I,3J} = y_{I,J}` is checked bit for bit, and a degree-3 B-spline with triple
//! interior knots takes the value of that control point at `(ξ_I, η_J)`; (ii) each boundary
//! curve of the approximant lies within the stated distance of the polyline through its
//! boundary grid points: every cubic piece lies in the convex hull of its Bézier control
//! points, whose distance to the chord is at most the larger distance of the two inner
//! control points, computed exactly in rationals and rounded up.

use super::discrete::Grid;
use super::project::OriginalMesh;
use crate::geom::{Point, dot, norm};
use crate::model::Model;
use crate::scalar::{Rational, Scalar};
use crate::spline::NurbsSurface;
use crate::spline::project::{descend, point_d1};
use rayon::prelude::*;
use serde::Serialize;

/// One error sample of (17).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Sample {
    /// `e` (u midpoint), `f` (v midpoint) or `g` (both).
    pub kind: char,
    pub i: usize,
    pub j: usize,
    /// `(ξ, η)` and the point `s(ξ, η)`.
    pub param: [f64; 2],
    pub point: [f64; 3],
    /// Over a gap: skipped.
    pub gap: bool,
    /// Measured distance to the original surfaces (`None` when skipped).
    pub distance: Option<f64>,
    /// The foot lies on the border of its surface's domain, or outside its face's trimmed
    /// region, and the sample is not perpendicular over it: the sample is beyond the
    /// original faces there.
    pub at_edge: bool,
}

/// Summary of the samples: evidence.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Evidence {
    pub samples: usize,
    pub measured: usize,
    pub skipped_gap: usize,
    /// Measured samples whose foot is on a surface's border (beyond the originals).
    pub at_edge: usize,
    /// Largest measured distance over all, `e`, `f`, `g` samples.
    pub max_error: f64,
    pub max_e: f64,
    pub max_f: f64,
    pub max_g: f64,
    /// `(ξ, η)` of the worst sample.
    pub worst: [f64; 2],
}

/// Proven facts about the approximant.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Proven {
    /// `s(ξ_I, η_J) = y_{I,J}` for every grid point (control points checked bit for bit).
    pub interpolates_grid_points: bool,
    /// Each boundary curve of the approximant lies within this distance of the polyline
    /// through its boundary grid points (convex hull, exact rationals, rounded up).
    pub boundary_hull_bound: f64,
}

fn samples_of(m: usize, n: usize) -> Vec<(char, usize, usize, [f64; 2])> {
    let (fm, fn_) = (m as f64, n as f64);
    let mut out = Vec::new();
    for i in 0..m {
        for j in 0..=n {
            out.push(('e', i, j, [(i as f64 + 0.5) / fm, j as f64 / fn_]));
        }
    }
    for i in 0..=m {
        for j in 0..n {
            out.push(('f', i, j, [i as f64 / fm, (j as f64 + 0.5) / fn_]));
        }
    }
    for i in 0..m {
        for j in 0..n {
            out.push(('g', i, j, [(i as f64 + 0.5) / fm, (j as f64 + 0.5) / fn_]));
        }
    }
    out
}

/// Distance from `p` to the original surfaces by projection, with the foot's edge flag:
/// the nearest triangle, and every other surface with a triangle about as near (within the
/// nearest triangle's size), each give a start for damped Gauss–Newton on its surface;
/// the nearest foot wins.
pub fn distance_to_originals(
    model: &Model,
    mesh: &OriginalMesh,
    p: &[f64; 3],
) -> Option<(f64, bool)> {
    let tri_dist2 = |ti: usize| {
        let [a, b, c] = mesh.triangles[ti].0.map(|i| &mesh.vertices[i as usize]);
        let (q, w) = crate::geom::triangle::closest_point(p, a, b, c);
        let d = q.sub(p);
        (dot(&d, &d), w)
    };
    let (t0, d0) = mesh.bvh.nearest(p, &mut |ti| tri_dist2(ti).0)?;
    let size = {
        let [a, b, c] = mesh.triangles[t0].0.map(|i| mesh.vertices[i as usize]);
        crate::geom::dist(&a, &b)
            .max(crate::geom::dist(&b, &c))
            .max(crate::geom::dist(&c, &a))
    };
    let reach = d0.sqrt() + size;
    // Per surface: its nearest triangle within reach.
    let mut starts: Vec<(usize, f64, usize, [f64; 3])> = Vec::new();
    mesh.bvh
        .query(&p.map(|c| c - reach), &p.map(|c| c + reach), &mut |ti| {
            let si = mesh.triangles[ti].1;
            let (d2, w) = tri_dist2(ti);
            match starts.iter_mut().find(|s| s.0 == si) {
                Some(s) if d2 < s.1 => *s = (si, d2, ti, w),
                Some(_) => {}
                None => starts.push((si, d2, ti, w)),
            }
        });
    starts.sort_by(|x, y| x.1.total_cmp(&y.1).then(x.0.cmp(&y.0)));
    let mut best: Option<(f64, bool)> = None;
    for (si, _, ti, w) in starts {
        let uvs = mesh.triangles[ti].0.map(|i| mesh.uv[i as usize]);
        let uv = [
            w[0] * uvs[0][0] + w[1] * uvs[1][0] + w[2] * uvs[2][0],
            w[0] * uvs[0][1] + w[1] * uvs[1][1] + w[2] * uvs[2][1],
        ];
        let s: &NurbsSurface<f64, 3> = &model.surfaces[si].nurbs;
        let (u0, u1, v0, v1) = s.hom.domain();
        let (uv, e) = descend(s, p, uv, &[u0, u1, v0, v1]);
        let dist = e.sqrt();
        if !dist.is_finite() || best.is_some_and(|b| b.0 <= dist) {
            continue;
        }
        let on_border = uv[0] <= u0 || uv[0] >= u1 || uv[1] <= v0 || uv[1] >= v1;
        let outside_face = !mesh.regions.contains(si, &uv);
        let at_edge = outside_face
            || on_border && {
                let (q, su, sv) = point_d1(s, uv[0], uv[1]);
                let r = p.sub(&q);
                let nr = norm(&r);
                nr > 0.0
                    && [su, sv].iter().any(|t| {
                        let nt = norm(t);
                        nt > 0.0 && (dot(&r, t) / (nr * nt)).abs() > 1e-3
                    })
            };
        best = Some((dist, at_edge));
    }
    best
}

/// Eq. (17): sample the approximant and measure; `artificial` marks grid points filled by
/// the multiquadric.
pub fn measure(
    model: &Model,
    mesh: &OriginalMesh,
    s: &NurbsSurface<f64, 3>,
    artificial: &Grid<bool>,
) -> (Vec<Sample>, Evidence) {
    let (m, n) = (artificial.m, artificial.n);
    let list = samples_of(m, n);
    let samples: Vec<Sample> = list
        .par_iter()
        .map(|&(kind, i, j, param)| {
            let nodes: Vec<(usize, usize)> = match kind {
                'e' => vec![(i, j), (i + 1, j)],
                'f' => vec![(i, j), (i, j + 1)],
                _ => vec![(i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1)],
            };
            let gap = nodes.iter().any(|&(a, b)| *artificial.at(a, b));
            let point = s.eval(&param[0], &param[1]);
            let (distance, at_edge) = if gap {
                (None, false)
            } else {
                match distance_to_originals(model, mesh, &point) {
                    Some((d, e)) => (Some(d), e),
                    None => (None, false),
                }
            };
            Sample {
                kind,
                i,
                j,
                param,
                point,
                gap,
                distance,
                at_edge,
            }
        })
        .collect();
    let mut ev = Evidence {
        samples: samples.len(),
        ..Default::default()
    };
    for sm in &samples {
        if sm.gap {
            ev.skipped_gap += 1;
        }
        if let Some(d) = sm.distance {
            ev.measured += 1;
            ev.at_edge += sm.at_edge as usize;
            if d > ev.max_error {
                ev.max_error = d;
                ev.worst = sm.param;
            }
            let slot = match sm.kind {
                'e' => &mut ev.max_e,
                'f' => &mut ev.max_f,
                _ => &mut ev.max_g,
            };
            *slot = slot.max(d);
        }
    }
    (samples, ev)
}

fn q(x: f64) -> Rational {
    Rational::try_from(x).unwrap_or_default()
}

/// Exact squared distance from `p` to segment `ab`.
fn seg_dist2_exact(p: &[f64; 3], a: &[f64; 3], b: &[f64; 3]) -> Rational {
    let (p, a, b) = (p.map(q), a.map(q), b.map(q));
    let ab: Vec<Rational> = (0..3).map(|k| &b[k] - &a[k]).collect();
    let ap: Vec<Rational> = (0..3).map(|k| &p[k] - &a[k]).collect();
    let l2 = ab.iter().fold(Rational::ZERO, |s, x| s + x * x);
    let dot = ab
        .iter()
        .zip(&ap)
        .fold(Rational::ZERO, |s, (x, y)| s + x * y);
    let t = if l2.is_zero() || dot <= Rational::ZERO {
        Rational::ZERO
    } else if dot >= l2 {
        Rational::ONE
    } else {
        dot / l2
    };
    (0..3).fold(Rational::ZERO, |s, k| {
        let d = &ap[k] - &t * &ab[k];
        s + &d * &d
    })
}

/// An `f64` at least `sqrt(x)`: each rounding checked exactly and bumped up if short.
fn sqrt_up(x: &Rational) -> f64 {
    let mut f = Scalar::to_f64(x);
    while f.is_finite() && q(f) < *x {
        f = f.next_up();
    }
    let mut r = f.sqrt();
    while r.is_finite() && q(r) * q(r) < q(f) {
        r = r.next_up();
    }
    r
}

/// The proven facts (i) and (ii) for the interpolant `s` of `y` (see the module docs).
/// Not finite control points give `false` and an infinite bound.
pub fn prove(s: &NurbsSurface<f64, 3>, y: &Grid<[f64; 3]>) -> Proven {
    let (m, n) = (y.m, y.n);
    let cv = 3 * n + 1;
    let (pts, w) = s.points_weights();
    let interpolates = w.iter().all(|w| *w == 1.0)
        && (0..=m).all(|i| (0..=n).all(|j| pts[3 * i * cv + 3 * j] == *y.at(i, j)));
    let at = |i: usize, j: usize| pts[i * cv + j];
    let mut worst = Rational::ZERO;
    let mut piece = |b: [[f64; 3]; 4]| {
        for inner in [b[1], b[2]] {
            let d = seg_dist2_exact(&inner, &b[0], &b[3]);
            if d > worst {
                worst = d;
            }
        }
    };
    for i in 0..m {
        for j in [0, 3 * n] {
            piece([0, 1, 2, 3].map(|k| at(3 * i + k, j)));
        }
    }
    for j in 0..n {
        for i in [0, 3 * m] {
            piece([0, 1, 2, 3].map(|k| at(i, 3 * j + k)));
        }
    }
    Proven {
        interpolates_grid_points: interpolates,
        boundary_hull_bound: sqrt_up(&worst),
    }
}
