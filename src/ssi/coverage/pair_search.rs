//! The crossing searches that decide a pair transversal (case 3 of the coverage theorem):
//! the four border curves of each piece against the other piece, and, on trimmed faces, the
//! loop polygons' edges in each piece against the other piece ([`super::trim_crossings`]).
//!
//! On trimmed faces the claim is about the faces' intersection `I_F = I ∩ (F_A × F_B)` (the
//! faces `F_A`, `F_B` as their loop polygons outline them, closed). *Lemma (trimmed pair).*
//! If the cones of `α × β` are separated, every component `K` of `I_F ∩ (α × β)` contains a
//! border crossing of `α × β` lying in `F_A × F_B`, or a point with `z_a` on a loop edge of
//! face A or `z_b` on one of face B. Proof: suppose `K` has neither. `K` is compact and lies
//! in the interior of `α × β` and of `F_A × F_B` (its points are not on their borders), at a
//! positive distance `ε` from both borders. In the compact space `I_F ∩ (α × β)` the
//! component `K` is the intersection of the sets that are open and closed in it and contain
//! it, so one such set `U` lies within `ε` of `K`. Within `ε` of `K` the sets `I_F ∩ (α × β)`
//! and `I ∩ (α × β)` agree, so `U` is also open and closed in `I ∩ (α × β)`: a union of its
//! components, none meeting the border of `α × β` — against the no-interior-loop lemma
//! (separated cones). So the searches below, with crossings outside the faces left out
//! ([`Skip`]: a crossing whose parameters lie outside `F_A` or `F_B` is no point of `I_F`),
//! decide the pair exactly as the border searches alone decide an untrimmed one.

use super::CoverageParams;
use super::along::Along;
use super::crossings::{Skip, search};
use super::near::Near;
use super::outcome::CoverageOut;
use super::patch::{Box3, SIDES, Side};
use super::pieces::Cell;
use super::trim_crossings::edge_image;

/// What one pair's searches read and count.
pub(super) struct SearchCtx<'a> {
    pub near: &'a Near,
    pub along: &'a Along,
    pub d: f64,
    pub tubes: &'a [(Near, f64)],
    pub prm: &'a CoverageParams,
    pub halves_kept: &'a std::cell::Cell<usize>,
    /// Boxes examined for the face pair (the budget).
    pub boxes: &'a mut usize,
    pub out: &'a mut CoverageOut,
}

impl SearchCtx<'_> {
    /// One search; its counts added. `Some(box)`: a possible crossing not proven near the
    /// output, in a tube or outside the faces.
    fn run(&mut self, curve: &super::patch::ICurve, to: &Cell, skip: Skip) -> Option<Box3> {
        let left = self.prm.max_boxes.saturating_sub(*self.boxes).max(1);
        let s = search(
            curve,
            &to.piece(),
            (self.near, self.along, self.d),
            self.tubes,
            (self.prm.max_crossing_depth, left),
            self.halves_kept,
            skip,
        );
        *self.boxes += s.boxes;
        self.out.crossing_boxes += s.boxes;
        self.out.crossing_boxes_near_output += s.near_output;
        self.out.crossing_boxes_near_shared_edges += s.near_tubes;
        self.out.crossing_boxes_outside_faces += s.outside_faces;
        s.open
    }

    /// The border curves of `a` against `b` and of `b` against `a`; the first possible
    /// crossing not decided, if any. A border shared by two neighbouring pieces is one exact
    /// curve: a search that succeeded against the same piece of the other surface holds for
    /// both (`searched`).
    pub fn borders(
        &mut self,
        a: &Cell,
        b: &Cell,
        searched: &mut rustc_hash::FxHashSet<[u64; 8]>,
    ) -> Option<Box3> {
        let r = self.prm.restrict.as_ref();
        for (k, (from, to)) in [(a, b), (b, a)].into_iter().enumerate() {
            let (own, other) = match r {
                Some(r) if k == 0 => (Some(&*r.outside_a), Some((&*r.outside_b, &*r.inside_b))),
                Some(r) => (Some(&*r.outside_b), Some((&*r.outside_a, &*r.inside_a))),
                None => (None, None),
            };
            for side in SIDES {
                let key = edge_key(k, &from.uv, side, &to.uv);
                if searched.contains(&key) {
                    continue;
                }
                let [u0, u1, v0, v1] = from.uv;
                let (p, q) = match side {
                    Side::U0 => ([u0, v0], [u0, v1]),
                    Side::U1 => ([u1, v0], [u1, v1]),
                    Side::V0 => ([u0, v0], [u1, v0]),
                    Side::V1 => ([u0, v1], [u1, v1]),
                };
                let skip = Skip {
                    curve: own.map(|f| (f, p, q)),
                    piece: other,
                };
                if let Some(bx) = self.run(&from.patch.edge(side), to, skip) {
                    return Some(bx);
                }
                searched.insert(key);
            }
        }
        None
    }

    /// The loop edges of face A in `a` against `b`, and of face B in `b` against `a`; the
    /// first possible crossing not decided, if any.
    pub fn trim_edges(&mut self, a: &Cell, b: &Cell) -> Option<Box3> {
        let r = self.prm.restrict.clone()?;
        let sides = [
            (a, b, &r.edges_a, (&*r.outside_b, &*r.inside_b)),
            (b, a, &r.edges_b, (&*r.outside_a, &*r.inside_a)),
        ];
        for (from, to, edges, other) in sides {
            for e in edges(&from.uv) {
                self.out.trim_edge_searches += 1;
                // No image: the edge misses the piece.
                let Some(curve) = edge_image(from, &e) else {
                    continue;
                };
                let skip = Skip {
                    curve: None,
                    piece: Some(other),
                };
                if let Some(bx) = self.run(&curve, to, skip) {
                    return Some(bx);
                }
            }
        }
        None
    }
}

/// A border curve of a piece (which surface, the fixed parameter and its value, the range of
/// the other) with the piece of the other surface it is searched against. Labels are the
/// subdivision's own values, so neighbours that share a border produce the same key.
fn edge_key(from: usize, uv: &[f64; 4], side: Side, to: &[f64; 4]) -> [u64; 8] {
    let (axis, fixed, lo, hi) = match side {
        Side::U0 => (0, uv[0], uv[2], uv[3]),
        Side::U1 => (0, uv[1], uv[2], uv[3]),
        Side::V0 => (1, uv[2], uv[0], uv[1]),
        Side::V1 => (1, uv[3], uv[0], uv[1]),
    };
    [
        (from * 2 + axis) as u64,
        fixed.to_bits(),
        lo.to_bits(),
        hi.to_bits(),
        to[0].to_bits(),
        to[1].to_bits(),
        to[2].to_bits(),
        to[3].to_bits(),
    ]
}
