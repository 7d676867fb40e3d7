//! Step 5 — group-of-patches growing (paper §5.2, Algorithm 2).
//!
//! Patches are taken as cells of a local grid: a patch's east edge (1) meets its east
//! neighbour's west edge (3), its north edge (2) the north neighbour's south edge (0), both
//! running opposite ways (consistently oriented). Rotated and flipped neighbours are turned
//! into such neighbours beforehand ([`super::orient`]). A group is a rectangle of
//! `i × j` patches. It grows one row or column at a time in the direction that brings the
//! aspect ratio ρ of eq. (1), `(len(north) + len(south)) / (len(east) + len(west))`, closest to
//! 1, provided every patch along that side has such a neighbour, not yet grouped, across an
//! edge that is not a feature edge, with the same "topological length" (control points and
//! knots, so the nets can be merged), and the new row/column is itself a proper strip of the
//! grid. Growth stops when no side can grow. Seeds are taken in patch order, so the result is
//! deterministic; patches outside a row/column topology become groups of one.

use super::average::compatible;
use super::connectivity::Connection;
use super::edges::{arc_length_samples, edge_curve};
use crate::spline::NurbsSurface;
use std::collections::{HashMap, HashSet};

/// A rectangle of patches: `cells[i][j]` is the patch at column `i` (east) and row `j` (north).
#[derive(Clone, Debug, serde::Serialize)]
pub struct Group {
    pub cells: Vec<Vec<usize>>,
}

impl Group {
    pub fn columns(&self) -> usize {
        self.cells.len()
    }
    pub fn rows(&self) -> usize {
        self.cells.first().map_or(0, |c| c.len())
    }
}

/// Neighbour across each edge, for aligned connections only, with its feature flag.
struct Grid {
    east: HashMap<usize, usize>,
    north: HashMap<usize, usize>,
    west: HashMap<usize, usize>,
    south: HashMap<usize, usize>,
}

fn grid(
    patches: &[NurbsSurface<f64, 3>],
    connections: &[Connection],
    features: &HashSet<(usize, usize)>,
) -> Grid {
    let mut g = Grid {
        east: HashMap::new(),
        north: HashMap::new(),
        west: HashMap::new(),
        south: HashMap::new(),
    };
    for c in connections {
        if c.same_direction || features.contains(&(c.p, c.ep)) || features.contains(&(c.q, c.eq)) {
            continue;
        }
        if !compatible(&patches[c.p], c.ep, &patches[c.q], c.eq, false) {
            continue;
        }
        let mut link = |a: usize, ea: usize, b: usize, eb: usize| match (ea, eb) {
            (1, 3) => {
                g.east.insert(a, b);
                g.west.insert(b, a);
            }
            (2, 0) => {
                g.north.insert(a, b);
                g.south.insert(b, a);
            }
            _ => {}
        };
        link(c.p, c.ep, c.q, c.eq);
        link(c.q, c.eq, c.p, c.ep);
    }
    g
}

fn edge_length(s: &NurbsSurface<f64, 3>, e: usize) -> f64 {
    let pts = arc_length_samples(&edge_curve(s, e), 9);
    pts.windows(2)
        .map(|w| {
            let (a, b) = (w[0].1, w[1].1);
            ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
        })
        .sum()
}

/// Eq. (1) for a group (`len[4 * patch + edge]` are the edge lengths).
fn rho(len: &[f64], g: &Group) -> f64 {
    let (ni, nj) = (g.columns(), g.rows());
    let l = |p: usize, e: usize| len[4 * p + e];
    let ns: f64 = (0..ni)
        .map(|i| l(g.cells[i][0], 0) + l(g.cells[i][nj - 1], 2))
        .sum();
    let ew: f64 = (0..nj)
        .map(|j| l(g.cells[0][j], 3) + l(g.cells[ni - 1][j], 1))
        .sum();
    if ew > 0.0 { ns / ew } else { f64::INFINITY }
}

/// The strip the group would gain on side `d` (0 south, 1 east, 2 north, 3 west), if valid.
fn strip(g: &Group, grid: &Grid, used: &HashSet<usize>, d: usize) -> Option<Vec<usize>> {
    let (ni, nj) = (g.columns(), g.rows());
    let side: Vec<usize> = match d {
        0 => (0..ni).map(|i| g.cells[i][0]).collect(),
        1 => g.cells[ni - 1].clone(),
        2 => (0..ni).map(|i| g.cells[i][nj - 1]).collect(),
        _ => g.cells[0].clone(),
    };
    let map = [&grid.south, &grid.east, &grid.north, &grid.west][d];
    let new: Vec<usize> = side
        .iter()
        .map(|p| map.get(p).copied())
        .collect::<Option<_>>()?;
    let mut seen = HashSet::new();
    if new.iter().any(|p| used.contains(p) || !seen.insert(*p)) {
        return None;
    }
    // The new cells must be neighbours of each other along the strip.
    let along = if d.is_multiple_of(2) {
        &grid.east
    } else {
        &grid.north
    };
    if new.windows(2).any(|w| along.get(&w[0]) != Some(&w[1])) {
        return None;
    }
    Some(new)
}

fn grow(g: &mut Group, d: usize, new: Vec<usize>) {
    match d {
        0 => g
            .cells
            .iter_mut()
            .zip(new)
            .for_each(|(c, p)| c.insert(0, p)),
        1 => g.cells.push(new),
        2 => g.cells.iter_mut().zip(new).for_each(|(c, p)| c.push(p)),
        _ => g.cells.insert(0, new),
    }
}

/// Algorithm 2: groups covering every patch exactly once.
pub fn groups(
    patches: &[NurbsSurface<f64, 3>],
    connections: &[Connection],
    features: &HashSet<(usize, usize)>,
) -> Vec<Group> {
    let grid = grid(patches, connections, features);
    let len: Vec<f64> = patches
        .iter()
        .flat_map(|s| (0..4).map(move |e| edge_length(s, e)))
        .collect();
    let mut used: HashSet<usize> = HashSet::new();
    let mut out = Vec::new();
    for seed in 0..patches.len() {
        if used.contains(&seed) {
            continue;
        }
        used.insert(seed);
        let mut g = Group {
            cells: vec![vec![seed]],
        };
        loop {
            // Candidate sides, best aspect ratio after growing first (ties: lowest side).
            let mut best: Option<(f64, usize, Vec<usize>)> = None;
            for d in 0..4 {
                if let Some(new) = strip(&g, &grid, &used, d) {
                    let mut trial = g.clone();
                    grow(&mut trial, d, new.clone());
                    let score = (rho(&len, &trial).ln()).abs();
                    if best.as_ref().is_none_or(|b| score < b.0) {
                        best = Some((score, d, new));
                    }
                }
            }
            let Some((_, d, new)) = best else { break };
            used.extend(new.iter().copied());
            grow(&mut g, d, new);
        }
        out.push(g);
    }
    out
}
