//! Step 5 — the topology data structure of the intersection (paper §4, "Data structure, loop
//! detection, and curve tracing", Fig. 17): unique `Point`s, `PointUse`s and `Segment`s.
//!
//! A Point is unique by its combinatorial identity ([`PointId`]: the mesh features it lies
//! on), not by its coordinates: a second segment arriving at the same identity adds a
//! `PointUse` to the existing Point, so the structure "does not depend on the order in which
//! the intersections occur". The paper's circular `prev`/`next` list of uses is the `uses`
//! vector of the Point.

use super::tri_tri::{Feature, PointId};
use crate::predicates::tri_tri::ConstructedPoint;
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

/// A unique intersection point.
#[derive(Clone, Debug)]
pub struct Point {
    pub id: PointId,
    /// Coordinates with a proven bound `err` on the distance to the exact crossing point of
    /// the two triangulations.
    pub xyz: [f64; 3],
    pub err: f64,
    /// Indices into [`Topology::uses`].
    pub uses: Vec<u32>,
}

/// One end of a Segment at a Point.
#[derive(Clone, Copy, Debug)]
pub struct PointUse {
    pub point: u32,
    pub segment: u32,
    /// 0 at the Segment's start, 1 at its end.
    pub location: u8,
    pub in_use: bool,
}

/// A crossing segment of triangle `ta` (surface A) and triangle `tb` (surface B).
#[derive(Clone, Copy, Debug)]
pub struct Segment {
    pub uses: [u32; 2],
    pub ta: u32,
    pub tb: u32,
    pub in_use: bool,
}

#[derive(Clone, Debug, Default)]
pub struct Topology {
    pub points: Vec<Point>,
    pub uses: Vec<PointUse>,
    pub segments: Vec<Segment>,
    index: HashMap<PointId, u32>,
    seen: HashSet<(PointId, PointId)>,
    /// Segments offered twice (same two end identities) and kept once.
    pub duplicate_segments: usize,
    /// Segments whose two ends have the same identity (never kept).
    pub degenerate_segments: usize,
}

impl Topology {
    pub fn new() -> Topology {
        Topology::default()
    }

    fn point(&mut self, id: PointId, at: &ConstructedPoint) -> u32 {
        if let Some(&i) = self.index.get(&id) {
            return i;
        }
        let i = self.points.len() as u32;
        self.points.push(Point {
            id,
            xyz: at.p,
            err: at.err,
            uses: Vec::new(),
        });
        self.index.insert(id, i);
        i
    }

    /// Add the segment between two named points. Returns whether it was new.
    pub fn add_segment(
        &mut self,
        p: (PointId, ConstructedPoint),
        q: (PointId, ConstructedPoint),
        ta: u32,
        tb: u32,
    ) -> bool {
        if p.0 == q.0 {
            self.degenerate_segments += 1;
            return false;
        }
        let key = if p.0 < q.0 { (p.0, q.0) } else { (q.0, p.0) };
        if !self.seen.insert(key) {
            self.duplicate_segments += 1;
            return false;
        }
        let (ip, iq) = (self.point(p.0, &p.1), self.point(q.0, &q.1));
        let s = self.segments.len() as u32;
        let u0 = self.uses.len() as u32;
        for (loc, ip) in [(0u8, ip), (1u8, iq)] {
            self.uses.push(PointUse {
                point: ip,
                segment: s,
                location: loc,
                in_use: false,
            });
            let u = self.uses.len() as u32 - 1;
            self.points[ip as usize].uses.push(u);
        }
        self.segments.push(Segment {
            uses: [u0, u0 + 1],
            ta,
            tb,
            in_use: false,
        });
        true
    }

    /// Build from an abstract segment soup (point numbers), for tests and fuzzing.
    pub fn from_soup(pairs: &[(u32, u32)]) -> Topology {
        let mut t = Topology::new();
        let named = |n: u32| {
            (
                PointId {
                    a: Feature::Triangle(n),
                    b: Feature::Triangle(n),
                },
                ConstructedPoint {
                    p: [n as f64, 0.0, 0.0],
                    err: 0.0,
                    exact_fallback: false,
                },
            )
        };
        for (k, &(p, q)) in pairs.iter().enumerate() {
            t.add_segment(named(p), named(q), k as u32, k as u32);
        }
        t
    }

    /// Number of uses of the Point named `id` (0 when there is none).
    pub fn uses_of(&self, id: &PointId) -> usize {
        self.index
            .get(id)
            .map_or(0, |&i| self.points[i as usize].uses.len())
    }

    /// The use at the other end of `use_`'s segment.
    pub fn opposite(&self, use_: u32) -> u32 {
        let u = &self.uses[use_ as usize];
        self.segments[u.segment as usize].uses[1 - u.location as usize]
    }
}
