//! Big-rational backends side by side on three of vericad's exact kernels.
//!
//! The kernels are written once, generically over [`Exact`] (the subset of vericad's
//! `Scalar` trait they use, by reference), and follow vericad's own code
//! (`src/scalar/mod.rs` `orient3d`, `src/spline/bezier_curve.rs` `subdivide`/`blossom`,
//! `src/spline/compose.rs` `compose_line`), so each backend does the same operations in
//! the same order on the same values:
//!
//! * [`orient3d`] — sign of `det[b-a, c-a, d-a]`;
//! * [`half_split`] — de Casteljau at `t = 1/2` of a bicubic net, in u and then in v: the
//!   four quarter nets;
//! * [`compose_line`] — the Bézier curve `S(a + t(b-a))` of degree `p + q` for a Bézier
//!   patch `S` of degrees `(p, q)` and a chord `a→b` of its domain, by blossoming (Yang et
//!   al. §4); `(3,3)` gives degree 6, `(3,5)` degree 8.
//!
//! Inputs are `f64` values (from a seeded xorshift generator, [`inputs`]) converted exactly to
//! rationals, so every backend computes the identical exact result; [`Exact::to_num_den`]
//! gives the common representation the results are compared in.

pub mod backends;
pub mod inputs;

/// What the kernels need from a rational type. Binary operations take references (every
/// backend has `&a op &b`), so no kernel clones an operand only to consume it.
pub trait Exact: Clone + Sized {
    /// Column name in reports.
    const NAME: &'static str;
    /// The exact value of a finite `f64` (every finite `f64` is a dyadic rational).
    fn from_f64(x: f64) -> Self;
    fn from_i64(i: i64) -> Self;
    fn add(&self, o: &Self) -> Self;
    fn sub(&self, o: &Self) -> Self;
    fn mul(&self, o: &Self) -> Self;
    fn div(&self, o: &Self) -> Self;
    fn add_assign(&mut self, o: &Self);
    /// -1, 0 or 1.
    fn sign(&self) -> i8;
    /// `(numerator, denominator)` in lowest terms, denominator positive, in decimal: the
    /// representation every backend's results are compared in.
    fn to_num_den(&self) -> (String, String);
}

pub type P3<T> = [T; 3];

fn sub3<T: Exact>(a: &P3<T>, b: &P3<T>) -> P3<T> {
    [a[0].sub(&b[0]), a[1].sub(&b[1]), a[2].sub(&b[2])]
}

/// `a + (b - a) t`, coordinatewise (vericad's `Point::lerp`).
fn lerp3<T: Exact>(a: &P3<T>, b: &P3<T>, t: &T) -> P3<T> {
    [
        a[0].add(&b[0].sub(&a[0]).mul(t)),
        a[1].add(&b[1].sub(&a[1]).mul(t)),
        a[2].add(&b[2].sub(&a[2]).mul(t)),
    ]
}

// ---------------------------------------------------------------------------------------
// 1. orient3d

/// `det[b-a, c-a, d-a]`, expanded along the first row as vericad's `det3` does.
pub fn orient3d_det<T: Exact>(a: &P3<T>, b: &P3<T>, c: &P3<T>, d: &P3<T>) -> T {
    let u = sub3(b, a);
    let v = sub3(c, a);
    let w = sub3(d, a);
    let m0 = v[1].mul(&w[2]).sub(&v[2].mul(&w[1]));
    let m1 = v[0].mul(&w[2]).sub(&v[2].mul(&w[0]));
    let m2 = v[0].mul(&w[1]).sub(&v[1].mul(&w[0]));
    u[0].mul(&m0).sub(&u[1].mul(&m1)).add(&u[2].mul(&m2))
}

/// Sign of `det[b-a, c-a, d-a]`: positive when `d` lies on the side of the plane `abc` into
/// which `(b-a)×(c-a)` points.
pub fn orient3d<T: Exact>(a: &P3<T>, b: &P3<T>, c: &P3<T>, d: &P3<T>) -> i8 {
    orient3d_det(a, b, c, d).sign()
}

// ---------------------------------------------------------------------------------------
// Bézier nets

/// A tensor-product Bézier net of degrees `(p, q)`: `(p+1)(q+1)` points, row-major,
/// `net[i * (q+1) + j]` with `i` the u index and `j` the v index (vericad's layout).
#[derive(Clone, Debug)]
pub struct Net<T> {
    pub p: usize,
    pub q: usize,
    pub pts: Vec<P3<T>>,
}

impl<T: Exact> Net<T> {
    pub fn at(&self, i: usize, j: usize) -> &P3<T> {
        &self.pts[i * (self.q + 1) + j]
    }
    fn row(&self, i: usize) -> Vec<P3<T>> {
        (0..=self.q).map(|j| self.at(i, j).clone()).collect()
    }
    fn column(&self, j: usize) -> Vec<P3<T>> {
        (0..=self.p).map(|i| self.at(i, j).clone()).collect()
    }
    fn from_rows(rows: Vec<Vec<P3<T>>>) -> Self {
        let p = rows.len() - 1;
        let q = rows[0].len() - 1;
        Net {
            p,
            q,
            pts: rows.into_iter().flatten().collect(),
        }
    }
    fn from_columns(cols: Vec<Vec<P3<T>>>) -> Self {
        let q = cols.len() - 1;
        let p = cols[0].len() - 1;
        let mut pts = Vec::with_capacity((p + 1) * (q + 1));
        for i in 0..=p {
            for col in &cols {
                pts.push(col[i].clone());
            }
        }
        Net { p, q, pts }
    }
    /// Split in u at `t` (every column by de Casteljau).
    pub fn subdivide_u(&self, t: &T) -> (Self, Self) {
        let (l, r): (Vec<_>, Vec<_>) = (0..=self.q).map(|j| subdivide(&self.column(j), t)).unzip();
        (Self::from_columns(l), Self::from_columns(r))
    }
    /// Split in v at `t` (every row).
    pub fn subdivide_v(&self, t: &T) -> (Self, Self) {
        let (l, r): (Vec<_>, Vec<_>) = (0..=self.p).map(|i| subdivide(&self.row(i), t)).unzip();
        (Self::from_rows(l), Self::from_rows(r))
    }
    /// Point at `(u, v)`: every row at `v`, then that column at `u`.
    pub fn eval(&self, u: &T, v: &T) -> P3<T> {
        let col: Vec<_> = (0..=self.p).map(|i| eval(&self.row(i), v)).collect();
        eval(&col, u)
    }
    /// Tensor-product blossom `f(us; vs)`.
    pub fn blossom(&self, us: &[T], vs: &[T]) -> P3<T> {
        let col: Vec<_> = (0..=self.p).map(|i| blossom(&self.row(i), vs)).collect();
        blossom(&col, us)
    }
    /// All `(p+1)(q+1)` values as `(num, den)` strings.
    pub fn to_num_den(&self) -> Vec<(String, String)> {
        points_num_den(&self.pts)
    }
}

pub fn points_num_den<T: Exact>(pts: &[P3<T>]) -> Vec<(String, String)> {
    pts.iter()
        .flat_map(|p| p.iter().map(Exact::to_num_den))
        .collect()
}

/// de Casteljau split of a curve at `t` (vericad's `BezierCurve::subdivide`).
pub fn subdivide<T: Exact>(control: &[P3<T>], t: &T) -> (Vec<P3<T>>, Vec<P3<T>>) {
    let n = control.len();
    let mut b = control.to_vec();
    let mut left = Vec::with_capacity(n);
    let mut right = Vec::with_capacity(n);
    left.push(b[0].clone());
    right.push(b[n - 1].clone());
    for level in 1..n {
        for i in 0..n - level {
            b[i] = lerp3(&b[i], &b[i + 1], t);
        }
        left.push(b[0].clone());
        right.push(b[n - 1 - level].clone());
    }
    right.reverse();
    (left, right)
}

/// Curve point at `t` (de Casteljau).
pub fn eval<T: Exact>(control: &[P3<T>], t: &T) -> P3<T> {
    let ts = vec![t.clone(); control.len() - 1];
    blossom(control, &ts)
}

/// Curve blossom `b[t_1, …, t_n]`: de Casteljau with parameter `t_l` at level `l`.
pub fn blossom<T: Exact>(control: &[P3<T>], ts: &[T]) -> P3<T> {
    assert_eq!(
        ts.len() + 1,
        control.len(),
        "blossom needs degree-many arguments"
    );
    let mut b = control.to_vec();
    for (level, t) in ts.iter().enumerate() {
        for i in 0..b.len() - 1 - level {
            b[i] = lerp3(&b[i], &b[i + 1], t);
        }
    }
    b.swap_remove(0)
}

// ---------------------------------------------------------------------------------------
// 2. half split

/// The four quarter nets of `s` split at `u = 1/2` and then `v = 1/2`, in the order
/// `[u-low v-low, u-low v-high, u-high v-low, u-high v-high]`. `half` is the rational 1/2.
pub fn half_split<T: Exact>(s: &Net<T>, half: &T) -> [Net<T>; 4] {
    let (lo, hi) = s.subdivide_u(half);
    let (a, b) = lo.subdivide_v(half);
    let (c, d) = hi.subdivide_v(half);
    [a, b, c, d]
}

// ---------------------------------------------------------------------------------------
// 3. composition with a chord

/// `C(n, k)` for the small degrees here.
pub fn binomial(n: usize, k: usize) -> i64 {
    if k > n {
        return 0;
    }
    let mut r: i64 = 1;
    for i in 0..k.min(n - k) {
        r = r * (n - i) as i64 / (i + 1) as i64;
    }
    r
}

/// Polar values `c[x^(n-j), y^j]`, `j = 0..=n`, of a curve of degree `n`.
fn polar_values<T: Exact>(control: &[P3<T>], x: &T, y: &T) -> Vec<P3<T>> {
    let n = control.len() - 1;
    (0..=n)
        .map(|j| {
            let mut ts = vec![x.clone(); n - j];
            ts.extend(std::iter::repeat_n(y.clone(), j));
            blossom(control, &ts)
        })
        .collect()
}

/// The exact image `S(a + t(b - a))` of the domain chord `a→b`: a Bézier curve of degree
/// `p + q`, control point `k` = `Σ_{i+j=k} C(p,i) C(q,j) / C(p+q,k) · f(a_u^{p-i} b_u^i;
/// a_v^{q-j} b_v^j)` (vericad's `compose_line`, Yang et al. §4).
#[allow(clippy::needless_range_loop)] // `i` indexes `h` and gives `j = k - i`
pub fn compose_line<T: Exact>(s: &Net<T>, a: &[T; 2], b: &[T; 2]) -> Vec<P3<T>> {
    let (p, q) = (s.p, s.q);
    let rows: Vec<Vec<P3<T>>> = (0..=p)
        .map(|r| polar_values(&s.row(r), &a[1], &b[1]))
        .collect();
    let mut h: Vec<Vec<Option<P3<T>>>> = vec![vec![None; q + 1]; p + 1];
    for j in 0..=q {
        let col: Vec<P3<T>> = (0..=p).map(|r| rows[r][j].clone()).collect();
        for (i, v) in polar_values(&col, &a[0], &b[0]).into_iter().enumerate() {
            h[i][j] = Some(v);
        }
    }
    let zero = T::from_i64(0);
    let mut out = Vec::with_capacity(p + q + 1);
    for k in 0..=p + q {
        let mut acc = [zero.clone(), zero.clone(), zero.clone()];
        let den = T::from_i64(binomial(p + q, k));
        for i in k.saturating_sub(q)..=k.min(p) {
            let j = k - i;
            let w = T::from_i64(binomial(p, i) * binomial(q, j)).div(&den);
            let hij = h[i][j].as_ref().expect("every polar value is set");
            for c in 0..3 {
                acc[c].add_assign(&hij[c].mul(&w));
            }
        }
        out.push(acc);
    }
    out
}

/// The same curve by a different route, for the tests: Bernstein products
/// `B_i^p(u(t)) B_j^q(v(t))` (vericad's general `compose`).
pub fn compose_line_by_products<T: Exact>(s: &Net<T>, a: &[T; 2], b: &[T; 2]) -> Vec<P3<T>> {
    let one = T::from_i64(1);
    let basis = |x0: &T, x1: &T, n: usize| -> Vec<Vec<T>> {
        let x = vec![x0.clone(), x1.clone()];
        let om = vec![one.sub(x0), one.sub(x1)];
        let mut px = vec![vec![one.clone()]];
        let mut pom = vec![vec![one.clone()]];
        for k in 1..=n {
            px.push(bern_mul(&px[k - 1], &x));
            pom.push(bern_mul(&pom[k - 1], &om));
        }
        (0..=n)
            .map(|i| {
                let c = T::from_i64(binomial(n, i));
                bern_mul(&px[i], &pom[n - i])
                    .iter()
                    .map(|v| v.mul(&c))
                    .collect()
            })
            .collect()
    };
    let bu = basis(&a[0], &b[0], s.p);
    let bv = basis(&a[1], &b[1], s.q);
    let zero = T::from_i64(0);
    let mut out = vec![[zero.clone(), zero.clone(), zero.clone()]; s.p + s.q + 1];
    for (i, bi) in bu.iter().enumerate() {
        for (j, bj) in bv.iter().enumerate() {
            let w = bern_mul(bi, bj);
            let pij = s.at(i, j);
            for (k, wk) in w.iter().enumerate() {
                for c in 0..3 {
                    out[k][c].add_assign(&pij[c].mul(wk));
                }
            }
        }
    }
    out
}

/// Exact product of Bernstein polynomials: `c_k = Σ_{i+j=k} C(m,i) C(n,j) / C(m+n,k) f_i g_j`.
pub fn bern_mul<T: Exact>(f: &[T], g: &[T]) -> Vec<T> {
    let (m, n) = (f.len() - 1, g.len() - 1);
    let mut c = vec![T::from_i64(0); m + n + 1];
    for (i, fi) in f.iter().enumerate() {
        for (j, gj) in g.iter().enumerate() {
            let w = T::from_i64(binomial(m, i) * binomial(n, j));
            c[i + j].add_assign(&w.mul(fi).mul(gj));
        }
    }
    for (k, ck) in c.iter_mut().enumerate() {
        *ck = ck.div(&T::from_i64(binomial(m + n, k)));
    }
    c
}

// ---------------------------------------------------------------------------------------
// The inputs of every kernel, lifted to one backend.

pub fn lift3<T: Exact>(p: &[f64; 3]) -> P3<T> {
    [T::from_f64(p[0]), T::from_f64(p[1]), T::from_f64(p[2])]
}

pub fn lift_net<T: Exact>(n: &inputs::NetF64) -> Net<T> {
    Net {
        p: n.p,
        q: n.q,
        pts: n.pts.iter().map(lift3).collect(),
    }
}

/// One backend's copy of all benchmark inputs.
pub struct Inputs<T> {
    pub orient: Vec<[P3<T>; 4]>,
    pub nets: Vec<Net<T>>,
    pub chords6: Vec<(Net<T>, [T; 2], [T; 2])>,
    pub chords8: Vec<(Net<T>, [T; 2], [T; 2])>,
    pub half: T,
}

impl<T: Exact> Inputs<T> {
    pub fn new() -> Self {
        let lift_chord = |c: &inputs::ChordF64| {
            (
                lift_net(&c.net),
                [T::from_f64(c.a[0]), T::from_f64(c.a[1])],
                [T::from_f64(c.b[0]), T::from_f64(c.b[1])],
            )
        };
        Inputs {
            orient: inputs::orient3d_cases()
                .iter()
                .map(|c| [lift3(&c[0]), lift3(&c[1]), lift3(&c[2]), lift3(&c[3])])
                .collect(),
            nets: inputs::bicubic_nets().iter().map(lift_net).collect(),
            chords6: inputs::chords(3, 3).iter().map(lift_chord).collect(),
            chords8: inputs::chords(3, 5).iter().map(lift_chord).collect(),
            half: T::from_f64(0.5),
        }
    }

    // One pass over all cases of a kernel: what a benchmark iteration times.

    pub fn run_orient3d(&self) -> Vec<i8> {
        self.orient
            .iter()
            .map(|[a, b, c, d]| orient3d(a, b, c, d))
            .collect()
    }
    pub fn run_half_split(&self) -> Vec<[Net<T>; 4]> {
        self.nets
            .iter()
            .map(|n| half_split(n, &self.half))
            .collect()
    }
    pub fn run_compose6(&self) -> Vec<Vec<P3<T>>> {
        self.chords6
            .iter()
            .map(|(s, a, b)| compose_line(s, a, b))
            .collect()
    }
    pub fn run_compose8(&self) -> Vec<Vec<P3<T>>> {
        self.chords8
            .iter()
            .map(|(s, a, b)| compose_line(s, a, b))
            .collect()
    }

    /// Every exact result of every kernel, as `(num, den)` strings, by kernel name: what
    /// the backends are compared on (for orient3d: the determinant itself, not only its
    /// sign).
    pub fn results(&self) -> Vec<(&'static str, Vec<(String, String)>)> {
        let dets = self
            .orient
            .iter()
            .map(|[a, b, c, d]| orient3d_det(a, b, c, d).to_num_den())
            .collect();
        let split = self
            .run_half_split()
            .iter()
            .flat_map(|q| q.iter().flat_map(Net::to_num_den).collect::<Vec<_>>())
            .collect();
        let c6 = self
            .run_compose6()
            .iter()
            .flat_map(|c| points_num_den(c))
            .collect();
        let c8 = self
            .run_compose8()
            .iter()
            .flat_map(|c| points_num_den(c))
            .collect();
        vec![
            ("orient3d", dets),
            ("half_split", split),
            ("compose6", c6),
            ("compose8", c8),
        ]
    }
}

impl<T: Exact> Default for Inputs<T> {
    fn default() -> Self {
        Self::new()
    }
}
