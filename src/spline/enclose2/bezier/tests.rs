use super::*;
use crate::spline::NurbsSurface;
use crate::spline::construct::{sphere, torus};
use crate::spline::enclose::tests::frame;
use crate::spline::enclose2::{group_jet, groups};
use crate::spline::enclosed_bezier::enclosed_bezier_patches;

/// A bicubic polynomial surface with two spans each way and wavy heights.
fn wavy() -> NurbsSurface<f64, 3> {
    let k = vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0];
    let mut pts = Vec::new();
    for i in 0..5 {
        for j in 0..5 {
            let z = ((i * 7 + j * 3) % 5) as f64 * 0.3 - 0.6;
            pts.push([i as f64 * 0.25, j as f64 * 0.25 + 0.05 * i as f64, z]);
        }
    }
    NurbsSurface::new(k.clone(), 3, k, 3, 5, 5, pts, vec![1.0; 25]).unwrap()
}

/// Cox–de Boor jet (the parent module's) at a point, with thin intervals.
fn point_jet(s: &NurbsSurface<f64, 3>, u: f64, v: f64) -> Jet2 {
    let g = [
        groups(&s.hom.ku, pt(u), false).unwrap(),
        groups(&s.hom.kv, pt(v), false).unwrap(),
    ];
    group_jet(s, &g[0][0], &g[1][0]).unwrap()
}

fn parts(j: &Jet2) -> [V; 6] {
    [j.s, j.su, j.sv, j.suu, j.suv, j.svv]
}

/// Boxes of several widths inside pieces of rational and polynomial surfaces: the jet of
/// every sample point inside (by the Cox–de Boor recurrence at the point, another algorithm)
/// lies in the box's Bernstein jet.
#[test]
fn box_jets_hold_every_point_jet_inside() {
    let surfaces = [
        torus(&frame(), 2.0, 0.7).unwrap(),
        sphere(&frame(), 1.5).unwrap(),
        wavy(),
    ];
    let mut rnd = crate::spline::test_params::rng(12345);
    let mut checked = 0;
    for s in &surfaces {
        let pieces = enclosed_bezier_patches(s).unwrap();
        for e in pieces.iter().step_by(3) {
            let [t0, t1, s0, s1] = e.uv;
            for frac in [0.9, 1e-1, 1e-2, 1e-4] {
                let (wu, wv) = (frac * (t1 - t0), frac * (s1 - s0));
                let u0 = t0 + rnd() * (t1 - t0 - wu);
                let v0 = s0 + rnd() * (s1 - s0 - wv);
                let (u, v) = (I::new(u0, u0 + wu), I::new(v0, v0 + wv));
                let j = bezier_jet(e, u, v).expect("a jet");
                for _ in 0..12 {
                    let (a, b) = (0.01 + 0.98 * rnd(), 0.01 + 0.98 * rnd());
                    let p = point_jet(s, u0 + a * wu, v0 + b * wv);
                    for (big, small) in parts(&j).iter().zip(parts(&p).iter()) {
                        for m in 0..3 {
                            let x = small[m].mid();
                            assert!(
                                big[m].lo <= x && x <= big[m].hi,
                                "{:?} not in {:?} (box {u:?} {v:?})",
                                small[m],
                                big[m]
                            );
                        }
                    }
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 100);
}

/// On a box a hundredth of a span wide, the Bernstein enclosures of the second derivatives
/// are far narrower than the Cox–de Boor ones over the same box.
#[test]
fn box_jets_are_tighter_than_cox_de_boor() {
    let s = torus(&frame(), 2.0, 0.7).unwrap();
    let pieces = enclosed_bezier_patches(&s).unwrap();
    let e = &pieces[5];
    let [t0, t1, s0, s1] = e.uv;
    let (um, vm) = (0.5 * (t0 + t1), 0.5 * (s0 + s1));
    let (hu, hv) = (0.005 * (t1 - t0), 0.005 * (s1 - s0));
    let (u, v) = (I::new(um - hu, um + hu), I::new(vm - hv, vm + hv));
    let b = bezier_jet(e, u, v).unwrap();
    let g = [
        groups(&s.hom.ku, u, false).unwrap(),
        groups(&s.hom.kv, v, false).unwrap(),
    ];
    let c = group_jet(&s, &g[0][0], &g[1][0]).unwrap();
    let width = |j: &Jet2| -> f64 {
        parts(j)[3..]
            .iter()
            .flatten()
            .map(|x| x.hi - x.lo)
            .fold(0.0, f64::max)
    };
    assert!(
        width(&b) < 0.25 * width(&c),
        "{} vs {}",
        width(&b),
        width(&c)
    );
}

/// Boxes outside the piece's span are refused.
#[test]
fn boxes_outside_the_span_are_refused() {
    let s = wavy();
    let e = &enclosed_bezier_patches(&s).unwrap()[0];
    let [t0, t1, s0, _] = e.uv;
    assert!(bezier_jet(e, I::new(t0, t1 + 0.01), I::new(s0, s0 + 0.1)).is_none());
    assert!(bezier_jet(e, I::new(t0 - 0.01, t1), I::new(s0, s0 + 0.1)).is_none());
}
