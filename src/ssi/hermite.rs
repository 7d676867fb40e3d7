//! Step 9 in cubic pieces (`--pieces cubic`; paper §4, step 9: "Interpolate the sample points
//! with a spline curve in 3D physical space, 2D parameter space, or both").
//!
//! A branch is output as its certified points `p_0, …, p_n` and, between consecutive points,
//! the cubic Hermite piece
//!
//! `H(τ) = (2τ³ − 3τ² + 1) p + (τ³ − 2τ² + τ) m a + (−2τ³ + 3τ²) q + (τ³ − τ²) m b`, `τ ∈ [0, 1]`,
//!
//! in the packed coordinates `(x, y, z, u_A, v_A, s_B, t_B)`. `a` and `b` are the *tangent jets*
//! of the true curve at the ends ([`tangent_jet`]): the unit tangent `n_A × n_B / ‖n_A × n_B‖`
//! and the parameter rates `d(u, v)/ds`, `d(s, t)/ds` per unit length, each oriented along the
//! chord `q − p`. The end derivative is `m = ‖q − p‖ / cos²(φ/4)` with `φ` the angle between
//! the two unit tangents: on a circular arc of angle `θ` (then `φ = θ`) this is the handle
//! `3 · (4/3) r tan(θ/4)` of the usual cubic arc, whose error falls with `θ⁶`, so a circle of
//! radius 2 is within 1e-7 in about 20 pieces where chords need about 10,000.
//!
//! A piece is the chord (`m a = m b = q − p`, so `H` is the straight segment, linear in the
//! parameters too) when a jet is missing — the surfaces meet at an angle whose sine is below
//! [`MIN_SIN`], or a normal is undefined — or a unit tangent makes more than 60° with the
//! chord. The rule depends only on the two end points and their jets, so a reader rebuilds
//! every piece from the JSON (`points`, `uv_a`, `uv_b` and `tangents`, each jet `{t, uv_a,
//! uv_b}`).
//!
//! What is proven about the pieces: nothing beyond their end points (each certified against
//! the true curve like every output point). That a piece lies within `tol` of the true curve
//! is *measured* at `τ = 1/4, 1/2, 3/4` ([`super::insert`]), as chords are measured at their
//! midpoints. The coverage certificate is stated for the pieces: [`densify`] replaces each by
//! a polyline within a proven distance of it.

use crate::geom::{cross, dot, norm};
use crate::spline::NurbsSurface;
use crate::spline::project::point_d1;

/// Packed point: `(x, y, z, u_A, v_A, s_B, t_B)`.
pub type P7 = [f64; 7];

/// Points with their parameters on A and on B, packed (as many as the shortest list).
pub fn pack(points: &[[f64; 3]], uv_a: &[[f64; 2]], uv_b: &[[f64; 2]]) -> Vec<P7> {
    points
        .iter()
        .zip(uv_a)
        .zip(uv_b)
        .map(|((p, a), b)| [p[0], p[1], p[2], a[0], a[1], b[0], b[1]])
        .collect()
}

/// A jet is kept where the sine of the angle between the normals is at least this. The
/// tangent `n_A × n_B` turns by about `ε / sin` for an error `ε` of the point's position,
/// and the points are on the curve to about 1e-13 (certified, moved onto the curve below a
/// sine of 1/4, [`super::insert`]): at this bound it turns by about 1e-10, and every piece is
/// measured against the curve anyway; closer to tangency the pieces are chords.
pub const MIN_SIN: f64 = 1e-3;

/// The tangent jet of the intersection curve at parameters `uv_a` on A and `uv_b` on B: the
/// unit tangent `t = n_A × n_B / ‖n_A × n_B‖` and `d(u, v)/ds`, `d(s, t)/ds`, the parameter
/// rates whose images `S_u du + S_v dv` are the projections of `t` onto each tangent plane
/// (least squares; equal to `t` on the curve). `None` where a normal is undefined or the
/// sine of the angle between them is below [`MIN_SIN`].
pub fn tangent_jet(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    uv_a: &[f64; 2],
    uv_b: &[f64; 2],
) -> Option<P7> {
    let (_, su, sv) = point_d1(sa, uv_a[0], uv_a[1]);
    let (_, rw, rt) = point_d1(sb, uv_b[0], uv_b[1]);
    let (na, nb) = (cross(&su, &sv), cross(&rw, &rt));
    let t = cross(&na, &nb);
    let (lt, la, lb) = (norm(&t), norm(&na), norm(&nb));
    if !(lt >= MIN_SIN * la * lb && lt.is_finite() && la > 0.0 && lb > 0.0) {
        return None;
    }
    let t = [t[0] / lt, t[1] / lt, t[2] / lt];
    let rates = |a: &[f64; 3], b: &[f64; 3]| -> Option<[f64; 2]> {
        let (aa, ab, bb) = (dot(a, a), dot(a, b), dot(b, b));
        let (ra, rb) = (dot(a, &t), dot(b, &t));
        let det = aa * bb - ab * ab;
        (det > 0.0 && det.is_finite())
            .then(|| [(ra * bb - rb * ab) / det, (rb * aa - ra * ab) / det])
    };
    let (ja, jb) = (rates(&su, &sv)?, rates(&rw, &rt)?);
    Some([t[0], t[1], t[2], ja[0], ja[1], jb[0], jb[1]])
}

/// A tangent jet as written in the JSON result (`tangents`): the unit tangent `t` and the
/// parameter rates on A (`uv_a`) and on B (`uv_b`), oriented along the branch (towards the
/// next point; at the last point of an open branch, away from the one before).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Jet {
    pub t: [f64; 3],
    pub uv_a: [f64; 2],
    pub uv_b: [f64; 2],
}

impl Jet {
    pub fn packed(&self) -> P7 {
        let (t, a, b) = (self.t, self.uv_a, self.uv_b);
        [t[0], t[1], t[2], a[0], a[1], b[0], b[1]]
    }
    pub fn from_packed(j: &P7) -> Jet {
        Jet {
            t: [j[0], j[1], j[2]],
            uv_a: [j[3], j[4]],
            uv_b: [j[5], j[6]],
        }
    }
}

/// The jets of a branch's points ([`tangent_jet`]), oriented along it: by the chord to the
/// next point (closed branches wrap; the last point of an open branch by the chord from the
/// one before).
pub fn branch_jets(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    pts: &[P7],
    closed: bool,
) -> Vec<Option<Jet>> {
    let n = pts.len();
    (0..n)
        .map(|i| {
            let (uv_a, uv_b) = ([pts[i][3], pts[i][4]], [pts[i][5], pts[i][6]]);
            let j = tangent_jet(sa, sb, &uv_a, &uv_b)?;
            let c = if i + 1 < n {
                d3(&pts[i], &pts[i + 1])
            } else if closed && n > 1 {
                d3(&pts[i], &pts[0])
            } else if i > 0 {
                d3(&pts[i - 1], &pts[i])
            } else {
                [0.0; 3]
            };
            let s = if j[0] * c[0] + j[1] * c[1] + j[2] * c[2] < 0.0 {
                -1.0
            } else {
                1.0
            };
            Some(Jet::from_packed(&j.map(|x| s * x)))
        })
        .collect()
}

/// The pieces of a branch from its packed points and jets (`jets` empty: chords).
pub fn branch_pieces(pts: &[P7], jets: &[Option<Jet>], closed: bool) -> Vec<Piece> {
    let n = pts.len();
    let spans = if closed && n > 1 {
        n
    } else {
        n.saturating_sub(1)
    };
    let jet = |i: usize| jets.get(i).copied().flatten().map(|j| j.packed());
    (0..spans)
        .map(|i| {
            let k = (i + 1) % n;
            Piece::new(&pts[i], jet(i).as_ref(), &pts[k], jet(k).as_ref())
        })
        .collect()
}

/// One piece: its ends and end derivatives (with respect to `τ`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Piece {
    pub p: P7,
    pub q: P7,
    pub dp: P7,
    pub dq: P7,
}

fn d3(a: &P7, b: &P7) -> [f64; 3] {
    [b[0] - a[0], b[1] - a[1], b[2] - a[2]]
}

impl Piece {
    /// The piece from `p` to `q` with the jets `jp`, `jq` (see the module comment; the chord
    /// where a jet is missing or a tangent makes more than 60° with the chord).
    pub fn new(p: &P7, jp: Option<&P7>, q: &P7, jq: Option<&P7>) -> Piece {
        match (jp, jq) {
            (Some(a), Some(b)) => Piece::cubic(p, a, q, b).unwrap_or_else(|| Piece::chord(p, q)),
            _ => Piece::chord(p, q),
        }
    }

    /// The straight piece from `p` to `q` (linear in every packed coordinate).
    pub fn chord(p: &P7, q: &P7) -> Piece {
        let d: P7 = std::array::from_fn(|k| q[k] - p[k]);
        Piece {
            p: *p,
            q: *q,
            dp: d,
            dq: d,
        }
    }

    /// The cubic piece from `p` to `q` with the jets `a`, `b`; `None` where it is the chord (a
    /// tangent more than 60° from the chord, or the chord of length zero).
    pub fn cubic(p: &P7, a: &P7, q: &P7, b: &P7) -> Option<Piece> {
        let c = d3(p, q);
        let l = norm(&c);
        let oriented = |j: &P7| -> Option<P7> {
            let s = j[0] * c[0] + j[1] * c[1] + j[2] * c[2];
            (s.abs() > 0.5 * l).then(|| j.map(|x| x * s.signum()))
        };
        let (a, b) = (oriented(a)?, oriented(b)?);
        let (ta, tb) = ([a[0], a[1], a[2]], [b[0], b[1], b[2]]);
        let phi = norm(&cross(&ta, &tb)).atan2(dot(&ta, &tb));
        let cq = (0.25 * phi).cos();
        let m = l / (cq * cq);
        (m.is_finite() && l > 0.0).then(|| Piece {
            p: *p,
            q: *q,
            dp: a.map(|x| m * x),
            dq: b.map(|x| m * x),
        })
    }

    /// The `per_piece − 1` points of the piece (3D) at `τ = i / per_piece`, `0 < i <
    /// per_piece`, for drawing; none for a chord (its ends are its points).
    pub fn interior(&self, per_piece: usize) -> Vec<[f64; 3]> {
        if self.dp == self.dq {
            return Vec::new();
        }
        (1..per_piece)
            .map(|i| {
                let x = self.eval(i as f64 / per_piece as f64);
                [x[0], x[1], x[2]]
            })
            .collect()
    }

    /// `H(τ)`.
    pub fn eval(&self, t: f64) -> P7 {
        let (t2, t3) = (t * t, t * t * t);
        let (h00, h10, h01, h11) = (
            2.0 * t3 - 3.0 * t2 + 1.0,
            t3 - 2.0 * t2 + t,
            -2.0 * t3 + 3.0 * t2,
            t3 - t2,
        );
        std::array::from_fn(|k| {
            h00 * self.p[k] + h10 * self.dp[k] + h01 * self.q[k] + h11 * self.dq[k]
        })
    }

    fn d1(&self, t: f64) -> [f64; 3] {
        let t2 = t * t;
        let (a, b, c, d) = (
            6.0 * t2 - 6.0 * t,
            3.0 * t2 - 4.0 * t + 1.0,
            -6.0 * t2 + 6.0 * t,
            3.0 * t2 - 2.0 * t,
        );
        std::array::from_fn(|k| a * self.p[k] + b * self.dp[k] + c * self.q[k] + d * self.dq[k])
    }

    fn d2(&self, t: f64) -> [f64; 3] {
        let (a, b, c, d) = (
            12.0 * t - 6.0,
            6.0 * t - 4.0,
            -12.0 * t + 6.0,
            6.0 * t - 2.0,
        );
        std::array::from_fn(|k| a * self.p[k] + b * self.dp[k] + c * self.q[k] + d * self.dq[k])
    }

    /// Bound on `‖H''(τ)‖` in 3D over `[0, 1]`: `H''` is linear in `τ`, so its norm (convex)
    /// is largest at an end. Each end value is a sum of four terms with coefficients of
    /// magnitude at most 12, so its rounding error is below `64 ε` times the coefficients'
    /// largest magnitude ([`Piece::size`]) per coordinate; that is added, and the norm's own
    /// rounding covered by a relative `1e-12`.
    pub fn d2_bound(&self) -> f64 {
        let e = norm(&self.d2(0.0)).max(norm(&self.d2(1.0)));
        e * (1.0 + 1e-12) + 2.0 * 64.0 * f64::EPSILON * self.size()
    }

    /// The largest magnitude of a 3D coordinate among the ends and end derivatives.
    pub fn size(&self) -> f64 {
        [self.p, self.q, self.dp, self.dq]
            .iter()
            .flat_map(|v| v[..3].iter())
            .fold(0.0f64, |m, x| m.max(x.abs()))
    }

    /// Distance (3D) from `x` to the piece, by Newton's method on `τ` from the best of nine
    /// samples, with both ends (a measurement: a local minimum of a smooth function).
    pub fn dist(&self, x: &[f64; 3]) -> f64 {
        self.foot(x).0
    }

    /// [`Piece::dist`] with the parameter `τ ∈ [0, 1]` where it is taken.
    pub fn foot(&self, x: &[f64; 3]) -> (f64, f64) {
        let at = |t: f64| {
            let h = self.eval(t);
            norm(&[h[0] - x[0], h[1] - x[1], h[2] - x[2]])
        };
        let mut best = (0..=8)
            .map(|i| i as f64 / 8.0)
            .map(|t| (at(t), t))
            .fold((f64::INFINITY, 0.0), |a, b| if b.0 < a.0 { b } else { a });
        let mut t = best.1;
        for _ in 0..8 {
            let h = self.eval(t);
            let e = [h[0] - x[0], h[1] - x[1], h[2] - x[2]];
            let (d1, d2) = (self.d1(t), self.d2(t));
            let f = dot(&e, &d1);
            let fp = dot(&d1, &d1) + dot(&e, &d2);
            if fp.is_nan() || fp <= 0.0 {
                break;
            }
            t = (t - f / fp).clamp(0.0, 1.0);
            let d = at(t);
            if d < best.0 {
                best = (d, t);
            }
        }
        best
    }
}

/// Relative rounding allowance of a vertex computed by [`Piece::eval`] (a few operations on
/// each of four terms), times the largest magnitude among the piece's coefficients.
pub const ROUNDING: f64 = 16.0 * f64::EPSILON;

/// The vertices of a polyline within `delta` (3D) of the piece, both ways (every chord point
/// within `delta` of the piece and every piece point within `delta` of the polyline), with
/// the distance actually proven (`≤ delta` unless the sample cap was reached).
///
/// Proof: on `[τ₀, τ₁]` with `h = τ₁ − τ₀` the difference `e(τ)` between `H` and the chord's
/// linear interpolant is `−∫ G(τ, σ) H''(σ) dσ` with Green's function `G ≥ 0` of mass
/// `(τ − τ₀)(τ₁ − τ)/2 ≤ h²/8`, so `‖e‖ ≤ h²/8 · max‖H''‖` ([`Piece::d2_bound`]). The vertices
/// are `f64` evaluations of `H`, each within [`ROUNDING`] times the coefficients' size of the
/// exact value, which is added. At most `max_samples` chords.
pub fn densify(piece: &Piece, delta: f64, max_samples: usize) -> (Vec<[f64; 3]>, f64) {
    let h2 = piece.d2_bound();
    let round = 2.0 * ROUNDING * 4.0 * piece.size();
    let room = (delta - round).max(delta * 1e-3);
    let want = (h2 / (8.0 * room)).sqrt().ceil();
    let n = if want.is_finite() {
        (want as usize).clamp(1, max_samples.max(1))
    } else {
        max_samples.max(1)
    };
    let pts = (0..=n)
        .map(|i| {
            let h = if i == n {
                piece.q
            } else if i == 0 {
                piece.p
            } else {
                piece.eval(i as f64 / n as f64)
            };
            [h[0], h[1], h[2]]
        })
        .collect();
    let proven = h2 / (8.0 * (n * n) as f64) + round;
    (pts, proven)
}

#[cfg(test)]
mod tests;
