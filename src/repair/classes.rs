//! Step 3, preparation — the representation that can hold the shared curves (paper §4 (v)
//! and §6: a boundary curve is shared by two patches only if both hold it as the same row of
//! control points, so both must have the same degree and knots along the shared edge).
//!
//! A patch direction (u: edges south/north, v: east/west) is tied to its neighbour's
//! direction along every shared edge, with a relative orientation (the neighbour's parameter
//! may run the other way). The ties form *knot classes*: a direction's knots cannot change
//! without changing every direction it is tied to, since each shared row must stay one row on
//! both sides (a patch's two opposite edges share its knots, so a column of patches is one
//! class). A class is refined when one of its ties joins incompatible rows: its degree becomes
//! the largest of its members' and at least 3 (the paper's cubic), and its knots (on `[0, 1]`,
//! in the orientation of its first member) the union of the members' normalized knots after
//! elevation (each value with its largest multiplicity) and of the knots the fitted curves add.
//! Knot values of different members closer than [`SNAP`] are taken as one value (the
//! smaller). Every member is then reparametrized affinely to `[0, 1]`, raised to the class
//! degree and refined to the class knots (mirrored for members running the other way), which
//! keeps its geometry exactly (in exact arithmetic). A class whose ties are inconsistent (a
//! cycle reverses the orientation) is not refined; its incompatible ties are reported.

use super::average::normalized;
use super::connectivity::Connection;
use crate::spline::elevate::{elevate_surface_to, refine_surface_to, runs};
use crate::spline::{KnotVector, NurbsSurface};
use std::collections::HashMap;

/// Knot values closer than this (on the normalized `[0, 1]`) are one value.
pub const SNAP: f64 = 1e-10;

/// A class needing more control points per row than this is not refined (its knots would be
/// inserted into every member: long chains of patches with unrelated knots); its incompatible
/// ties are left and reported.
pub const MAX_CLASS_CONTROL_POINTS: usize = 256;

/// Direction along edge `e` (0 = u, 1 = v) and whether the edge runs with the parameter.
pub fn side(e: usize) -> (usize, bool) {
    (e % 2, e < 2)
}

/// One patch direction in a class; `flipped` when its parameter runs against the class's.
#[derive(Clone, Copy, Debug)]
pub struct Member {
    pub patch: usize,
    pub dir: usize,
    pub flipped: bool,
}

#[derive(Clone, Debug, Default)]
pub struct KnotClass {
    pub members: Vec<Member>,
    /// No tie cycle reverses the orientation.
    pub consistent: bool,
    /// Some tie joins incompatible rows.
    pub refine: bool,
    pub degree: usize,
    /// `(value, multiplicity)` on `[0, 1]` in the class orientation, ends of multiplicity
    /// `degree + 1`.
    pub runs: Vec<(f64, usize)>,
}

impl KnotClass {
    /// The representative of `x` (an existing value within [`SNAP`]), or `x`.
    pub fn snap(&self, x: f64) -> f64 {
        self.runs
            .iter()
            .map(|r| r.0)
            .filter(|v| (v - x).abs() <= SNAP)
            .min_by(|a, b| (a - x).abs().total_cmp(&(b - x).abs()))
            .unwrap_or(x)
    }
    /// Add the value `x` with multiplicity `m` (raising an existing value's multiplicity).
    pub fn add(&mut self, x: f64, m: usize) {
        let x = self.snap(x);
        let m = m.min(self.degree);
        match self.runs.iter_mut().find(|r| r.0 == x) {
            Some(r) => r.1 = r.1.max(m),
            None => {
                self.runs.push((x, m));
                self.runs.sort_by(|a, b| a.0.total_cmp(&b.0));
            }
        }
    }
    /// The knot vector in the class orientation.
    pub fn knots(&self) -> Vec<f64> {
        expand(&self.runs)
    }
    /// The knot vector of a member running the other way: `1 - x`, reversed (computed the
    /// same way for every such member, so their knots agree bit for bit).
    pub fn mirrored(&self) -> Vec<f64> {
        self.knots().iter().rev().map(|x| 1.0 - x).collect()
    }
}

/// Knots from `(value, multiplicity)` runs.
pub fn expand(r: &[(f64, usize)]) -> Vec<f64> {
    r.iter()
        .flat_map(|(v, m)| std::iter::repeat_n(*v, *m))
        .collect()
}

/// Normalized knots of `s` in direction `dir`, in the orientation of `flipped`.
fn oriented(s: &NurbsSurface<f64, 3>, dir: usize, flipped: bool) -> Vec<f64> {
    let k = if dir == 0 {
        s.hom.ku.knots()
    } else {
        s.hom.kv.knots()
    };
    let n = normalized(k);
    if flipped {
        n.iter().rev().map(|x| 1.0 - x).collect()
    } else {
        n
    }
}

/// Whether the knots of `s` in `dir` are clamped (ends of multiplicity degree + 1).
pub fn clamped(s: &NurbsSurface<f64, 3>, dir: usize) -> bool {
    let kv = if dir == 0 { &s.hom.ku } else { &s.hom.kv };
    let (k, p) = (kv.knots(), kv.degree());
    k[..=p].iter().all(|x| *x == k[0]) && k[k.len() - p - 1..].iter().all(|x| *x == k[k.len() - 1])
}

/// The member's knots in the class orientation after elevation to the class degree, with
/// values snapped to the class: `(value, multiplicity)`.
pub fn member_runs(class: &KnotClass, s: &NurbsSurface<f64, 3>, m: &Member) -> Vec<(f64, usize)> {
    let p = if m.dir == 0 {
        s.hom.ku.degree()
    } else {
        s.hom.kv.degree()
    };
    let d = class.degree;
    let r = runs(&oriented(s, m.dir, m.flipped));
    let last = r.len() - 1;
    let mut out: Vec<(f64, usize)> = Vec::new();
    for (i, (v, k)) in r.into_iter().enumerate() {
        let k = if i == 0 || i == last {
            d + 1
        } else {
            (k + d - p).min(d)
        };
        let v = class.snap(v);
        match out.last_mut() {
            Some(l) if l.0 == v => l.1 = (l.1 + k).min(d + 1),
            _ => out.push((v, k)),
        }
    }
    out
}

/// The knot classes of the tied patch directions, and each direction's class.
pub fn classes(
    patches: &[NurbsSurface<f64, 3>],
    ties: &[Connection],
    incompatible: &[bool],
) -> (Vec<KnotClass>, HashMap<(usize, usize), usize>) {
    let n = 2 * patches.len();
    let mut parent: Vec<usize> = (0..n).collect();
    let mut parity = vec![false; n];
    fn find(parent: &mut [usize], parity: &mut [bool], x: usize) -> (usize, bool) {
        let mut path = Vec::new();
        let mut r = x;
        while parent[r] != r {
            path.push(r);
            r = parent[r];
        }
        // Compress, accumulating parities from the root down.
        let mut acc = false;
        for &y in path.iter().rev() {
            acc ^= parity[y];
            parity[y] = acc;
            parent[y] = r;
        }
        (r, if path.is_empty() { false } else { parity[x] })
    }
    let mut tied = vec![false; n];
    let mut bad_roots = Vec::new();
    let mut refine_roots = Vec::new();
    for (c, inc) in ties.iter().zip(incompatible) {
        let ((dp, fp), (dq, fq)) = (side(c.ep), side(c.eq));
        let flip = (fp == fq) != c.same_direction;
        let (a, b) = (2 * c.p + dp, 2 * c.q + dq);
        tied[a] = true;
        tied[b] = true;
        let (ra, pa) = find(&mut parent, &mut parity, a);
        let (rb, pb) = find(&mut parent, &mut parity, b);
        if ra == rb {
            if (pa ^ pb) != flip {
                bad_roots.push(ra);
            }
        } else {
            parent[rb] = ra;
            parity[rb] = pa ^ pb ^ flip;
        }
        if *inc {
            refine_roots.push(a);
        }
    }
    let mut index: HashMap<usize, usize> = HashMap::new();
    let mut out: Vec<KnotClass> = Vec::new();
    let mut of: HashMap<(usize, usize), usize> = HashMap::new();
    for x in 0..n {
        if !tied[x] {
            continue;
        }
        let (r, par) = find(&mut parent, &mut parity, x);
        let k = *index.entry(r).or_insert_with(|| {
            out.push(KnotClass {
                consistent: true,
                ..Default::default()
            });
            out.len() - 1
        });
        out[k].members.push(Member {
            patch: x / 2,
            dir: x % 2,
            flipped: par,
        });
        of.insert((x / 2, x % 2), k);
    }
    for r in bad_roots {
        let (r, _) = find(&mut parent, &mut parity, r);
        if let Some(&k) = index.get(&r) {
            out[k].consistent = false;
        }
    }
    for a in refine_roots {
        let (r, _) = find(&mut parent, &mut parity, a);
        if let Some(&k) = index.get(&r) {
            out[k].refine = true;
        }
    }
    // Classes are keyed by their root; make the first member's orientation the class's.
    for cl in &mut out {
        if cl.members[0].flipped {
            for m in &mut cl.members {
                m.flipped = !m.flipped;
            }
        }
        if cl.refine && cl.consistent {
            cl.degree = cl
                .members
                .iter()
                .map(|m| {
                    let h = &patches[m.patch].hom;
                    if m.dir == 0 {
                        h.ku.degree()
                    } else {
                        h.kv.degree()
                    }
                })
                .max()
                .unwrap_or(3)
                .max(3);
            for m in cl.members.clone() {
                for (v, k) in member_runs(cl, &patches[m.patch], &m) {
                    cl.add(v, k);
                }
            }
            let d = cl.degree;
            if let Some(f) = cl.runs.first_mut() {
                f.1 = d + 1;
            }
            if let Some(l) = cl.runs.last_mut() {
                l.1 = d + 1;
            }
        }
    }
    (out, of)
}

/// The member reparametrized to `[0, 1]` in its direction, raised to the class degree and
/// refined to the class knots; `None` when that fails (snapping merged two of its knots
/// beyond the degree, or knots that are not clamped).
pub fn refine_member(
    class: &KnotClass,
    s: &NurbsSurface<f64, 3>,
    m: &Member,
) -> Option<NurbsSurface<f64, 3>> {
    if !clamped(s, m.dir) {
        return None;
    }
    let h = &s.hom;
    let kv = if m.dir == 0 { &h.ku } else { &h.kv };
    let own: Vec<f64> = normalized(kv.knots())
        .iter()
        .map(|&x| {
            if m.flipped {
                1.0 - class.snap(1.0 - x)
            } else {
                class.snap(x)
            }
        })
        .collect();
    let p = kv.degree();
    let nk = KnotVector::new(own, p, kv.n_ctrl()).ok()?;
    let mut hom = h.clone();
    if m.dir == 0 {
        hom.ku = nk;
    } else {
        hom.kv = nk;
    }
    let hom = elevate_surface_to(&hom, m.dir, class.degree);
    let target = if m.flipped {
        class.mirrored()
    } else {
        class.knots()
    };
    let hom = refine_surface_to(&hom, m.dir, &target)?;
    Some(NurbsSurface { hom })
}
