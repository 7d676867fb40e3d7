//! Step 3, the faces' extent (§3.3, "the original surfaces"): the region of each surface's
//! parameter plane its face covers, as polygons of its trimming loops, so that segments
//! meet only the faces — a gap made by trimming stays a gap.
//!
//! Sources: IGES trimming loops (curves in the parameter plane, sampled directly) and STEP
//! B-rep loops (3D edge curves, sampled and projected onto the face's surface by local
//! closest point, [`crate::spline::project::project`]). A point is inside by the even-odd
//! rule over all loops of the surface. A loop whose parameter polygon jumps by more than
//! half the domain between consecutive samples crosses a seam; such a surface is left
//! untrimmed and named in a warning. The polygons are approximations of the loops
//! (sampling and projection), not certified.

use crate::model::Model;
use crate::spline::NurbsCurve;

/// Parameter-plane polygons per surface (`None`: the whole surface is the face).
#[derive(Clone, Debug, Default)]
pub struct Regions {
    pub polygons: Vec<Option<Vec<Vec<[f64; 2]>>>>,
    /// Faces whose trimming could not be used, and why.
    pub warnings: Vec<String>,
}

impl Regions {
    /// Whether `uv` lies in the face of surface `s` (even-odd over its loops).
    pub fn contains(&self, s: usize, uv: &[f64; 2]) -> bool {
        match self.polygons.get(s) {
            Some(Some(polys)) => inside(polys, uv),
            _ => true,
        }
    }
}

impl Regions {
    /// Whether the parameter triangle `t` may meet the face of surface `s`: a vertex or the
    /// centroid inside, or a loop point within the triangle's box.
    pub fn touches(&self, s: usize, t: &[[f64; 2]; 3]) -> bool {
        let Some(Some(polys)) = self.polygons.get(s) else {
            return true;
        };
        let c = [
            (t[0][0] + t[1][0] + t[2][0]) / 3.0,
            (t[0][1] + t[1][1] + t[2][1]) / 3.0,
        ];
        if t.iter().chain([&c]).any(|p| inside(polys, p)) {
            return true;
        }
        let lo = [
            t[0][0].min(t[1][0]).min(t[2][0]),
            t[0][1].min(t[1][1]).min(t[2][1]),
        ];
        let hi = [
            t[0][0].max(t[1][0]).max(t[2][0]),
            t[0][1].max(t[1][1]).max(t[2][1]),
        ];
        polys
            .iter()
            .flatten()
            .any(|p| p[0] >= lo[0] && p[0] <= hi[0] && p[1] >= lo[1] && p[1] <= hi[1])
    }
}

/// Even-odd point-in-polygons test.
pub fn inside(polys: &[Vec<[f64; 2]>], x: &[f64; 2]) -> bool {
    let mut c = false;
    for p in polys {
        let n = p.len();
        for i in 0..n {
            let (a, b) = (p[i], p[(i + 1) % n]);
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

fn samples_per_curve<const D: usize>(c: &NurbsCurve<f64, D>) -> usize {
    (16 * (c.hom.knots.interior_breaks().len() + 1)).clamp(16, 512)
}

/// Sample a curve at `k` parameter steps (the end point left to the next curve).
fn sample<const D: usize>(c: &NurbsCurve<f64, D>, forward: bool) -> Vec<[f64; D]> {
    let k = samples_per_curve(c);
    let (t0, t1) = c.hom.domain();
    (0..k)
        .map(|i| {
            let f = i as f64 / k as f64;
            let f = if forward { f } else { 1.0 - f };
            c.eval(&(t0 + (t1 - t0) * f))
        })
        .collect()
}

/// Whether a closed polygon jumps by more than half the domain somewhere (a seam).
fn jumps(p: &[[f64; 2]], d: (f64, f64, f64, f64)) -> bool {
    let (wu, wv) = (d.1 - d.0, d.3 - d.2);
    (0..p.len()).any(|i| {
        let (a, b) = (p[i], p[(i + 1) % p.len()]);
        (a[0] - b[0]).abs() > 0.5 * wu || (a[1] - b[1]).abs() > 0.5 * wv
    })
}

/// The trimmed regions of every surface of the model.
pub fn regions(model: &Model) -> Regions {
    let mut r = Regions {
        polygons: vec![None; model.surfaces.len()],
        warnings: vec![],
    };
    for (si, s) in model.surfaces.iter().enumerate() {
        if s.trim_loops.is_empty() {
            continue;
        }
        let polys: Vec<Vec<[f64; 2]>> = s
            .trim_loops
            .iter()
            .map(|l| l.curves.iter().flat_map(|c| sample(c, true)).collect())
            .filter(|p: &Vec<[f64; 2]>| p.len() >= 3 && p.iter().flatten().all(|c| c.is_finite()))
            .collect();
        if !polys.is_empty() {
            r.polygons[si] = Some(polys);
        }
    }
    let Some(brep) = &model.brep else {
        return r;
    };
    for f in &brep.faces {
        let Some(si) = f.surface.filter(|s| *s < model.surfaces.len()) else {
            continue;
        };
        let surf = &model.surfaces[si].nurbs;
        let d = surf.hom.domain();
        let mut polys = Vec::new();
        let mut usable = true;
        for l in &f.loops {
            let crate::brep::LoopKind::Edges(es) = &l.kind else {
                continue;
            };
            let mut p: Vec<[f64; 2]> = Vec::new();
            for oe in es {
                let Some(c) = brep.edges.get(oe.edge).and_then(|e| e.curve.as_ref()) else {
                    usable = false;
                    break;
                };
                for q in sample(&c.nurbs, oe.forward) {
                    p.push(crate::spline::project::project(surf, &q));
                }
            }
            if !usable || p.len() < 3 || jumps(&p, d) {
                usable = false;
                break;
            }
            polys.push(p);
        }
        if !usable {
            r.warnings.push(format!(
                "face {}: its loops could not be mapped to the parameter plane of surface {si} (a seam or an edge without a curve); the whole surface is used",
                f.source
            ));
            continue;
        }
        if !polys.is_empty() {
            r.polygons[si].get_or_insert_with(Vec::new).extend(polys);
        }
    }
    r
}
