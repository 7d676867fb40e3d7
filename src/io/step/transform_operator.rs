//! `cartesian_transformation_operator_3d` (ISO 10303-42, geometry resource): the map
//! `p ↦ local_origin + scale · T p`, where the columns of `T` are the orthonormal axes
//! `base_axis(3, axis1, axis2, axis3)` of the standard:
//!
//! - `d₃ = normalise(axis3)`, or `(0, 0, 1)` when `axis3` is unset;
//! - `d₁ = first_proj_axis(d₃, axis1)`: `v = normalise(axis1)`, or when unset `(1, 0, 0)`
//!   (`(0, 1, 0)` if `d₃ = ±(1, 0, 0)`); `d₁ = normalise(v − (v·d₃) d₃)`;
//! - `d₂ = second_proj_axis(d₃, d₁, axis2)`: `v = axis2`, or `(0, 1, 0)` when unset;
//!   `d₂ = normalise(v − (v·d₃) d₃ − (v·d₁) d₁)`;
//! - `T = [d₁ d₂ d₃]`. `second_proj_axis` does not force `d₂ = d₃ × d₁`: a left-handed set
//!   (`det T = −1`) is a mirroring, which the standard allows. This holds with `axis2` unset
//!   too (`axis1 = (−1, 0, 0)` alone gives a mirroring); readers that take `d₃ × d₁` there
//!   differ from the standard. Where a step divides by zero (e.g. `axis3 = ±x` with `axis1`
//!   and `axis2` unset: both defaults are `y`) the result is indeterminate and the operator
//!   is refused with that reason.
//!
//! `scale` defaults to 1 and must be positive. Both instance forms seen in files are read:
//! `(name, axis1, axis2, local_origin, scale, axis3)` and, with the
//! `functionally_defined_transformation` description, `(name, description, axis1, axis2,
//! local_origin, scale, axis3)`. Used where an assembly places a representation: the
//! `transformation_operator` of a `representation_relationship_with_transformation` and the
//! `mapping_target` of a `mapped_item`.

use super::StepError;
use super::entities::Reader;
use super::part21::Val;
use crate::brep::place::Motion;
use crate::geom::{cross, dot, norm};

type R<T> = Result<T, StepError>;

/// The entity name read here.
pub(super) const NAME: &str = "CARTESIAN_TRANSFORMATION_OPERATOR_3D";

impl Reader<'_> {
    /// The map of the `cartesian_transformation_operator_3d` `id` (see the module comment);
    /// an error names the instance and the fault (missing origin, axes that are parallel or
    /// zero, a scale that is not positive).
    pub(super) fn transformation_operator(&self, id: u64) -> R<Motion> {
        let Some(a) = self.p.entities.inst(id).and_then(|e| e.part(NAME)) else {
            return self.fail(id, format!("expected a {NAME}"));
        };
        let off = match a.len() {
            6 => 1,
            7 => 2,
            n => return self.fail(id, format!("{n} attributes (6 or 7 expected)")),
        };
        // Every attribute is there: the count was checked.
        let at = |i: usize| a.get(off + i).unwrap_or_default();
        let dir = |v: Val| -> R<Option<[f64; 3]>> {
            if v.is_unset() {
                return Ok(None);
            }
            match v.reference() {
                Some(r) => self.direction(r).map(Some),
                None => self.fail(id, "an axis is neither a DIRECTION nor unset"),
            }
        };
        let (axis1, axis2, axis3) = (dir(at(0))?, dir(at(1))?, dir(at(4))?);
        let Some(origin) = at(2).reference() else {
            return self.fail(id, "local_origin is not a reference");
        };
        let origin = self.point(origin)?;
        let scale = match at(3) {
            v if v.is_unset() => 1.0,
            v => match v.num() {
                Some(s) if s > 0.0 && s.is_finite() => s,
                _ => return self.fail(id, "scale is not a positive number"),
            },
        };
        let Some([d1, d2, d3]) = base_axis(axis1, axis2, axis3) else {
            return self.fail(id, "its axes do not span space (parallel or degenerate)");
        };
        let m = Motion::from_frame(origin, d1, d2, d3);
        Ok(Motion {
            rotation: m.rotation.map(|row| row.map(|x| x * scale)),
            translation: origin,
        })
    }

    fn fail<T>(&self, id: u64, reason: impl Into<String>) -> R<T> {
        Err(StepError {
            file: self.file.into(),
            location: format!("#{id}"),
            reason: reason.into(),
        })
    }
}

/// `v / |v|`, `None` for a zero or non-finite vector.
fn normalise(v: [f64; 3]) -> Option<[f64; 3]> {
    let l = norm(&v);
    (l > 0.0 && l.is_finite()).then(|| v.map(|x| x / l))
}

/// `v − (v·d) d`.
fn reject(v: [f64; 3], d: [f64; 3]) -> [f64; 3] {
    let k = dot(&v, &d);
    [0, 1, 2].map(|i| v[i] - k * d[i])
}

/// ISO 10303-42 `base_axis` for three dimensions (module comment): `[d₁, d₂, d₃]`, `None`
/// where a step divides by zero (the standard's indeterminate result).
pub(super) fn base_axis(
    axis1: Option<[f64; 3]>,
    axis2: Option<[f64; 3]>,
    axis3: Option<[f64; 3]>,
) -> Option<[[f64; 3]; 3]> {
    let d3 = normalise(axis3.unwrap_or([0.0, 0.0, 1.0]))?;
    let v = match axis1 {
        Some(a) => {
            if norm(&cross(&a, &d3)) == 0.0 {
                return None;
            }
            normalise(a)?
        }
        None if d3 == [1.0, 0.0, 0.0] || d3 == [-1.0, 0.0, 0.0] => [0.0, 1.0, 0.0],
        None => [1.0, 0.0, 0.0],
    };
    let d1 = normalise(reject(v, d3))?;
    let v = axis2.unwrap_or([0.0, 1.0, 0.0]);
    let d2 = normalise(reject(reject(v, d3), d1))?;
    Some([d1, d2, d3])
}

#[cfg(test)]
mod tests {
    use super::base_axis;

    #[test]
    fn base_axis_follows_the_standard() {
        // Unset axes: the world frame.
        assert_eq!(
            base_axis(None, None, None),
            Some([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
        );
        // axis2 against z × x: a left-handed (mirroring) set is kept as given.
        let [d1, d2, d3] = base_axis(Some([0.0, 1.0, 0.0]), Some([1.0, 0.0, 0.0]), None).unwrap();
        assert_eq!(
            (d1, d2, d3),
            ([0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0])
        );
        // axis3 along x with axis1 unset: the default first axis is y, and the default
        // second axis (also y) is then indeterminate; with axis2 given, z × x = −z here.
        assert_eq!(base_axis(None, None, Some([-1.0, 0.0, 0.0])), None);
        assert_eq!(
            base_axis(None, Some([0.0, 0.0, -1.0]), Some([-1.0, 0.0, 0.0])),
            Some([[0.0, 1.0, 0.0], [0.0, 0.0, -1.0], [-1.0, 0.0, 0.0]])
        );
        // axis2 unset is (0, 1, 0) projected, not z × x: with x reversed the set is
        // left-handed (a mirroring), as the standard's functions give it.
        assert_eq!(
            base_axis(Some([-1.0, 0.0, 0.0]), None, None),
            Some([[-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
        );
        // axis1 parallel to axis3, or axis2 in the plane of the other two: indeterminate.
        assert_eq!(base_axis(Some([0.0, 0.0, 2.0]), None, None), None);
        assert_eq!(base_axis(Some([0.0, 1.0, 0.0]), None, None), None);
    }
}
