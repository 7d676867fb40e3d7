//! The closest point of a triangle to a point (Ericson, *Real-Time Collision Detection*,
//! §5.1.5), with its barycentric coordinates. Floating point: a measurement, not a proof.

use super::{Point, dot};

/// Closest point of triangle `abc` to `p` and its barycentric coordinates `(wa, wb, wc)`.
pub fn closest_point(
    p: &[f64; 3],
    a: &[f64; 3],
    b: &[f64; 3],
    c: &[f64; 3],
) -> ([f64; 3], [f64; 3]) {
    let ab = b.sub(a);
    let ac = c.sub(a);
    let ap = p.sub(a);
    let d1 = dot(&ab, &ap);
    let d2 = dot(&ac, &ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return (*a, [1.0, 0.0, 0.0]);
    }
    let bp = p.sub(b);
    let d3 = dot(&ab, &bp);
    let d4 = dot(&ac, &bp);
    if d3 >= 0.0 && d4 <= d3 {
        return (*b, [0.0, 1.0, 0.0]);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return (a.add(&ab.scale(&v)), [1.0 - v, v, 0.0]);
    }
    let cp = p.sub(c);
    let d5 = dot(&ab, &cp);
    let d6 = dot(&ac, &cp);
    if d6 >= 0.0 && d5 <= d6 {
        return (*c, [0.0, 0.0, 1.0]);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return (a.add(&ac.scale(&w)), [1.0 - w, 0.0, w]);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (b.add(&c.sub(b).scale(&w)), [0.0, 1.0 - w, w]);
    }
    let denom = 1.0 / (va + vb + vc);
    let v = vb * denom;
    let w = vc * denom;
    if !(v.is_finite() && w.is_finite()) {
        // Degenerate triangle: the nearest vertex.
        let best = [a, b, c]
            .into_iter()
            .enumerate()
            .min_by(|x, y| {
                let dx = x.1.sub(p);
                let dy = y.1.sub(p);
                dot(&dx, &dx).total_cmp(&dot(&dy, &dy))
            })
            .map_or(0, |x| x.0);
        let mut bary = [0.0; 3];
        bary[best] = 1.0;
        return ([*a, *b, *c][best], bary);
    }
    (a.add(&ab.scale(&v)).add(&ac.scale(&w)), [1.0 - v - w, v, w])
}
