//! Axis-aligned bounding boxes.

use crate::scalar::Scalar;

/// Axis-aligned box `[min, max]` in `D` dimensions.
#[derive(Clone, Debug, PartialEq)]
pub struct Aabb<S: Scalar, const D: usize> {
    pub min: [S; D],
    pub max: [S; D],
}

impl<S: Scalar, const D: usize> Aabb<S, D> {
    /// The smallest box holding every point; `None` for no points.
    pub fn of_points<'a, I: IntoIterator<Item = &'a [S; D]>>(pts: I) -> Option<Self> {
        let mut it = pts.into_iter();
        let first = it.next()?;
        let mut b = Aabb {
            min: first.clone(),
            max: first.clone(),
        };
        for p in it {
            b.include(p);
        }
        Some(b)
    }
    /// Grow to hold `p`.
    pub fn include(&mut self, p: &[S; D]) {
        for i in 0..D {
            if p[i] < self.min[i] {
                self.min[i] = p[i].clone();
            }
            if p[i] > self.max[i] {
                self.max[i] = p[i].clone();
            }
        }
    }
    /// Whether the closed boxes share a point (decided exactly by comparisons).
    pub fn overlaps(&self, o: &Self) -> bool {
        (0..D).all(|i| self.min[i] <= o.max[i] && o.min[i] <= self.max[i])
    }
}

impl<const D: usize> Aabb<f64, D> {
    /// Box in `f32` rounded *outward*: every point of the `f64` box lies inside, so culling
    /// with `f32` boxes never discards an intersecting pair.
    pub fn to_f32_outward(&self) -> ([f32; D], [f32; D]) {
        let lo = std::array::from_fn(|i| {
            let f = self.min[i] as f32;
            if (f as f64) > self.min[i] {
                f.next_down()
            } else {
                f
            }
        });
        let hi = std::array::from_fn(|i| {
            let f = self.max[i] as f32;
            if (f as f64) < self.max[i] {
                f.next_up()
            } else {
                f
            }
        });
        (lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn f32_boxes_are_rounded_outward() {
        let b = Aabb::of_points([&[0.1f64, -0.1, 1e-40], &[0.3, 1.0 / 3.0, 7.0]]).unwrap();
        let (lo, hi) = b.to_f32_outward();
        for i in 0..3 {
            assert!((lo[i] as f64) <= b.min[i]);
            assert!((hi[i] as f64) >= b.max[i]);
        }
    }
}
