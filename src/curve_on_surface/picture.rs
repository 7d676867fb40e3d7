//! The 3D picture of a curve-on-surface run (`vericad curve-on-surface --svg-3d`): the
//! surface shaded, the Bézier segments drawn over it — green where a segment's proven
//! Hausdorff bound is within ε_d, red where it is not — and the segments' joints dotted
//! ([`crate::io::picture`]).

use super::CurveOnSurface;
use crate::io::picture::{BORDER, NOT_PROVEN, PAGE, PROVEN, Rgb, Scene, View, render};
use crate::spline::NurbsSurface;

const SURFACE: Rgb = [172, 190, 214];
const WITHIN: Rgb = PROVEN;
const ABOVE: Rgb = NOT_PROVEN;
const JOINT: Rgb = [40, 40, 40];
/// Grid steps per direction of the surface, and samples per segment.
const GRID: usize = 32;
const SAMPLES: usize = 24;

/// The picture of `r` on `s` seen along `view`; `unit` labels the scale bar.
pub fn picture(
    r: &CurveOnSurface,
    s: &NurbsSurface<f64, 3>,
    unit: Option<&str>,
    view: &View,
) -> String {
    let eps = r.certificate.eps_d;
    let mut scene = Scene {
        title: format!(
            "vericad curve-on-surface: {} segments of degree {}, proven Hausdorff bound {:.3e} (ε_d {:e})",
            r.num_segments,
            r.segments.first().map_or(0, |s| s.degree),
            r.certificate.hausdorff_bound,
            eps
        ),
        unit: unit.map(str::to_string),
        ..Default::default()
    };
    scene.add_surface(s, GRID, SURFACE, BORDER);
    let (mut within, mut above) = (0, 0);
    for sg in &r.segments {
        let pts: Vec<[f64; 3]> = (0..=SAMPLES)
            .map(|i| sg.eval(i as f64 / SAMPLES as f64))
            .collect();
        let ok = sg.bound <= eps;
        if ok {
            within += 1;
        } else {
            above += 1;
        }
        if let Some(p) = pts.first() {
            scene.dots.push((*p, JOINT));
        }
        scene.polylines.push((pts, if ok { WITHIN } else { ABOVE }));
    }
    if let Some(p) = r.segments.last().and_then(|s| s.control_points.last()) {
        scene.dots.push((*p, JOINT));
    }
    scene.legend.push((SURFACE, "surface".into()));
    scene.legend.push((
        WITHIN,
        format!("segments with proven bound within ε_d ({within})"),
    ));
    if above > 0 {
        scene
            .legend
            .push((ABOVE, format!("segments with bound above ε_d ({above})")));
    }
    scene
        .legend
        .push((JOINT, format!("segment joints ({})", r.segments.len() + 1)));
    render(&scene, view, PAGE[0], PAGE[1])
}
