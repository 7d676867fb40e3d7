//! Oracles from the construction: arcs of a circle of radius `R` (a rational quadratic quarter
//! circle, its weight enclosed), against a cubic output piece built on the same circle from
//! its exact points and tangents, and against the same arc moved off the circle by a known
//! offset.

use super::*;

const R: f64 = 2.0;

/// The quarter circle of radius `r` about the origin in `z = 0` from angle 0 to 90°, its
/// middle weight `√2 / 2` enclosed (so the exact circle is among the curves enclosed).
fn quarter(r: f64) -> ICurve {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let iw = I::new(w.next_down(), w.next_up());
    let rw = I::point(r) * iw;
    ICurve {
        x: vec![
            [I::point(r), I::point(0.0), I::point(0.0)],
            [rw, rw, I::point(0.0)],
            [I::point(0.0), I::point(r), I::point(0.0)],
        ],
        w: vec![I::point(1.0), iw, I::point(1.0)],
    }
}

/// The cubic output piece on the circle of radius `R` from angle `a` to angle `b`: exact end
/// points and unit tangents as the tracer's jets give them ([`Piece::cubic`]).
fn piece(a: f64, b: f64) -> Piece {
    piece_on(R, a, b)
}

/// [`piece`] on the circle of radius `r`.
fn piece_on(r: f64, a: f64, b: f64) -> Piece {
    let at = |t: f64| -> [f64; 7] { [r * t.cos(), r * t.sin(), 0.0, 0.0, 0.0, 0.0, 0.0] };
    let jet = |t: f64| -> [f64; 7] { [-t.sin(), t.cos(), 0.0, 0.0, 0.0, 0.0, 0.0] };
    Piece::cubic(&at(a), &jet(a), &at(b), &jet(b)).unwrap()
}

/// The angle of the part's point at `s` (de Casteljau on the midpoints: the part is known).
fn angle(c: &ICurve, s: f64) -> f64 {
    let p = point_at(c, s).unwrap();
    p[1].atan2(p[0])
}

fn cbox(c: &ICurve) -> (Box3, f64) {
    let b = super::super::patch::box_of(&c.cartesian().unwrap());
    let diag = (0..3)
        .map(|k| (b.1[k] - b.0[k]).powi(2))
        .sum::<f64>()
        .sqrt();
    (b, diag)
}

/// The largest distance of the piece from the circle, `max_τ |‖H(τ)‖ − R|`, at 4001 samples:
/// the piece's own deviation, known to be about `R θ⁶ / 2000` for an arc of angle `θ`.
fn deviation(h: &Piece) -> f64 {
    (0..=4000)
        .map(|i| {
            let x = h.eval(i as f64 / 4000.0);
            ((x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt() - R).abs()
        })
        .fold(0.0, f64::max)
}

/// Parts of the circle lying along a piece on the same circle are decided within `d`; the
/// same parts moved off the circle by `δ = 10 d` are not, and their bound is at least the
/// distance the construction puts them at (`δ` less the piece's own deviation).
#[test]
fn arcs_along_a_piece_are_within_and_moved_arcs_are_not() {
    let d = 1e-6;
    // The quarter halved four times: sixteen parts of about 5.6° (the search halves a border
    // curve until its parts follow a piece this closely), each with the piece on its angles.
    let mut parts = vec![quarter(R)];
    for _ in 0..4 {
        parts = parts
            .iter()
            .flat_map(|c| {
                let (a, b) = c.halve();
                [a, b]
            })
            .collect();
    }
    for c in &parts {
        let h = piece(angle(c, 0.0), angle(c, 1.0));
        let dev = deviation(&h);
        assert!(dev < 2e-7, "the piece's deviation {dev}");
        let along = Along::new([h]);
        let (b, diag) = cbox(c);
        assert!(along.curve_within(c, &b, diag, d), "a part on the circle");
        // The same part scaled by (R + δ) / R: every point δ off the circle, so at least
        // δ − dev from the piece.
        for delta in [10.0 * d, -10.0 * d] {
            let s = I::point((R + delta) / R);
            let moved = ICurve {
                x: c.x.iter().map(|p| p.map(|v| v * s)).collect(),
                w: c.w.clone(),
            };
            let (mb, mdiag) = cbox(&moved);
            assert!(!along.curve_within(&moved, &mb, mdiag, d), "δ = {delta}");
            let (hh, hb, _) = &along.pieces[0];
            if let Some(r) = bound(hh, hb, &moved, 100.0 * d) {
                assert!(
                    r >= delta.abs() - dev,
                    "bound {r} below {}",
                    delta.abs() - dev
                );
            }
        }
        // Moved by half the distance: still within (the bound is tight to the piece's
        // deviation and the fit of σ).
        let s = I::point((R + 0.5 * d) / R);
        let moved = ICurve {
            x: c.x.iter().map(|p| p.map(|v| v * s)).collect(),
            w: c.w.clone(),
        };
        let (mb, mdiag) = cbox(&moved);
        assert!(along.curve_within(&moved, &mb, mdiag, d), "δ = d / 2");
    }
}

/// A part covering only some of a piece (its parameter speed unlike the piece's) is decided
/// too; a part reaching past the piece's end is not (its far end is not near the piece), nor
/// is a part of another circle crossing it.
#[test]
fn partial_overhanging_and_crossing_parts() {
    let d = 1e-6;
    let (l, _) = quarter(R).halve();
    let (a, _) = l.halve().0.halve();
    let (first, _) = a.halve();
    // The piece spans the whole of `a` (an eighth of the quarter); `first` is half of it
    // in parameter.
    let h = piece(angle(&a, 0.0), angle(&a, 1.0));
    let along = Along::new([h]);
    let (b, diag) = cbox(&first);
    assert!(along.curve_within(&first, &b, diag, d));
    // `l` reaches 45°, past the piece's end at about 11°.
    let (b, diag) = cbox(&l);
    assert!(!along.curve_within(&l, &b, diag, d));
    // A circle of radius R about (R, 0, 0) crosses the first one at 60°: its part near there
    // is not along the piece on the first circle.
    let h60 = piece(50f64.to_radians(), 70f64.to_radians());
    let along = Along::new([h60]);
    let shifted = ICurve {
        x: quarter(R)
            .x
            .iter()
            .zip(&quarter(R).w)
            .map(|(p, w)| [p[0] * I::point(-1.0) + I::point(R) * *w, p[1], p[2]])
            .collect(),
        w: quarter(R).w,
    };
    // Its part about the crossing, halved until it lies in the piece's box (grown by `d`).
    let x = [0.5 * R, 0.75f64.sqrt() * R];
    let mut part = shifted;
    let hb = along.pieces[0].2;
    let inside = |b: &Box3| (0..3).all(|k| hb.0[k] - d <= b.0[k] && b.1[k] <= hb.1[k] + d);
    while !inside(&cbox(&part).0) {
        let (a, b) = part.halve();
        let holds = |c: &ICurve| {
            let b = cbox(c).0;
            (0..2).all(|k| b.0[k] <= x[k] && x[k] <= b.1[k])
        };
        part = if holds(&a) { a } else { b };
    }
    let (b, diag) = cbox(&part);
    assert!(diag > MIN_PART * d, "a part of {diag}");
    assert!(!along.curve_within(&part, &b, diag, d));
}

/// Small parts are left to the segment and chord tests, and chord pieces are not taken.
#[test]
fn small_parts_and_chords_are_left_to_the_segment_tests() {
    let d = 1e-6;
    let mut c = quarter(R);
    while cbox(&c).1 > 8.0 * d {
        c = c.halve().0;
    }
    let h = piece(angle(&c, 0.0), angle(&c, 1.0));
    let (b, diag) = cbox(&c);
    assert!(!Along::new([h]).curve_within(&c, &b, diag, d));
    let p = [R, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    let q = [0.0, R, 0.0, 0.0, 0.0, 0.0, 0.0];
    assert!(Along::new([Piece::chord(&p, &q)]).pieces.is_empty());
}

/// Random arcs (radius, part of the quarter, offset off the circle) against pieces on their
/// circle spanning the part's angles, widened at random: wherever a bound comes out, it is at
/// least the distance the construction puts the part at (its offset less the piece's own
/// deviation from the circle), and a part on its circle (offset 0) within `d` is decided.
#[test]
fn random_arcs_are_bounded_soundly() {
    let mut unit = crate::spline::test_params::rng(0x2545_f491_4f6c_dd1d);
    let d = 1e-6;
    let (mut bounded, mut decided) = (0, 0);
    for _ in 0..200 {
        let r = 0.5 + 4.0 * unit();
        let mut c = quarter(r);
        // A random part, four to six halvings deep.
        for _ in 0..4 + (unit() * 3.0) as usize {
            let (a, b) = c.halve();
            c = if unit() < 0.5 { a } else { b };
        }
        let (a0, a1) = (angle(&c, 0.0), angle(&c, 1.0));
        let widen = (a1 - a0) * 0.5 * unit();
        let (h0, h1) = (a0 - widen * unit(), a1 + widen * unit());
        let h = piece_on(r, h0, h1);
        let dev = (0..=4000)
            .map(|i| {
                let x = h.eval(i as f64 / 4000.0);
                ((x[0] * x[0] + x[1] * x[1]).sqrt() - r).abs()
            })
            .fold(0.0, f64::max);
        let along = Along::new([h]);
        let (hh, hb, _) = &along.pieces[0];
        let delta = if unit() < 0.3 {
            0.0
        } else {
            (unit() - 0.5) * 40.0 * d
        };
        let s = I::point((r + delta) / r);
        let moved = ICurve {
            x: c.x.iter().map(|p| p.map(|v| v * s)).collect(),
            w: c.w.clone(),
        };
        if let Some(b) = bound(hh, hb, &moved, 100.0 * d) {
            bounded += 1;
            assert!(
                b >= delta.abs() - dev,
                "bound {b} below {} (r {r}, δ {delta})",
                delta.abs() - dev
            );
        }
        let (mb, mdiag) = cbox(&moved);
        if along.curve_within(&moved, &mb, mdiag, d) {
            decided += 1;
            assert!(delta.abs() - dev <= d, "decided within {d} at {delta} off");
        }
    }
    assert!(
        bounded > 100 && decided > 30,
        "{bounded} bounded, {decided} decided"
    );
}
