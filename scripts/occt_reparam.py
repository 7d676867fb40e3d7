#!/usr/bin/env python3
"""vericad reparam beside Open CASCADE's GeomAPI_PointsToBSplineSurface (chord-length
parameters, C2, tolerance TOL) on the B-spline faces of a STEP file.

Rows per face:
  given        S as read by OCCT;
  vericad      R, vericad's bicubic (`vericad reparam FILE:FACE --tol TOL --out r.json`, read from the
               "vericad-model" JSON at full precision);
  OCCT grid    GeomAPI_PointsToBSplineSurface on vericad's own final grid points Q_ij (same count,
               same points: the points R interpolates), degree 3..8;
  OCCT grid3   the same with degree 3 at most (bicubic, like R);
  OCCT unif    the degree 3..8 fit on points of S on a uniform parameter grid of the same size (what a user
               of GeomAPI_PointsToBSplineSurface without vericad would give it).
For each: control points, the spacing ratio on a uniform 20 x 20 parameter grid (min..max, 1 = chord
length), and the largest distances from 41 x 41 (OCCT_REPARAM_SAMPLES + 1 squared) uniform parameter samples of the result to S and of S to
the result (OCCT's GeomAPI_ProjectPointOnSurf; where it fails or returns more than TOL, Gauss-Newton
from the nearest of 61 x 61 samples of the target, the smaller distance kept: measured, evidence, one
procedure for all rows; vericad's own E_max is printed beside it).

Where Q_ij come from: the report's `faces[0].result.xi` and `.eta`, the final grid lines'
parameters on R (chord-length fractions in [0, 1]); R interpolates Q_ij at (xi_i, eta_j), so
Q_ij = R(xi_i, eta_j), evaluated here in Python by Cox-de Boor (The NURBS Book A2.2, homogeneous
coordinates when the JSON has weights) from R's knots, degrees and control points in the
"vericad-model" JSON. Checks, per face: the counts of xi and eta equal the report's lines_final and
R's control net (an interpolant has as many control points as points); R's knots are the averages
of three consecutive xi (eta) (The NURBS Book eq. 9.8, as src/reparam/surface.rs builds them;
"knots" in the notes, the largest difference); OCCT's evaluation of the same R (Geom_BSplineSurface
built from the JSON) agrees with the Python one at every (xi_i, eta_j) ("R(grid)-Q" in the notes,
absolute and relative to the size); and the Q_ij lie on the given S ("Q to S", distance by the same
procedure as the table, on at most ~400 of them). No vericad code runs besides the CLI.

Times (wall clock, best of 3): the CLI as a subprocess on FILE:FACE with and without the proven bound
(process start and reading the STEP file included), the report's in-process seconds of the
--no-bound runs (best of 3), and OCCT's fit alone (GeomAPI_PointsToBSplineSurface.Init on points in memory);
ratios are vericad / OCCT. Compare ratios, not absolute times, across machines.
Lengths: OCCT reads STEP in mm; vericad keeps the file's unit (the JSON's "unit"); vericad's points
are scaled to mm before they meet OCCT, and the distance from Q_ij to S ("Q to S") checks it.

Usage: cargo build --release && python3 scripts/occt_reparam.py FILE.step [TOL] [FACE ...]
Env: VERICAD (the CLI; default $CARGO_TARGET_DIR/release/vericad, CARGO_TARGET_DIR defaulting to the
repository's target/), OCCT_REPARAM_SAMPLES (sample intervals per direction of the distances,
default 40).
"""
import json, math, os, subprocess, sys, tempfile, time

import OCP.OCP as o

from occt_io import from_json

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, ".."))
TARGET = os.environ.get("CARGO_TARGET_DIR", os.path.join(REPO, "target"))
VERICAD = os.environ.get("VERICAD", os.path.join(TARGET, "release", "vericad"))
TO_MM = {"mm": 1.0, "millimetre": 1.0, "cm": 10.0, "m": 1000.0, "metre": 1000.0, "in": 25.4,
         "inch": 25.4, "ft": 304.8, "foot": 304.8, "um": 1e-3, "micrometre": 1e-3}

def find_span(knots, p, n, x):
    """The span index k (p <= k <= n - 1, n control points) with knots[k] <= x < knots[k + 1];
    the last non-empty span at the upper end (The NURBS Book A2.1)."""
    if x >= knots[n]:
        k = n - 1
        while k > p and knots[k] >= knots[k + 1]:
            k -= 1
        return k
    lo, hi = p, n
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if x < knots[mid]:
            hi = mid
        else:
            lo = mid
    return lo


def basis(knots, p, k, x):
    """The p + 1 non-zero B-spline basis functions N_{k-p..k, p}(x) (Cox-de Boor, A2.2)."""
    n, left, right = [1.0] + [0.0] * p, [0.0] * (p + 1), [0.0] * (p + 1)
    for j in range(1, p + 1):
        left[j], right[j] = x - knots[k + 1 - j], knots[k + j] - x
        saved = 0.0
        for r in range(j):
            t = n[r] / (right[r + 1] + left[j - r])
            n[r] = saved + right[r + 1] * t
            saved = left[j - r] * t
        n[j] = saved
    return n


def evaluate(s, u, v):
    """A vericad-model JSON surface at (u, v): sum N_i(u) N_j(v) w_ij P_ij / sum N_i N_j w_ij."""
    c, w = s["control_points"], s.get("weights")
    pu, pv, ku, kv = s["degree_u"], s["degree_v"], s["knots_u"], s["knots_v"]
    iu, iv = find_span(ku, pu, len(c), u), find_span(kv, pv, len(c[0]), v)
    bu, bv = basis(ku, pu, iu, u), basis(kv, pv, iv, v)
    acc = [0.0, 0.0, 0.0, 0.0]
    for a in range(pu + 1):
        i = iu - pu + a
        for b in range(pv + 1):
            j = iv - pv + b
            f = bu[a] * bv[b] * (w[i][j] if w else 1.0)
            for d in range(3):
                acc[d] += f * c[i][j][d]
            acc[3] += f
    return [x / acc[3] for x in acc[:3]]


def averaged_knots_error(knots, params, p):
    """Largest |knot - average of p consecutive params| over R's interior knots (eq. 9.8), and
    the clamped ends' distance from params[0], params[-1]."""
    n = len(params)
    want = [params[0]] * (p + 1) + [sum(params[j:j + p]) / p for j in range(1, n - p)] + [params[-1]] * (p + 1)
    if len(want) != len(knots):
        return math.inf
    return max(abs(a - b) for a, b in zip(knots, want))


def read_step(path):
    rd = o.STEPControl.STEPControl_Reader()
    if rd.ReadFile(path) != o.IFSelect.IFSelect_ReturnStatus.IFSelect_RetDone:
        raise RuntimeError(f"OCCT cannot read {path}")
    rd.TransferRoots()
    ex = o.TopExp.TopExp_Explorer(rd.OneShape(), o.TopAbs.TopAbs_ShapeEnum.TopAbs_FACE)
    out = []
    while ex.More():
        out.append(o.BRep.BRep_Tool.Surface_s(o.TopoDS.TopoDS.Face(ex.Current())))
        ex.Next()
    return out


def spacing(s, n=20):
    u0, u1, v0, v1 = s.Bounds()
    pts = [[s.Value(u0 + (u1 - u0) * i / n, v0 + (v1 - v0) * j / n) for j in range(n + 1)] for i in range(n + 1)]
    lines = pts + [[pts[i][j] for i in range(n + 1)] for j in range(n + 1)]
    steps = [[a.Distance(b) for a, b in zip(l, l[1:])] for l in lines]
    longest = max(sum(d) for d in steps)
    r = [x * n / sum(d) for d in steps if sum(d) > 1e-9 * longest for x in d]
    return min(r), max(r)


class Distance:
    """Distance of points to S: OCCT's projection, checked by Gauss-Newton from dense samples."""

    def __init__(self, s, tol, n=60):
        self.s, self.tol = s, tol
        self.b = s.Bounds()
        u0, u1, v0, v1 = self.b
        self.samples = [(u0 + (u1 - u0) * i / n, v0 + (v1 - v0) * j / n) for i in range(n + 1) for j in range(n + 1)]
        self.xyz = [s.Value(u, v).Coord() for u, v in self.samples]

    def newton(self, p):
        q = p.Coord()
        k = min(range(len(self.xyz)), key=lambda k: sum((a - b) ** 2 for a, b in zip(self.xyz[k], q)))
        u, v = self.samples[k]
        u0, u1, v0, v1 = self.b
        P, Du, Dv = o.gp.gp_Pnt(), o.gp.gp_Vec(), o.gp.gp_Vec()
        best = math.dist(self.xyz[k], q)
        for _ in range(40):
            self.s.D1(u, v, P, Du, Dv)
            r = o.gp.gp_Vec(p, P)
            best = min(best, r.Magnitude())
            a, b, c = Du.Dot(Du), Du.Dot(Dv), Dv.Dot(Dv)
            lam = 1e-12 * (a + c) + 1e-300
            a, c = a + lam, c + lam
            g1, g2 = -Du.Dot(r), -Dv.Dot(r)
            det = a * c - b * b
            if det <= 0:
                break
            du, dv = (c * g1 - b * g2) / det, (a * g2 - b * g1) / det
            un, vn = min(max(u + du, u0), u1), min(max(v + dv, v0), v1)
            if abs(un - u) + abs(vn - v) < 1e-15 * (abs(u1 - u0) + abs(v1 - v0)):
                break
            u, v = un, vn
        return min(best, p.Distance(self.s.Value(u, v)))

    def __call__(self, p):
        pr = o.GeomAPI.GeomAPI_ProjectPointOnSurf(p, self.s)
        d = pr.LowerDistance() if pr.NbPoints() > 0 else math.inf
        if d > self.tol:
            d = min(d, self.newton(p))
        return d


SAMPLES = int(os.environ.get("OCCT_REPARAM_SAMPLES", "40"))


def one_sided(a, dist, n=None):
    """Largest distance from n+1 x n+1 (default SAMPLES + 1) uniform parameter samples of `a` to the surface of `dist`."""
    n = n or SAMPLES
    u0, u1, v0, v1 = a.Bounds()
    return max(dist(a.Value(u0 + (u1 - u0) * i / n, v0 + (v1 - v0) * j / n))
               for i in range(n + 1) for j in range(n + 1))


def deviation(r, s, to_s, tol):
    """(result -> S, S -> result), both measured at SAMPLES + 1 squared samples."""
    return one_sided(r, to_s), one_sided(s, Distance(r, tol))


def best_of(k, f):
    best, out = math.inf, None
    for _ in range(k):
        t = time.perf_counter()
        out = f()
        best = min(best, time.perf_counter() - t)
    return best, out


def occt_fit(pts, tol, deg_max=8):
    """GeomAPI_PointsToBSplineSurface on an Array2_gp_Pnt; (best of 3 seconds of Init, surface)."""
    def fit():
        api = o.GeomAPI.GeomAPI_PointsToBSplineSurface()
        api.Init(pts, o.Approx.Approx_ParametrizationType.Approx_ChordLength, 3, deg_max,
                 o.GeomAbs.GeomAbs_Shape.GeomAbs_C2, tol)
        return api.Surface() if api.IsDone() else None
    return best_of(3, fit)


def uniform_points(s, nu, nv):
    u0, u1, v0, v1 = s.Bounds()
    pts = o.collections.Array2_gp_Pnt(1, nu, 1, nv)
    for i in range(nu):
        for j in range(nv):
            pts.SetValue(i + 1, j + 1, s.Value(u0 + (u1 - u0) * i / (nu - 1), v0 + (v1 - v0) * j / (nv - 1)))
    return pts


def row(k, who, surf, sp, dev, extra=""):
    ctrl = f"{surf.NbUPoles()}x{surf.NbVPoles()}" if surf is not None else "-"
    sps = f"{sp[0]:.4f}..{sp[1]:.4f}" if sp else ""
    ds = f"{dev[0]:.2e} / {dev[1]:.2e}" if dev is not None else ""
    print(f"{k:>4}  {who:<10} {ctrl:>9} {sps:>17} {ds:>19}  {extra}", flush=True)


def main(path, tol, only):
    print(f"{path}, tol {tol}; vericad {VERICAD}")
    print(f"{'face':>4}  {'who':<10} {'ctrl':>9} {'spacing':>17} {'to S / from S':>19}  notes")
    tmp = tempfile.mkdtemp()
    for k, s in enumerate(read_step(path)):
        if only and k not in only:
            continue
        if s.DynamicType().Name() != "Geom_BSplineSurface":
            continue
        out, rep = os.path.join(tmp, f"r{k}.json"), os.path.join(tmp, f"rep{k}.json")
        cmd = [VERICAD, "reparam", f"{path}:{k}", "--tol", str(tol), "--out", out, "--report", rep]
        t_bound, run = best_of(3, lambda: subprocess.run(cmd, capture_output=True, text=True))
        if not os.path.exists(rep):
            print(f"{k:>4}  vericad    not reparametrized: {run.stderr.strip()}")
            continue
        t_fast, inproc = math.inf, math.inf
        for _ in range(3):
            t0 = time.perf_counter()
            subprocess.run(cmd + ["--no-bound"], capture_output=True)
            t_fast = min(t_fast, time.perf_counter() - t0)
            f = json.load(open(rep))["faces"][0]["result"]
            inproc = min(inproc, f["seconds"])
        model = json.load(open(out))
        scale = TO_MM[model["unit"]]
        r = from_json(model["surfaces"][0], scale)
        rs = model["surfaces"][0]
        xi, eta = f["xi"], f["eta"]
        nu, nv = len(xi), len(eta)
        net = [len(rs["control_points"]), len(rs["control_points"][0])]
        if [nu, nv] != f["lines_final"] or net != f["control_points_after"] or net != [nu, nv]:
            print(f"{k:>4}  report's xi, eta {nu}x{nv}, lines_final {f['lines_final']} and R's control net "
                  f"{net[0]}x{net[1]} (report: {f['control_points_after']}) disagree: skipped")
            continue
        knots = max(averaged_knots_error(rs["knots_u"], xi, rs["degree_u"]),
                    averaged_knots_error(rs["knots_v"], eta, rs["degree_v"]))
        q = o.collections.Array2_gp_Pnt(1, nu, 1, nv)
        dist = Distance(s, tol)
        pts = [[[scale * c for c in evaluate(rs, x, y)] for y in eta] for x in xi]
        size = max(abs(c) for rw in pts for p in rw for c in p)
        back = on_s = 0.0
        for i in range(nu):
            for j in range(nv):
                p = o.gp.gp_Pnt(*pts[i][j])
                q.SetValue(i + 1, j + 1, p)
                back = max(back, p.Distance(r.Value(xi[i], eta[j])))
                if (i * nv + j) % max(1, nu * nv // 400) == 0:
                    on_s = max(on_s, dist(p))
        row(k, "given", s, spacing(s), None)
        row(k, "vericad", r, (f["spacing_after"]["min"], f["spacing_after"]["max"]), deviation(r, s, dist, tol),
            f"E_max {f['deviation']['e_max']:.2e}, grid {nu}x{nv}, knots {knots:.0e}, R(grid)-Q {back:.1e} "
            f"({back / size:.0e} of the size), Q to S {on_s:.1e}; "
            f"run {1e3 * t_bound:.3g} ms, --no-bound {1e3 * t_fast:.3g} ms (in-process {1e3 * inproc:.3g} ms)")
        t_grid, og = occt_fit(q, tol)
        t_cubic, oc = occt_fit(q, tol, 3)
        t_unif, ou = occt_fit(uniform_points(s, nu, nv), tol)
        for who, surf, t in (("OCCT grid", og, t_grid), ("OCCT grid3", oc, t_cubic), ("OCCT unif", ou, t_unif)):
            if surf is None:
                row(k, who, None, None, None, "fit failed")
                continue
            row(k, who, surf, spacing(surf), deviation(surf, s, dist, tol),
                f"fit {1e3 * t:.3g} ms; vericad/OCCT {t_fast / t:.3g} (--no-bound run), "
                f"{inproc / t:.3g} (in-process), {t_bound / t:.3g} (run with the bound)")


if __name__ == "__main__":
    main(sys.argv[1], float(sys.argv[2]) if len(sys.argv) > 2 else 1e-4, {int(a) for a in sys.argv[3:]})
