//! Step 4 — feature lines (paper §5.1, Fig. 9): along each connected edge pair, the largest
//! angle between the two patches' unit normals at closest-point pairs of the samples. Above
//! the feature angle the edge is a feature edge. A flipped neighbour (edges running the same
//! way) has its normal reversed first. User overrides add or remove feature edges by
//! `(patch, edge)`.

use super::edges::{CurveFoot, arc_length_samples, edge_curve, edge_uv};
use super::verify::VerifiedEdge;
use crate::spline::NurbsSurface;
use serde::{Deserialize, Serialize};

/// A connected edge pair with its normal-angle measurement.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct FeatureEdge {
    pub p: usize,
    pub ep: usize,
    pub q: usize,
    pub eq: usize,
    /// Largest angle between the normals at the samples, degrees.
    pub max_angle_deg: f64,
    pub feature: bool,
    /// Set or cleared by a user override.
    pub overridden: bool,
}

/// Overrides: `{"add": [[patch, edge], ...], "remove": [[patch, edge], ...]}`.
#[derive(Clone, Debug, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct FeatureOverrides {
    #[serde(default)]
    pub add: Vec<(usize, usize)>,
    #[serde(default)]
    pub remove: Vec<(usize, usize)>,
}

/// `v / |v|`, scaled by its largest component first so that neither squaring overflows
/// (coordinates near 1e160) nor underflows (near 1e-160): the direction does not depend on
/// the model's scale.
fn unit(v: [f64; 3]) -> Option<[f64; 3]> {
    let m = v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    if !(m > 0.0 && m.is_finite()) {
        return None;
    }
    let w = v.map(|c| c / m);
    let l = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
    Some(w.map(|c| c / l))
}

fn unit_normal(s: &NurbsSurface<f64, 3>, uv: [f64; 2]) -> Option<[f64; 3]> {
    let (_, su, sv) = crate::spline::project::point_d1(s, uv[0], uv[1]);
    // The normal's direction from the tangents' directions: scale-independent.
    let (su, sv) = (unit(su)?, unit(sv)?);
    unit([
        su[1] * sv[2] - su[2] * sv[1],
        su[2] * sv[0] - su[0] * sv[2],
        su[0] * sv[1] - su[1] * sv[0],
    ])
}

/// Largest normal angle (degrees) along a connected edge pair, at `n` samples.
pub fn max_normal_angle(patches: &[NurbsSurface<f64, 3>], v: &VerifiedEdge, n: usize) -> f64 {
    let c = v.connection;
    let (sp, sq) = (&patches[c.p], &patches[c.q]);
    let (a, b) = (edge_curve(sp, c.ep), edge_curve(sq, c.eq));
    let mut worst = 0.0f64;
    let foot = CurveFoot::new(&b);
    for (t, x) in arc_length_samples(&a, n) {
        let (s, _, _) = foot.closest(&x);
        let (Some(np), Some(nq)) = (
            unit_normal(sp, edge_uv(sp, c.ep, t)),
            unit_normal(sq, edge_uv(sq, c.eq, s)),
        ) else {
            continue; // degenerate normal (collapsed edge): no angle there
        };
        let sign = if c.same_direction { -1.0 } else { 1.0 };
        let d = (sign * (np[0] * nq[0] + np[1] * nq[1] + np[2] * nq[2])).clamp(-1.0, 1.0);
        worst = worst.max(d.acos().to_degrees());
    }
    worst
}

pub fn features(
    patches: &[NurbsSurface<f64, 3>],
    edges: &[VerifiedEdge],
    angle_deg: f64,
    n: usize,
    overrides: &FeatureOverrides,
) -> Vec<FeatureEdge> {
    use rayon::prelude::*;
    edges
        .par_iter()
        .filter(|v| v.connected)
        .map(|v| {
            let c = v.connection;
            let a = max_normal_angle(patches, v, n);
            let hit = |list: &[(usize, usize)]| {
                list.iter()
                    .any(|&(p, e)| (p, e) == (c.p, c.ep) || (p, e) == (c.q, c.eq))
            };
            let (add, remove) = (hit(&overrides.add), hit(&overrides.remove));
            let auto = a > angle_deg;
            let feature = if remove { false } else { add || auto };
            FeatureEdge {
                p: c.p,
                ep: c.ep,
                q: c.q,
                eq: c.eq,
                max_angle_deg: a,
                feature,
                overridden: feature != auto,
            }
        })
        .collect()
}
