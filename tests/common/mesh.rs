//! Measuring triangulations against surfaces known from their construction.

use vericad::model::Triangulation;

/// Largest `off(p)` (a point's distance from the true surface, computed by the caller from the
/// construction) over every triangle of `t`, at 66 barycentric points each (a grid of step
/// 1/10, corners included).
pub fn dense_max(t: &Triangulation, off: impl Fn(&[f64; 3]) -> f64) -> f64 {
    let mut worst: f64 = 0.0;
    for tri in &t.triangles {
        let [a, b, c] = tri.map(|i| t.vertices[i as usize]);
        for i in 0..=10 {
            for j in 0..=10 - i {
                let (s, u) = (i as f64 / 10.0, j as f64 / 10.0);
                let w = 1.0 - s - u;
                let p: [f64; 3] = std::array::from_fn(|k| w * a[k] + s * b[k] + u * c[k]);
                worst = worst.max(off(&p));
            }
        }
    }
    worst
}
