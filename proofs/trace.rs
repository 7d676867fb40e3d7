//! The SSI tracer's invariants (`vericad::ssi::trace`, `vericad::ssi::topology`): the
//! branches reported as open and closed curves are read off the segment structure by
//! `trace`; the report's branch count, closedness and end kinds rest on this.

use crate::common::cases;
use std::collections::{BTreeMap, BTreeSet};
use vericad::ssi::topology::Topology;
use vericad::ssi::trace::{check_invariants, trace};

/// Tracing a segment soup (pairs of point numbers) gives branches such that, checked here
/// independently of `check_invariants` (which must accept them too):
/// * the structure keeps exactly the distinct non-degenerate segments of the soup;
/// * every kept segment is used by exactly one branch, once;
/// * consecutive points of a branch are the two ends of the segment between them;
/// * a closed branch returns to its start and passes only through points of use count 2;
/// * interior points of an open branch have use count 2 and appear once;
/// * the multiset of open-branch ends is exactly the multiset of uses at points whose use
///   count is not 2 (so every point of odd use is an end, as often as it is used).
pub fn prop_trace_invariants(soup: &[(u8, u8)]) {
    let pairs: Vec<(u32, u32)> = soup.iter().map(|&(a, b)| (a as u32, b as u32)).collect();
    let mut t = Topology::from_soup(&pairs);
    let distinct: BTreeSet<(u32, u32)> = pairs
        .iter()
        .filter(|(a, b)| a != b)
        .map(|&(a, b)| (a.min(b), a.max(b)))
        .collect();
    assert_eq!(t.segments.len(), distinct.len(), "{soup:?}");
    let branches = trace(&mut t);
    if let Err(e) = check_invariants(&t, &branches) {
        panic!("{soup:?}: {e}");
    }
    let count = |p: u32| t.points[p as usize].uses.len();
    let ends_of = |s: u32| {
        let seg = &t.segments[s as usize];
        [
            t.uses[seg.uses[0] as usize].point,
            t.uses[seg.uses[1] as usize].point,
        ]
    };
    let mut used = vec![0usize; t.segments.len()];
    let mut ends: BTreeMap<u32, usize> = BTreeMap::new();
    for b in &branches {
        assert_eq!(b.points.len(), b.segments.len() + 1, "{soup:?}: {b:?}");
        assert!(!b.segments.is_empty(), "{soup:?}: empty branch");
        for (k, &s) in b.segments.iter().enumerate() {
            used[s as usize] += 1;
            let e = ends_of(s);
            let (p, q) = (b.points[k], b.points[k + 1]);
            assert!(
                (e[0] == p && e[1] == q) || (e[0] == q && e[1] == p),
                "{soup:?}: {b:?}"
            );
        }
        let n = b.points.len();
        let interior = if b.closed {
            assert_eq!(b.points[0], b.points[n - 1], "{soup:?}: {b:?}");
            assert!(b.points.iter().all(|&p| count(p) == 2), "{soup:?}: {b:?}");
            &b.points[..n - 1]
        } else {
            *ends.entry(b.points[0]).or_default() += 1;
            *ends.entry(b.points[n - 1]).or_default() += 1;
            &b.points[1..n - 1]
        };
        assert!(interior.iter().all(|&p| count(p) == 2), "{soup:?}: {b:?}");
        let set: BTreeSet<u32> = interior.iter().copied().collect();
        assert_eq!(set.len(), interior.len(), "{soup:?}: {b:?} not simple");
    }
    assert!(used.iter().all(|&u| u == 1), "{soup:?}: uses {used:?}");
    let want: BTreeMap<u32, usize> = (0..t.points.len() as u32)
        .filter(|&p| count(p) != 2)
        .map(|p| (p, count(p)))
        .collect();
    assert_eq!(ends, want, "{soup:?}: open ends");
}

#[cfg(kani)]
mod kani_drivers {
    #[kani::proof]
    #[kani::unwind(10)]
    fn trace_invariants() {
        let soup: [(u8, u8); 4] = kani::any();
        let n: usize = kani::any();
        kani::assume(n <= 4 && soup.iter().all(|&(a, b)| a < 4 && b < 4));
        super::prop_trace_invariants(&soup[..n]);
    }
}

fn all_soups(points: u8, max_len: usize, f: &mut impl FnMut(&[(u8, u8)])) {
    let all: Vec<(u8, u8)> = (0..points)
        .flat_map(|a| (0..points).map(move |b| (a, b)))
        .collect();
    fn rec(
        all: &[(u8, u8)],
        soup: &mut Vec<(u8, u8)>,
        left: usize,
        f: &mut impl FnMut(&[(u8, u8)]),
    ) {
        f(soup);
        if left == 0 {
            return;
        }
        for &s in all {
            soup.push(s);
            rec(all, soup, left - 1, f);
            soup.pop();
        }
    }
    rec(&all, &mut Vec::new(), max_len, f);
}

/// Every soup of up to 4 segments over 4 points (every sequence: self-loops, duplicates and
/// both orientations included; 69,905 soups). `VERICAD_LARGE=1`: up to 5 segments over 5
/// points (10.2 million soups).
#[test]
fn trace_invariants_exhaustive() {
    let (p, n) = if std::env::var("VERICAD_LARGE").is_ok() {
        (5, 5)
    } else {
        (4, 4)
    };
    all_soups(p, n, &mut |s| prop_trace_invariants(s));
}

/// Random structures of the shape the SSI produces: unions of paths and cycles over up to 12
/// points (every point used twice except the ends), with random extra segments making branch
/// points (use count 3 or more), in random order and orientation.
#[test]
fn trace_invariants_random_curves() {
    let mut rng = crate::common::Rng::new(77);
    let n = cases(20_000, 200_000);
    for _ in 0..n {
        let np = 2 + rng.below(11) as u8;
        let mut perm: Vec<u8> = (0..np).collect();
        for i in (1..perm.len()).rev() {
            perm.swap(i, rng.below(i as u64 + 1) as usize);
        }
        let mut soup = Vec::new();
        let mut i = 0;
        while i + 1 < perm.len() {
            let len = 2 + rng.below(5) as usize;
            let piece = &perm[i..(i + len).min(perm.len())];
            for w in piece.windows(2) {
                soup.push((w[0], w[1]));
            }
            if piece.len() >= 3 && rng.coin() {
                soup.push((piece[piece.len() - 1], piece[0]));
            }
            i += len;
        }
        for _ in 0..rng.below(3) {
            soup.push((rng.below(np as u64) as u8, rng.below(np as u64) as u8));
        }
        for k in (1..soup.len()).rev() {
            soup.swap(k, rng.below(k as u64 + 1) as usize);
        }
        for s in soup.iter_mut() {
            if rng.coin() {
                *s = (s.1, s.0);
            }
        }
        prop_trace_invariants(&soup);
    }
}
