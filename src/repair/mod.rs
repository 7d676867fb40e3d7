//! Repair of faulty CAD patch sets (Uva, Monno & Hamann; docs/papers.md §C), one file per step:
//!
//! | step | file |
//! |---|---|
//! | corners, edges, arc-length samples, closest points | [`edges`] |
//! | 1 connectivity (Algorithm 1), T-connectivity | [`connectivity`], [`kdtree`] |
//! | 2 edge verification | [`fn@verify`] |
//! | 3 boundary averaging | [`average`]; knot classes [`classes`], fitted shared curves [`fit_edge`], interior blending and deviation [`blend`] |
//! | 4 feature lines | [`fn@features`] |
//! | 5 group-of-patches growing (Algorithm 2) | [`group`]; common i/j directions [`orient`] |
//! | 6 merging control information | [`merge`] |

pub mod average;
pub mod blend;
pub mod classes;
pub mod connectivity;
pub mod edges;
pub mod faces;
pub mod features;
pub mod fit_edge;
pub mod group;
pub mod job;
pub mod kdtree;
pub mod merge;
pub mod orient;
pub mod picture;
pub mod verify;

use connectivity::{Connection, TJunction, connect, split, t_junctions};
use features::{FeatureEdge, FeatureOverrides, features};
use serde::Serialize;
use verify::{VerifiedEdge, verify};

use crate::spline::NurbsSurface;

#[derive(Debug, thiserror::Error)]
pub enum RepairError {
    #[error("{0} must be a positive finite number, got {1}")]
    Parameter(&'static str, f64),
    #[error("patch {0}: {1}")]
    Patch(usize, String),
    #[error("no patches to repair")]
    Empty,
    #[error("no faces to repair: the model has no B-rep")]
    NoFaces,
    #[error("B-rep: {0}")]
    Brep(String),
    #[error(
        "feature override [{0}, {1}] names no patch edge (patches 0..{2}, edges 0 south, 1 east, 2 north, 3 west)"
    )]
    Override(usize, usize, usize),
}

#[derive(Clone, Debug)]
pub struct RepairParams {
    /// Corner distance threshold of Algorithm 1.
    pub u1: f64,
    /// Largest gap along an edge for two edges to count as shared (§3.1).
    pub u2: f64,
    pub feature_angle_deg: f64,
    /// Samples per edge for verification and feature detection.
    pub samples: usize,
    /// Rounds of T-junction splitting.
    pub max_t_rounds: usize,
    /// T-junction splits allowed per input patch, in total: a split's new corners can land
    /// on other patches' edges (folded or degenerate patches), so splitting is bounded
    /// linearly in the input; T-junctions left when the budget is spent are reported.
    pub max_t_splits_per_patch: usize,
}

impl Default for RepairParams {
    fn default() -> Self {
        RepairParams {
            u1: 1e-3,
            u2: 1e-3,
            feature_angle_deg: 30.0,
            samples: 16,
            max_t_rounds: 8,
            max_t_splits_per_patch: 4,
        }
    }
}

/// The report (JSON and human).
#[derive(Clone, Debug, Serialize)]
pub struct RepairReport {
    pub patches_in: usize,
    pub patches_out: usize,
    /// For every output patch, the input patches it is made of (a T-junction split keeps its
    /// origin; a merged group lists all): every input patch is accounted for.
    pub patch_origin: Vec<Vec<usize>>,
    pub candidate_edges: usize,
    pub edges_connected: usize,
    pub t_junctions: usize,
    pub t_junction_splits: Vec<TJunction>,
    /// Edges with more than one partner `(patch, edge, partners)`: reported, not forced.
    pub non_manifold: Vec<(usize, usize, usize)>,
    /// Connected pairs whose edges run the same way (one patch flipped).
    pub flipped_pairs: usize,
    pub collapsed_edges: usize,
    /// Patch edges without a connected partner and not collapsed (boundary of the set, or
    /// gaps left).
    pub free_edges: usize,
    pub gap_max_before: f64,
    pub gap_mean_before: f64,
    /// `(upper bound of bin, count)`, bins by decades of u2.
    pub gap_histogram: Vec<(f64, usize)>,
    /// Candidate pairs with a gap of at least u2: left disconnected.
    pub gaps_left: Vec<VerifiedEdge>,
    /// Largest gap over connected pairs after averaging (measured at samples).
    pub gap_max_after: f64,
    pub shared_edges_identical: usize,
    pub averaging: average::AveragingOutcome,
    pub feature_edges: usize,
    pub features_overridden: usize,
    pub edges: Vec<FeatureEdge>,
    /// Number of groups of patches (Algorithm 2), and their sizes `(columns, rows)`.
    pub groups: Option<usize>,
    pub group_sizes: Vec<(usize, usize)>,
    /// Groups whose nets could not be merged (kept as their patches).
    pub groups_not_merged: usize,
    /// Patches of merged groups that were turned (u/v swap, reversal) to fit their group's
    /// rows and columns.
    pub reoriented: usize,
    /// Largest measured deviation of a merged surface from one of its patches (7 × 7 samples).
    pub max_merge_deviation: Option<f64>,
    pub not_done: Vec<String>,
    pub seconds: f64,
}

pub struct RepairResult {
    /// The output patches (merged groups, and patches left alone).
    pub patches: Vec<NurbsSurface<f64, 3>>,
    /// The patches after T-junction splitting and averaging, before merging: the indices in
    /// the report's edges, gaps and groups refer to these.
    pub connected_patches: Vec<NurbsSurface<f64, 3>>,
    pub report: RepairReport,
}

/// The parameters checked: `u1`, `u2` positive and finite, the feature angle in (0, 180).
fn check_params(prm: &RepairParams) -> Result<(), RepairError> {
    for (name, v) in [("u1", prm.u1), ("u2", prm.u2)] {
        if !(v > 0.0 && v.is_finite()) {
            return Err(RepairError::Parameter(name, v));
        }
    }
    if !(prm.feature_angle_deg > 0.0 && prm.feature_angle_deg < 180.0) {
        return Err(RepairError::Parameter(
            "feature angle (degrees, in (0, 180))",
            prm.feature_angle_deg,
        ));
    }
    Ok(())
}

fn check(prm: &RepairParams, patches: &[NurbsSurface<f64, 3>]) -> Result<(), RepairError> {
    check_params(prm)?;
    if patches.is_empty() {
        return Err(RepairError::Empty);
    }
    for (i, s) in patches.iter().enumerate() {
        let (pts, w) = s.points_weights();
        if let Some(k) = pts.iter().position(|p| p.iter().any(|c| !c.is_finite())) {
            return Err(RepairError::Patch(
                i,
                format!("control point {k} is not finite"),
            ));
        }
        if w.iter().any(|x| !(x.is_finite() && *x > 0.0)) {
            return Err(RepairError::Patch(
                i,
                "a weight is not a positive finite number".into(),
            ));
        }
    }
    Ok(())
}

/// Run steps 1–4 on `patches`.
pub fn repair(
    patches: Vec<NurbsSurface<f64, 3>>,
    prm: &RepairParams,
    overrides: &FeatureOverrides,
    progress: &dyn Fn(&str),
) -> Result<RepairResult, RepairError> {
    let t0 = std::time::Instant::now();
    check(prm, &patches)?;
    let patches_in = patches.len();
    let mut patches = patches;
    let mut origin: Vec<usize> = (0..patches_in).collect();
    let mut splits = Vec::new();
    progress("connectivity and T-junctions");
    let split_budget = prm.max_t_splits_per_patch.saturating_mul(patches_in);
    let mut unsplit = 0;
    for _ in 0..prm.max_t_rounds {
        let tj = t_junctions(&patches, prm.u1);
        if tj.is_empty() {
            break;
        }
        if splits.len() >= split_budget {
            unsplit = tj.len();
            break;
        }
        // One split per patch per round (the others are found again on the halves).
        let mut done = std::collections::BTreeSet::new();
        for t in tj {
            if splits.len() >= split_budget {
                unsplit += 1;
                continue;
            }
            if !done.insert(t.patch) {
                continue;
            }
            if let Some((a, b)) = split(&patches[t.patch], t.edge % 2 == 0, t.parameter) {
                patches[t.patch] = a;
                patches.push(b);
                origin.push(origin[t.patch]);
                splits.push(t);
            }
        }
    }
    // Overrides name edges of the patches after splitting (as the report does); one that
    // names no edge would be ignored silently.
    if let Some(&(p, e)) = overrides
        .add
        .iter()
        .chain(&overrides.remove)
        .find(|(p, e)| *p >= patches.len() || *e >= 4)
    {
        return Err(RepairError::Override(p, e, patches.len()));
    }
    let candidates = connect(&patches, prm.u1);
    progress("edge verification");
    let verified = verify(&patches, &candidates, prm.u2, prm.samples);
    let connected: Vec<Connection> = verified
        .iter()
        .filter(|v| v.connected)
        .map(|v| v.connection)
        .collect();
    let mut partners: std::collections::BTreeMap<(usize, usize), usize> =
        std::collections::BTreeMap::new();
    for c in &connected {
        *partners.entry((c.p, c.ep)).or_default() += 1;
        *partners.entry((c.q, c.eq)).or_default() += 1;
    }
    let non_manifold: Vec<(usize, usize, usize)> = partners
        .iter()
        .filter(|(_, n)| **n > 1)
        .map(|(&(p, e), &n)| (p, e, n))
        .collect();
    let manifold_gaps: Vec<(Connection, f64)> = verified
        .iter()
        .filter(|v| v.connected)
        .filter(|v| {
            let c = &v.connection;
            partners[&(c.p, c.ep)] == 1 && partners[&(c.q, c.eq)] == 1
        })
        .map(|v| (v.connection, v.gap))
        .collect();
    let manifold: Vec<Connection> = manifold_gaps.iter().map(|x| x.0).collect();
    let gaps_of: Vec<f64> = manifold_gaps.iter().map(|x| x.1).collect();
    progress("feature lines");
    let fe = features(
        &patches,
        &verified,
        prm.feature_angle_deg,
        prm.samples,
        overrides,
    );
    progress("boundary averaging");
    let averaging = average::average(&mut patches, &manifold, &gaps_of);
    let n_left = averaging.left.len();
    use rayon::prelude::*;
    let gap_max_after = manifold
        .par_iter()
        .map(|c| verify::edge_gap(&patches[c.p], c.ep, &patches[c.q], c.eq, prm.samples))
        .reduce(|| 0.0, f64::max);
    let shared_edges_identical = manifold
        .iter()
        .filter(|c| average::identical(&patches[c.p], c.ep, &patches[c.q], c.eq, c.same_direction))
        .count();
    progress("grouping and merging");
    let feature_set: std::collections::HashSet<(usize, usize)> = fe
        .iter()
        .filter(|f| f.feature)
        .flat_map(|f| [(f.p, f.ep), (f.q, f.eq)])
        .collect();
    // Rotated and flipped neighbours are turned into east-west / north-south neighbours first.
    let usable: Vec<Connection> = manifold
        .iter()
        .filter(|c| !feature_set.contains(&(c.p, c.ep)) && !feature_set.contains(&(c.q, c.eq)))
        .copied()
        .collect();
    let orientation = orient::orient(patches.len(), &usable);
    let turned: Vec<NurbsSurface<f64, 3>> = patches
        .iter()
        .zip(&orientation)
        .map(|(s, o)| {
            if o.is_identity() {
                s.clone()
            } else {
                orient::apply(s, o)
            }
        })
        .collect();
    let turned_conns: Vec<Connection> = manifold
        .iter()
        .map(|c| orient::transform(c, &orientation))
        .collect();
    let turned_features: std::collections::HashSet<(usize, usize)> = feature_set
        .iter()
        .map(|&(p, e)| (p, orientation[p].edge(e)))
        .collect();
    let gs = group::groups(&turned, &turned_conns, &turned_features);
    let mut reoriented = 0;
    let mut out_patches = Vec::new();
    let mut out_origin: Vec<Vec<usize>> = Vec::new();
    let mut max_dev: f64 = 0.0;
    let mut not_merged = 0;
    for g in &gs {
        let members: Vec<usize> = g.cells.iter().flatten().copied().collect();
        if members.len() > 1
            && let Some((m, d)) = merge::merge(&turned, g)
        {
            max_dev = max_dev.max(d);
            reoriented += members
                .iter()
                .filter(|&&k| !orientation[k].is_identity())
                .count();
            out_patches.push(m);
            let mut o: Vec<usize> = members.iter().map(|&k| origin[k]).collect();
            o.sort_unstable();
            o.dedup();
            out_origin.push(o);
            continue;
        }
        not_merged += usize::from(members.len() > 1);
        for k in members {
            out_patches.push(patches[k].clone());
            out_origin.push(vec![origin[k]]);
        }
    }
    let gaps: Vec<f64> = verified
        .iter()
        .filter(|v| v.connected)
        .map(|v| v.gap)
        .collect();
    let mut hist = Vec::new();
    let mut top = prm.u2;
    for _ in 0..6 {
        hist.push((
            top,
            gaps.iter()
                .filter(|g| **g <= top && **g > top / 10.0)
                .count(),
        ));
        top /= 10.0;
    }
    hist.push((top, gaps.iter().filter(|g| **g <= top).count()));
    let collapsed_edges = patches
        .iter()
        .map(|s| {
            (0..4)
                .filter(|&k| edges::collapsed(&edges::edge_curve(s, k)))
                .count()
        })
        .sum();
    let free_edges = 4 * patches.len() - collapsed_edges - partners.len();
    let report = RepairReport {
        free_edges,
        patches_in,
        patches_out: out_patches.len(),
        patch_origin: out_origin,
        candidate_edges: candidates.len(),
        edges_connected: connected.len(),
        t_junctions: splits.len(),
        t_junction_splits: splits,
        non_manifold,
        flipped_pairs: connected.iter().filter(|c| c.same_direction).count(),
        collapsed_edges,
        gap_max_before: gaps.iter().copied().fold(0.0, f64::max),
        gap_mean_before: if gaps.is_empty() {
            0.0
        } else {
            gaps.iter().sum::<f64>() / gaps.len() as f64
        },
        gap_histogram: hist,
        gaps_left: verified.iter().filter(|v| !v.connected).copied().collect(),
        gap_max_after,
        shared_edges_identical,
        averaging,
        feature_edges: fe.iter().filter(|f| f.feature).count(),
        features_overridden: fe.iter().filter(|f| f.overridden).count(),
        edges: fe,
        groups: Some(gs.len()),
        group_sizes: gs.iter().map(|g| (g.columns(), g.rows())).collect(),
        groups_not_merged: not_merged,
        reoriented,
        max_merge_deviation: Some(max_dev),
        not_done: {
            let mut v: Vec<String> = Vec::new();
            if n_left > 0 {
                v.push(format!(
                    "{n_left} connected pair(s) left as they were: averaging.left gives each one's reason"
                ));
            }
            if unsplit > 0 {
                v.push(format!(
                    "T-junction split budget ({} per input patch, {split_budget} in all) spent: {unsplit} T-junction(s) left unsplit",
                    prm.max_t_splits_per_patch
                ));
            }
            v
        },
        seconds: t0.elapsed().as_secs_f64(),
    };
    Ok(RepairResult {
        patches: out_patches,
        connected_patches: patches,
        report,
    })
}
