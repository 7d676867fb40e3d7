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

/// The loop-topology invariants: every Segment is used by exactly one branch, once;
/// consecutive Points are the two ends of the Segment between them; closed branches end where
/// they start and pass only through Points of use count two; open branches end at Points of
/// use count other than two and pass through interior Points of use count two; no Point
/// appears twice inside a branch (branches are simple paths / simple loops).
pub fn check_invariants(t: &Topology, branches: &[Branch]) -> Result<(), String> {
    let mut seg_used = vec![0u32; t.segments.len()];
    for (bi, b) in branches.iter().enumerate() {
        if b.points.len() != b.segments.len() + 1 || b.segments.is_empty() {
            return Err(format!(
                "branch {bi}: {} points for {} segments",
                b.points.len(),
                b.segments.len()
            ));
        }
        for (k, &s) in b.segments.iter().enumerate() {
            let seg = &t.segments[s as usize];
            let ends = [
                t.uses[seg.uses[0] as usize].point,
                t.uses[seg.uses[1] as usize].point,
            ];
            let (p, q) = (b.points[k], b.points[k + 1]);
            if !((ends[0] == p && ends[1] == q) || (ends[0] == q && ends[1] == p)) {
                return Err(format!(
                    "branch {bi}: segment {s} does not join points {p} and {q}"
                ));
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
                return Err(format!(
                    "branch {bi}: closed but does not return to its start"
                ));
            }
            if b.points.iter().any(|&p| count(p) != 2) {
                return Err(format!(
                    "branch {bi}: closed through a point of use count != 2"
                ));
            }
        } else {
            for &e in [b.points[0], b.points[n - 1]].iter() {
                if count(e) == 2 {
                    return Err(format!("branch {bi}: open end at point {e} of use count 2"));
                }
            }
            if interior.iter().any(|&p| count(p) != 2) {
                return Err(format!("branch {bi}: passes through an end point"));
            }
        }
        let mut seen = std::collections::HashSet::new();
        for &p in interior {
            if !seen.insert(p) {
                return Err(format!("branch {bi}: point {p} visited twice"));
            }
        }
    }
    if let Some(s) = seg_used.iter().position(|&c| c != 1) {
        return Err(format!("segment {s} used {} times", seg_used[s]));
    }
    Ok(())
}
