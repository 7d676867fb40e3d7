//! The proof step of the singular-point classification (the "Proof." and "Type."
//! paragraphs of the parent module): Newton on `G` in `f64`, Krawczyk's test per piece over a
//! growing box around the Newton solution, and, once every piece passed, the conclusions —
//! the root box inside both domains, the type from the sign of `det J` and `det J12`
//! (extremum or saddle), and the enclosed distance between the surfaces at the root.

use super::{
    BoxGroups, I, MAX_PIECES, NEWTON_STEPS, PieceIdx, Proven, Roles, TRIES, V, det4, pt, sign,
    system,
};
use crate::ssi::enclose2::Jet2;
use crate::ssi::krawczyk::{M4, inverse4, mul4};
use crate::ssi::report::SingularReason;

/// Krawczyk's operator of piece `c` (groups `g` of a box holding `x`) for the centre
/// `y ∈ x` and preconditioner `yinv`, with the Jacobian enclosure over `x`.
fn krawczyk_op(
    r: &Roles,
    g: &BoxGroups,
    c: &PieceIdx,
    y: &[f64; 4],
    yinv: &M4,
    x: &[I; 4],
) -> Option<([I; 4], [[I; 4]; 4])> {
    let (ya, yb) = r.jets(g, c, &y.map(pt))?;
    let (gy, _) = system(&ya, &yb);
    let (xa, xb) = r.jets(g, c, x)?;
    let (_, jx) = system(&xa, &xb);
    let mut k = [pt(0.0); 4];
    for i in 0..4 {
        let mut acc = pt(y[i]);
        for l in 0..4 {
            acc = acc - pt(yinv[i][l]) * gy[l];
        }
        for col in 0..4 {
            let mut cij = pt(if i == col { 1.0 } else { 0.0 });
            for l in 0..4 {
                cij = cij - pt(yinv[i][l]) * jx[l][col];
            }
            acc = acc + cij * (x[col] - pt(y[col]));
        }
        k[i] = acc;
    }
    Some((k, jx))
}

/// The proof for one assignment of roles, from the seed `z0`.
pub(super) fn prove(r: &Roles, z0: [f64; 4]) -> Result<Proven, SingularReason> {
    if !z0.iter().all(|x| x.is_finite()) {
        return Err(SingularReason::NotFinite);
    }
    // Newton on G in f64 from the seed.
    let mut y = z0;
    for _ in 0..NEWTON_STEPS {
        let (f, j) = r.eval_f64(&y).ok_or(SingularReason::Enclosure)?;
        let ji = inverse4(j).ok_or(SingularReason::Singular)?;
        let d = mul4(&ji, &f);
        let next: [f64; 4] = std::array::from_fn(|i| y[i] - d[i]);
        if !next.iter().all(|x| x.is_finite()) {
            return Err(SingularReason::NoContraction);
        }
        y = next;
        if (0..4).all(|i| d[i].abs() <= 1e-14 * (r.hi[i] - r.lo[i] + y[i].abs())) {
            break;
        }
    }
    // Newton left the faces: nothing isolated near the seed.
    if !(0..4).all(|i| {
        let w = r.hi[i] - r.lo[i];
        y[i] >= r.lo[i] - 0.05 * w && y[i] <= r.hi[i] + 0.05 * w
    }) {
        return Err(SingularReason::OutsideDomain);
    }
    let yi: [I; 4] = y.map(pt);
    let gy = r.box_groups(&yi).ok_or(SingularReason::Enclosure)?;
    // Starting radius: twice the enclosed Newton correction (largest over the pieces at y)
    // plus a few ulps of the scale.
    let mut rad = [0.0f64; 4];
    for c in Roles::pieces(&gy) {
        let (ja, jb) = r.jets(&gy, &c, &yi).ok_or(SingularReason::Enclosure)?;
        let (g, j) = system(&ja, &jb);
        let Some(yinv) = inverse4(j.map(|row| row.map(|x| x.mid()))) else {
            return Err(SingularReason::Singular);
        };
        for i in 0..4 {
            let corr = (0..4).fold(pt(0.0), |acc, l| acc + pt(yinv[i][l]) * g[l]);
            rad[i] = rad[i].max(2.0 * corr.mag());
        }
    }
    for i in 0..4 {
        rad[i] += 64.0 * f64::EPSILON * (y[i].abs() + (r.hi[i] - r.lo[i]));
    }
    for _ in 0..TRIES {
        let x: [I; 4] =
            std::array::from_fn(|i| I::new((pt(y[i]) - pt(rad[i])).lo, (pt(y[i]) + pt(rad[i])).hi));
        let g = r.box_groups(&x).ok_or(SingularReason::Enclosure)?;
        let pieces = Roles::pieces(&g);
        if pieces.len() > MAX_PIECES {
            return Err(SingularReason::Enclosure);
        }
        let mut all_in = true;
        let mut reach = [0.0f64; 4];
        let mut results = Vec::new();
        for c in &pieces {
            // The piece's function at y; its own preconditioner.
            let (ya, yb) = r.jets(&g, c, &yi).ok_or(SingularReason::Enclosure)?;
            let (_, jy) = system(&ya, &yb);
            let yinv =
                inverse4(jy.map(|row| row.map(|x| x.mid()))).ok_or(SingularReason::Singular)?;
            let (k, jx) =
                krawczyk_op(r, &g, c, &y, &yinv, &x).ok_or(SingularReason::NoContraction)?;
            if !k.iter().all(|v| v.is_finite()) {
                return Err(SingularReason::NoContraction);
            }
            for i in 0..4 {
                if !(k[i].lo > x[i].lo && k[i].hi < x[i].hi) {
                    all_in = false;
                }
                reach[i] = reach[i].max((k[i].lo - y[i]).abs().max((k[i].hi - y[i]).abs()));
            }
            results.push((*c, k, jx, yinv));
        }
        if all_in {
            return conclude(r, &g, &x, &results);
        }
        for i in 0..4 {
            rad[i] = (2.0 * rad[i]).max(1.25 * reach[i]);
        }
        if !(0..4).all(|i| rad[i].is_finite() && rad[i] <= 0.05 * (r.hi[i] - r.lo[i])) {
            break;
        }
    }
    Err(SingularReason::NoContraction)
}

/// A piece that passed the test: its Krawczyk box `K`, Jacobian enclosure over `X`, and
/// preconditioner.
type PieceResult = (PieceIdx, [I; 4], [[I; 4]; 4], M4);

/// After the test passed for every piece: domain check, type, distance at the root.
fn conclude(
    r: &Roles,
    g: &BoxGroups,
    x: &[I; 4],
    results: &[PieceResult],
) -> Result<Proven, SingularReason> {
    let mut root: Option<[I; 4]> = None;
    let mut hess_sign: Option<i8> = None;
    let mut dist = [f64::INFINITY, 0.0f64];
    let meet4 = |a: &[I; 4], b: &[I; 4]| -> [I; 4] {
        std::array::from_fn(|i| I::new(a[i].lo.max(b[i].lo), a[i].hi.min(b[i].hi)))
    };
    for (c, k, jx, yinv) in results {
        // The zero lies in K(X) ∩ X. Any zero in a box Z lies in K(Z) for a centre in Z, so
        // Z ← K(Z) ∩ Z about Z's midpoint narrows the enclosure (kept if it would empty).
        let mut z = meet4(k, x);
        for _ in 0..3 {
            let m = z.map(|i| i.mid());
            if !(0..4).all(|i| z[i].lo <= m[i] && m[i] <= z[i].hi) {
                break;
            }
            let Some((kz, _)) = krawczyk_op(r, g, c, &m, yinv, &z) else {
                break;
            };
            let n = meet4(&kz, &z);
            if !(0..4).all(|i| n[i].lo <= n[i].hi) {
                break;
            }
            z = n;
        }
        // The root box must lie in both closed domains.
        if (0..4).any(|i| !r.per[i] && (z[i].lo < r.lo[i] || z[i].hi > r.hi[i])) {
            return Err(SingularReason::OutsideDomain);
        }
        root = Some(match root {
            None => z,
            Some(o) => std::array::from_fn(|i| o[i].hull(z[i])),
        });
        // Sign of det J over J(X): constant (every matrix in it is non-singular); that of the
        // midpoint matrix, enclosed.
        let mid: M4 = jx.map(|row| row.map(|e| e.mid()));
        if !(0..4).all(|i| (0..4).all(|l| jx[i][l].lo <= mid[i][l] && mid[i][l] <= jx[i][l].hi)) {
            return Err(SingularReason::TypeUndecided);
        }
        let s_det = sign(det4(&mid)).ok_or(SingularReason::TypeUndecided)?;
        // det J12 = det ∂(G1, G2)/∂(s, t) over X.
        let j12 = jx[0][2] * jx[1][3] - jx[0][3] * jx[1][2];
        let s12 = sign(j12).ok_or(SingularReason::TypeUndecided)?;
        let s = s_det * s12;
        if hess_sign.is_some_and(|h| h != s) {
            return Err(SingularReason::TypeUndecided);
        }
        hess_sign = Some(s);
        // |S_A − S_B| over the root box, with this piece's functions: the direct enclosure
        // intersected with the mean-value form about the box centre (both hold the value).
        let (ja, jb) = r.jets(g, c, &z).ok_or(SingularReason::Enclosure)?;
        let m: [I; 4] = z.map(|i| pt(i.mid()));
        let (ma, mb) = r.jets(g, c, &m).ok_or(SingularReason::Enclosure)?;
        let mv = |s0: &V, j: &Jet2, k: usize| -> V {
            let (du, dv) = (z[k] - m[k], z[k + 1] - m[k + 1]);
            std::array::from_fn(|c| s0[c] + j.su[c] * du + j.sv[c] * dv)
        };
        let (ea, eb) = (mv(&ma.s, &ja, 0), mv(&mb.s, &jb, 2));
        let meet = |x: I, y: I| I::new(x.lo.max(y.lo), x.hi.min(y.hi));
        let d: V = std::array::from_fn(|k| {
            let (a, b) = (meet(ja.s[k], ea[k]), meet(jb.s[k], eb[k]));
            if a.lo > a.hi || b.lo > b.hi {
                // Both hold the value: cannot happen; keep the direct enclosure.
                ja.s[k] - jb.s[k]
            } else {
                a - b
            }
        });
        let (mut lo2, mut hi2) = (0.0f64, 0.0f64);
        for dk in d {
            let m = dk.mag();
            let mig = if dk.contains_zero() {
                0.0
            } else {
                dk.lo.abs().min(dk.hi.abs())
            };
            hi2 = (hi2 + (m * m).next_up()).next_up();
            lo2 = (lo2 + (mig * mig).next_down().max(0.0))
                .next_down()
                .max(0.0);
        }
        dist[0] = dist[0].min(lo2.sqrt().next_down().max(0.0));
        dist[1] = dist[1].max(hi2.sqrt().next_up());
    }
    let (Some(root), Some(h)) = (root, hess_sign) else {
        return Err(SingularReason::Enclosure);
    };
    if !dist[1].is_finite() {
        return Err(SingularReason::Enclosure);
    }
    Ok(Proven {
        x: *x,
        root,
        pieces: results.len(),
        saddle: h < 0,
        distance: dist,
    })
}
