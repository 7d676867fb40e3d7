//! Coincidence and tangency, from `tests/data/faulty` (the row "sphere.step against itself;
//! cyl-a.step with cyl-b-tangent / cyl-c-inner-tangent / cyl-e-sameaxis" of its README): a
//! coincidence is reported as such, and an external and an internal line contact are told the
//! same way — a tangent contact along the line, not branches or a row of touch points — and
//! neither run is certified. Truth from the files' construction (STEP placements and radii,
//! cylinders of height 1 along their axes from the placement's origin):
//!
//! * cyl-a: x² + y² = 1, z ∈ [−1, 0];
//! * cyl-b-tangent: (x − 2)² + y² = 1, z ∈ [−1, 0] — touches cyl-a from outside along the
//!   segment x = 1, y = 0;
//! * cyl-c-inner-tangent: (x − 1)² + y² = 4, z ∈ [−1, 0] — holds cyl-a inside, touching it
//!   along x = −1, y = 0;
//! * cyl-d-crossing: x² + (z − ½)² = ¼, y ∈ [−2, −1] — meets cyl-a in the one point (0, −1, 0);
//! * cyl-e-sameaxis: the same cylinder as cyl-a; sphere.step: the unit sphere.

use std::path::PathBuf;
use vericad::io::read_model;
use vericad::model::Model;
use vericad::ssi::{SsiParams, SsiResult, intersect_models};

fn model(name: &str) -> Model {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/faulty")
        .join(name);
    read_model(&p).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn ssi(a: &str, b: &str) -> SsiResult {
    let prm = SsiParams::default();
    intersect_models(&model(a), Some(&model(b)), &prm, &|_, _| {}).expect("runs")
}

#[test]
fn coincident_surfaces_are_reported_as_coincident() {
    for (a, b) in [
        ("sphere.step", "sphere.step"),
        ("cyl-a.step", "cyl-e-sameaxis.step"),
    ] {
        let r = ssi(a, b);
        assert_eq!(r.summary.coincident_pairs, 1, "{a} {b}");
        assert!(
            r.pairs
                .iter()
                .all(|p| p.branches.is_empty() && p.touch_points.is_empty())
        );
        assert!(!r.summary.certified, "{a} {b}");
    }
}

/// Both line contacts: no branch, no touch point, one tangent contact whose every point lies
/// within tol of both true cylinders and near the true contact segment, from one end of it to
/// the other; not certified.
#[test]
fn external_and_internal_line_contacts_are_told_the_same_way() {
    let tol = SsiParams::default().tol;
    // (file, the other cylinder's centre x and radius, the contact line's x)
    for (b, cx, rb, x_line) in [
        ("cyl-b-tangent.step", 2.0, 1.0, 1.0),
        ("cyl-c-inner-tangent.step", 1.0, 2.0, -1.0),
    ] {
        let r = ssi("cyl-a.step", b);
        assert!(!r.summary.certified, "{b}");
        assert_eq!(r.summary.tangent_contact_pairs, 1, "{b}");
        assert_eq!(r.summary.branches, 0, "{b}");
        let p = &r.pairs[0];
        assert!(p.touch_points.is_empty(), "{b}");
        let c = p.tangent_contact.as_ref().expect("a tangent contact");
        assert!(c.points.len() >= 10, "{b}: {}", c.points.len());
        assert_eq!(c.points_not_listed(), 0);
        for q in &c.points {
            let da = ((q[0] * q[0] + q[1] * q[1]).sqrt() - 1.0).abs();
            let db = (((q[0] - cx).powi(2) + q[1] * q[1]).sqrt() - rb).abs();
            assert!(da <= tol && db <= tol, "{b}: {q:?} {da:e} {db:e}");
            // Within tol of both, a point is at most ~√(2 tol) from the contact line.
            assert!(
                (q[0] - x_line).abs() <= 1e-5 && q[1].abs() <= 1e-2,
                "{b}: {q:?}"
            );
            assert!((-1.0 - 1e-9..=1e-9).contains(&q[2]), "{b}: {q:?}");
        }
        // The chain runs along the segment: from one end to the other, in order.
        let z: Vec<f64> = c.points.iter().map(|q| q[2]).collect();
        let (lo, hi) = (z[0].min(z[z.len() - 1]), z[0].max(z[z.len() - 1]));
        assert!(lo <= -0.95 && hi >= -0.05, "{b}: {lo} {hi}");
        assert!(
            z.windows(2).all(|w| w[1] >= w[0]) || z.windows(2).all(|w| w[1] <= w[0]),
            "{b}: not monotone along the line"
        );
        assert!(c.max_sin_angle <= 1e-3 && c.max_gap <= tol, "{b}");
    }
}

/// A single common point (the corner (0, −1, 0) of both patches) is not a contact curve.
#[test]
fn a_single_common_point_is_not_a_contact_curve() {
    let r = ssi("cyl-a.step", "cyl-d-crossing.step");
    assert_eq!(r.summary.tangent_contact_pairs, 0);
    for b in &r.pairs[0].branches {
        for q in &b.points {
            let d = (q[0] * q[0] + (q[1] + 1.0).powi(2) + q[2] * q[2]).sqrt();
            assert!(d <= 1e-3, "{q:?}");
        }
    }
}
