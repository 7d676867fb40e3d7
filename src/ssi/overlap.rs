//! Overlapping curved surfaces (measured, not proven): where two surfaces share a piece of
//! area — the same cylinder over overlapping angle ranges, a surface and a differently
//! parametrized piece of it — their intersection is a region, and the curve pipeline returns
//! hundreds of meaningless branches and touch points while the coverage certificate refuses
//! (normals parallel). [`super::coincide`] proves the identical and coplanar cases exactly;
//! this module diagnoses the rest.
//!
//! Test: a 17×17 grid of parameter points of each surface is projected onto the other (local
//! closest point from grid starts, [`crate::spline::project`]). A grid point is an *overlap
//! sample* when its distance to the other surface is at most the run's tolerance and the two
//! normals there are parallel within 1e-6 rad. Two surfaces *overlap* when some 2×2 block of
//! adjacent grid points are all overlap samples — a two-dimensional patch of area, which a
//! touching point or a tangent curve (contact along a line) does not give. This is evidence:
//! sampled, with a local search; it is run only for pairs whose coverage is already refused
//! with parallel normals, and it never turns a refused certificate into a proven one.
//!
//! When the test holds, the pair is reported `coincident` with kind `overlap` (the boxes of
//! the overlap samples in both parameter planes, the count, the largest distance), and the
//! branches and touch points lying wholly inside those boxes (widened by one grid step) are
//! removed and counted: they are artefacts of intersecting a surface with itself.

use super::coincide::{CoincidenceKind, CoincidenceOut};
use super::report::PairOut;
use crate::geom::{cross, dist, norm};
use crate::spline::NurbsSurface;
use crate::spline::project::{point_d1, project};

/// An overlap sample: its parameters on the gridded surface, on the other, its distance.
type Sample = ([f64; 2], [f64; 2], f64);

/// Grid points per direction.
const GRID: usize = 17;
/// Largest angle between the normals at an overlap sample (radians).
const PARALLEL: f64 = 1e-6;

/// The sine of the angle between the normals of `sa` at `ua` and of `sb` at `ub`, and the gap
/// `|S_A(ua) − S_B(ub)|` (f64: measured); `None` where a normal vanishes or a value is not
/// finite.
pub(super) fn sine_and_gap(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    ua: &[f64; 2],
    ub: &[f64; 2],
) -> Option<(f64, f64)> {
    let (p, su, sv) = point_d1(sa, ua[0], ua[1]);
    let (q, tu, tv) = point_d1(sb, ub[0], ub[1]);
    let (na, nb) = (cross(&su, &sv), cross(&tu, &tv));
    let (la, lb) = (norm(&na), norm(&nb));
    let sin = norm(&cross(&na, &nb)) / (la * lb);
    let gap = dist(&p, &q);
    (la > 0.0 && lb > 0.0 && sin.is_finite() && gap.is_finite()).then_some((sin, gap))
}

/// The overlap samples of `s` against `t`: for each grid point of `s`, `Some(uv on t,
/// distance)` when it is one.
fn samples(
    s: &NurbsSurface<f64, 3>,
    t: &NurbsSurface<f64, 3>,
    tol: f64,
) -> Vec<Vec<Option<Sample>>> {
    let (u0, u1, v0, v1) = s.hom.domain();
    (0..GRID)
        .map(|i| {
            (0..GRID)
                .map(|j| {
                    let u = u0 + (u1 - u0) * i as f64 / (GRID - 1) as f64;
                    let v = v0 + (v1 - v0) * j as f64 / (GRID - 1) as f64;
                    let uv = project(t, &point_d1(s, u, v).0);
                    let (sin, d) = sine_and_gap(s, t, &[u, v], &uv)?;
                    (d <= tol && sin <= PARALLEL).then_some(([u, v], uv, d))
                })
                .collect()
        })
        .collect()
}

/// Boxes `[u0, u1, v0, v1]` of the samples in 2×2 blocks (on `s`, on `t`), their count and
/// largest distance; `None` without such a block.
fn blocks(g: &[Vec<Option<Sample>>]) -> Option<([f64; 4], [f64; 4], usize, f64)> {
    let mut in_block = vec![vec![false; GRID]; GRID];
    for i in 0..GRID - 1 {
        for j in 0..GRID - 1 {
            if g[i][j].is_some()
                && g[i + 1][j].is_some()
                && g[i][j + 1].is_some()
                && g[i + 1][j + 1].is_some()
            {
                for (a, b) in [(i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1)] {
                    in_block[a][b] = true;
                }
            }
        }
    }
    let mut bs = [
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    let mut bt = bs;
    let (mut n, mut dmax) = (0, 0.0f64);
    for i in 0..GRID {
        for j in 0..GRID {
            if let (true, Some((a, b, d))) = (in_block[i][j], g[i][j]) {
                grow(&mut bs, &a);
                grow(&mut bt, &b);
                n += 1;
                dmax = dmax.max(d);
            }
        }
    }
    (n > 0).then_some((bs, bt, n, dmax))
}

/// `b` grown to hold the parameter point `p`.
pub(super) fn grow(b: &mut [f64; 4], p: &[f64; 2]) {
    b[0] = b[0].min(p[0]);
    b[1] = b[1].max(p[0]);
    b[2] = b[2].min(p[1]);
    b[3] = b[3].max(p[1]);
}

fn union(a: Option<[f64; 4]>, b: Option<[f64; 4]>) -> Option<[f64; 4]> {
    match (a, b) {
        (Some(x), Some(y)) => Some([
            x[0].min(y[0]),
            x[1].max(y[1]),
            x[2].min(y[2]),
            x[3].max(y[3]),
        ]),
        (x, None) => x,
        (None, y) => y,
    }
}

/// `b` widened by one grid step of the surface's domain.
fn widened(b: &[f64; 4], s: &NurbsSurface<f64, 3>) -> [f64; 4] {
    let (u0, u1, v0, v1) = s.hom.domain();
    let (du, dv) = ((u1 - u0) / (GRID - 1) as f64, (v1 - v0) / (GRID - 1) as f64);
    [b[0] - du, b[1] + du, b[2] - dv, b[3] + dv]
}

fn inside(b: &[f64; 4], p: &[f64; 2]) -> bool {
    b[0] <= p[0] && p[0] <= b[1] && b[2] <= p[1] && p[1] <= b[3]
}

/// Diagnose an overlap of `sa` and `sb` (see the module comment) and, when found, mark the
/// pair and remove its branches and touch points inside the overlap.
pub fn diagnose(p: &mut PairOut, sa: &NurbsSurface<f64, 3>, sb: &NurbsSurface<f64, 3>, tol: f64) {
    let ab = blocks(&samples(sa, sb, tol));
    let ba = blocks(&samples(sb, sa, tol));
    let (Some(box_a), Some(box_b)) = (
        union(ab.map(|x| x.0), ba.map(|x| x.1)),
        union(ab.map(|x| x.1), ba.map(|x| x.0)),
    ) else {
        return;
    };
    let n = ab.map_or(0, |x| x.2) + ba.map_or(0, |x| x.2);
    let dmax = ab.map_or(0.0, |x| x.3).max(ba.map_or(0.0, |x| x.3));
    let (wa, wb) = (widened(&box_a, sa), widened(&box_b, sb));
    let before = (p.branches.len(), p.touch_points.len());
    p.branches.retain(|b| {
        !(b.uv_a.iter().all(|x| inside(&wa, x)) && b.uv_b.iter().all(|x| inside(&wb, x)))
    });
    p.touch_points.retain(|t| {
        !(t.uv_a.is_some_and(|x| inside(&wa, &x)) && t.uv_b.is_some_and(|x| inside(&wb, &x)))
    });
    p.coincident = Some(CoincidenceOut {
        kind: CoincidenceKind::Overlap,
        plane_point: None,
        plane_normal: None,
        overlap: Some(super::coincide::OverlapOut {
            uv_a: box_a,
            uv_b: box_b,
            samples: n,
            max_distance: dmax,
            branches_removed: before.0 - p.branches.len(),
            touch_points_removed: before.1 - p.touch_points.len(),
        }),
    });
}
