//! The output set `O` the coverage claim refers to.

use super::near::Near;
use crate::ssi::report::{BranchOut, TouchOut};

/// Chords per cubic piece at most, when the output set replaces it by a polyline.
const MAX_PIECE_CHORDS: usize = 1 << 16;

/// The output set: branch polylines and touching points, with its *slack*: the proven
/// Hausdorff distance between the set and the output it stands for. Chords are themselves
/// (slack 0); cubic pieces ([`crate::ssi::hermite`]) are replaced by polylines within `d / 16`
/// of them ([`crate::ssi::hermite::densify`]; more only past [`MAX_PIECE_CHORDS`] chords), so a
/// point within `d − slack` of the set is within `d` of the output. `borders`: further
/// polylines of the output (common borders), taken as they are.
pub(crate) fn output_set(
    branches: &[BranchOut],
    touches: &[TouchOut],
    borders: &[Vec<[f64; 3]>],
    d: f64,
) -> (Near, f64) {
    let mut segs = Vec::new();
    let mut slack = 0.0f64;
    for b in branches {
        let n = b.points.len();
        if !b.tangents.is_empty() {
            for h in b.pieces() {
                let (pts, proven) = crate::ssi::hermite::densify(&h, d / 16.0, MAX_PIECE_CHORDS);
                slack = slack.max(proven);
                segs.extend(pts.windows(2).map(|w| (w[0], w[1])));
            }
            if n == 1 {
                segs.push((b.points[0], b.points[0]));
            }
            continue;
        }
        for k in 0..n {
            if k + 1 < n {
                segs.push((b.points[k], b.points[k + 1]));
            } else if b.closed && n > 1 {
                segs.push((b.points[k], b.points[0]));
            } else if n == 1 {
                segs.push((b.points[0], b.points[0]));
            }
        }
    }
    for t in touches {
        segs.push((t.point, t.point));
    }
    for p in borders {
        segs.extend(p.windows(2).map(|w| (w[0], w[1])));
    }
    (Near::with_chords(segs, (d - slack).max(0.0)), slack)
}

/// The faces the output is restricted to, as the restriction of the faces mode makes it
/// ([`crate::ssi::brep_faces`]): the coverage claim is made about the output *so
/// restricted*, so no part of it removed by the restriction can have decided a pair.
#[derive(Clone)]
pub struct FaceRestriction {
    /// Parameters on A and on B inside both faces (exact, against the loop polygons).
    pub inside: std::sync::Arc<PointPairTest>,
    /// Parameter boxes on A and on B meeting both faces, within the faces' margin.
    pub meets: std::sync::Arc<super::BoxPairTest>,
    /// A point on an edge or vertex the two faces share (one-file runs on a B-rep).
    pub shared: std::sync::Arc<PointTest>,
    /// Parameter boxes on A and on B wholly inside both faces (their boxes widened by the
    /// faces' margin).
    pub pair_inside: std::sync::Arc<super::BoxPairTest>,
    /// A parameter box of A (of B) lies outside face A (face B), widened by the faces'
    /// margin: no point of it is in the face.
    pub outside_a: std::sync::Arc<BoxTest>,
    pub outside_b: std::sync::Arc<BoxTest>,
    /// A parameter box of A (of B), widened by the faces' margin, lies wholly inside face A
    /// (face B); always for an untrimmed face.
    pub inside_a: std::sync::Arc<BoxTest>,
    pub inside_b: std::sync::Arc<BoxTest>,
    /// The loop polygons' edges of face A (of B) meeting a parameter box widened by the faces'
    /// margin, each with its shift by whole periods: every point of the box on the face's
    /// border lies on one (none for an untrimmed face: its border is the domain's).
    pub edges_a: std::sync::Arc<EdgesTest>,
    pub edges_b: std::sync::Arc<EdgesTest>,
}

/// A decision on one parameter box `[u0, u1, v0, v1]`.
pub type BoxTest = dyn Fn(&[f64; 4]) -> bool + Send + Sync;
/// Loop edges ([`crate::tessellate::region::LoopEdge`]) found for a parameter box.
pub type EdgesTest = dyn Fn(&[f64; 4]) -> Vec<crate::tessellate::region::LoopEdge> + Send + Sync;

/// A decision on a pair of parameter points (on A, on B).
pub type PointPairTest = dyn Fn(&[f64; 2], &[f64; 2]) -> bool + Send + Sync;
/// A decision on a model point.
pub type PointTest = dyn Fn(&[f64; 3]) -> bool + Send + Sync;

impl std::fmt::Debug for FaceRestriction {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("FaceRestriction")
    }
}

impl FaceRestriction {
    /// The same restriction with the two surfaces' roles exchanged.
    pub fn swapped(&self) -> FaceRestriction {
        let (i, m, p) = (
            self.inside.clone(),
            self.meets.clone(),
            self.pair_inside.clone(),
        );
        FaceRestriction {
            inside: std::sync::Arc::new(move |a, b| i(b, a)),
            meets: std::sync::Arc::new(move |a, b| m(b, a)),
            shared: self.shared.clone(),
            pair_inside: std::sync::Arc::new(move |a, b| p(b, a)),
            outside_a: self.outside_b.clone(),
            outside_b: self.outside_a.clone(),
            inside_a: self.inside_b.clone(),
            inside_b: self.inside_a.clone(),
            edges_a: self.edges_b.clone(),
            edges_b: self.edges_a.clone(),
        }
    }

    /// The branches and touch points as the faces mode keeps them: branch points by
    /// [`keep_mask`], touch points not shared and not outside.
    pub fn apply(
        &self,
        branches: &[BranchOut],
        touches: &[TouchOut],
    ) -> (Vec<BranchOut>, Vec<TouchOut>) {
        let mut out = Vec::with_capacity(branches.len());
        for b in branches {
            let shared: Vec<bool> = b.points.iter().map(|x| (self.shared)(x)).collect();
            let inside: Vec<bool> = (0..b.points.len())
                .map(|i| (self.inside)(&b.uv_a[i], &b.uv_b[i]))
                .collect();
            let keep = keep_mask(b, &shared, &inside);
            out.extend(crate::ssi::trims::clip_mask(b, &keep));
        }
        let touch = touches
            .iter()
            .filter(|t| {
                !(self.shared)(&t.point)
                    && t.uv_a
                        .zip(t.uv_b)
                        .is_none_or(|(a, b)| (self.inside)(&a, &b))
            })
            .cloned()
            .collect();
        (out, touch)
    }
}

/// Which points of branch `b` the faces keep, given which are `shared`: those inside both
/// faces and not shared, and the outer end of every chord that leaves the faces from a kept
/// point (not shared): the curve inside the faces runs on to the loop along that chord, and
/// the chord is output with it (its end outside counted `chord_ends_outside`), so that the
/// output reaches the loop.
/// `inside`: each point's parameters inside both faces.
pub fn keep_mask(b: &BranchOut, shared: &[bool], inside: &[bool]) -> Vec<bool> {
    let n = b.points.len();
    let ins: Vec<bool> = (0..n).map(|i| !shared[i] && inside[i]).collect();
    let segs = if b.closed { n } else { n.saturating_sub(1) };
    let mut keep = ins.clone();
    for i in 0..segs {
        let j = (i + 1) % n;
        if ins[i] != ins[j] && !shared[i] && !shared[j] {
            keep[i] = true;
            keep[j] = true;
        }
    }
    keep
}
