//! Step 9b over a branch's points: the curve certificate of every output point, runs of
//! consecutive points sharing what they can (see [`certify_run`]).

use super::branch::PairGeometry;
use super::certify::distance_upper;
use super::insert::{onto_curve, small_angle};
use super::jet_cache::JetCache;
use super::krawczyk::{RunCertifier, Uncertified};
use super::refine::{RefineParams, Refined, domain};
use crate::geom::dist;

/// Consecutive points sharing one Jacobian enclosure in the per-point certificates.
pub(super) const JET_RUN: usize = 16;

/// Runs shorter than twice this are not halved further (see [`certify_run`]).
const MIN_RUN: usize = 4;

/// Per point of the run: its curve radius (or why there is none) and its distances to each
/// surface.
pub(super) type PointCert = (Result<f64, Uncertified>, f64, f64);

/// The certificates of a run of consecutive points. They share one Jacobian enclosure
/// ([`JetCache`]) and, where it settles them, one Krawczyk matrix ([`RunCertifier`]); a run
/// whose parameters spread too far for one enclosure, or whose shared matrix does not contract
/// at its first point, is halved, down to [`MIN_RUN`] points. The shared test stops for a run
/// after two misses in a row; the points it does not settle are certified alone. Near
/// tangency the shared enclosure is wider than a point's own: there the shared test is kept
/// only while it gives radii within tol · 1e-5, stops at its first miss, and the points it
/// leaves are certified without the cache. Which test runs first is a choice: either is the
/// same theorem.
pub(super) fn certify_run(
    g: &PairGeometry,
    prm: &RefineParams,
    run: &mut [Refined],
) -> Vec<PointCert> {
    let narrow = small_angle(g, &run[0]);
    let cache = prm
        .curve_certificates
        .then(|| JetCache::over(g.sa, g.sb, run.iter().map(|r| (r.uv_a, r.uv_b))))
        .flatten();
    // One plane direction, preconditioner and Krawczyk matrix for the whole run where they
    // settle a point within `keep`; other points on their own.
    let shared = cache.as_ref().and_then(|c| {
        let m = &run[run.len() / 2];
        RunCertifier::new(g.sa, g.sb, c, (&m.uv_a, &m.uv_b))
    });
    // Halved where the points spread too far for one enclosure, or for one Krawczyk matrix
    // to contract at the first point (whose certificate, if any, is used below).
    let mut first = shared
        .as_ref()
        .and_then(|s| s.certify(&run[0].xyz, &run[0].uv_a, &run[0].uv_b));
    let spread = prm.curve_certificates && first.is_none();
    if spread && run.len() >= 2 * MIN_RUN {
        let (l, r) = run.split_at_mut(run.len() / 2);
        let mut out = certify_run(g, prm, l);
        out.extend(certify_run(g, prm, r));
        return out;
    }
    let keep = if narrow {
        prm.tol * 1e-5
    } else {
        prm.tol / 8.0
    };
    let own_cache = if narrow { None } else { cache.as_ref() };
    // The shared test stops for the run after this many misses in a row.
    let limit = if narrow { 1 } else { 2 };
    let mut misses = 0;
    run.iter_mut()
        .enumerate()
        .map(|(i, r)| {
            // Kept when the radius, measured from the point moved to the certificate's centre
            // (a point left up to tol/8 off the curve by the refinement lands on it), is
            // within `keep`.
            let attempt = if i == 0 {
                first.take()
            } else {
                shared
                    .as_ref()
                    .filter(|_| misses < limit)
                    .and_then(|s| s.certify(&r.xyz, &r.uv_a, &r.uv_b))
            };
            let fast = attempt
                .map(|c| adopt_centre(g, r, c))
                .filter(|c| c.0 <= keep);
            misses = if fast.is_some() { 0 } else { misses + 1 };
            let c = if let Some(c) = fast {
                Ok(c)
            } else if prm.curve_certificates {
                onto_curve(g, r, prm.tol, own_cache).map(|c| adopt_centre(g, r, c))
            } else {
                Err(Uncertified::NotRequested)
            };
            let radius = c.as_ref().map(|c| c.0).map_err(|u| *u);
            let (da, db) = match c {
                Ok((_, Some(d))) => d,
                _ => (
                    g.ea.distance_bound(&r.xyz, &r.uv_a)
                        .unwrap_or(f64::INFINITY),
                    g.eb.distance_bound(&r.xyz, &r.uv_b)
                        .unwrap_or(f64::INFINITY),
                ),
            };
            (radius, da, db)
        })
        .collect()
}

/// The certified point moved to the centre of its root box: `p' = (S_A(y_uv) + S_B(y_st)) / 2`
/// at the Newton solution `y`, which lies on the curve to `f64` accuracy. Kept when `y` lies in
/// both closed domains and the radius measured from `p'` to the enclosed true point is not
/// larger than from `p`; then `r` takes `p'` and `y` as its parameters, and its distances to
/// each surface are bounded from the certificate's enclosures at `y` (no second evaluation).
/// Returns the radius, and the two distances when moved.
fn adopt_centre(
    g: &PairGeometry,
    r: &mut Refined,
    c: super::krawczyk::CurveCertificate,
) -> (f64, Option<(f64, f64)>) {
    let y = c.centre;
    let (da, db) = (domain(g.sa), domain(g.sb));
    let inside = (0..2).all(|k| y[k] >= da[2 * k] && y[k] <= da[2 * k + 1])
        && (0..2).all(|k| y[k + 2] >= db[2 * k] && y[k + 2] <= db[2 * k + 1]);
    if !inside {
        return (c.radius, None);
    }
    let [a, b] = c.at_centre;
    let p: [f64; 3] = std::array::from_fn(|k| 0.5 * (a[k].mid() + b[k].mid()));
    let up = |box3: &[crate::scalar::Interval; 3]| distance_upper(&p, box3);
    match (up(&c.point), up(&a), up(&b)) {
        (Some(radius), Some(dist_a), Some(dist_b)) if radius <= c.radius => {
            r.gap = dist(&a.map(|x| x.mid()), &b.map(|x| x.mid()));
            r.xyz = p;
            r.uv_a = [y[0], y[1]];
            r.uv_b = [y[2], y[3]];
            (radius, Some((dist_a, dist_b)))
        }
        _ => (c.radius, None),
    }
}
