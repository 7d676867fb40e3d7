//! Trim loops of IGES faces in their surface's parameter plane: trimmed surfaces (144) over
//! curves on a surface (142, the parameter-space curve BPTR), bounded surfaces (143) over
//! boundaries (141, the parameter-space curves PSCPT of each model-space curve), and B-rep
//! faces (510) over loops (508, the parameter-space curves of each edge use).

use super::{R, Reader};
use crate::brep::sew::BoundaryLoop;
use crate::model::TrimLoop;
use crate::spline::{NurbsCurve, NurbsSurface};

impl Reader<'_> {
    /// A parameter-space loop from a curve entity (x, y are u, v).
    pub(super) fn loop_2d(&self, de: usize, outer: bool) -> R<Option<TrimLoop>> {
        let Some(segs) = self.segments(de, 0)? else {
            return Ok(None);
        };
        // Parameter-space curves: x, y are u, v (z, normally 0, is dropped as IGES prescribes).
        let curves: Vec<NurbsCurve<f64, 2>> = segs
            .into_iter()
            .map(|c| NurbsCurve {
                hom: c.hom.map(
                    |k| *k,
                    |h| crate::geom::Hom {
                        wp: [h.wp[0], h.wp[1]],
                        w: h.w,
                    },
                ),
            })
            .collect();
        Ok(Some(TrimLoop { outer, curves }))
    }
    /// Trim loops of a face entity (144 via 142 curves on surface, 143 via 141 boundaries);
    /// the number of boundaries given only in model space is returned too.
    pub(super) fn trims(&self, face: usize) -> R<(Vec<TrimLoop>, usize)> {
        let x = &self.e[&face];
        let mut loops = Vec::new();
        let mut missing = 0;
        match x.etype {
            144 => {
                let h = self.nums(face, 2, 3)?;
                let (n1, n2) = (h[0] as usize, h[1] as usize);
                let mut bounds = Vec::new();
                if n1 != 0 {
                    bounds.push((self.ptr(face, 4)?, true));
                }
                for k in 0..n2.min(100_000) {
                    bounds.push((self.ptr(face, 5 + k)?, false));
                }
                for (b, outer) in bounds {
                    // 142: CRTN, SPTR, BPTR (parameter space), CPTR, PREF.
                    let bp = self.nums(b, 3, 1)?[0];
                    if bp >= 1.0 && self.e.contains_key(&(bp as usize)) {
                        match self.loop_2d(bp as usize, outer)? {
                            Some(l) => loops.push(l),
                            None => missing += 1,
                        }
                    } else {
                        missing += 1;
                    }
                }
            }
            143 => {
                let n = self.nums(face, 3, 1)?[0] as usize;
                for k in 0..n.min(100_000) {
                    let b = self.ptr(face, 4 + k)?;
                    // 141: TYPE, PREF, SPTR, N, then (CRVPT, SENSE, K, PSCPT x K) per curve.
                    let nc = self.nums(b, 4, 1)?[0] as usize;
                    let mut at = 5;
                    let mut curves = Vec::new();
                    let mut ok = true;
                    for _ in 0..nc.min(100_000) {
                        let v = self.nums(b, at, 3)?;
                        // SENSE (v[1]) orients the shared model-space curve; the parameter-space
                        // curves of a face are already oriented along its loop (checked on
                        // real files: reversing them by SENSE opens the loops).
                        let kk = v[2] as usize;
                        if kk == 0 {
                            ok = false;
                        }
                        for j in 0..kk {
                            match self.loop_2d(self.ptr(b, at + 3 + j)?, k == 0)? {
                                Some(l) => curves.extend(l.curves),
                                None => ok = false,
                            }
                        }
                        at += 3 + kk;
                    }
                    if ok {
                        loops.push(TrimLoop {
                            outer: k == 0,
                            curves,
                        });
                    } else {
                        missing += 1;
                    }
                }
            }
            510 => {
                // 510: SURF, N, OF, LOOP x N (508 loops). 508: N, then per edge TYPE, EDGE,
                // NDX, OF, K, (ISOP, CURV) x K: the CURV are the parameter-space curves.
                let h = self.nums(face, 2, 2)?;
                let (n, first_outer) = (h[0] as usize, h[1] == 1.0);
                for k in 0..n.min(100_000) {
                    let outer = k == 0 && first_outer;
                    let lp = self.ptr(face, 4 + k)?;
                    if self.e[&lp].etype != 508 {
                        return self.err(face, format!("loop {k} (DE {lp}) is not a 508 loop"));
                    }
                    let ne = self.nums(lp, 1, 1)?[0] as usize;
                    let mut at = 2;
                    let mut curves = Vec::new();
                    let mut ok = ne > 0;
                    for _ in 0..ne.min(100_000) {
                        let kk = self.nums(lp, at + 4, 1)?[0] as usize;
                        if kk == 0 {
                            ok = false;
                        }
                        for j in 0..kk.min(100_000) {
                            match self.loop_2d(self.ptr(lp, at + 6 + 2 * j)?, outer)? {
                                Some(l) => curves.extend(l.curves),
                                None => ok = false,
                            }
                        }
                        at += 5 + 2 * kk;
                    }
                    if ok {
                        loops.push(TrimLoop { outer, curves });
                    } else {
                        missing += 1;
                    }
                }
            }
            _ => {}
        }
        Ok((loops, missing))
    }
}

/// A model-space curve with its source id.
type Named = (String, NurbsCurve<f64, 3>);

/// Boundaries (142 ids) built from their parameter-space curve, and those whose parameter-space
/// curve is preferred but could not be mapped (with the reason).
#[derive(Default)]
pub(super) struct PreferredNotes {
    pub mapped: Vec<String>,
    pub kept: Vec<String>,
}

impl Reader<'_> {
    /// A model-space curve entity as `(source, curve)` segments, reversed when `reverse`;
    /// `None` when a member is not converted.
    fn space_curves(&self, de: usize, reverse: bool) -> R<Option<Vec<Named>>> {
        let Some(segs) = self.segments(de, 0)? else {
            return Ok(None);
        };
        let mut out: Vec<Named> = segs
            .into_iter()
            .enumerate()
            .map(|(k, c)| (format!("DE {de}#{}", k + 1), c))
            .collect();
        if reverse {
            out.reverse();
            for (_, c) in &mut out {
                *c = c.reversed();
            }
        }
        Ok(Some(out))
    }

    /// The loops of a trimmed (144) or bounded (143) face as model-space curves (142 CPTR,
    /// 141 CRVPT with its SENSE); `None` when a boundary has no model-space curve or one
    /// that is not converted. A 142 whose parameter-space curve is preferred (PREF = 1) or
    /// the only one given is mapped onto `surface` instead, when given (the face's surface in
    /// the parametrization of its trims; see `preferred.rs`); what was done is noted in `notes`.
    pub(super) fn space_loops(
        &self,
        face: usize,
        surface: Option<&NurbsSurface<f64, 3>>,
        notes: &mut PreferredNotes,
    ) -> R<Option<Vec<BoundaryLoop>>> {
        let mut out = Vec::new();
        match self.e[&face].etype {
            144 => {
                let h = self.nums(face, 2, 3)?;
                let (n1, n2) = (h[0] as usize, h[1] as usize);
                let mut bounds = Vec::new();
                if n1 != 0 {
                    bounds.push((self.ptr(face, 4)?, true));
                }
                for k in 0..n2.min(100_000) {
                    bounds.push((self.ptr(face, 5 + k)?, false));
                }
                for (b, outer) in bounds {
                    let cp = self.nums(b, 4, 1)?[0];
                    let has_copy = cp >= 1.0 && self.e.contains_key(&(cp as usize));
                    let pref = self.nums(b, 5, 1).map_or(0.0, |v| v[0]);
                    let bp = self.nums(b, 3, 1)?[0];
                    let mut image = None;
                    if (pref == 1.0 || !has_copy)
                        && bp >= 1.0
                        && self.e.contains_key(&(bp as usize))
                    {
                        let why = match surface {
                            Some(s) => match self.image_curves(bp as usize, s)? {
                                Ok(c) => {
                                    image = Some(c);
                                    None
                                }
                                Err(why) => Some(why),
                            },
                            None => Some("its surface is not in the trims' parametrization".into()),
                        };
                        match why {
                            None => notes.mapped.push(format!("DE {b}")),
                            Some(why) if has_copy => notes
                                .kept
                                .push(format!("DE {b} (model-space copy kept: {why})")),
                            Some(_) => {}
                        }
                    }
                    let curves = match image {
                        Some(c) => c,
                        None if has_copy => match self.space_curves(cp as usize, false)? {
                            Some(c) => c,
                            None => return Ok(None),
                        },
                        None => return Ok(None),
                    };
                    out.push(BoundaryLoop {
                        outer,
                        source: format!("DE {b}"),
                        curves,
                    });
                }
            }
            143 => {
                let n = self.nums(face, 3, 1)?[0] as usize;
                for k in 0..n.min(100_000) {
                    let b = self.ptr(face, 4 + k)?;
                    let nc = self.nums(b, 4, 1)?[0] as usize;
                    let mut at = 5;
                    let mut curves = Vec::new();
                    for _ in 0..nc.min(100_000) {
                        let v = self.nums(b, at, 3)?;
                        let Some(c) = self.space_curves(self.ptr(b, at)?, v[1] == 2.0)? else {
                            return Ok(None);
                        };
                        curves.extend(c);
                        at += 3 + v[2].max(0.0) as usize;
                    }
                    out.push(BoundaryLoop {
                        outer: k == 0,
                        source: format!("DE {b}"),
                        curves,
                    });
                }
            }
            _ => return Ok(None),
        }
        Ok(Some(out))
    }
}
