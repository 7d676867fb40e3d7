//! The picture of a faces repair (`vericad repair --svg` on trimmed faces): the faces
//! tessellated inside their trims, one colour each, with the feature edges dark, the edges
//! still free orange and the shared edges whose gap is at or above `u2` red
//! ([`crate::io::picture`]).

use super::FacesResult;
use crate::brep::Brep;
use crate::io::picture::{PAGE, Rgb, Scene, View, render};
use crate::repair::picture::{FEATURE, GAP, PALETTE};
use crate::tessellate::BrepMesh;

const FREE: Rgb = [240, 140, 20];
/// Points along an edge curve.
const SAMPLES: usize = 32;

/// Points along edge `e`'s 3D curve (none without one).
pub fn edge_points(b: &Brep, e: usize) -> Vec<[f64; 3]> {
    let Some(c) = b.edges.get(e).and_then(|x| x.curve.as_ref()) else {
        return Vec::new();
    };
    let (t0, t1) = c.nurbs.hom.domain();
    (0..=SAMPLES)
        .map(|i| c.nurbs.eval(&(t0 + (t1 - t0) * i as f64 / SAMPLES as f64)))
        .collect()
}

/// The picture of `r` (its faces meshed as `mesh`) seen along `view`; `unit` labels the
/// scale bar.
pub fn picture(r: &FacesResult, mesh: &BrepMesh, unit: Option<&str>, view: &View) -> String {
    let rep = &r.report;
    let mut scene = Scene {
        title: format!(
            "vericad repair: {} faces ({} trimmed); {} free edges, {} feature edges, {} gaps left above u2",
            rep.faces,
            rep.trimmed_faces.len(),
            rep.free_edges_after,
            rep.feature_edges,
            rep.gaps_left.len()
        ),
        unit: unit.map(str::to_string),
        ..Default::default()
    };
    let t = &mesh.triangulation;
    for (k, f) in mesh.faces.iter().enumerate() {
        let Ok((range, _)) = f else { continue };
        for tri in &t.triangles[range.clone()] {
            let p = tri.map(|i| t.vertices[i as usize]);
            scene.triangles.push((p, PALETTE[k % PALETTE.len()]));
        }
    }
    let mut lines = |edges: &mut dyn Iterator<Item = usize>, colour: Rgb| {
        let mut n = 0;
        for e in edges {
            let pts = edge_points(&r.brep, e);
            if pts.len() > 1 {
                scene.polylines.push((pts, colour));
                n += 1;
            }
        }
        n
    };
    let features = lines(
        &mut rep.edges.iter().filter(|e| e.feature).map(|e| e.index),
        FEATURE,
    );
    let free = lines(&mut rep.free_edge_index.iter().copied(), FREE);
    let gaps = lines(
        &mut rep
            .edges
            .iter()
            .filter(|e| rep.gaps_left.contains(&e.edge))
            .map(|e| e.index),
        GAP,
    );
    scene.legend.push((
        PALETTE[0],
        format!("faces ({}), one colour each, inside their trims", rep.faces),
    ));
    scene
        .legend
        .push((FEATURE, format!("feature edges ({features})")));
    if free > 0 {
        scene.legend.push((FREE, format!("free edges ({free})")));
    }
    if gaps > 0 {
        scene
            .legend
            .push((GAP, format!("gaps at or above u2 ({gaps})")));
    }
    render(&scene, view, PAGE[0], PAGE[1])
}
