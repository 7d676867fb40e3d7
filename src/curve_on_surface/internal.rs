//! Internal consistency failures of curve-on-surface ([`super::CosError::Internal`]): each a
//! check that should never fail on valid input, named with what it found.

use super::float::Undecided;

/// Which internal check failed, and where.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CosInternal {
    /// A knot cell `[u0, u1] × [v0, v1]` of the surface could not be converted (an invalid
    /// knot vector would be the only cause).
    #[error("invalid knots near cell [{}, {}] x [{}, {}]", cell[0], cell[1], cell[2], cell[3])]
    CellKnots { cell: [f64; 4] },
    /// A segment of the domain curve whose bound stays above `eps_d` cannot be halved again.
    #[error("segment t in [{}, {}] cannot be split further (bound {bound:.3e} > eps_d)", t[0], t[1])]
    Unsplittable { t: [f64; 2], bound: f64 },
    /// A chord of the domain curve leaves the patch it was assigned to.
    #[error("chord {a:?} -> {b:?} leaves its patch")]
    ChordLeavesPatch { a: [f64; 2], b: [f64; 2] },
    /// The certified bound of the result exceeds the requested `eps_d`.
    #[error("certified bound {bound} exceeds eps_d")]
    BoundAboveTolerance { bound: f64 },
    /// The `f64` enclosures could not decide (where no exact rerun follows).
    #[error("undecided: {0}")]
    Undecided(Undecided),
    /// A result curve could not be built.
    #[error("{0}")]
    Curve(#[from] crate::spline::SplineError),
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve_on_surface::CosError;

    /// The messages read as they did when they were strings.
    #[test]
    fn messages_read_as_before() {
        let e: CosError = CosInternal::Unsplittable {
            t: [0.5, 0.75],
            bound: 2.5e-3,
        }
        .into();
        assert_eq!(
            e.to_string(),
            "internal consistency check failed: segment t in [0.5, 0.75] cannot be split further (bound 2.500e-3 > eps_d)"
        );
        assert_eq!(
            CosInternal::CellKnots {
                cell: [0.0, 0.5, 0.25, 1.0]
            }
            .to_string(),
            "invalid knots near cell [0, 0.5] x [0.25, 1]"
        );
        assert_eq!(
            CosInternal::ChordLeavesPatch {
                a: [0.0, 1.0],
                b: [0.5, 2.0]
            }
            .to_string(),
            "chord [0.0, 1.0] -> [0.5, 2.0] leaves its patch"
        );
        assert_eq!(
            CosInternal::Undecided(crate::curve_on_surface::float::Undecided::DomainKnots)
                .to_string(),
            "undecided: domain curve knots"
        );
    }
}
