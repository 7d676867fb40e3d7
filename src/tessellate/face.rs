//! One trimmed face: the parameter-plane polygons of its loops ([`super::domain`]), a grid of
//! interior points kept clear of the boundary, a constrained Delaunay triangulation whose
//! constraint edges are exactly the boundary segments (no point is added on the boundary, so
//! neighbouring faces see the same edge vertices), the triangles inside the polygons (even-odd),
//! oriented with the face, and the face's area integrated over those parameter triangles.

use super::domain::{self, BoundaryPoint, FaceSurface, Ring};
use super::outline::Sense;
use crate::geom::{Point, cross, dist, norm};
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

/// The triangles of one face and its area.
pub struct FaceMesh {
    pub triangles: Vec<[usize; 3]>,
    /// The parameter points of each triangle's corners, in the order of `triangles`.
    pub uv: Vec<[[f64; 2]; 3]>,
    /// `∫∫ |S_u × S_v| du dv` over the parameter triangles (3-point rule per triangle).
    pub area: f64,
}

/// Why a face could not be triangulated.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FaceError {
    #[error(
        "{0} loops wind around the seam of direction {1}; only bands of two and caps of one are triangulated"
    )]
    Winding(usize, char),
    #[error("the loop winds around the seam but the border it leaves open is not a pole")]
    OpenBorder,
    #[error("loop boundary segments cross in the parameter plane (at {0})")]
    Crossing(String),
    #[error(
        "the face's loops wind around direction {0} on its side of a strip whose other side is the surface's open border; not triangulated"
    )]
    BandSide(char),
    #[error(
        "the face's holes cover a whole period of the surface between them; its outline has no place for the seam"
    )]
    Covered,
    #[error("loops winding around both periodic directions are not outlined")]
    BothDirections,
    #[error("the parameter-plane region is empty")]
    Empty,
    #[error("parameter point not representable: {0}")]
    Point(String),
}

/// Grid resolution along the parameter box `lo..hi` in direction `d`: enough segments for
/// length `h` and a turn of at most `max_turn` per segment along the middle iso-curve.
pub(super) fn resolution(
    fs: &FaceSurface,
    lo: [f64; 2],
    hi: [f64; 2],
    d: usize,
    h: f64,
    max_turn: f64,
) -> usize {
    let mid = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
    let n = 96;
    let pts: Vec<[f64; 3]> = (0..=n)
        .map(|i| {
            let mut uv = mid;
            uv[d] = lo[d] + (hi[d] - lo[d]) * i as f64 / n as f64;
            fs.eval(&uv)
        })
        .collect();
    let len: f64 = pts.windows(2).map(|w| dist(&w[0], &w[1])).sum();
    let mut turn = 0.0;
    for w in pts.windows(3) {
        let (a, b) = (w[1].sub(&w[0]), w[2].sub(&w[1]));
        let (la, lb) = (norm(&a), norm(&b));
        if la > 0.0 && lb > 0.0 {
            turn += (crate::geom::dot(&a, &b) / (la * lb))
                .clamp(-1.0, 1.0)
                .acos();
        }
    }
    let by_len = (len / h).ceil();
    let by_turn = (turn / max_turn).ceil();
    (by_len.max(by_turn).clamp(1.0, 400.0) as usize).max(1)
}

/// Triangulate a face. `rings`: its loops in the parameter plane; `vertex_loop`: the mesh
/// vertex of a vertex loop, if any (a pole); `sense`: the face normal's sense and whether a
/// loop is declared outer ([`Sense`]); `add` makes a new mesh vertex; `h`: target edge length.
pub fn mesh_face(
    fs: &FaceSurface,
    rings: Vec<Ring>,
    vertex_loop: Option<usize>,
    sense: Sense,
    h: f64,
    max_turn: f64,
    add: &mut dyn FnMut([f64; 3]) -> usize,
) -> Result<FaceMesh, FaceError> {
    let polys = super::polygons::face_polygons(fs, rings, vertex_loop, sense, h, max_turn, add)?;
    triangulate(fs, &polys, sense.same_sense, h, max_turn, add)
}

/// The constrained triangulation of a face's polygons ([`super::polygons::face_polygons`]).
pub(super) fn triangulate(
    fs: &FaceSurface,
    polys: &[Vec<BoundaryPoint>],
    same_sense: bool,
    h: f64,
    max_turn: f64,
    add: &mut dyn FnMut([f64; 3]) -> usize,
) -> Result<FaceMesh, FaceError> {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for p in polys.iter().flatten() {
        for k in 0..2 {
            lo[k] = lo[k].min(p.uv[k]);
            hi[k] = hi[k].max(p.uv[k]);
        }
    }
    if !(lo[0] < hi[0] && lo[1] < hi[1]) {
        return Err(FaceError::Empty);
    }
    let n = [
        resolution(fs, lo, hi, 0, h, max_turn),
        resolution(fs, lo, hi, 1, h, max_turn),
    ];
    let cell = [(hi[0] - lo[0]) / n[0] as f64, (hi[1] - lo[1]) / n[1] as f64];
    // In grid-cell units; magnitudes below 1e-30 (rounding residue at the box's corner, e.g.
    // of a rotated placement) are 0: the triangulation refuses nonzero values below ~1e-43.
    let flush = |x: f64| if x.abs() < 1e-30 { 0.0 } else { x };
    let norm_of = |uv: &[f64; 2]| {
        Point2::new(
            flush((uv[0] - lo[0]) / cell[0]),
            flush((uv[1] - lo[1]) / cell[1]),
        )
    };
    let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> =
        ConstrainedDelaunayTriangulation::new();
    // Mesh vertex and parameter point of each CDT vertex (by handle index).
    let mut info: Vec<(usize, [f64; 2])> = Vec::new();
    let insert = |cdt: &mut ConstrainedDelaunayTriangulation<Point2<f64>>,
                  info: &mut Vec<(usize, [f64; 2])>,
                  uv: [f64; 2],
                  vertex: usize| {
        let hd = cdt
            .insert(norm_of(&uv))
            .map_err(|e| FaceError::Point(format!("{e:?}")))?;
        if hd.index() == info.len() {
            info.push((vertex, uv));
        } else if info[hd.index()].0 != vertex {
            // Two different mesh vertices at one parameter point: the boundary touches
            // itself there; triangles would join the wrong vertices.
            return Err(FaceError::Point(format!(
                "mesh vertices {} and {vertex} at one parameter point {uv:?}",
                info[hd.index()].0
            )));
        }
        Ok::<_, FaceError>(hd)
    };
    let mut segments = Vec::new();
    // Middle points of the boundary segments that follow edges, by CDT vertex pair.
    let mut middles: std::collections::HashMap<(usize, usize), [f64; 2]> =
        std::collections::HashMap::new();
    for p in polys {
        let handles = p
            .iter()
            .map(|b| insert(&mut cdt, &mut info, b.uv, b.vertex))
            .collect::<Result<Vec<_>, _>>()?;
        for i in 0..handles.len() {
            let (a, b) = (handles[i], handles[(i + 1) % handles.len()]);
            if a == b {
                continue;
            }
            if !cdt.can_add_constraint(a, b) {
                return Err(FaceError::Crossing(format!("#{}", p[i].vertex)));
            }
            cdt.add_constraint(a, b);
            segments.push((p[i].uv, p[(i + 1) % p.len()].uv));
            if let Some(m) = p[i].mid {
                middles.insert((a.index(), b.index()), m);
                middles.insert((b.index(), a.index()), m);
            }
        }
    }
    // Interior grid points, at least 0.35 cells from the boundary: rows scanned for
    // boundary crossings (even-odd), segments binned by cell for the clearance test.
    let scaled: Vec<([f64; 2], [f64; 2])> = segments
        .iter()
        .map(|(a, b)| {
            (
                [(a[0] - lo[0]) / cell[0], (a[1] - lo[1]) / cell[1]],
                [(b[0] - lo[0]) / cell[0], (b[1] - lo[1]) / cell[1]],
            )
        })
        .collect();
    let mut bins: std::collections::HashMap<(i64, i64), Vec<usize>> =
        std::collections::HashMap::new();
    for (k, (a, b)) in scaled.iter().enumerate() {
        let (x0, x1) = (
            (a[0].min(b[0]) - 0.35).floor() as i64,
            (a[0].max(b[0]) + 0.35).ceil() as i64,
        );
        let (y0, y1) = (
            (a[1].min(b[1]) - 0.35).floor() as i64,
            (a[1].max(b[1]) + 0.35).ceil() as i64,
        );
        for x in x0..=x1 {
            for y in y0..=y1 {
                bins.entry((x, y)).or_default().push(k);
            }
        }
    }
    for j in 1..n[1] {
        let y = j as f64;
        let mut xs: Vec<f64> = scaled
            .iter()
            .filter(|(a, b)| (a[1] > y) != (b[1] > y))
            .map(|(a, b)| a[0] + (y - a[1]) / (b[1] - a[1]) * (b[0] - a[0]))
            .collect();
        xs.sort_by(f64::total_cmp);
        for i in 1..n[0] {
            let x = i as f64;
            if xs.iter().take_while(|&&c| c < x).count() % 2 == 0 {
                continue;
            }
            let near = bins.get(&(i as i64, j as i64)).is_some_and(|ks| {
                ks.iter()
                    .any(|&k| domain::seg_dist(&[x, y], &scaled[k].0, &scaled[k].1) < 0.35)
            });
            if near {
                continue;
            }
            let uv = [lo[0] + cell[0] * x, lo[1] + cell[1] * y];
            let v = add(fs.eval(&uv));
            insert(&mut cdt, &mut info, uv, v)?;
        }
    }
    // Inside: an odd number of constraint edges crossed from the outer face (decided on the
    // triangulation's adjacency, so slivers along straight boundaries are classified by
    // topology, not by a rounded centroid test).
    let mut inside: Vec<Option<bool>> = vec![None; cdt.num_all_faces()];
    let mut queue = std::collections::VecDeque::new();
    for f in cdt.inner_faces() {
        for e in f.adjacent_edges() {
            if e.rev().face().is_outer() && inside[f.fix().index()].is_none() {
                inside[f.fix().index()] = Some(e.is_constraint_edge());
                queue.push_back(f.fix());
            }
        }
    }
    while let Some(fh) = queue.pop_front() {
        let st = inside[fh.index()] == Some(true);
        for e in cdt.face(fh).adjacent_edges() {
            if let Some(nb) = e.rev().face().fix().as_inner()
                && inside[nb.index()].is_none()
            {
                inside[nb.index()] = Some(st ^ e.is_constraint_edge());
                queue.push_back(nb);
            }
        }
    }
    let mut triangles = Vec::new();
    let mut corners = Vec::new();
    let mut area = 0.0;
    for f in cdt.inner_faces() {
        if inside[f.fix().index()] != Some(true) {
            continue;
        }
        let [a, b, c] = f.vertices().map(|v| v.fix().index());
        let (pa, pb, pc) = (info[a].1, info[b].1, info[c].1);
        area += triangle_area(fs, &pa, &pb, &pc);
        // The sliver between a boundary chord and the curve it stands for: a parabola
        // through the chord's ends and the curve's middle point bounds (4/3) the triangle of
        // the three, weighted by |S_u × S_v| there. Interior lies left of the CCW edges.
        for (p, q) in [(a, b), (b, c), (c, a)] {
            if let Some(m) = middles.get(&(p, q)) {
                let (x, y) = (info[p].1, info[q].1);
                let cr = (y[0] - x[0]) * (m[1] - x[1]) - (y[1] - x[1]) * (m[0] - x[0]);
                area -= 2.0 / 3.0 * cr * jacobian(fs, m);
            }
        }
        let (va, vb, vc) = (info[a].0, info[b].0, info[c].0);
        if va == vb || vb == vc || va == vc {
            continue;
        }
        if same_sense {
            triangles.push([va, vb, vc]);
            corners.push([pa, pb, pc]);
        } else {
            triangles.push([va, vc, vb]);
            corners.push([pa, pc, pb]);
        }
    }
    if triangles.is_empty() {
        return Err(FaceError::Empty);
    }
    Ok(FaceMesh {
        triangles,
        uv: corners,
        area,
    })
}

/// `|S_u × S_v|` at a parameter point (periodic parameters reduced, others clamped).
fn jacobian(fs: &FaceSurface, uv: &[f64; 2]) -> f64 {
    let mut p = *uv;
    for d in 0..2 {
        let (lo, hi) = (fs.domain[2 * d], fs.domain[2 * d + 1]);
        p[d] = match fs.period[d] {
            Some(per) => (lo + (p[d] - lo).rem_euclid(per)).min(hi),
            None => p[d].clamp(lo, hi),
        };
    }
    let (_, su, sv) = crate::spline::project::point_d1(fs.s, p[0], p[1]);
    norm(&cross(&su, &sv))
}

/// `∫∫ |S_u × S_v| du dv` over a parameter triangle: the 3-point rule at
/// `(1/6, 1/6), (2/3, 1/6), (1/6, 2/3)` (exact for quadratics).
fn triangle_area(fs: &FaceSurface, a: &[f64; 2], b: &[f64; 2], c: &[f64; 2]) -> f64 {
    let jac = ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])).abs() / 2.0;
    let mut sum = 0.0;
    for (s, t) in [
        (1.0 / 6.0, 1.0 / 6.0),
        (2.0 / 3.0, 1.0 / 6.0),
        (1.0 / 6.0, 2.0 / 3.0),
    ] {
        let uv = [
            a[0] + s * (b[0] - a[0]) + t * (c[0] - a[0]),
            a[1] + s * (b[1] - a[1]) + t * (c[1] - a[1]),
        ];
        sum += jacobian(fs, &uv) / 3.0;
    }
    sum * jac
}
