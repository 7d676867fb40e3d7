//! Step 1 — adaptive triangulation of a parametric surface by recursive subdivision
//! (paper §4, "Triangulation", Fig. 14; quadtree subdivision after Samet '90).
//!
//! The domain is first cut at the surface's distinct knots (each root cell is one polynomial
//! piece), then every cell is split into four until it is flat within the flatness tolerance:
//! the surface at the cell centre and at its edge midpoints lies within `flatness` of the
//! bilinear interpolant of the corners, and the cell's corner span is at most `max_edge`.
//!
//! Parameters live on an integer lattice (`2^LEVELS` steps per knot span), so a vertex is a
//! lattice key, evaluated once and shared by every cell that touches it: one vertex list, no
//! slight mismatches. Cracks between cells of different levels are closed by fanning each
//! leaf around its centre through every vertex on its boundary, including the hanging
//! corners of finer neighbours. Each vertex keeps its `(u, v)`.

use crate::geom::dist;
use crate::spline::NurbsSurface;
use crate::spline::closure::Closure;
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};
use std::collections::BTreeSet;

/// Lattice steps per knot span are `2^LEVELS`; leaves stop one level above so their centre
/// is a lattice point.
pub const LEVELS: u32 = 20;
const SPAN: u64 = 1 << LEVELS;
/// Most leaf cells of one surface's triangulation.
pub const MAX_CELLS: usize = 1 << 18;

/// A cell of the subdivision, by its lattice corners `[u0, u1) × [v0, v1)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct CellKey {
    pub u0: u64,
    pub u1: u64,
    pub v0: u64,
    pub v1: u64,
}

/// How finely to triangulate.
#[derive(Clone, Copy, Debug)]
pub struct TriangulateParams {
    /// Largest allowed distance of centre / edge-midpoint samples from the bilinear cell.
    pub flatness: f64,
    /// Largest allowed distance between opposite cell corners (model units).
    pub max_edge: f64,
    /// Deepest subdivision level below a knot span.
    pub max_depth: u32,
}

/// A triangulated surface: shared vertices with their parameters, and triangles that are
/// counter-clockwise in `(u, v)` (so their normals follow `S_u × S_v`).
#[derive(Clone, Debug, Default)]
pub struct SurfaceMesh {
    pub vertices: Vec<[f64; 3]>,
    pub uv: Vec<[f64; 2]>,
    pub triangles: Vec<[u32; 3]>,
    /// Leaf cells; `tri_cell[t]` is the index of the leaf triangle `t` lies in.
    pub cells: Vec<CellKey>,
    pub tri_cell: Vec<u32>,
    /// Cells that reached `max_depth` while still not flat.
    pub unresolved_cells: usize,
    /// Topological vertex number: vertices on the domain border with bit-identical
    /// coordinates (a closed seam, a collapsed edge) share one, so a curve crossing a seam
    /// stays one curve. Parameters stay per vertex.
    pub topo_id: Vec<u32>,
}

impl SurfaceMesh {
    /// The parameter box `[u0, u1, v0, v1]` of triangle `t`'s vertices.
    pub fn uv_box(&self, t: u32) -> [f64; 4] {
        let v = self.triangles[t as usize].map(|i| self.uv[i as usize]);
        [
            v[0][0].min(v[1][0]).min(v[2][0]),
            v[0][0].max(v[1][0]).max(v[2][0]),
            v[0][1].min(v[1][1]).min(v[2][1]),
            v[0][1].max(v[1][1]).max(v[2][1]),
        ]
    }
    /// Triangle `t` with topological vertex numbers.
    pub fn topo_triangle(&self, t: u32) -> [u32; 3] {
        self.triangles[t as usize].map(|v| self.topo_id[v as usize])
    }
}

/// Weld border vertices by the surface's closure ([`Closure`], decided exactly from the
/// control net): every vertex of a collapsed border becomes the border's single point, and a
/// vertex on one side of a closed seam takes the coordinates and number of its partner on the
/// other side (same lattice parameter along the seam). Remaining border vertices with
/// bit-identical coordinates share a number too. See [`SurfaceMesh::topo_id`].
fn weld_border(
    m: &mut SurfaceMesh,
    keys: &[(u64, u64)],
    closure: &Closure,
    poles: &[[f64; 3]; 4],
    top: (u64, u64),
) {
    m.topo_id = (0..m.vertices.len() as u32).collect();
    let index: HashMap<(u64, u64), u32> = keys
        .iter()
        .enumerate()
        .map(|(k, &ij)| (ij, k as u32))
        .collect();
    let mut pole_id: [Option<u32>; 4] = [None; 4];
    for (k, &(i, j)) in keys.iter().enumerate() {
        let sides = [i == 0, i == top.0, j == 0, j == top.1];
        for s in 0..4 {
            if sides[s] && closure.degenerate[s] {
                let id = *pole_id[s].get_or_insert(k as u32);
                m.topo_id[k] = id;
                m.vertices[k] = poles[s];
            }
        }
    }
    for (k, &(i, j)) in keys.iter().enumerate() {
        let partner = if closure.seam_u && i == top.0 {
            index.get(&(0, j))
        } else if closure.seam_v && j == top.1 {
            index.get(&(i, 0))
        } else {
            None
        };
        if let Some(&p) = partner {
            let root = m.topo_id[p as usize];
            m.vertices[k] = m.vertices[root as usize];
            m.topo_id[k] = root;
        }
    }
    // Corners on two seams (a torus) or a seam and a pole: follow chains to the root.
    for k in 0..m.topo_id.len() {
        let mut r = m.topo_id[k];
        while m.topo_id[r as usize] != r {
            r = m.topo_id[r as usize];
        }
        m.topo_id[k] = r;
        m.vertices[k] = m.vertices[r as usize];
    }
    let (u0, u1, v0, v1) = bounds(m);
    let mut first: HashMap<[u64; 3], u32> = HashMap::default();
    for i in 0..m.vertices.len() {
        let uv = m.uv[i];
        if m.topo_id[i] != i as u32 || !(uv[0] == u0 || uv[0] == u1 || uv[1] == v0 || uv[1] == v1) {
            continue;
        }
        let key = m.vertices[i].map(|c| if c == 0.0 { 0 } else { c.to_bits() });
        let id = *first.entry(key).or_insert(i as u32);
        m.topo_id[i] = id;
    }
    for k in 0..m.topo_id.len() {
        let r = m.topo_id[m.topo_id[k] as usize];
        m.topo_id[k] = r;
    }
}

/// The surface's parameter lattice: distinct knots per direction.
pub struct Lattice {
    pub knots_u: Vec<f64>,
    pub knots_v: Vec<f64>,
}

impl Lattice {
    pub fn of(s: &NurbsSurface<f64, 3>) -> Lattice {
        Lattice {
            knots_u: s.hom.ku.breakpoints(),
            knots_v: s.hom.kv.breakpoints(),
        }
    }
    fn coord(knots: &[f64], i: u64) -> f64 {
        let span = (i / SPAN) as usize;
        let k = i % SPAN;
        if span + 1 >= knots.len() {
            return knots[knots.len() - 1];
        }
        if k == 0 {
            return knots[span];
        }
        let (a, b) = (knots[span], knots[span + 1]);
        a + (b - a) * (k as f64 / SPAN as f64)
    }
    /// Parameter of lattice point `(i, j)`.
    pub fn uv(&self, i: u64, j: u64) -> [f64; 2] {
        [Self::coord(&self.knots_u, i), Self::coord(&self.knots_v, j)]
    }
}

struct Evaluator<'a> {
    s: &'a NurbsSurface<f64, 3>,
    lat: &'a Lattice,
    cache: &'a mut Evaluations,
}

/// Points of one surface at lattice parameters, kept between the triangulations of a run
/// (the rounds of refinement near tangency evaluate the same corners and midpoints again).
/// Valid for one surface only: the keys are its lattice's indices.
#[derive(Debug, Default)]
pub struct Evaluations(HashMap<(u64, u64), [f64; 3]>);

impl Evaluator<'_> {
    fn at(&mut self, i: u64, j: u64) -> [f64; 3] {
        let (s, lat) = (self.s, self.lat);
        *self.cache.0.entry((i, j)).or_insert_with(|| {
            let [u, v] = lat.uv(i, j);
            s.eval(&u, &v)
        })
    }
}

fn mid(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    std::array::from_fn(|k| 0.5 * (a[k] + b[k]))
}

/// Whether a cell must be split: not flat, too large, or not finite.
fn needs_split(ev: &mut Evaluator, c: &CellKey, prm: &TriangulateParams) -> bool {
    let (um, vm) = ((c.u0 + c.u1) / 2, (c.v0 + c.v1) / 2);
    let p00 = ev.at(c.u0, c.v0);
    let p10 = ev.at(c.u1, c.v0);
    let p01 = ev.at(c.u0, c.v1);
    let p11 = ev.at(c.u1, c.v1);
    if dist(&p00, &p11) > prm.max_edge || dist(&p10, &p01) > prm.max_edge {
        return true;
    }
    let checks = [
        (ev.at(um, c.v0), mid(&p00, &p10)),
        (ev.at(um, c.v1), mid(&p01, &p11)),
        (ev.at(c.u0, vm), mid(&p00, &p01)),
        (ev.at(c.u1, vm), mid(&p10, &p11)),
        (ev.at(um, vm), mid(&mid(&p00, &p11), &mid(&p10, &p01))),
    ];
    checks.iter().any(|(s, l)| {
        let d = dist(s, l);
        d.is_nan() || d > prm.flatness
    })
}

/// Leaf cells of the adaptive subdivision. `force` lists cells that must be split once more
/// (used to refine near tangency).
pub fn leaf_cells(
    s: &NurbsSurface<f64, 3>,
    lat: &Lattice,
    prm: &TriangulateParams,
    force: &HashSet<CellKey>,
) -> (Vec<CellKey>, usize) {
    leaf_cells_with(s, lat, prm, force, &mut Evaluations::default())
}

/// [`leaf_cells`] with the surface's points taken from, and added to, `cache`.
fn leaf_cells_with(
    s: &NurbsSurface<f64, 3>,
    lat: &Lattice,
    prm: &TriangulateParams,
    force: &HashSet<CellKey>,
    cache: &mut Evaluations,
) -> (Vec<CellKey>, usize) {
    let mut ev = Evaluator { s, lat, cache };
    let depth_cap = prm.max_depth.min(LEVELS - 1);
    let mut stack: Vec<(CellKey, u32)> = Vec::new();
    for i in (0..lat.knots_u.len().saturating_sub(1)).rev() {
        for j in (0..lat.knots_v.len().saturating_sub(1)).rev() {
            let (i, j) = (i as u64, j as u64);
            stack.push((
                CellKey {
                    u0: i * SPAN,
                    u1: (i + 1) * SPAN,
                    v0: j * SPAN,
                    v1: (j + 1) * SPAN,
                },
                0,
            ));
        }
    }
    let mut leaves = Vec::new();
    let mut unresolved = 0;
    while let Some((c, d)) = stack.pop() {
        let split = force.contains(&c) || needs_split(&mut ev, &c, prm);
        // A cell budget bounds time and memory whatever the flatness asked for (e.g.
        // `--flatness 1e-300`): past it, cells stay unsplit and are counted unresolved.
        let room = leaves.len() + stack.len() + 4 <= MAX_CELLS;
        if split && d < depth_cap && room {
            let (um, vm) = ((c.u0 + c.u1) / 2, (c.v0 + c.v1) / 2);
            for (u0, u1, v0, v1) in [
                (um, c.u1, vm, c.v1),
                (c.u0, um, vm, c.v1),
                (um, c.u1, c.v0, vm),
                (c.u0, um, c.v0, vm),
            ] {
                stack.push((CellKey { u0, u1, v0, v1 }, d + 1));
            }
        } else {
            if split {
                unresolved += 1;
            }
            leaves.push(c);
        }
    }
    leaves.sort();
    (leaves, unresolved)
}

/// Give both sides of a closed seam the same border vertices: `first` holds lattice points
/// keyed by the coordinate across the seam (0 or `top` on its two sides), `second` the same
/// points with the keys swapped.
fn mirror_seam(first: &mut BTreeSet<(u64, u64)>, second: &mut BTreeSet<(u64, u64)>, top: u64) {
    let side: Vec<u64> = first
        .iter()
        .filter(|&&(a, _)| a == 0 || a == top)
        .map(|&(_, b)| b)
        .collect();
    for b in side {
        for a in [0, top] {
            first.insert((a, b));
            second.insert((b, a));
        }
    }
}

/// Triangulate the leaves crack-free (see the module comment).
pub fn triangulate_cells(
    s: &NurbsSurface<f64, 3>,
    lat: &Lattice,
    leaves: Vec<CellKey>,
    unresolved: usize,
) -> SurfaceMesh {
    triangulate_cells_with(s, lat, leaves, unresolved, &mut Evaluations::default())
}

/// [`triangulate_cells`] with the vertices taken from, and added to, `cache`.
fn triangulate_cells_with(
    s: &NurbsSurface<f64, 3>,
    lat: &Lattice,
    leaves: Vec<CellKey>,
    unresolved: usize,
    cache: &mut Evaluations,
) -> SurfaceMesh {
    // Corners of all leaves, sorted along horizontal (v, u) and vertical (u, v) lines.
    let mut horiz: BTreeSet<(u64, u64)> = BTreeSet::new();
    let mut vert: BTreeSet<(u64, u64)> = BTreeSet::new();
    for c in &leaves {
        for (i, j) in [(c.u0, c.v0), (c.u1, c.v0), (c.u0, c.v1), (c.u1, c.v1)] {
            horiz.insert((j, i));
            vert.insert((i, j));
        }
    }
    // Across a closed seam both sides get the same border vertices (hanging vertices where
    // the two sides are subdivided differently), so the seam can be welded crack-free.
    let closure = Closure::of(s);
    let top = (
        (lat.knots_u.len().max(1) as u64 - 1) * SPAN,
        (lat.knots_v.len().max(1) as u64 - 1) * SPAN,
    );
    if closure.seam_u {
        mirror_seam(&mut vert, &mut horiz, top.0);
    }
    if closure.seam_v {
        mirror_seam(&mut horiz, &mut vert, top.1);
    }
    let poles: [[f64; 3]; 4] = std::array::from_fn(|k| {
        if closure.degenerate[k] {
            Closure::pole(s, k)
        } else {
            [0.0; 3]
        }
    });
    let mut keys: Vec<(u64, u64)> = Vec::new();
    let mut mesh = SurfaceMesh {
        unresolved_cells: unresolved,
        ..Default::default()
    };
    let mut index: HashMap<(u64, u64), u32> = HashMap::default();
    let mut vertex = |mesh: &mut SurfaceMesh, i: u64, j: u64| -> u32 {
        *index.entry((i, j)).or_insert_with(|| {
            keys.push((i, j));
            let uv = lat.uv(i, j);
            let p = *cache
                .0
                .entry((i, j))
                .or_insert_with(|| s.eval(&uv[0], &uv[1]));
            mesh.vertices.push(p);
            mesh.uv.push(uv);
            (mesh.vertices.len() - 1) as u32
        })
    };
    for (ci, c) in leaves.iter().enumerate() {
        // Boundary polygon, counter-clockwise in (u, v).
        let mut poly: Vec<(u64, u64)> = vec![(c.u0, c.v0)];
        poly.extend(
            horiz
                .range((c.v0, c.u0 + 1)..(c.v0, c.u1))
                .map(|&(j, i)| (i, j)),
        );
        poly.push((c.u1, c.v0));
        poly.extend(vert.range((c.u1, c.v0 + 1)..(c.u1, c.v1)).copied());
        poly.push((c.u1, c.v1));
        poly.extend(
            horiz
                .range((c.v1, c.u0 + 1)..(c.v1, c.u1))
                .rev()
                .map(|&(j, i)| (i, j)),
        );
        poly.push((c.u0, c.v1));
        poly.extend(vert.range((c.u0, c.v0 + 1)..(c.u0, c.v1)).rev().copied());
        let ids: Vec<u32> = poly.iter().map(|&(i, j)| vertex(&mut mesh, i, j)).collect();
        let cell = ci as u32;
        if ids.len() == 4 {
            // Split along the shorter diagonal.
            let d02 = dist(
                &mesh.vertices[ids[0] as usize],
                &mesh.vertices[ids[2] as usize],
            );
            let d13 = dist(
                &mesh.vertices[ids[1] as usize],
                &mesh.vertices[ids[3] as usize],
            );
            let tris = if d02 <= d13 {
                [[ids[0], ids[1], ids[2]], [ids[0], ids[2], ids[3]]]
            } else {
                [[ids[0], ids[1], ids[3]], [ids[1], ids[2], ids[3]]]
            };
            for t in tris {
                mesh.triangles.push(t);
                mesh.tri_cell.push(cell);
            }
        } else {
            let centre = vertex(&mut mesh, (c.u0 + c.u1) / 2, (c.v0 + c.v1) / 2);
            for k in 0..ids.len() {
                mesh.triangles
                    .push([ids[k], ids[(k + 1) % ids.len()], centre]);
                mesh.tri_cell.push(cell);
            }
        }
    }
    mesh.cells = leaves;
    weld_border(&mut mesh, &keys, &closure, &poles, top);
    mesh
}

/// Adaptive, crack-free triangulation of `s`.
pub fn triangulate(
    s: &NurbsSurface<f64, 3>,
    prm: &TriangulateParams,
    force: &HashSet<CellKey>,
) -> SurfaceMesh {
    triangulate_cached(s, prm, force, &mut Evaluations::default())
}

/// [`triangulate`] with the surface's points taken from, and added to, `cache` (one cache per
/// surface; the same mesh as without it).
pub fn triangulate_cached(
    s: &NurbsSurface<f64, 3>,
    prm: &TriangulateParams,
    force: &HashSet<CellKey>,
    cache: &mut Evaluations,
) -> SurfaceMesh {
    let lat = Lattice::of(s);
    let (leaves, unresolved) = leaf_cells_with(s, &lat, prm, force, cache);
    triangulate_cells_with(s, &lat, leaves, unresolved, cache)
}

/// Every mesh edge is shared by exactly two triangles with opposite orientation, except
/// edges on the domain boundary (used once). Returns the number of boundary edges, or the
/// first edge that breaks the rule (a crack or a fold).
pub fn check_crack_free(m: &SurfaceMesh) -> Result<usize, (u32, u32)> {
    let mut count: HashMap<(u32, u32), i32> = HashMap::default();
    for t in &m.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *count.entry((a, b)).or_default() += 1;
        }
    }
    let mut boundary = 0;
    for (&(a, b), &n) in &count {
        let back = count.get(&(b, a)).copied().unwrap_or(0);
        if n != 1 || back > 1 {
            return Err((a, b));
        }
        if back == 0 {
            let on_boundary = |x: f64, lo: f64, hi: f64| x == lo || x == hi;
            let (ua, ub) = (m.uv[a as usize], m.uv[b as usize]);
            let (u0, u1, v0, v1) = bounds(m);
            let same_u = ua[0] == ub[0] && on_boundary(ua[0], u0, u1);
            let same_v = ua[1] == ub[1] && on_boundary(ua[1], v0, v1);
            if !(same_u || same_v) {
                return Err((a, b));
            }
            boundary += 1;
        }
    }
    Ok(boundary)
}

fn bounds(m: &SurfaceMesh) -> (f64, f64, f64, f64) {
    m.uv.iter().fold(
        (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ),
        |(a, b, c, d), p| (a.min(p[0]), b.max(p[0]), c.min(p[1]), d.max(p[1])),
    )
}
