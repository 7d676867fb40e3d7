//! Steps 6–7 — finding loops and tracing them (paper §4, curve tracing steps 1–9).
//!
//! An end point of a curve is a Point whose number of PointUses is not two; with more than
//! two it is a singular (branch) point, and curves are broken there. Open curves are traced
//! first from such points; the Segments left unused afterwards form closed curves, traced from
//! their lowest-numbered unused PointUse until the start is reached again. The order of the
//! scan is the order of the Points and Segments, so the result is deterministic.

use super::topology::Topology;

/// One traced intersection curve: Points in order and the Segments between them
/// (`segments[k]` joins `points[k]` and `points[k + 1]`). A closed curve repeats its first
/// Point at the end.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Branch {
    pub points: Vec<u32>,
    pub segments: Vec<u32>,
    pub closed: bool,
}

fn walk(t: &mut Topology, start_use: u32, closed: bool) -> Branch {
    let mut b = Branch {
        points: Vec::new(),
        segments: Vec::new(),
        closed,
    };
    let start_point = t.uses[start_use as usize].point;
    let mut u = start_use;
    t.uses[u as usize].in_use = true; // step 3
    b.points.push(start_point);
    loop {
        let seg = t.uses[u as usize].segment; // step 4
        t.segments[seg as usize].in_use = true;
        b.segments.push(seg);
        let v = t.opposite(u); // step 5
        t.uses[v as usize].in_use = true; // step 6
        let p = t.uses[v as usize].point;
        b.points.push(p);
        if closed && p == start_point {
            break;
        }
        let uses = &t.points[p as usize].uses;
        if uses.len() != 2 {
            break; // step 8: an end point
        }
        // Step 7: the other use of this Point.
        let next = if uses[0] == v { uses[1] } else { uses[0] };
        if t.uses[next as usize].in_use {
            break; // cannot happen on a consistent structure; never loop forever
        }
        t.uses[next as usize].in_use = true;
        u = next;
    }
    b
}

/// Trace every curve of `t` (marks uses and segments in use).
pub fn trace(t: &mut Topology) -> Vec<Branch> {
    let mut out = Vec::new();
    // Open curves: from Points with a use count other than two.
    for p in 0..t.points.len() {
        if t.points[p].uses.len() == 2 {
            continue;
        }
        for k in 0..t.points[p].uses.len() {
            let u = t.points[p].uses[k];
            if !t.uses[u as usize].in_use {
                out.push(walk(t, u, false));
            }
        }
    }
    // Closed curves: what is left.
    for s in 0..t.segments.len() {
        if !t.segments[s].in_use {
            let u = t.segments[s].uses[0];
            out.push(walk(t, u, true));
        }
    }
    out
}

/// A violated loop-topology invariant ([`check_invariants`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum InvariantError {
    #[error("branch {branch}: {points} points for {segments} segments")]
    PointCount {
        branch: usize,
        points: usize,
        segments: usize,
    },
    #[error("branch {branch}: segment {segment} does not join points {p} and {q}")]
    SegmentNotJoining {
        branch: usize,
        segment: u32,
        p: u32,
        q: u32,
    },
    #[error("branch {branch}: closed but does not return to its start")]
    ClosedOpen { branch: usize },
    #[error("branch {branch}: closed through a point of use count != 2")]
    ClosedThroughEnd { branch: usize },
    #[error("branch {branch}: open end at point {point} of use count 2")]
    OpenEndInterior { branch: usize, point: u32 },
    #[error("branch {branch}: passes through an end point")]
    OpenThroughEnd { branch: usize },
    #[error("branch {branch}: point {point} visited twice")]
    PointTwice { branch: usize, point: u32 },
    #[error("segment {segment} used {uses} times")]
    SegmentUse { segment: usize, uses: u32 },
}

/// The loop-topology invariants: every Segment is used by exactly one branch, once;
/// consecutive Points are the two ends of the Segment between them; closed branches end where
/// they start and pass only through Points of use count two; open branches end at Points of
/// use count other than two and pass through interior Points of use count two; no Point
/// appears twice inside a branch (branches are simple paths / simple loops).
pub fn check_invariants(t: &Topology, branches: &[Branch]) -> Result<(), InvariantError> {
    let mut seg_used = vec![0u32; t.segments.len()];
    for (bi, b) in branches.iter().enumerate() {
        if b.points.len() != b.segments.len() + 1 || b.segments.is_empty() {
            return Err(InvariantError::PointCount {
                branch: bi,
                points: b.points.len(),
                segments: b.segments.len(),
            });
        }
        for (k, &s) in b.segments.iter().enumerate() {
            let seg = &t.segments[s as usize];
            let ends = [
                t.uses[seg.uses[0] as usize].point,
                t.uses[seg.uses[1] as usize].point,
            ];
            let (p, q) = (b.points[k], b.points[k + 1]);
            if !((ends[0] == p && ends[1] == q) || (ends[0] == q && ends[1] == p)) {
                return Err(InvariantError::SegmentNotJoining {
                    branch: bi,
                    segment: s,
                    p,
                    q,
                });
            }
            seg_used[s as usize] += 1;
        }
        let n = b.points.len();
        let count = |p: u32| t.points[p as usize].uses.len();
        let interior = if b.closed {
            &b.points[..n - 1]
        } else {
            &b.points[1..n - 1]
        };
        if b.closed {
            if b.points[0] != b.points[n - 1] {
                return Err(InvariantError::ClosedOpen { branch: bi });
            }
            if b.points.iter().any(|&p| count(p) != 2) {
                return Err(InvariantError::ClosedThroughEnd { branch: bi });
            }
        } else {
            for &e in [b.points[0], b.points[n - 1]].iter() {
                if count(e) == 2 {
                    return Err(InvariantError::OpenEndInterior {
                        branch: bi,
                        point: e,
                    });
                }
            }
            if interior.iter().any(|&p| count(p) != 2) {
                return Err(InvariantError::OpenThroughEnd { branch: bi });
            }
        }
        let mut seen = rustc_hash::FxHashSet::default();
        for &p in interior {
            if !seen.insert(p) {
                return Err(InvariantError::PointTwice {
                    branch: bi,
                    point: p,
                });
            }
        }
    }
    if let Some(s) = seg_used.iter().position(|&c| c != 1) {
        return Err(InvariantError::SegmentUse {
            segment: s,
            uses: seg_used[s],
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A triangle loop passes; the same branch listed twice, or cut short, is named by the
    /// violated invariant.
    #[test]
    fn violations_are_named() {
        let mut t = Topology::from_soup(&[(0, 1), (1, 2), (2, 0)]);
        let branches = trace(&mut t);
        assert_eq!(branches.len(), 1);
        assert_eq!(check_invariants(&t, &branches), Ok(()));
        let twice = vec![branches[0].clone(), branches[0].clone()];
        assert!(matches!(
            check_invariants(&t, &twice),
            Err(InvariantError::SegmentUse { uses: 2, .. })
        ));
        let mut open = branches[0].clone();
        open.points[3] = open.points[1];
        assert!(matches!(
            check_invariants(&t, &[open]),
            Err(InvariantError::SegmentNotJoining { branch: 0, .. })
                | Err(InvariantError::ClosedOpen { branch: 0 })
        ));
        let mut unclosed = branches[0].clone();
        unclosed.closed = false;
        assert!(matches!(
            check_invariants(&t, &[unclosed]),
            Err(InvariantError::OpenEndInterior { branch: 0, .. })
        ));
        let mut short = branches[0].clone();
        short.points.pop();
        assert_eq!(
            check_invariants(&t, &[short]),
            Err(InvariantError::PointCount {
                branch: 0,
                points: 3,
                segments: 3
            })
        );
    }
}
