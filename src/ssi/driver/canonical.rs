//! The driver's canonical pair order (paper §4, the driver): every pair of surfaces is
//! intersected in one order fixed by the bits of their knots, weights and control points, and
//! the result is reported in the caller's order (sides swapped back), so `(A, B)` and `(B, A)`
//! give the same output; with the check every input surface passes first.

use crate::model::check::{MAX_COORDINATE, check_surface};
use crate::spline::NurbsSurface;
use crate::ssi::pair::intersect_surfaces;
use crate::ssi::report::PairOut;
use crate::ssi::{SsiError, SsiParams};
use std::time::Instant;

/// A total order on surfaces by the bits of their knots, weights and control points.
fn canonical_key(s: &NurbsSurface<f64, 3>) -> Vec<u64> {
    let h = &s.hom;
    let mut k: Vec<u64> = vec![
        h.ku.degree() as u64,
        h.kv.degree() as u64,
        h.ku.n_ctrl() as u64,
        h.kv.n_ctrl() as u64,
    ];
    k.extend(h.ku.knots().iter().chain(h.kv.knots()).map(|x| x.to_bits()));
    for p in &h.net {
        k.extend(p.wp.iter().map(|x| x.to_bits()));
        k.push(p.w.to_bits());
    }
    k
}

fn swap_sides(mut p: PairOut) -> PairOut {
    std::mem::swap(&mut p.a, &mut p.b);
    for b in &mut p.branches {
        std::mem::swap(&mut b.uv_a, &mut b.uv_b);
        std::mem::swap(&mut b.dist_a_max, &mut b.dist_b_max);
        if let Some(f) = &mut b.fit {
            std::mem::swap(&mut f.control_points_uv_a, &mut f.control_points_uv_b);
        }
    }
    for t in &mut p.touch_points {
        std::mem::swap(&mut t.uv_a, &mut t.uv_b);
        std::mem::swap(&mut t.dist_a, &mut t.dist_b);
        if let Some(s) = &mut t.singular {
            std::mem::swap(&mut s.box_a, &mut s.box_b);
            std::mem::swap(&mut s.root_a, &mut s.root_b);
            s.critical_on = s.critical_on.map(|c| if c == 'a' { 'b' } else { 'a' });
        }
    }
    if let Some(c) = &mut p.coverage {
        std::mem::swap(&mut c.boxes_a, &mut c.boxes_b);
        for r in &mut c.uncertified_regions {
            std::mem::swap(&mut r.uv_a, &mut r.uv_b);
        }
    }
    for c in &mut p.contacts {
        std::mem::swap(&mut c.triangle_a, &mut c.triangle_b);
    }
    for c in &mut p.common_borders {
        std::mem::swap(&mut c.border_a, &mut c.border_b);
        std::mem::swap(&mut c.uv_a, &mut c.uv_b);
        std::mem::swap(&mut c.dist_a_max, &mut c.dist_b_max);
    }
    if let Some(o) = p.coincident.as_mut().and_then(|c| c.overlap.as_mut()) {
        std::mem::swap(&mut o.uv_a, &mut o.uv_b);
    }
    if let Some(c) = p.tangent_contact.as_mut() {
        std::mem::swap(&mut c.uv_a, &mut c.uv_b);
        for (a, b) in &mut c.params {
            std::mem::swap(a, b);
        }
        for (_, a, b) in &mut c.unlisted {
            std::mem::swap(a, b);
        }
    }
    let s = &mut p.stats;
    std::mem::swap(&mut s.triangles_a, &mut s.triangles_b);
    std::mem::swap(&mut s.unresolved_cells_a, &mut s.unresolved_cells_b);
    p
}

/// A surface the intersection can compute with: finite (the constructor rules, re-checked
/// for nets changed in code) and within [`MAX_COORDINATE`], so that exact lifts and squared
/// distances never meet an infinity.
fn check_input(s: &NurbsSurface<f64, 3>, what: &dyn Fn() -> String) -> Result<(), SsiError> {
    check_surface(s).map_err(|e| SsiError::Input(format!("{}: {e}", what())))?;
    let big = s
        .hom
        .net
        .iter()
        .flat_map(|h| h.wp.map(|x| x / h.w))
        .fold(0.0f64, |a, x| a.max(x.abs()));
    if big > MAX_COORDINATE {
        return Err(SsiError::Input(format!(
            "{}: coordinate {big:e} is outside the supported range |x| <= 2^500 (about 3.3e150): squared distances would overflow f64",
            what()
        )));
    }
    Ok(())
}

/// Intersect two surfaces in their canonical order, reporting in the caller's order.
pub fn intersect_pair_canonical(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    ids: (usize, usize),
    prm: &SsiParams,
    deadline: Option<Instant>,
) -> Result<PairOut, SsiError> {
    check_input(sa, &|| format!("surface {}", ids.0))?;
    check_input(sb, &|| format!("surface {}", ids.1))?;
    pair_canonical(sa, sb, ids, prm, deadline)
}

/// [`intersect_pair_canonical`] on surfaces checked already.
pub(super) fn pair_canonical(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    ids: (usize, usize),
    prm: &SsiParams,
    deadline: Option<Instant>,
) -> Result<PairOut, SsiError> {
    if canonical_key(sa) <= canonical_key(sb) {
        intersect_surfaces(sa, sb, ids, prm, deadline)
    } else if prm.coverage_outside.is_some() || prm.coverage_restrict.is_some() {
        let mut swapped = prm.clone();
        swapped.coverage_outside = prm.coverage_outside.as_ref().map(|o| o.swapped());
        swapped.coverage_restrict = prm.coverage_restrict.as_ref().map(|r| r.swapped());
        intersect_surfaces(sb, sa, (ids.1, ids.0), &swapped, deadline).map(swap_sides)
    } else {
        intersect_surfaces(sb, sa, (ids.1, ids.0), prm, deadline).map(swap_sides)
    }
}
