//! Many local approximants, connected as in §3.7: a *layout* names a set of boundary
//! curves once and lists the approximants, each by the ids of its four sides (eq. (3)/(4) order: `J = 0`, `I = M`,
//! `J = N`, `I = 0`). Every approximant is built by [`approximate`]; then the resolutions
//! along shared curves are made equal (the larger count wins: an approximant whose count
//! along a shared side is smaller is rebuilt starting from the larger one), and
//! [`super::join`] makes the shared boundary rows identical bit for bit.
//!
//! Topology (§3.7): each boundary curve is shared by at most two approximants — a curve
//! used by more is refused ([`LayoutError::Overused`]); curves used once are the open
//! boundary of the replacement. Neighbours have the same number of control points along a
//! common curve (§3.7's compatibility, here per shared curve rather than one global count).
//! Not checked: the full-face interface property (a corner of one approximant lying inside
//! a side of another).

use super::boundary::{BoundarySpec, CurveSpec};
use super::{Approximant, CoonsError, Params, approximate};
use crate::model::Model;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One side of an approximant in the layout file: `{"curve": "id", "reversed": true}`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SideRef {
    pub curve: String,
    /// Traverse the curve backwards (otherwise the loop is oriented automatically).
    #[serde(default)]
    pub reversed: bool,
}

/// One approximant of the layout: four sides in loop order, an optional initial resolution.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ApproximantSpec {
    #[serde(default)]
    pub name: Option<String>,
    pub sides: Vec<SideRef>,
    /// Initial `M` and `N` (default: the parameters').
    #[serde(default)]
    pub m: Option<usize>,
    #[serde(default)]
    pub n: Option<usize>,
}

/// The layout file: boundary curves by id (entries as in the boundary file) and the
/// approximants.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Layout {
    pub curves: BTreeMap<String, CurveSpec>,
    pub approximants: Vec<ApproximantSpec>,
}

/// Errors of a layout.
#[derive(Debug, thiserror::Error)]
pub enum LayoutError {
    #[error("layout: {0}")]
    Parse(String),
    #[error("layout: approximant {approximant} has {count} sides, expected 4")]
    Sides { approximant: String, count: usize },
    #[error(
        "layout: approximant {approximant} names curve `{curve}`, which the layout does not define"
    )]
    UnknownCurve { approximant: String, curve: String },
    #[error("layout: approximant {approximant} uses curve `{curve}` twice")]
    Repeated { approximant: String, curve: String },
    /// A curve shared by more than two approximants: the replacement would not be a surface.
    #[error("layout: curve `{curve}` is used by {} approximants ({}), at most 2 may share a curve", users.len(), users.join(", "))]
    Overused { curve: String, users: Vec<String> },
    #[error("layout: no approximants")]
    Empty,
    #[error("approximant {approximant}: {source}")]
    Coons {
        approximant: String,
        source: CoonsError,
    },
}

impl LayoutError {
    /// Whether the user's input is at fault.
    pub fn is_bad_input(&self) -> bool {
        match self {
            LayoutError::Coons { source, .. } => {
                !matches!(source, CoonsError::NotFinite(_) | CoonsError::Spline(_))
            }
            _ => true,
        }
    }
}

impl Layout {
    /// Parse the JSON text; a fault names its JSON path.
    pub fn parse(text: &str) -> Result<Layout, LayoutError> {
        let de = &mut serde_json::Deserializer::from_str(text);
        serde_path_to_error::deserialize(de)
            .map_err(|e| LayoutError::Parse(format!("{}: {}", e.path(), e.inner())))
    }

    /// Name of approximant `a` (its own or `#a`).
    pub fn name(&self, a: usize) -> String {
        self.approximants[a]
            .name
            .clone()
            .unwrap_or_else(|| format!("#{a}"))
    }
}

/// Where a curve is used: approximant and side.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Use {
    pub approximant: usize,
    pub side: usize,
}

/// The layout's topology: the users of every curve.
#[derive(Clone, Debug, Serialize)]
pub struct Topology {
    /// Curves used by two approximants: `(curve id, [first use, second use])`.
    pub shared: Vec<(String, [Use; 2])>,
    /// Curves used by one approximant: the open boundary of the replacement.
    pub open: Vec<String>,
    /// Curves defined but not used.
    pub unused: Vec<String>,
}

/// Check the layout: four sides each, known curves, no curve twice in one approximant, no
/// curve in more than two approximants.
pub fn topology(layout: &Layout) -> Result<Topology, LayoutError> {
    if layout.approximants.is_empty() {
        return Err(LayoutError::Empty);
    }
    let mut users: BTreeMap<&str, Vec<Use>> = BTreeMap::new();
    for (a, spec) in layout.approximants.iter().enumerate() {
        if spec.sides.len() != 4 {
            return Err(LayoutError::Sides {
                approximant: layout.name(a),
                count: spec.sides.len(),
            });
        }
        for (k, s) in spec.sides.iter().enumerate() {
            if !layout.curves.contains_key(&s.curve) {
                return Err(LayoutError::UnknownCurve {
                    approximant: layout.name(a),
                    curve: s.curve.clone(),
                });
            }
            let u = users.entry(s.curve.as_str()).or_default();
            if u.iter().any(|u| u.approximant == a) {
                return Err(LayoutError::Repeated {
                    approximant: layout.name(a),
                    curve: s.curve.clone(),
                });
            }
            u.push(Use {
                approximant: a,
                side: k,
            });
        }
    }
    let mut t = Topology {
        shared: Vec::new(),
        open: Vec::new(),
        unused: Vec::new(),
    };
    for id in layout.curves.keys() {
        match users.get(id.as_str()).map(|u| u.as_slice()) {
            None | Some([]) => t.unused.push(id.clone()),
            Some([_]) => t.open.push(id.clone()),
            Some([a, b]) => t.shared.push((id.clone(), [a.clone(), b.clone()])),
            Some(u) => {
                return Err(LayoutError::Overused {
                    curve: id.clone(),
                    users: u.iter().map(|u| layout.name(u.approximant)).collect(),
                });
            }
        }
    }
    Ok(t)
}

/// The boundary file of approximant `a`: its four curves, reversed as the side says
/// (relative to the curve's own entry), named by their ids unless the entry names them.
pub fn boundary_spec(layout: &Layout, a: usize) -> Result<BoundarySpec, LayoutError> {
    let mut curves = Vec::with_capacity(4);
    for s in &layout.approximants[a].sides {
        let mut c = layout
            .curves
            .get(&s.curve)
            .ok_or_else(|| LayoutError::UnknownCurve {
                approximant: layout.name(a),
                curve: s.curve.clone(),
            })?
            .clone();
        c.reversed ^= s.reversed;
        c.name = Some(c.name.unwrap_or_else(|| s.curve.clone()));
        curves.push(c);
    }
    Ok(BoundarySpec { curves })
}

/// The count of grid intervals along side `k` (`M` on sides 0 and 2, `N` on 1 and 3).
pub fn side_count(m: usize, n: usize, k: usize) -> usize {
    if k.is_multiple_of(2) { m } else { n }
}

/// Build every approximant with [`approximate`] and make the resolution along every shared
/// curve equal: where one neighbour ended with a smaller count along the shared side, it is
/// rebuilt from the larger count (counts only grow, bounded by `max_resolution`, so this
/// ends). Returns the approximants and how many rebuilds it took.
pub fn build_all(
    model: &Model,
    layout: &Layout,
    topo: &Topology,
    params: &Params,
    progress: &mut dyn FnMut(&str, usize),
) -> Result<(Vec<Approximant>, usize), LayoutError> {
    let count = layout.approximants.len();
    let mut start: Vec<(usize, usize)> = layout
        .approximants
        .iter()
        .map(|s| (s.m.unwrap_or(params.m), s.n.unwrap_or(params.n)))
        .collect();
    // The requested counts along shared sides: the larger of the two.
    for (_, [p, q]) in &topo.shared {
        let want = side_count(start[p.approximant].0, start[p.approximant].1, p.side).max(
            side_count(start[q.approximant].0, start[q.approximant].1, q.side),
        );
        for u in [p, q] {
            raise(&mut start[u.approximant], u.side, want);
        }
    }
    let one = |a: usize, (m, n): (usize, usize)| {
        let p = Params {
            m: m.min(params.max_resolution),
            n: n.min(params.max_resolution),
            ..params.clone()
        };
        approximate(model, &boundary_spec(layout, a)?, &p).map_err(|source| LayoutError::Coons {
            approximant: layout.name(a),
            source,
        })
    };
    let mut aps = Vec::with_capacity(count);
    for (a, s) in start.iter().enumerate() {
        progress("approximant", a);
        aps.push(one(a, *s)?);
    }
    let mut rebuilds = 0;
    loop {
        let mut want: Vec<(usize, usize)> =
            aps.iter().map(|ap| (ap.report.m, ap.report.n)).collect();
        for (_, [p, q]) in &topo.shared {
            let c = |u: &Use| {
                let r = &aps[u.approximant].report;
                side_count(r.m, r.n, u.side)
            };
            let w = c(p).max(c(q));
            for u in [p, q] {
                raise(&mut want[u.approximant], u.side, w);
            }
        }
        let stale: Vec<usize> = (0..count)
            .filter(|a| want[*a] != (aps[*a].report.m, aps[*a].report.n))
            .collect();
        if stale.is_empty() {
            return Ok((aps, rebuilds));
        }
        for a in stale {
            progress("rebuilt approximant", a);
            aps[a] = one(a, want[a])?;
            rebuilds += 1;
        }
    }
}

fn raise(mn: &mut (usize, usize), side: usize, want: usize) {
    let c = if side.is_multiple_of(2) {
        &mut mn.0
    } else {
        &mut mn.1
    };
    *c = (*c).max(want);
}
