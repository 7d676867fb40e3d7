//! Step 4 on trimmed faces (§5.1 with edges in place of patch borders): the angle between
//! the two faces' normals across each edge they share, the largest over seven interior
//! points of the edge. Each point is taken to each face's surface parameters by a
//! closest-point search; the face normal is the surface normal `S_u × S_v`, reversed where
//! the face's sense is reversed, and the second face's is reversed again when both faces'
//! loops run along the edge the same way (faces oriented inconsistently), so that a smooth
//! join gives an angle near 0 whatever the orientation. Points where a surface's normal
//! vanishes (poles) are left out. Sampled: evidence.

use crate::brep::{Brep, LoopKind};
use crate::geom::{cross, dot, norm};
use crate::model::Model;
use crate::spline::project::{SurfaceFoot, point_d1};
use std::collections::BTreeMap;

/// Interior points of an edge at which the angle is measured.
const POINTS: usize = 7;

/// One use of an edge by a face: the face and whether the loop runs along the edge's
/// direction.
#[derive(Clone, Copy, Debug)]
pub struct Use {
    pub face: usize,
    pub along: bool,
}

/// Per edge, the faces' uses of it (loop order).
pub fn edge_uses(b: &Brep) -> BTreeMap<usize, Vec<Use>> {
    let mut out: BTreeMap<usize, Vec<Use>> = BTreeMap::new();
    for (fi, f) in b.faces.iter().enumerate() {
        for l in &f.loops {
            if let LoopKind::Edges(oes) = &l.kind {
                for oe in oes {
                    out.entry(oe.edge).or_default().push(Use {
                        face: fi,
                        along: oe.forward == l.orientation,
                    });
                }
            }
        }
    }
    out
}

/// The largest angle (degrees) between the normals of the two faces using `edge` (see the
/// module comment); `None` where no point gave two normals.
pub fn normal_angle<'m>(
    b: &Brep,
    m: &'m Model,
    feet: &mut BTreeMap<usize, SurfaceFoot<'m>>,
    edge: usize,
    uses: [Use; 2],
) -> Option<f64> {
    let c = &b.edges.get(edge)?.curve.as_ref()?.nurbs;
    let (t0, t1) = c.hom.domain();
    let mut worst: Option<f64> = None;
    for i in 1..=POINTS {
        let x = c.eval(&(t0 + (t1 - t0) * i as f64 / (POINTS + 1) as f64));
        let mut normals = [[0.0; 3]; 2];
        let mut ok = true;
        for (k, u) in uses.iter().enumerate() {
            let face = &b.faces[u.face];
            let si = face.surface.filter(|s| *s < m.surfaces.len())?;
            let s = &m.surfaces[si].nurbs;
            let foot = feet.entry(si).or_insert_with(|| SurfaceFoot::new(s));
            let uv = foot.closest(&x);
            let (_, su, sv) = point_d1(s, uv[0], uv[1]);
            let n = cross(&su, &sv);
            let l = norm(&n);
            // Also false for NaN: such points are left out.
            if l.partial_cmp(&(1e-8 * norm(&su) * norm(&sv))) != Some(std::cmp::Ordering::Greater) {
                ok = false;
                break;
            }
            let sign = if face.same_sense { 1.0 } else { -1.0 };
            normals[k] = n.map(|x| sign * x / l);
        }
        if !ok {
            continue;
        }
        if uses[0].along == uses[1].along {
            normals[1] = normals[1].map(|x| -x);
        }
        let angle = dot(&normals[0], &normals[1])
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees();
        worst = Some(worst.map_or(angle, |w: f64| w.max(angle)));
    }
    worst
}
