//! Placed copies of solids and shells: the occurrences of parts in an assembly. Each copy
//! has its own vertices, edges, faces and surfaces, moved by a rigid motion `x ↦ R·x + t`
//! applied to every point and control point. For a NURBS curve or surface with homogeneous
//! control points `(w·P, w)` the moved form is `(R·(w·P) + w·t, w)`: an affine map commutes
//! with the rational basis (Piegl & Tiller, *The NURBS Book*, §4.2, affine invariance), so
//! knots and weights are kept and the only error is the rounding of the products.
//! Pcurves lie in the parameter plane, which the motion does not change.

use super::{Brep, Face, LoopKind, OrientedEdge, Shell, Solid};
use crate::geom::Hom;
use crate::model::Surface;
use crate::spline::{NurbsCurve, NurbsSurface};
use std::collections::BTreeMap;

/// A motion `x ↦ R·x + t` (rows of `R`, then `t`): the placement of an occurrence in the
/// model's coordinates.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Motion {
    pub rotation: [[f64; 3]; 3],
    pub translation: [f64; 3],
}

impl Motion {
    pub const IDENTITY: Motion = Motion {
        rotation: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        translation: [0.0; 3],
    };

    /// The motion taking the world frame to the frame with origin `o` and axes `x, y, z`
    /// (columns of `R`): local coordinates `c` go to `o + c₀x + c₁y + c₂z`.
    pub fn from_frame(o: [f64; 3], x: [f64; 3], y: [f64; 3], z: [f64; 3]) -> Motion {
        Motion {
            rotation: [[x[0], y[0], z[0]], [x[1], y[1], z[1]], [x[2], y[2], z[2]]],
            translation: o,
        }
    }

    /// `R·x` (no translation): directions.
    pub fn rotate(&self, x: &[f64; 3]) -> [f64; 3] {
        let r = &self.rotation;
        [0, 1, 2].map(|i| r[i][0] * x[0] + r[i][1] * x[1] + r[i][2] * x[2])
    }

    /// `R·x + t`.
    pub fn apply(&self, x: &[f64; 3]) -> [f64; 3] {
        let r = self.rotate(x);
        [0, 1, 2].map(|i| r[i] + self.translation[i])
    }

    /// `self ∘ other`: first `other`, then `self`.
    pub fn then_after(&self, other: &Motion) -> Motion {
        let cols = [0, 1, 2].map(|j| self.rotate(&[0, 1, 2].map(|i| other.rotation[i][j])));
        Motion {
            rotation: [0, 1, 2].map(|i| [cols[0][i], cols[1][i], cols[2][i]]),
            translation: self.apply(&other.translation),
        }
    }

    /// The inverse of a rigid motion (`R` orthonormal): `x ↦ Rᵀ·(x − t)`.
    pub fn inverse_rigid(&self) -> Motion {
        let r = &self.rotation;
        let rt = [0, 1, 2].map(|i| [r[0][i], r[1][i], r[2][i]]);
        let m = Motion {
            rotation: rt,
            translation: [0.0; 3],
        };
        let t = m.rotate(&self.translation);
        Motion {
            rotation: rt,
            translation: t.map(|x| -x),
        }
    }

    /// Whether this is exactly the identity.
    pub fn is_identity(&self) -> bool {
        *self == Motion::IDENTITY
    }

    /// Largest deviation of `RᵀR` from the identity and the determinant of `R`: a rigid
    /// motion has 0 (to rounding) and +1.
    pub fn rigidity(&self) -> (f64, f64) {
        let r = &self.rotation;
        let mut dev: f64 = 0.0;
        for i in 0..3 {
            for j in 0..3 {
                let d: f64 = (0..3).map(|k| r[k][i] * r[k][j]).sum();
                dev = dev.max((d - if i == j { 1.0 } else { 0.0 }).abs());
            }
        }
        (dev, self.determinant())
    }

    /// `det R`: negative for a mirroring.
    pub fn determinant(&self) -> f64 {
        let r = &self.rotation;
        r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1])
            - r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0])
            + r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0])
    }

    /// The inverse map of any invertible `R` (scaled or mirroring, as a
    /// `cartesian_transformation_operator` gives them): `R⁻¹ = adj(R) / det R`, translation
    /// `−R⁻¹ t`; `None` when `det R` is zero or not finite. Rigid motions use
    /// [`Motion::inverse_rigid`] (the exact transpose).
    pub fn inverse(&self) -> Option<Motion> {
        let det = self.determinant();
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let r = &self.rotation;
        // adj(R)[i][j] is the cofactor of R[j][i].
        let c = |i: usize, j: usize| {
            let (a, b) = ((j + 1) % 3, (j + 2) % 3);
            let (x, y) = ((i + 1) % 3, (i + 2) % 3);
            (r[a][x] * r[b][y] - r[a][y] * r[b][x]) / det
        };
        let m = Motion {
            rotation: [0, 1, 2].map(|i| [0, 1, 2].map(|j| c(i, j))),
            translation: [0.0; 3],
        };
        let t = m.rotate(&self.translation);
        Some(Motion {
            translation: t.map(|x| -x),
            ..m
        })
    }

    fn hom(&self, h: &Hom<f64, 3>) -> Hom<f64, 3> {
        let r = self.rotate(&h.wp);
        Hom {
            wp: [0, 1, 2].map(|i| r[i] + h.w * self.translation[i]),
            w: h.w,
        }
    }

    /// The curve moved (knots and weights kept).
    pub fn curve(&self, c: &NurbsCurve<f64, 3>) -> NurbsCurve<f64, 3> {
        NurbsCurve {
            hom: c.hom.map(|k| *k, |h| self.hom(h)),
        }
    }

    /// The surface moved (knots and weights kept).
    pub fn surface(&self, s: &NurbsSurface<f64, 3>) -> NurbsSurface<f64, 3> {
        NurbsSurface {
            hom: s.hom.map(|k| *k, |h| self.hom(h)),
        }
    }
}

/// One placed occurrence to build: the solids and shells of the source B-rep (indices) and
/// the motion that places them.
#[derive(Clone, Debug)]
pub struct Placement {
    pub motion: Motion,
    pub solids: Vec<usize>,
    pub shells: Vec<usize>,
    /// Faces outside any shell.
    pub faces: Vec<usize>,
    /// Appended to the names of the moved surfaces (e.g. `" @ #376"`).
    pub label: String,
}

/// What one placement became in the new B-rep: indices of its solids and shells.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Placed {
    pub solids: Vec<usize>,
    pub shells: Vec<usize>,
}

/// Copies of the source's items, one per placement, each moved by its motion: a new B-rep
/// (the source's report and tolerance kept) and its surfaces (faces refer to them by index).
/// A shell that is the outer shell or a void of a placed solid is copied once, with the solid.
pub fn place(
    src: &Brep,
    surfaces: &[Surface],
    placements: &[Placement],
) -> (Brep, Vec<Surface>, Vec<Placed>) {
    let mut b = Brep {
        tolerance: src.tolerance,
        report: src.report.clone(),
        ..Brep::default()
    };
    let mut out_surfaces = Vec::new();
    let mut placed = Vec::with_capacity(placements.len());
    for p in placements {
        let mut c = Copier {
            src,
            surfaces,
            m: p.motion,
            label: &p.label,
            b: &mut b,
            out_surfaces: &mut out_surfaces,
            vertices: BTreeMap::new(),
            edges: BTreeMap::new(),
            faces: BTreeMap::new(),
            shells: BTreeMap::new(),
        };
        let mut r = Placed::default();
        for &s in &p.solids {
            let Some(solid) = src.solids.get(s) else {
                continue;
            };
            let outer = c.shell(solid.outer);
            let voids = solid.voids.iter().map(|&v| c.shell(v)).collect();
            r.solids.push(c.b.solids.len());
            c.b.solids.push(Solid {
                source: solid.source.clone(),
                outer,
                voids,
            });
        }
        for &s in &p.shells {
            if s < src.shells.len() {
                r.shells.push(c.shell(s));
            }
        }
        for &f in &p.faces {
            if f < src.faces.len() {
                c.face(f);
            }
        }
        placed.push(r);
    }
    (b, out_surfaces, placed)
}

struct Copier<'a> {
    src: &'a Brep,
    surfaces: &'a [Surface],
    m: Motion,
    label: &'a str,
    b: &'a mut Brep,
    out_surfaces: &'a mut Vec<Surface>,
    vertices: BTreeMap<usize, usize>,
    edges: BTreeMap<usize, usize>,
    faces: BTreeMap<usize, usize>,
    shells: BTreeMap<usize, usize>,
}

impl Copier<'_> {
    fn vertex(&mut self, v: usize) -> usize {
        if let Some(i) = self.vertices.get(&v) {
            return *i;
        }
        let mut x = self.src.vertices[v].clone();
        x.point = self.m.apply(&x.point);
        let i = self.b.vertices.len();
        self.b.vertices.push(x);
        self.vertices.insert(v, i);
        i
    }

    fn edge(&mut self, e: usize) -> usize {
        if let Some(i) = self.edges.get(&e) {
            return *i;
        }
        let mut x = self.src.edges[e].clone();
        x.start = self.vertex(x.start);
        x.end = self.vertex(x.end);
        if let Some(c) = &mut x.curve {
            c.nurbs = self.m.curve(&c.nurbs);
        }
        let i = self.b.edges.len();
        self.b.edges.push(x);
        self.edges.insert(e, i);
        i
    }

    fn face(&mut self, f: usize) -> usize {
        if let Some(i) = self.faces.get(&f) {
            return *i;
        }
        let src = &self.src.faces[f];
        let surface = src.surface.and_then(|s| self.surfaces.get(s)).map(|s| {
            self.out_surfaces.push(Surface {
                name: format!("{}{}", s.name, self.label),
                nurbs: self.m.surface(&s.nurbs),
                ..s.clone()
            });
            self.out_surfaces.len() - 1
        });
        // A mirroring turns S_u × S_v against the image of the face's normal and the loops'
        // sense of turning with it: the face's sense and each bound's orientation flip, so the
        // placed face keeps its outward normal and the material on the loops' left.
        let mirror = self.m.determinant() < 0.0;
        let mut loops = src.loops.clone();
        for l in &mut loops {
            l.orientation ^= mirror;
            match &mut l.kind {
                LoopKind::Edges(es) => {
                    for oe in es.iter_mut() {
                        *oe = OrientedEdge {
                            edge: self.edge(oe.edge),
                            forward: oe.forward,
                        };
                    }
                }
                LoopKind::Vertex(v) => *v = self.vertex(*v),
            }
        }
        let i = self.b.faces.len();
        self.b.faces.push(Face {
            source: src.source.clone(),
            surface,
            surface_source: src.surface_source.clone(),
            same_sense: src.same_sense ^ mirror,
            loops,
        });
        self.faces.insert(f, i);
        i
    }

    fn shell(&mut self, s: usize) -> usize {
        if let Some(i) = self.shells.get(&s) {
            return *i;
        }
        let src = &self.src.shells[s];
        let faces = src.faces.iter().map(|&(f, o)| (self.face(f), o)).collect();
        let i = self.b.shells.len();
        self.b.shells.push(Shell {
            source: src.source.clone(),
            closed: src.closed,
            faces,
        });
        self.shells.insert(s, i);
        i
    }
}

#[cfg(test)]
mod tests {
    use super::Motion;

    #[test]
    fn inverse_undoes_scaled_and_mirroring_maps() {
        // A mirroring (x and y swapped) scaled by 3 after a rotation, then a translation.
        let (c, s) = (0.6, 0.8);
        let m = Motion {
            rotation: [
                [0.0, 3.0, 0.0],
                [3.0 * c, 0.0, -3.0 * s],
                [3.0 * s, 0.0, 3.0 * c],
            ],
            translation: [1.0, -2.0, 5.0],
        };
        assert!((m.determinant() + 27.0).abs() < 1e-12);
        let inv = m.inverse().unwrap();
        for p in [[0.0, 0.0, 0.0], [1.5, -4.0, 2.25], [-7.0, 3.0, 11.0]] {
            let back = inv.apply(&m.apply(&p));
            assert!(
                (0..3).all(|i| (back[i] - p[i]).abs() < 1e-12),
                "{back:?} {p:?}"
            );
        }
        let singular = Motion {
            rotation: [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 0.0, 1.0]],
            translation: [0.0; 3],
        };
        assert!(singular.inverse().is_none());
    }
}
