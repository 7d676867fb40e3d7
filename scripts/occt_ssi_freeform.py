#!/usr/bin/env python3
"""Surface–surface intersection on free-form (non-quadric) surfaces: vericad beside Open
CASCADE's `GeomAPI_IntSS`, a speed benchmark on the same NURBS data in both systems.

What it does
  Builds each case's surfaces once, as NURBS data (degrees, full knot vectors, control points,
  weights), and hands exactly that data to both systems: to vericad as native JSON models
  (docs/model-format.md, one file per side, several surfaces per file allowed), to OCCT as
  `Geom_BSplineSurface` objects through scripts/occt_io.py's `from_json`. No file format with
  a length unit is involved; both systems run with tolerance 1e-6. Every case is fixed by its
  construction (no random numbers), so runs are repeatable.
  Cases (scripts/occt_ssi_cases.py covers quadrics, planes and a dome):
    * bicubic n × n, n = 8, 16: two bicubic B-spline surfaces, clamped uniform knots on [0, 1],
      n × n control points at x_i = 4i/(n−1), y_j = 4j/(n−1) over [0, 4]²:
        A: z = 0.5 sin(1.3x) cos(1.1y);
        B: z = 0.3 cos(0.9x + 0.4) + 0.25 sin(1.7y) − 0.05, its net turned 0.25 rad about the
           vertical axis through (2, 2, 0) and tilted 0.06 rad about the turned x axis;
      transversal open curves (one for n = 8, two for n = 16: the nets only approximate the
      functions, more closely the finer they are);
    * rational bicubic n × n, n = 8, 16: the same nets, weights
      w = 1 + 0.3 sin(2.1 s + 0.7) cos(1.7 t + 0.2) (s, t = i/(n−1), j/(n−1); A and B with
      different phases), all in [0.7, 1.3];
    * sheets r × c (2 × 4, 5 × 10, 10 × 20: 8, 50, 200 faces on each side): side A tiles
      [0, 4] × [0, 8] with r × c bicubic Bézier patches whose 4 × 4 control points lie on
      z = 0.35 sin(1.1x + 0.3) cos(0.7y + 0.2) (neighbours share their border control points,
      so the sheet is C0); side B tiles the same rectangle, r × c patches on
      z = 0.15(x − 2) + 0.2 sin(0.6x + 0.9y + 0.1) − 0.03, turned 0.2 rad about the vertical
      axis through (2, 4, 0): a tilted wavy sheet crossing A along a few long curves that run
      across many patches. vericad gets A.json (r·c surfaces) and B.json (r·c surfaces) and
      intersects every face of A with every face of B itself (culling pairs by bounds); OCCT
      gets a loop over all r·c × r·c pairs: a `Bnd_Box` per face (`BndLib_AddSurface::Add`,
      enlarged by the tolerance), and `GeomAPI_IntSS` for every pair whose boxes meet.
  For each case:
    vericad: `vericad ssi A.json B.json --tol 1e-6 --threads 1 --out r.json --json`; records
      summary.branches, .points, .certified, .uncertified_box_pairs, .dist_curve_max,
      .pairs_intersected, .seconds (its own compute time) and the exit code (0 certified, 3 not
      certified; anything else is an error). Run once more with `--no-certify` (a single run,
      not best of; exit 3 expected: the run is reported as not certified), so the cost of the
      certificates is visible.
    OCCT: `GeomAPI_IntSS(S1, S2, 1e-6)` per pair; records the number of lines (and of pairs
      whose `IsDone()` is false).
    Agreement (not timed): every OCCT line is sampled (chords ≤ 1e-3 long), and each sample's
      distance to vericad's polylines is measured, and each vericad point's distance to the
      sampled OCCT lines; the fraction within 1e-5 (10 × tol, vericad's coverage match
      distance) is printed both ways — below 100 % means one side has curve the other lacks.
  Times: best of --repeat wall-clock runs (default 3). vericad is timed as a subprocess (process
  start, JSON reading and writing included; its own in-process `summary.seconds` is shown
  beside it); OCCT in-process: the `GeomAPI_IntSS` call only for single pairs; for sheets the
  whole loop, box computation and culling included. Building OCCT's `Geom_BSplineSurface`
  objects from the data is not timed; vericad's reading of its JSON files is.
  The script fails (exit 1) if a case has no intersection on either side, if an OCCT pair is
  not done, or if vericad exits with anything other than 0 or 3, so a comparison of nothing
  cannot pass.

How to run
  pip install cadquery-ocp-novtk      # OCCT 8 Python bindings (module OCP)
  cargo build --release               # target/release/vericad, or set VERICAD=/path/to/vericad
  python3 scripts/occt_ssi_freeform.py [--repeat 3] [--only SUBSTRING] [--keep DIR] [--pieces chords|cubic]
  (--pieces cubic: vericad outputs cubic pieces; its curves are compared through the pieces,
  rebuilt at 16 samples each by scripts/occt_ssi_cases.py's hermite_samples.)
  Prints one markdown table and a detail line per case on stderr; --keep DIR keeps each case's
  a.json, b.json, r.json (and r_nocert.json) in DIR/<case-name>/."""
import argparse, json, math, os, subprocess, sys, tempfile, time

from occt_ssi_cases import hermite_samples  # scripts/ is the script's own directory

PIECES = "chords"

import OCP.OCP as o

from occt_io import from_json

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.environ.get("VERICAD") or os.path.join(
    os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target")), "release", "vericad")
TOL = 1e-6
NEAR = 1e-5        # agreement threshold: a point of one side within this of the other's curves
CHORD = 1e-3       # OCCT lines sampled with chords at most this long

# ---------------------------------------------------------------- geometry construction


def surface(du, dv, ku, kv, pts, ws=None):
    """pts[i][j] = P_ij, i along u; full knot vectors."""
    return dict(degree_u=du, degree_v=dv, knots_u=[float(k) for k in ku], knots_v=[float(k) for k in kv],
                control_points=pts, weights=ws or [[1.0] * len(r) for r in pts])


def clamped(n, p=3):
    """Clamped uniform knot vector on [0, 1] for n control points of degree p."""
    m = n - p
    return [0.0] * (p + 1) + [i / m for i in range(1, m)] + [1.0] * (p + 1)


def placement(cx, cy, turn, tilt=0.0):
    """Map (x, y, z) → turned by `turn` about the vertical axis through (cx, cy, 0), then tilted
    by `tilt` about the turned x axis."""
    ct, st, ca, sa = math.cos(turn), math.sin(turn), math.cos(tilt), math.sin(tilt)
    ex = (ct, st, 0.0)
    ey = (-st * ca, ct * ca, sa)
    ez = (st * sa, -ct * sa, ca)

    def at(x, y, z):
        a, b = x - cx, y - cy
        return [c + a * ex[k] + b * ey[k] + z * ez[k] for k, c in enumerate((cx, cy, 0.0))]
    return at


def ident(x, y, z):
    return [x, y, z]


def fa(x, y):
    return 0.5 * math.sin(1.3 * x) * math.cos(1.1 * y)


def fb(x, y):
    return 0.3 * math.cos(0.9 * x + 0.4) + 0.25 * math.sin(1.7 * y) - 0.05


def bicubic_net(n, f, place, weight=None):
    """n × n clamped uniform bicubic B-spline, control points on z = f(x, y) over [0, 4]²."""
    pts = [[place(4 * i / (n - 1), 4 * j / (n - 1), f(4 * i / (n - 1), 4 * j / (n - 1))) for j in range(n)]
           for i in range(n)]
    ws = None
    if weight:
        ws = [[weight(i / (n - 1), j / (n - 1)) for j in range(n)] for i in range(n)]
    return surface(3, 3, clamped(n), clamped(n), pts, ws)


def wa(s, t):
    return 1 + 0.3 * math.sin(2.1 * s + 0.7) * math.cos(1.7 * t + 0.2)


def wb(s, t):
    return 1 + 0.3 * math.cos(1.9 * s + 0.3) * math.sin(2.3 * t + 1.1)


def sheet_a(x, y):
    return 0.35 * math.sin(1.1 * x + 0.3) * math.cos(0.7 * y + 0.2)


def sheet_b(x, y):
    return 0.15 * (x - 2) + 0.2 * math.sin(0.6 * x + 0.9 * y + 0.1) - 0.03


def sheet(rows, cols, f, place, w=4.0, h=8.0):
    """rows × cols bicubic Bézier patches tiling [0, w] × [0, h], control points on z = f."""
    out = []
    bez = [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]
    for r in range(rows):
        for c in range(cols):
            x0, x1 = w * r / rows, w * (r + 1) / rows
            y0, y1 = h * c / cols, h * (c + 1) / cols
            pts = []
            for i in range(4):
                x = x0 + (x1 - x0) * i / 3 if i < 3 else x1
                row = []
                for j in range(4):
                    y = y0 + (y1 - y0) * j / 3 if j < 3 else y1
                    row.append(place(x, y, f(x, y)))
                pts.append(row)
            s = surface(3, 3, bez, bez, pts)
            s["name"] = f"patch {r},{c}"
            out.append(s)
    return out


def cases():
    """(name, surfaces of A, surfaces of B)."""
    out = []
    pb = placement(2.0, 2.0, 0.25, 0.06)
    for n in (8, 16):
        out.append((f"bicubic {n}x{n}", [bicubic_net(n, fa, ident)], [bicubic_net(n, fb, pb)]))
    for n in (8, 16):
        out.append((f"rational bicubic {n}x{n}", [bicubic_net(n, fa, ident, wa)], [bicubic_net(n, fb, pb, wb)]))
    ps = placement(2.0, 4.0, 0.2)
    for r, c in ((2, 4), (5, 10), (10, 20)):
        out.append((f"sheets {r}x{c} ({r * c} faces each)", sheet(r, c, sheet_a, ident), sheet(r, c, sheet_b, ps)))
    return out


# ---------------------------------------------------------------- agreement (not timed)

class SegmentGrid:
    """Polylines' segments hashed into cubes of side `h`, for distance queries up to NEAR."""

    def __init__(self, polylines, h=0.02):
        self.h, self.cells, self.segs = h, {}, []
        for pts, closed in polylines:
            n = len(pts)
            if n == 1:
                self.add(pts[0], pts[0])
            for i in range(n if closed else n - 1):
                self.add(pts[i], pts[(i + 1) % n])

    def add(self, p, q):
        k = len(self.segs)
        self.segs.append((p, q))
        lo = [int(math.floor((min(p[a], q[a]) - NEAR) / self.h)) for a in range(3)]
        hi = [int(math.floor((max(p[a], q[a]) + NEAR) / self.h)) for a in range(3)]
        for i in range(lo[0], hi[0] + 1):
            for j in range(lo[1], hi[1] + 1):
                for l in range(lo[2], hi[2] + 1):
                    self.cells.setdefault((i, j, l), []).append(k)

    def near(self, x):
        key = tuple(int(math.floor(x[a] / self.h)) for a in range(3))
        for k in self.cells.get(key, ()):
            p, q = self.segs[k]
            d = [q[a] - p[a] for a in range(3)]
            dd = sum(c * c for c in d)
            t = 0.0 if dd == 0 else max(0.0, min(1.0, sum((x[a] - p[a]) * d[a] for a in range(3)) / dd))
            if math.dist(x, [p[a] + t * d[a] for a in range(3)]) <= NEAR:
                return True
        return False


def fraction_near(points, grid):
    if not points:
        return None
    return sum(grid.near(p) for p in points) / len(points)


def sample_line(c):
    """An OCCT line as points with chords ≤ CHORD (length estimated from 200 samples)."""
    t0, t1 = max(c.FirstParameter(), -1e3), min(c.LastParameter(), 1e3)
    val = lambda t: (lambda p: (p.X(), p.Y(), p.Z()))(c.Value(t))
    coarse = [val(t0 + (t1 - t0) * k / 200) for k in range(201)]
    length = sum(math.dist(coarse[k], coarse[k + 1]) for k in range(200))
    n = max(200, int(math.ceil(length / CHORD)))
    pts = [val(t0 + (t1 - t0) * k / n) for k in range(n + 1)]
    return pts, length


# ---------------------------------------------------------------- running both systems

def write_model(path, surfaces):
    with open(path, "w") as fh:
        json.dump({"format": "vericad-model", "version": 1, "surfaces": surfaces}, fh)


def run_vericad(a, b, work, repeat):
    pa, pb, out, out_nc = (os.path.join(work, n) for n in ("a.json", "b.json", "r.json", "r_nocert.json"))
    write_model(pa, a)
    write_model(pb, b)
    cmd = [EXE, "ssi", pa, pb, "--tol", str(TOL), "--threads", "1", "--json", "--pieces", PIECES]
    best, own, proc = math.inf, math.inf, None
    for _ in range(repeat):
        t = time.perf_counter()
        proc = subprocess.run(cmd + ["--out", out], capture_output=True, text=True, timeout=1800)
        best = min(best, time.perf_counter() - t)
        if proc.returncode not in (0, 3):
            raise RuntimeError(f"vericad exit {proc.returncode}: {proc.stderr.strip()[-2000:]}")
        with open(out) as fh:
            r = json.load(fh)
        if r["summary"].get("seconds") is not None:
            own = min(own, r["summary"]["seconds"])
    t = time.perf_counter()
    pnc = subprocess.run(cmd + ["--out", out_nc, "--no-certify"], capture_output=True, text=True, timeout=1800)
    t_nc = time.perf_counter() - t
    if pnc.returncode not in (0, 3):
        raise RuntimeError(f"vericad --no-certify exit {pnc.returncode}: {pnc.stderr.strip()[-2000:]}")
    with open(out_nc) as fh:
        r_nc = json.load(fh)
    # With cubic pieces the output curve is the pieces (16 samples each, rebuilt by the rule
    # of docs/ssi.md in scripts/occt_ssi_cases.py).
    branches = [(hermite_samples(br) if br.get("tangents") else br["points"], br["closed"])
                for pr in r["pairs"] for br in pr["branches"]]
    reasons = {}
    for pr in r["pairs"]:
        for reg in ((pr.get("coverage") or {}).get("uncertified_regions") or []):
            reasons[reg.get("reason")] = reasons.get(reg.get("reason"), 0) + 1
    empty = [pr for pr in r["pairs"] if not pr["branches"]]
    split = dict(empty_pairs=len(empty), empty_seconds=sum((pr.get("stats") or {}).get("seconds") or 0 for pr in empty),
                 coverage_seconds=sum((pr.get("coverage") or {}).get("seconds") or 0 for pr in r["pairs"]))
    return dict(time=best, own=None if own == math.inf else own, summary=r["summary"], code=proc.returncode, split=split,
                branches=branches, reasons=reasons, time_nc=t_nc, code_nc=pnc.returncode,
                branches_nc=r_nc["summary"].get("branches"))


def run_occt(a, b, repeat):
    sa = [from_json(s) for s in a]
    sb = [from_json(s) for s in b]
    single = len(sa) == 1 and len(sb) == 1
    best, res, npairs = math.inf, None, 0
    for _ in range(repeat):
        if single:
            t = time.perf_counter()
            x = o.GeomAPI.GeomAPI_IntSS(sa[0], sb[0], TOL)
            dt = time.perf_counter() - t
            res, npairs = [x], 1
        else:
            t = time.perf_counter()
            boxes = []
            for ss in (sa, sb):
                bx = []
                for s in ss:
                    box = o.Bnd.Bnd_Box()
                    o.BndLib.BndLib_AddSurface.Add_s(o.GeomAdaptor.GeomAdaptor_Surface(s), TOL, box)
                    bx.append(box)
                boxes.append(bx)
            res = []
            for i, s1 in enumerate(sa):
                b1 = boxes[0][i]
                for j, s2 in enumerate(sb):
                    if not b1.IsOut(boxes[1][j]):
                        res.append(o.GeomAPI.GeomAPI_IntSS(s1, s2, TOL))
            dt = time.perf_counter() - t
            npairs = len(res)
        best = min(best, dt)
    not_done = sum(not x.IsDone() for x in res)
    lines = [x.Line(i) for x in res if x.IsDone() for i in range(1, x.NbLines() + 1)]
    return dict(time=best, pairs=npairs, not_done=not_done, lines=lines)


def fmt_t(t):
    if t is None:
        return "—"
    return f"{t * 1e3:.1f} ms" if t < 10 else f"{t:.1f} s"


def fmt_frac(f):
    return "—" if f is None else f"{100 * f:.4g} %"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--only", default="")
    ap.add_argument("--keep", default="", help="directory to keep each case's a.json, b.json, r.json in")
    ap.add_argument("--pieces", default="chords", choices=["chords", "cubic"],
                    help="vericad's output pieces (cubic: compared on the pieces, 16 samples each)")
    args = ap.parse_args()
    global PIECES
    PIECES = args.pieces
    if not os.path.exists(EXE):
        sys.exit(f"no vericad binary at {EXE} (build it or set VERICAD)")
    tmp = tempfile.mkdtemp()
    rows, failures = [], []
    t_all = time.perf_counter()
    for name, a, b in cases():
        if args.only not in name:
            continue
        work = tmp
        if args.keep:
            work = os.path.join(args.keep, "".join(c if c.isalnum() or c in ".-" else "_" for c in name))
            os.makedirs(work, exist_ok=True)
        v = run_vericad(a, b, work, args.repeat)
        oc = run_occt(a, b, args.repeat)
        s = v["summary"]
        # agreement, both ways
        samples, olen = [], 0.0
        for c in oc["lines"]:
            pts, length = sample_line(c)
            samples += pts
            olen += length
        vpts = [p for pts, _ in v["branches"] for p in pts]
        vlen = sum(math.dist(pts[k], pts[(k + 1) % len(pts)])
                   for pts, cl in v["branches"] for k in range(len(pts) if cl else len(pts) - 1))
        o_near_v = fraction_near(samples, SegmentGrid(v["branches"]))
        v_near_o = fraction_near(vpts, SegmentGrid([(pts, False) for pts in
                                                    [sample_line(c)[0] for c in oc["lines"]]]))
        if not s.get("branches"):
            failures.append(f"{name}: vericad found no intersection")
        if not oc["lines"]:
            failures.append(f"{name}: OCCT found no intersection")
        if oc["not_done"]:
            failures.append(f"{name}: OCCT IsDone() false on {oc['not_done']} of {oc['pairs']} pairs")
        dcm = s.get("dist_curve_max")
        cert = (f"{'yes' if s.get('certified') else 'no'} (exit {v['code']}; uncertified box pairs "
                f"{s.get('uncertified_box_pairs')}; dist_curve_max {'—' if dcm is None else f'{dcm:.1e}'})")
        ratio = v["time"] / oc["time"]
        rows.append((name, f"{len(a)} × {len(b)}", f"{s.get('branches')} / {s.get('points')}", cert,
                     f"{len(oc['lines'])}", f"{fmt_frac(o_near_v)} / {fmt_frac(v_near_o)}",
                     f"{fmt_t(v['time'])} ({fmt_t(v['own'])})", f"{fmt_t(v['time_nc'])}",
                     fmt_t(oc["time"]), f"{ratio:.3g}×"))
        print(f"{name}: vericad {fmt_t(v['time'])} (own {fmt_t(v['own'])}), exit {v['code']}, "
              f"certified {s.get('certified')}, no_missed_branches {s.get('no_missed_branches')}, "
              f"pairs intersected {s.get('pairs_intersected')} of {s.get('pairs_considered')}, "
              f"branches {s.get('branches')} ({s.get('closed_branches')} closed), points {s.get('points')}, "
              f"curve length {vlen:.6g}, dist_max {s.get('dist_max')}, dist_curve_max {dcm}, "
              f"uncertified box pairs {s.get('uncertified_box_pairs')}"
              f"{', reasons ' + json.dumps(v['reasons']) if v['reasons'] else ''}; "
              f"of its pairs {v['split']['empty_pairs']} without branches took {v['split']['empty_seconds']:.3f} s, "
              f"coverage {v['split']['coverage_seconds']:.3f} s (last run's r.json); "
              f"--no-certify {fmt_t(v['time_nc'])} exit {v['code_nc']} branches {v['branches_nc']} | "
              f"OCCT {fmt_t(oc['time'])}, pairs {oc['pairs']} (not done {oc['not_done']}), lines {len(oc['lines'])}, "
              f"curve length {olen:.6g} | OCCT samples near vericad {fmt_frac(o_near_v)}, vericad points near "
              f"OCCT {fmt_frac(v_near_o)} | vericad/OCCT {ratio:.3g}×", file=sys.stderr, flush=True)
    print("| case | faces A × B | vericad branches / points | vericad certified | OCCT lines "
          "| agree: OCCT near vericad / vericad near OCCT | time vericad (own) | vericad --no-certify "
          "| time OCCT | vericad / OCCT |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print("| " + " | ".join(r) + " |")
    print(f"total run time {time.perf_counter() - t_all:.1f} s", file=sys.stderr)
    if not rows:
        failures.append(f"no case matches --only {args.only!r}")
    for f in failures:
        print("FAIL: " + f, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
