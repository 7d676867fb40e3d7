//! Step 6 — merging the control information of a group of patches (paper §6, matrix (2)
//! as corrected in docs/papers.md §C).
//!
//! Column `i` of a group maps its patches' normalized u-knots onto `[i, i+1]`; the merged knot
//! vector is the union with the break knots `1, 2, …` of multiplicity equal to the degree —
//! the choice docs/papers.md §C asks to state: multiplicity `p` already gives a C0 joint with one
//! shared control row, which is exactly what averaging made identical (the paper's quadruple
//! knot, `p + 1`, would double that row). Likewise in v. The net is the union of the patches'
//! nets with shared rows/columns written once (the mean of the coincident rows, identical after
//! averaging). Patches of a lower degree than the group's largest are raised first (exact
//! degree elevation). Each original patch is the merged surface over its cell, reparametrized
//! affinely; the largest deviation at 7 × 7 samples per patch is measured and reported.

use super::average::normalized;
use super::group::Group;
use crate::geom::Hom;
use crate::spline::elevate::elevate_surface_to;
use crate::spline::{BSplineSurface, KnotVector, NurbsSurface};

fn union_knots(parts: &[Vec<f64>], p: usize) -> Vec<f64> {
    let n = parts.len();
    let mut k = vec![0.0; p + 1];
    for (i, part) in parts.iter().enumerate() {
        let interior = &part[p + 1..part.len() - p - 1];
        k.extend(interior.iter().map(|x| i as f64 + x));
        if i + 1 < n {
            k.extend(std::iter::repeat_n((i + 1) as f64, p));
        }
    }
    k.extend(std::iter::repeat_n(n as f64, p + 1));
    k
}

/// The merged surface of a group and the largest measured deviation from its patches; `None`
/// when the patches' degrees or knot vectors do not line up (the group then stays as is).
pub fn merge(patches: &[NurbsSurface<f64, 3>], g: &Group) -> Option<(NurbsSurface<f64, 3>, f64)> {
    let (ni, nj) = (g.columns(), g.rows());
    // Columns (rows) of different degrees are raised to the group's largest, exactly.
    let members: Vec<usize> = g.cells.iter().flatten().copied().collect();
    let p = members.iter().map(|&k| patches[k].hom.ku.degree()).max()?;
    let q = members.iter().map(|&k| patches[k].hom.kv.degree()).max()?;
    let mut raised: std::collections::HashMap<usize, NurbsSurface<f64, 3>> =
        std::collections::HashMap::new();
    for &k in &members {
        let h = elevate_surface_to(&elevate_surface_to(&patches[k].hom, 0, p), 1, q);
        raised.insert(k, NurbsSurface { hom: h });
    }
    let patches = |k: usize| -> &NurbsSurface<f64, 3> { &raised[&k] };
    let cols: Vec<Vec<f64>> = (0..ni)
        .map(|i| normalized(patches(g.cells[i][0]).hom.ku.knots()))
        .collect();
    let rows: Vec<Vec<f64>> = (0..nj)
        .map(|j| normalized(patches(g.cells[0][j]).hom.kv.knots()))
        .collect();
    for i in 0..ni {
        for j in 0..nj {
            let h = &patches(g.cells[i][j]).hom;
            if h.ku.degree() != p || h.kv.degree() != q {
                return None;
            }
            let (ku, kv) = (normalized(h.ku.knots()), normalized(h.kv.knots()));
            let same = |a: &[f64], b: &[f64]| {
                a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-12)
            };
            if !same(&ku, &cols[i]) || !same(&kv, &rows[j]) {
                return None;
            }
        }
    }
    let nu: Vec<usize> = (0..ni).map(|i| patches(g.cells[i][0]).hom.nu()).collect();
    let nv: Vec<usize> = (0..nj).map(|j| patches(g.cells[0][j]).hom.nv()).collect();
    let off_u: Vec<usize> = (0..ni)
        .map(|i| nu[..i].iter().map(|n| n - 1).sum())
        .collect();
    let off_v: Vec<usize> = (0..nj)
        .map(|j| nv[..j].iter().map(|n| n - 1).sum())
        .collect();
    let (tu, tv) = (off_u[ni - 1] + nu[ni - 1], off_v[nj - 1] + nv[nj - 1]);
    let mut sum = vec![
        Hom {
            wp: [0.0; 3],
            w: 0.0
        };
        tu * tv
    ];
    let mut count = vec![0u32; tu * tv];
    for i in 0..ni {
        for j in 0..nj {
            let h = &patches(g.cells[i][j]).hom;
            for a in 0..h.nu() {
                for b in 0..h.nv() {
                    let k = (off_u[i] + a) * tv + off_v[j] + b;
                    let c = h.at(a, b);
                    for d in 0..3 {
                        sum[k].wp[d] += c.wp[d];
                    }
                    sum[k].w += c.w;
                    count[k] += 1;
                }
            }
        }
    }
    let net: Vec<Hom<f64, 3>> = sum
        .into_iter()
        .zip(&count)
        .map(|(h, &c)| {
            let c = c.max(1) as f64;
            Hom {
                wp: h.wp.map(|x| x / c),
                w: h.w / c,
            }
        })
        .collect();
    let ku = KnotVector::new(union_knots(&cols, p), p, tu).ok()?;
    let kv = KnotVector::new(union_knots(&rows, q), q, tv).ok()?;
    let merged = NurbsSurface {
        hom: BSplineSurface { ku, kv, net },
    };
    let mut dev = 0.0f64;
    for i in 0..ni {
        for j in 0..nj {
            let s = &patches(g.cells[i][j]);
            let (u0, u1, v0, v1) = s.hom.domain();
            for a in 0..7 {
                for b in 0..7 {
                    let (fu, fv) = (a as f64 / 6.0, b as f64 / 6.0);
                    let x = s.eval(&(u0 + fu * (u1 - u0)), &(v0 + fv * (v1 - v0)));
                    let y = merged.eval(&(i as f64 + fu), &(j as f64 + fv));
                    dev = dev.max(
                        ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2))
                            .sqrt(),
                    );
                }
            }
        }
    }
    Some((merged, dev))
}
