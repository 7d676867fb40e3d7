//! Certificates where the curve leaves both parameter domains at one point: the plane moved
//! along the curve, and the search started across a seam (see the parent's module comment).

use super::system::{Fourth, System};
use super::{Attempt, CurveCertificate, Uncertified, attempt};
use crate::spline::closure::Closure;

/// Where the curve leaves both domains at once (a corner of both, e.g. two faces cut at
/// the same line), no zero on the plane through `p` has parameters in both domains. A zero
/// on a parallel plane moved by `±δ` along the curve may: its certificate still measures the
/// distance from `p` (the plane only selects which zero is isolated), so the radius is about
/// `δ`. `δ` grows from `1e-12` to `1e-6` of the point's scale; the first success counts (the
/// radius says how far it had to go).
pub(super) fn inside_near(
    sys: &mut System,
    z0: [f64; 4],
    n: [f64; 3],
    p: &[f64; 3],
) -> Result<CurveCertificate, Uncertified> {
    let scale = 1.0 + p.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let starts = seam_starts(sys, z0);
    for rel in [1e-12, 1e-10, 1e-9, 3e-9, 1e-8, 3e-8, 1e-7, 3e-7, 1e-6] {
        for sign in [1.0, -1.0] {
            let d = sign * rel * scale;
            sys.e = Fourth::Plane {
                n,
                p: std::array::from_fn(|k| p[k] + d * n[k]),
            };
            for z in &starts {
                if let Attempt::Done(c) = attempt(sys, *z, None) {
                    return Ok(c);
                }
            }
        }
    }
    Err(Uncertified::OutsideDomain)
}

/// Starting points for [`inside_near`]: `z0`, and where a parameter lies on (within a
/// relative 1e-6 of) a border of a direction whose two borders are one curve — a seam proven
/// from the control net ([`Closure`]) — the same with that parameter on the other border (every
/// combination): where the curve crosses a seam, the zero on a plane moved one way lies just
/// across it. Only where the search starts: what is certified is checked as always (the
/// zero's box inside both closed domains).
fn seam_starts(sys: &System, z0: [f64; 4]) -> Vec<[f64; 4]> {
    let (ca, cb) = (Closure::of(sys.sa), Closure::of(sys.sb));
    let closed = [ca.seam_u, ca.seam_v, cb.seam_u, cb.seam_v];
    let mut out = vec![z0];
    for k in 0..4 {
        let w = 1e-6 * (sys.hi[k] - sys.lo[k]);
        let other = if !closed[k] {
            None
        } else if z0[k] - sys.lo[k] <= w {
            Some(sys.hi[k])
        } else if sys.hi[k] - z0[k] <= w {
            Some(sys.lo[k])
        } else {
            None
        };
        if let Some(o) = other {
            for i in 0..out.len() {
                let mut z = out[i];
                z[k] = o;
                out.push(z);
            }
        }
    }
    out
}
