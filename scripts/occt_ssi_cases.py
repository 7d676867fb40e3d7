#!/usr/bin/env python3
"""Surface–surface intersection on constructed cases with known answers: vericad beside
Open CASCADE's `GeomAPI_IntSS`, the same NURBS surfaces in both systems.

What it does
  Builds each case's two surfaces once, as NURBS data (degrees, full knot vectors, control
  points, weights), and hands exactly that data to both systems: to vericad as a native JSON
  model (docs/model-format.md), to OCCT as `Geom_BSplineSurface` objects (distinct knots plus
  multiplicities). No file format with a length unit is involved, so both systems see the same
  numbers in the same unit and both run with tolerance 1e-7.
  Cases (true answer from the construction, in the local frame of the case):
    * exact rational sphere of radius 2 (revolved 5-point quadratic profile, weights √2/2, as
      `spline::construct::sphere`) in a rotated frame, cut by the plane z' = h,
      h = 0, 1.5, 1.9, 1.99, 1.999: one circle of radius √(4 − h²);
    * torus (major 3, minor 1) in a rotated frame, cut by z' = 0.5 (two circles), by x' = 3
      (one loop through the tube) and by x' = 2 (plane tangent to the inner equator: a
      figure-eight whose two lobes meet at the tangent point);
    * the dome z = c − ((x−½)² + (y−½)²) (biquadratic Bézier) over the unit square against the
      100 × 100 plane z = 0, c = r², r = 0.2, 1e-1, 1e-2, 1e-3, 1e-4: one circle of radius r;
    * two bilinear planes in a rotated frame crossing at 1e-1 … 1e-4 rad: one segment;
    * two equal cylinders (radius 1) with perpendicular axes, in a rotated frame: two ellipses
      (x' = ±z') crossing at two branch points, where the surfaces are tangent.
  For each case:
    vericad: `vericad ssi A.json B.json --tol 1e-7 --threads 1 --out r.json --json`; records
      branches (closed), summary.certified, summary.no_missed_branches, summary.dist_curve_max
      and the exit code (0 certified, 3 not certified).
    OCCT: `GeomAPI_IntSS(S1, S2, 1e-7)`; each line sampled at 2000 parameters, closed when
      its first and last points are within 1e-6.
  Both outputs are measured against the construction: the distance of every output point
  (vericad: every polyline vertex, with `--pieces cubic` 16 samples of every cubic piece,
  rebuilt here from the points and tangent jets by the rule of docs/ssi.md; OCCT: every
  sample) to the true curve — closed forms for
  circles and lines, a golden-section search on the curve's parametrization (torus sections,
  ellipses; parameter to 1e-12, float error far below the 1e-6 threshold) otherwise — and the
  fraction of each true component covered by output segments whose two ends are within 1e-6
  of it. A system "finds" a component when ≥ 99 % of it is covered.
  Times: best of 3 wall-clock runs. vericad is timed as a subprocess (process start, JSON
  reading and writing included) and, in brackets, by its own `summary.seconds` (the
  intersection in-process, best of the same runs); OCCT in-process (the `GeomAPI_IntSS` call
  only).

How to run
  pip install cadquery-ocp-novtk      # OCCT 8 Python bindings (module OCP)
  cargo build --release               # target/release/vericad, or set VERICAD=/path/to/vericad
  python3 scripts/occt_ssi_cases.py [--repeat 3] [--only SUBSTRING] [--pieces chords|cubic]
  Prints one markdown table (the one in docs/ssi.md, "Against Open CASCADE on constructed
  cases") and a detail line per case on stderr."""
import argparse, json, math, os, subprocess, sys, tempfile, time

import OCP.OCP as o

from occt_io import from_json

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.environ.get("VERICAD") or os.path.join(
    os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target")), "release", "vericad")
TOL = 1e-7
ON = 1e-6          # on-curve threshold (distance to the true curve)
FOUND = 0.99       # fraction of a true component covered to count as found
H = math.sqrt(0.5)
TAU = 2 * math.pi

# ---------------------------------------------------------------- geometry construction

UNIT_CIRCLE = [((1, 0), 1), ((1, 1), H), ((0, 1), 1), ((-1, 1), H), ((-1, 0), 1),
               ((-1, -1), H), ((0, -1), 1), ((1, -1), H), ((1, 0), 1)]
CIRCLE_KNOTS = [0, 0, 0, .25, .25, .5, .5, .75, .75, 1, 1, 1]


class Frame:
    def __init__(self, o_, x, y, z):
        self.o, self.x, self.y, self.z = o_, x, y, z

    def at(self, a, b, c):
        return [self.o[k] + a * self.x[k] + b * self.y[k] + c * self.z[k] for k in range(3)]

    def local(self, q):
        d = [q[k] - self.o[k] for k in range(3)]
        return tuple(sum(d[k] * u[k] for k in range(3)) for u in (self.x, self.y, self.z))


IDENTITY = Frame([0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1])


def rotated(seed):
    """The rotated frames of tests/ssi_coverage.rs (unit quaternion from a fixed sequence)."""
    s = float(seed)
    q = [0.3 + math.sin(s), 0.7 * math.cos(1.3 * s), 0.5 - math.sin(0.7 * s), 0.2 + math.cos(2.1 * s)]
    n = math.sqrt(sum(c * c for c in q))
    w, x, y, z = [c / n for c in q]
    return Frame([0.1 * math.cos(s), -0.2, 0.3],
                 [1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)],
                 [2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)],
                 [2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)])


def surface(du, dv, ku, kv, pts, ws=None):
    """pts[i][j] = P_ij, i along u; full knot vectors."""
    return dict(degree_u=du, degree_v=dv, knots_u=[float(k) for k in ku], knots_v=[float(k) for k in kv],
                control_points=pts, weights=ws or [[1.0] * len(r) for r in pts])


def revolve(f, profile, pknots, pdeg):
    pts = [[f.at(p[0] * c[0], p[0] * c[1], p[1]) for p, _ in profile] for c, _ in UNIT_CIRCLE]
    ws = [[wc * wp for _, wp in profile] for _, wc in UNIT_CIRCLE]
    return surface(2, pdeg, CIRCLE_KNOTS, pknots, pts, ws)


def sphere(f, r):
    prof = [((0, -r), 1), ((r, -r), H), ((r, 0), 1), ((r, r), H), ((0, r), 1)]
    return revolve(f, prof, [0, 0, 0, .5, .5, 1, 1, 1], 2)


def torus(f, major, minor):
    prof = [((major + minor * c[0], minor * c[1]), w) for c, w in UNIT_CIRCLE]
    return revolve(f, prof, CIRCLE_KNOTS, 2)


def cylinder(f, r, h0, h1):
    return revolve(f, [((r, h0), 1), ((r, h1), 1)], [0, 0, 1, 1], 1)


def bilinear(p00, p10, p01, p11):
    return surface(1, 1, [0, 0, 1, 1], [0, 0, 1, 1], [[p00, p01], [p10, p11]])


def dome(c):
    g, xs = [0.25, -0.25, 0.25], [0.0, 0.5, 1.0]
    pts = [[[xs[i], xs[j], c - (g[i] + g[j])] for j in range(3)] for i in range(3)]
    return surface(2, 2, [0, 0, 0, 1, 1, 1], [0, 0, 0, 1, 1, 1], pts)


# ---------------------------------------------------------------- true curves
# A truth maps a local point to (distance, component, parameter); components have a period
# (closed) or an interval (open) for the coverage measure.

def golden(fn, a, b, it=64):
    g = (math.sqrt(5) - 1) / 2
    c, d = b - g * (b - a), a + g * (b - a)
    fc, fd = fn(c), fn(d)
    for _ in range(it):
        if fc < fd:
            b, d, fd = d, c, fc
            c = b - g * (b - a)
            fc = fn(c)
        else:
            a, c, fc = c, d, fd
            d = a + g * (b - a)
            fd = fn(d)
    t = (a + b) / 2
    return fn(t), t


class Circles:
    """Circles of radii rhos[k] about the local z axis through (cx, cy), at local height h."""
    def __init__(self, rhos, h, cx=0.0, cy=0.0):
        self.rhos, self.h, self.cx, self.cy = rhos, h, cx, cy
        self.comps = [("closed", TAU)] * len(rhos)

    def project(self, q):
        x, y, z = q[0] - self.cx, q[1] - self.cy, q[2]
        rho = math.hypot(x, y)
        best = min((math.hypot(rho - r, z - self.h), k) for k, r in enumerate(self.rhos))
        return best[0], best[1], math.atan2(y, x) % TAU


class Segment:
    """The local x axis, x in [a, b]."""
    def __init__(self, a, b):
        self.a, self.b = a, b
        self.comps = [("open", (a, b))]

    def project(self, q):
        t = min(max(q[0], self.a), self.b)
        return math.sqrt((q[0] - t) ** 2 + q[1] ** 2 + q[2] ** 2), 0, t


class TorusVertical:
    """Torus (R, r) about local z cut by x = c, curve points (c, ±√((R + r cos φ)² − c²), r sin φ)."""
    def __init__(self, R, r, c):
        self.R, self.r, self.c = R, r, c
        self.lo = -math.acos(min(1.0, (c - R) / r)) if c > R - r else -math.pi
        self.hi = -self.lo
        self.figure8 = c <= R - r
        self.comps = [("closed", TAU)] * (2 if self.figure8 else 1)

    def point(self, phi, sign):
        rr = (self.R + self.r * math.cos(phi)) ** 2 - self.c ** 2
        return (self.c, sign * math.sqrt(max(rr, 0.0)), self.r * math.sin(phi))

    def project(self, q):
        phi0 = math.atan2(q[2], math.hypot(q[0], q[1]) - self.R)
        best = None
        for sign in (1.0, -1.0):
            if sign * q[1] < -0.5:
                continue
            def fn(phi):
                p = self.point(phi, sign)
                return math.dist(p, q)
            if self.figure8:
                a, b = phi0 - 0.3, phi0 + 0.3
            else:
                a, b = max(self.lo, phi0 - 0.3), min(self.hi, phi0 + 0.3)
                if a >= b:
                    a, b = self.lo, self.hi
            d, phi = golden(fn, a, b)
            for e in (a, b):
                if fn(e) < d:
                    d, phi = fn(e), e
            if best is None or d < best[0]:
                best = (d, sign, phi)
        d, sign, phi = best
        if self.figure8:
            return d, 0 if sign > 0 else 1, phi % TAU
        # one loop: up the y > 0 side (phi from lo to hi), back down the y < 0 side
        span = self.hi - self.lo
        s = (phi - self.lo) if sign > 0 else span + (self.hi - phi)
        return d, 0, s / (2 * span) * TAU


class CrossedCylinders:
    """Cylinders x² + y² = 1 and y² + z² = 1 (local): ellipses (cos t, sin t, ±cos t)."""
    comps = [("closed", TAU)] * 2

    def project(self, q):
        t0 = math.atan2(q[1], q[0])
        best = None
        for k, sg in enumerate((1.0, -1.0)):
            fn = lambda t: math.dist((math.cos(t), math.sin(t), sg * math.cos(t)), q)
            d, t = golden(fn, t0 - 0.4, t0 + 0.4)
            if best is None or d < best[0]:
                best = (d, k, t % TAU)
        return best


# ---------------------------------------------------------------- cases

def cases():
    out = []
    for seed, h in [(4, 0.0), (6, 1.5), (3, 1.9), (2, 1.99), (1, 1.999)]:
        f = rotated(seed)
        e = 3.0
        at = lambda a, b: f.at(a, b, h)
        out.append((f"sphere r=2 ∩ plane h={h}", "1 loop", sphere(f, 2.0),
                    bilinear(at(-e, -e), at(e, -e), at(-e, e), at(e, e)), f,
                    Circles([math.sqrt(4 - h * h)], h)))
    f = rotated(7)
    T = torus(f, 3.0, 1.0)
    out.append(("torus ∩ plane z=0.5", "2 loops", T,
                bilinear(f.at(-5, -5, .5), f.at(5, -5, .5), f.at(-5, 5, .5), f.at(5, 5, .5)), f,
                Circles([3 + math.sqrt(.75), 3 - math.sqrt(.75)], 0.5)))
    for c, truth in [(3.0, "1 loop"), (2.0, "figure-eight (2 lobes, tangent point)")]:
        out.append((f"torus ∩ plane x={c:g}", truth, T,
                    bilinear(f.at(c, -5, -2), f.at(c, 5, -2), f.at(c, -5, 2), f.at(c, 5, 2)), f,
                    TorusVertical(3.0, 1.0, c)))
    big = bilinear([-50, -50, 0], [50, -50, 0], [-50, 50, 0], [50, 50, 0])
    for r in [0.2, 1e-1, 1e-2, 1e-3, 1e-4]:
        out.append((f"dome ∩ plane, r={r:g}", "1 loop", dome(r * r), big, IDENTITY,
                    Circles([r], 0.0, 0.5, 0.5)))
    f = rotated(8)
    A = bilinear(f.at(-1, -1, 0), f.at(1, -1, 0), f.at(-1, 1, 0), f.at(1, 1, 0))
    for th in [1e-1, 1e-2, 1e-3, 1e-4]:
        b = lambda x, y: f.at(x, y * math.cos(th), y * math.sin(th))
        out.append((f"planes at {th:g} rad", "1 open segment", A,
                    bilinear(b(-1, -.7), b(1, -.7), b(-1, 1.3), b(1, 1.3)), f, Segment(-1, 1)))
    f = rotated(9)
    a = 0.3  # generic placement of the seams about each axis
    fa = Frame(f.o, [math.cos(a) * f.x[k] + math.sin(a) * f.y[k] for k in range(3)],
               [-math.sin(a) * f.x[k] + math.cos(a) * f.y[k] for k in range(3)], f.z)
    b_ = 0.7
    xb = [math.cos(b_) * f.y[k] + math.sin(b_) * f.z[k] for k in range(3)]
    yb = [-math.sin(b_) * f.y[k] + math.cos(b_) * f.z[k] for k in range(3)]
    fb = Frame(f.o, xb, yb, f.x)  # axis along the local x
    out.append(("two cylinders r=1, perpendicular", "2 ellipses crossing at 2 branch points",
                cylinder(fa, 1.0, -2.0, 2.0), cylinder(fb, 1.0, -2.0, 2.0), f, CrossedCylinders()))
    return out


# ---------------------------------------------------------------- measuring an output

PIECES = "chords"


def measure(polylines, truth, frame):
    """polylines: (points, closed). Returns (max distance to the truth, coverage per component)."""
    dmax = 0.0
    covered = [[] for _ in truth.comps]
    for pts, closed in polylines:
        pr = [truth.project(frame.local(p)) for p in pts]
        dmax = max([dmax] + [d for d, _, _ in pr])
        n = len(pr)
        for i in range(n if closed else n - 1):
            (d0, c0, s0), (d1, c1, s1) = pr[i], pr[(i + 1) % n]
            if d0 > ON or d1 > ON or c0 != c1:
                continue
            kind, dom = truth.comps[c0]
            if kind == "closed":
                a, b = min(s0, s1), max(s0, s1)
                if b - a > dom / 2:  # the short way round passes through 0
                    covered[c0] += [(b, dom), (0.0, a)]
                elif b - a < dom / 3:
                    covered[c0].append((a, b))
            else:
                covered[c0].append((min(s0, s1), max(s0, s1)))
    fr = []
    for (kind, dom), iv in zip(truth.comps, covered):
        total = dom if kind == "closed" else dom[1] - dom[0]
        iv.sort()
        length, end = 0.0, -math.inf
        for a, b in iv:
            if b > end:
                length += b - max(a, end)
                end = b
        fr.append(length / total)
    return dmax, fr


def hermite_samples(br, per_piece=16):
    """The branch's cubic pieces (docs/ssi.md, "Cubic pieces"), rebuilt from `points`, `uv_a`,
    `uv_b` and `tangents` by the documented rule, sampled at `per_piece` parameters each."""
    pts, ua, ub, tg = br["points"], br["uv_a"], br["uv_b"], br["tangents"]
    n = len(pts)
    pk = [list(pts[i]) + list(ua[i]) + list(ub[i]) for i in range(n)]
    jet = [None if j is None else list(j["t"]) + list(j["uv_a"]) + list(j["uv_b"]) for j in tg]
    out = []
    for i in range(n if br["closed"] else n - 1):
        k = (i + 1) % n
        p, q = pk[i], pk[k]
        c = [q[d] - p[d] for d in range(3)]
        length = math.sqrt(sum(x * x for x in c))
        dp = dq = [q[d] - p[d] for d in range(7)]
        if jet[i] is not None and jet[k] is not None:
            def orient(j):
                s = sum(j[d] * c[d] for d in range(3))
                return [x * math.copysign(1.0, s) for x in j] if abs(s) > 0.5 * length else None
            a, b = orient(jet[i]), orient(jet[k])
            if a is not None and b is not None and length > 0:
                cr = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
                phi = math.atan2(math.sqrt(sum(x * x for x in cr)), sum(a[d] * b[d] for d in range(3)))
                m = length / math.cos(phi / 4) ** 2
                dp, dq = [m * x for x in a], [m * x for x in b]
        for s in range(per_piece):
            t = s / per_piece
            h = (2 * t**3 - 3 * t**2 + 1, t**3 - 2 * t**2 + t, -2 * t**3 + 3 * t**2, t**3 - t**2)
            out.append(tuple(h[0] * p[d] + h[1] * dp[d] + h[2] * q[d] + h[3] * dq[d] for d in range(3)))
    if not br["closed"]:
        out.append(tuple(pts[-1]))
    return out


def run_vericad(a, b, tmp, repeat):
    pa, pb, out = (os.path.join(tmp, n) for n in ("a.json", "b.json", "r.json"))
    for p, s in ((pa, a), (pb, b)):
        with open(p, "w") as fh:
            json.dump({"format": "vericad-model", "version": 1, "surfaces": [s]}, fh)
    best, inproc, proc, r = math.inf, math.inf, None, None
    for _ in range(repeat):
        t = time.perf_counter()
        proc = subprocess.run([EXE, "ssi", pa, pb, "--tol", str(TOL), "--threads", "1", "--out", out, "--json",
                               "--pieces", PIECES], capture_output=True, text=True, timeout=900)
        best = min(best, time.perf_counter() - t)
        if proc.returncode not in (0, 3):
            raise RuntimeError(f"vericad exit {proc.returncode}: {proc.stderr.strip()}")
        with open(out) as fh:
            r = json.load(fh)
        # vericad's own figure: the intersection in-process (summary.seconds), without process
        # start and JSON reading and writing.
        inproc = min(inproc, r["summary"]["seconds"])
    # With cubic pieces the output curve is the pieces: measured at 16 samples per piece.
    branches = [(hermite_samples(br) if br.get("tangents") else br["points"], br["closed"])
                for pr in r["pairs"] for br in pr["branches"]]
    touch = sum(len(pr.get("touch_points", [])) for pr in r["pairs"])
    return (best, inproc), r["summary"], proc.returncode, branches, touch


def run_occt(a, b, repeat):
    sa, sb = from_json(a), from_json(b)
    best, x = math.inf, None
    for _ in range(repeat):
        t = time.perf_counter()
        x = o.GeomAPI.GeomAPI_IntSS(sa, sb, TOL)
        best = min(best, time.perf_counter() - t)
    lines = []
    if x.IsDone():
        for i in range(1, x.NbLines() + 1):
            c = x.Line(i)
            t0, t1 = c.FirstParameter(), c.LastParameter()
            t0, t1 = max(t0, -1e3), min(t1, 1e3)
            pts = []
            for k in range(2000):
                p = c.Value(t0 + (t1 - t0) * k / 1999)
                pts.append((p.X(), p.Y(), p.Z()))
            closed = math.dist(pts[0], pts[-1]) <= ON
            lines.append((pts[:-1] if closed else pts, closed))
    return best, x.IsDone(), lines


def found_text(n, closed, fr):
    cov = ", ".join(f"{100 * f:.4g} %" for f in fr)
    nf = sum(f >= FOUND for f in fr)
    return f"{n} ({closed} closed); found {nf}/{len(fr)} (covers {cov})"


def fmt_t(t):
    return f"{t * 1e3:.1f} ms" if t < 10 else f"{t:.1f} s"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--only", default="")
    ap.add_argument("--keep", default="", help="directory to keep each case's a.json, b.json, r.json in")
    ap.add_argument("--pieces", default="chords", choices=["chords", "cubic"],
                    help="vericad's output pieces (cubic: measured on the pieces, 16 samples each)")
    args = ap.parse_args()
    global PIECES
    PIECES = args.pieces
    tmp = tempfile.mkdtemp()
    rows = []
    for name, truth_text, a, b, frame, truth in cases():
        if args.only not in name:
            continue
        work = tmp
        if args.keep:
            work = os.path.join(args.keep, "".join(c if c.isalnum() or c in ".-" else "_" for c in name))
            os.makedirs(work, exist_ok=True)
        (tv, ti), summ, code, branches, touch = run_vericad(a, b, work, args.repeat)
        dv, fv = measure(branches, truth, frame)
        to, done, lines = run_occt(a, b, args.repeat)
        do, fo = measure(lines, truth, frame)
        ncl_v = sum(c for _, c in branches)
        ncl_o = sum(c for _, c in lines)
        dcm = summ.get("dist_curve_max")
        cert = (f"certified {'yes' if summ['certified'] else 'no'} (exit {code}; no missed branch "
                f"{'proven' if summ['no_missed_branches'] else 'not proven'}; dist_curve_max "
                f"{'—' if dcm is None else f'{dcm:.1e}'})")
        vtxt = found_text(len(branches), ncl_v, fv) + (f", {touch} touch pt" if touch else "") + "; " + cert
        otxt = found_text(len(lines), ncl_o, fo) if done else "IsDone() false"
        on_v = "—" if not branches else f"{'yes' if dv <= ON else 'no'} ({dv:.1e})"
        on_o = "—" if not lines else f"{'yes' if do <= ON else 'no'} ({do:.1e})"
        rows.append((name, truth_text, vtxt, otxt, on_v, on_o, f"{fmt_t(tv)} ({fmt_t(ti)})", fmt_t(to),
                     f"{tv / to:.3g}× ({ti / to:.3g}×)"))
        print(" | ".join(rows[-1]), file=sys.stderr, flush=True)
    print("| case | truth | vericad: branches, found / certified | OCCT: lines, found | on curve, vericad (max dist) "
          "| on curve, OCCT (max dist) | time vericad (in-process) | time OCCT | vericad / OCCT (in-process) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print("| " + " | ".join(r) + " |")


if __name__ == "__main__":
    sys.exit(main())
