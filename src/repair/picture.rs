//! The picture of a repair (`vericad repair --svg`): the output patches shaded, each in its
//! own colour (a merged group is one patch, so one colour), with their borders; the feature
//! edges drawn dark and the gaps left above `u2` red ([`crate::io::picture`]).

use super::RepairResult;
use super::edges::{arc_length_samples, edge_curve};
use crate::io::picture::{BORDER, NOT_PROVEN, PAGE, Rgb, Scene, View, render};

/// Patch colours, in turn (faces' too: [`super::faces::picture`]).
pub(super) const PALETTE: [Rgb; 8] = [
    [166, 190, 222],
    [232, 196, 150],
    [170, 214, 170],
    [222, 170, 196],
    [200, 200, 150],
    [160, 206, 214],
    [214, 178, 150],
    [190, 176, 222],
];
pub(super) const FEATURE: Rgb = [20, 20, 20];
pub(super) const GAP: Rgb = NOT_PROVEN;
/// Grid steps per direction of a patch.
const GRID: usize = 12;
/// Samples along an edge curve.
const SAMPLES: usize = 32;

/// The picture of `r` seen along `view`; `unit` labels the scale bar.
pub fn picture(r: &RepairResult, unit: Option<&str>, view: &View) -> String {
    let rep = &r.report;
    let mut scene = Scene {
        title: format!(
            "vericad repair: {} patches in, {} out; {} feature edges, {} gaps left above u2",
            rep.patches_in,
            rep.patches_out,
            rep.feature_edges,
            rep.gaps_left.len()
        ),
        unit: unit.map(str::to_string),
        ..Default::default()
    };
    for (k, s) in r.patches.iter().enumerate() {
        scene.add_surface(s, GRID, PALETTE[k % PALETTE.len()], BORDER);
    }
    let curve = |p: usize, ep: usize| -> Vec<[f64; 3]> {
        match r.connected_patches.get(p) {
            Some(s) if ep < 4 => arc_length_samples(&edge_curve(s, ep), SAMPLES)
                .into_iter()
                .map(|x| x.1)
                .collect(),
            _ => Vec::new(),
        }
    };
    let mut features = 0;
    for e in rep.edges.iter().filter(|e| e.feature) {
        let pts = curve(e.p, e.ep);
        if pts.len() > 1 {
            scene.polylines.push((pts, FEATURE));
            features += 1;
        }
    }
    for g in &rep.gaps_left {
        let pts = curve(g.connection.p, g.connection.ep);
        if pts.len() > 1 {
            scene.polylines.push((pts, GAP));
        }
    }
    scene.legend.push((
        PALETTE[0],
        format!("output patches ({}), one colour each", r.patches.len()),
    ));
    scene
        .legend
        .push((FEATURE, format!("feature edges ({features})")));
    if !rep.gaps_left.is_empty() {
        scene
            .legend
            .push((GAP, format!("gaps left above u2 ({})", rep.gaps_left.len())));
    }
    render(&scene, view, PAGE[0], PAGE[1])
}
