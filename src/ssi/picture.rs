//! The picture of an intersection run (`vericad ssi --svg`): the faces shaded, the branches
//! drawn over them and coloured by what is proven about each point, the singular points and
//! the uncertified coverage regions marked ([`crate::io::picture`]).
//!
//! Colours: a branch segment is green when both its points are proven within tol of the
//! intersection curve (`curve_radius ≤ tol`), amber when proven but farther than tol, red when
//! a point is not proven against the curve. Singular points whose kind is proven are blue,
//! other touch points red; the model-space points of uncertified coverage regions orange.
//! Faces of a B-rep are drawn trimmed (the model's face triangulation), other faces as their
//! whole surfaces sampled on a grid, with their border curves.

use super::report::{SingularKind, SsiResult};
use crate::io::picture::{BORDER, NOT_PROVEN, PAGE, PROVEN, Rgb, Scene, View, render};
use crate::model::Model;
use crate::tessellate::{MeshParams, mesh_brep};

const FACE_A: Rgb = [170, 188, 214];
const FACE_B: Rgb = [218, 200, 166];
const ABOVE_TOL: Rgb = [235, 150, 0];
const SINGULAR: Rgb = [40, 70, 210];
const REGION: Rgb = [245, 110, 0];

/// Grid steps per direction of a face drawn as its whole surface.
const GRID: usize = 32;

/// The faces of `m` as triangles (and border curves of untrimmed faces) in `colour`;
/// returns the number of faces drawn.
fn add_faces(scene: &mut Scene, m: &Model, colour: Rgb) -> usize {
    if let Some(brep) = &m.brep {
        let mesh = mesh_brep(m, brep, &MeshParams::default());
        let t = &mesh.triangulation;
        for tri in &t.triangles {
            let p = tri.map(|i| t.vertices.get(i as usize).copied().unwrap_or([f64::NAN; 3]));
            scene.triangles.push((p, colour));
        }
        return mesh.faces.iter().filter(|f| f.is_ok()).count();
    }
    for s in &m.surfaces {
        scene.add_surface(&s.nurbs, GRID, colour, BORDER);
    }
    m.surfaces.len()
}

/// 0: proven within tol, 1: proven above tol, 2: not proven.
fn status(radius: Option<f64>, tol: f64) -> usize {
    match radius {
        Some(r) if r <= tol => 0,
        Some(_) => 1,
        None => 2,
    }
}

/// The picture of `r` (faces of `a`, and of `b` in a two-file run) seen along `view`.
pub fn picture(r: &SsiResult, a: &Model, b: Option<&Model>, view: &View) -> String {
    let s = &r.summary;
    let mut scene = Scene {
        title: format!(
            "vericad ssi: {} branches, {} points, tol {:e}: {}",
            s.branches,
            s.points,
            s.tol,
            if s.certified {
                "certified"
            } else {
                "NOT certified"
            }
        ),
        unit: a.unit.clone(),
        ..Default::default()
    };
    let na = add_faces(&mut scene, a, FACE_A);
    let nb = b.map(|b| add_faces(&mut scene, b, FACE_B));
    let colour = [PROVEN, ABOVE_TOL, NOT_PROVEN];
    let mut count = [0usize; 3];
    for br in r.pairs.iter().flat_map(|p| &p.branches) {
        let n = br.points.len();
        let st: Vec<usize> = (0..n)
            .map(|i| status(br.curve_radius.get(i).copied().flatten(), s.tol))
            .collect();
        for k in &st {
            count[*k] += 1;
        }
        if n == 1 {
            scene.markers.push((br.points[0], colour[st[0]]));
            continue;
        }
        // Runs of segments of one status (a segment takes the worse of its ends).
        let segs = if br.closed { n } else { n - 1 };
        // Cubic pieces are drawn through 16 samples each.
        let pieces = if br.tangents.is_empty() {
            Vec::new()
        } else {
            br.pieces()
        };
        let mut run: Vec<[f64; 3]> = Vec::new();
        let mut run_status = usize::MAX;
        for k in 0..segs {
            let (i, j) = (k, (k + 1) % n);
            let sg = st[i].max(st[j]);
            if sg != run_status {
                if run.len() > 1 {
                    scene
                        .polylines
                        .push((std::mem::take(&mut run), colour[run_status]));
                }
                run = vec![br.points[i]];
                run_status = sg;
            }
            if let Some(h) = pieces.get(k) {
                run.extend(h.interior(16));
            }
            run.push(br.points[j]);
        }
        if run.len() > 1 {
            scene.polylines.push((run, colour[run_status]));
        }
    }
    // Common borders: proven ones as proven curve, the others as not proven.
    let mut borders = [0usize; 2];
    for c in r.pairs.iter().flat_map(|p| &p.common_borders) {
        let k = usize::from(!c.certified());
        borders[k] += 1;
        scene
            .polylines
            .push((c.points.clone(), if k == 0 { PROVEN } else { NOT_PROVEN }));
    }
    let (mut singular, mut touch) = (0, 0);
    for t in r.pairs.iter().flat_map(|p| &p.touch_points) {
        let proven = t
            .singular
            .as_ref()
            .is_some_and(|x| x.kind != SingularKind::Uncertified);
        scene
            .markers
            .push((t.point, if proven { SINGULAR } else { NOT_PROVEN }));
        if proven {
            singular += 1;
        } else {
            touch += 1;
        }
    }
    let mut regions = 0;
    for reg in r
        .pairs
        .iter()
        .filter_map(|p| p.coverage.as_ref())
        .flat_map(|c| &c.uncertified_regions)
    {
        if let Some(p) = reg.point {
            scene.markers.push((p, REGION));
            regions += 1;
        }
    }
    let legend = &mut scene.legend;
    match nb {
        Some(nb) => {
            legend.push((FACE_A, format!("faces of the first file ({na})")));
            legend.push((FACE_B, format!("faces of the second file ({nb})")));
        }
        None => legend.push((FACE_A, format!("faces ({na})"))),
    }
    let rows = [
        "points proven within tol of the curve",
        "points proven, radius above tol",
        "points not proven against the curve",
    ];
    for k in 0..3 {
        if count[k] > 0 || k == 0 {
            legend.push((colour[k], format!("{} ({})", rows[k], count[k])));
        }
    }
    if borders[0] > 0 {
        legend.push((
            PROVEN,
            format!("common borders, exact: on both faces ({})", borders[0]),
        ));
    }
    if borders[1] > 0 {
        legend.push((
            NOT_PROVEN,
            format!("common borders within a gap, not proven ({})", borders[1]),
        ));
    }
    if singular > 0 {
        legend.push((
            SINGULAR,
            format!("singular points, kind proven ({singular})"),
        ));
    }
    if touch > 0 {
        legend.push((
            NOT_PROVEN,
            format!("touch points, kind not proven ({touch})"),
        ));
    }
    if regions > 0 {
        legend.push((REGION, format!("uncertified coverage regions ({regions})")));
    }
    render(&scene, view, PAGE[0], PAGE[1])
}
