//! The result read back: segments evaluated (rational ones on homogeneous points), the bound
//! on the printed output, and the human summary.

use super::{CurveOnSurface, Segment};

impl Segment {
    /// The point at `t ∈ [0, 1]` (de Casteljau on the homogeneous points when rational).
    pub fn eval(&self, t: f64) -> [f64; 3] {
        eval_segment(&self.control_points, self.weights.as_deref(), t)
    }
}

/// A Bézier curve with optional weights at `t` (de Casteljau on homogeneous points).
pub(crate) fn eval_segment(cps: &[[f64; 3]], weights: Option<&[f64]>, t: f64) -> [f64; 3] {
    let mut h: Vec<[f64; 4]> = cps
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let w = weights.and_then(|w| w.get(k)).copied().unwrap_or(1.0);
            [w * p[0], w * p[1], w * p[2], w]
        })
        .collect();
    for r in 1..h.len() {
        for i in 0..h.len() - r {
            for c in 0..4 {
                h[i][c] = (1.0 - t) * h[i][c] + t * h[i + 1][c];
            }
        }
    }
    match h.first() {
        Some(x) => [x[0] / x[3], x[1] / x[3], x[2] / x[3]],
        None => [f64::NAN; 3],
    }
}

impl CurveOnSurface {
    /// A proven bound on the Hausdorff distance between the *printed* segments and `S(D)`:
    /// the certified bound on the exact segments plus the printed curves' distance from them
    /// (for polynomial segments `√3 ×` the coordinate rounding — a Bézier curve is a convex
    /// combination of its control points; for rational ones the rounding is that distance).
    pub fn printed_bound(&self) -> f64 {
        let c = &self.certificate;
        let r = if self.bspline.weights.is_some() {
            c.control_point_rounding
        } else {
            (3f64.sqrt() * 1.000001 * c.control_point_rounding).next_up()
        };
        (c.hausdorff_bound + r).next_up()
    }
}

impl std::fmt::Display for CurveOnSurface {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let c = &self.certificate;
        writeln!(
            f,
            "Curve on surface: {} segments of degree {}, {} control points (B-spline form)",
            self.num_segments, self.bspline.degree, self.num_control_points
        )?;
        writeln!(
            f,
            "  certified: Hausdorff distance to S(D) <= {:.3e} (eps_D = {:.1e}); the certified curve (S blossomed on each chord) lies exactly on S",
            c.hausdorff_bound, c.eps_d
        )?;
        writeln!(
            f,
            "  tangent angles <= {:.3} deg (eps_T = {} deg, computed in f64){}",
            c.max_angle_deg,
            c.eps_t_deg,
            if c.unresolved_junctions > 0 {
                format!(", {} corner junction(s) left", c.unresolved_junctions)
            } else {
                String::new()
            }
        )?;
        writeln!(
            f,
            "  f64 output rounding <= {:.1e} ({}); joints shared exactly: {}",
            c.control_point_rounding,
            if self.bspline.weights.is_some() {
                "distance of the printed rational curve from the exact one"
            } else {
                "of each control point coordinate"
            },
            self.bspline.joints_exact
        )?;
        if self.evidence.measured {
            writeln!(
                f,
                "  evidence (measured, not proof): max distance {:.3e} over {} samples ({:.1} ms)",
                self.evidence.max_distance_sampled, self.evidence.samples, self.evidence.elapsed_ms
            )?;
        } else {
            writeln!(
                f,
                "  evidence: not measured (--evidence samples the segments; the bound above is the proof)"
            )?;
        }
        let s = &self.steps;
        writeln!(
            f,
            "  steps: {} patches; {} domain Bézier pieces; {} after knot-line split; {} double-sided split; {} after distance; {} eps_T splits; min d = {:.3e}",
            s.bezier_patches,
            s.domain_bezier_pieces,
            s.after_knot_line_split,
            s.sidedness.double_sided_split,
            s.after_distance,
            s.g1.splits,
            s.min_2d_tolerance
        )?;
        writeln!(
            f,
            "  exact reference: degree {}, {} segment(s), {} control points",
            self.exact_reference.degree,
            self.exact_reference.segments,
            self.exact_reference.control_points
        )?;
        writeln!(f, "  arithmetic: {}", c.arithmetic)?;
        writeln!(
            f,
            "  time {:.3} ms (algorithm and certificate; evidence not included)",
            self.elapsed_ms
        )
    }
}
