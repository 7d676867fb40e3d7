#!/usr/bin/env python3
"""Triangle-mesh intersection: vericad's mesh mode beside CGAL's exact
`Polygon_mesh_processing::surface_intersection`, on the same two binary STL files.

    python3 scripts/cgal_mesh_ssi/run.py [--sizes 100k,1m] [--vericad PATH] [--cgal PATH]
                                         [--runs 3] [--same-grid] [--keep DIR]

Needs a release build of vericad (`cargo build --release`; default
target/release/vericad) and CGAL 5.x with a C++ compiler (Debian/Ubuntu:
`apt-get install -y libcgal-dev cmake g++`). The CGAL program (cgal_ssi.cpp beside this
file) is built by build.sh into --cgal (default /tmp/cgal_ssi) when that file is missing
or older than the source; nothing is built or written inside the repository.

The meshes: two height fields, each a regular n x n grid of cells, 2 triangles a cell,
written as binary STL (float32) into a temporary folder:
  A: z = 0.3 sin(2.1x) cos(1.7y)                     over [0,4]^2
  B: z = 0.1(x-2) + 0.25 sin(1.3x + 0.9y) - 0.05     over [-sqrt2/40, 4+pi/50] x
                                                        [-sqrt3/40, 4+e/100]
B's grid is deliberately not A's: on one shared lattice every grid line of B lies in the
same vertical plane as one of A, and every crossing of the curve with a grid line is an
edge-edge contact (a degenerate case for both programs). The irrational offsets keep B's
rows and columns off A's (decimal offsets do not: -0.053 + 96*4.082/224 = 380/224, a row
of A); the script checks the float32 coordinates and warns of any shared grid line.
--same-grid puts B on A's lattice ([0,4]^2) to measure the degenerate case (there vericad,
as of this writing, lists each edge-edge contact point twice in a row, CGAL once; the
distinct points agree). A size is triangles per mesh: 100k -> n = 224 (100,352 triangles),
1m -> n = 707 (999,698 triangles). The default run takes about a minute (plus a minute to
build cgal_ssi the first time).

For each size, one untimed warm-up run of each side (its results are the ones compared),
then --runs timed runs taken in turn (vericad, CGAL, vericad, CGAL, ...):
  vericad: VERICAD ssi A.stl B.stl --threads 1 --out r.json --json   (mesh mode: STL input)
  CGAL:    cgal_ssi A.stl B.stl      (Epick kernel; prints its own read and intersection ms)
Whole-command wall time (monotonic clock around the child, reading the files included) and
peak resident memory (the child's ru_maxrss from wait4, in MiB) are measured here; each
side's own figure is vericad's summary.seconds and CGAL's intersection_ms (reading
excluded). Medians are printed; the whole-command ratio vericad/CGAL is the median of the
pair-by-pair ratios, the own-figure ratio the ratio of the medians.

Checks: both sides must find at least one curve and every command must succeed (vericad
exit 0, or 3 = finished but not certified); otherwise the exit status is 1. Curve counts,
point counts and distinct points (matched within 1e-9 a coordinate) are compared and any
difference is printed as a warning (not a failure). Prints a markdown table.
"""
import argparse
import json
import math
import os
import shutil
import statistics
import struct
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
DEFAULT_VERICAD = os.path.join(ROOT, "target", "release", "vericad")
DEFAULT_CGAL = "/tmp/cgal_ssi"


def surface_a(x, y):
    return 0.3 * math.sin(2.1 * x) * math.cos(1.7 * y)


def surface_b(x, y):
    return 0.1 * (x - 2.0) + 0.25 * math.sin(1.3 * x + 0.9 * y) - 0.05


def write_height_field_stl(path, f, n, lo, hi):
    """n x n cells over [lo[0],hi[0]] x [lo[1],hi[1]], 2 triangles a cell (counter-clockwise
    seen from +z), binary STL with zero normals. Deterministic: the same bytes every time."""
    hx = (hi[0] - lo[0]) / n
    hy = (hi[1] - lo[1]) / n
    pack = struct.Struct("<3f").pack
    row = n + 1
    verts = []
    for j in range(row):
        y = lo[1] + j * hy
        for i in range(row):
            x = lo[0] + i * hx
            verts.append(pack(x, y, f(x, y)))
    normal, attr = b"\0" * 12, b"\0\0"
    out = [struct.pack("<80sI", b"vericad cgal_mesh_ssi height field", 2 * n * n)]
    for j in range(n):
        for i in range(n):
            v00 = verts[j * row + i]
            v10 = verts[j * row + i + 1]
            v01 = verts[(j + 1) * row + i]
            v11 = verts[(j + 1) * row + i + 1]
            out.append(normal + v00 + v10 + v11 + attr)
            out.append(normal + v00 + v11 + v01 + attr)
    with open(path, "wb") as fh:
        fh.write(b"".join(out))


B_LO = (-math.sqrt(2.0) / 40.0, -math.sqrt(3.0) / 40.0)
B_HI = (4.0 + math.pi / 50.0, 4.0 + math.e / 100.0)


def grid_lines(n, lo, hi):
    """The float32 x and y values of a grid's columns and rows, as written to the STL."""
    f32 = struct.Struct("<f")
    r = lambda v: f32.unpack(f32.pack(v))[0]
    hx = (hi[0] - lo[0]) / n
    hy = (hi[1] - lo[1]) / n
    return ({r(lo[0] + i * hx) for i in range(n + 1)}, {r(lo[1] + j * hy) for j in range(n + 1)})


def parse_size(s):
    s = s.strip().lower()
    mult = {"k": 1_000, "m": 1_000_000}.get(s[-1:], 1)
    num = float(s[:-1]) if s[-1:] in ("k", "m") else float(s)
    triangles = int(round(num * mult))
    n = max(1, int(round(math.sqrt(triangles / 2.0))))
    return s, n


def run_timed(cmd, want_stdout):
    """Run cmd; return (exit code, wall seconds, peak RSS in MiB of that child from wait4,
    stdout, stderr)."""
    t0 = time.monotonic()
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE if want_stdout else subprocess.DEVNULL,
                         stderr=subprocess.PIPE, stdin=subprocess.DEVNULL)
    # The outputs are small (one JSON line, or vericad's --json summary); read them before
    # reaping so a full pipe cannot block the child.
    stdout = p.stdout.read() if want_stdout else b""
    stderr = p.stderr.read()
    _, status, ru = os.wait4(p.pid, 0)
    wall = time.monotonic() - t0
    p.returncode = os.waitstatus_to_exitcode(status)
    return p.returncode, wall, ru.ru_maxrss / 1024.0, stdout.decode(errors="replace"), \
        stderr.decode(errors="replace")


def ensure_cgal(path):
    src = os.path.join(HERE, "cgal_ssi.cpp")
    if os.path.exists(path) and os.path.getmtime(path) >= os.path.getmtime(src):
        return path
    print(f"building {path} from cgal_ssi.cpp (about a minute) ...", file=sys.stderr)
    subprocess.run(["sh", os.path.join(HERE, "build.sh"), path], check=True,
                   stdout=subprocess.DEVNULL)
    return path


def cgal_version():
    for inc in ("/usr/include", "/usr/local/include"):
        p = os.path.join(inc, "CGAL", "version.h")
        if os.path.exists(p):
            for line in open(p):
                if line.startswith("#define CGAL_VERSION "):
                    return line.split()[2]
    return "?"


def key(p):
    """A point's coordinates in units of 1e-9."""
    return tuple(int(round(float(x) * 1e9)) for x in p)


def unmatched(these, those):
    """Keys of `these` with no key of `those` within one unit in every coordinate (so a
    rounding boundary between two nearly equal points does not count as a difference)."""
    near = [(i, j, k) for i in (-1, 0, 1) for j in (-1, 0, 1) for k in (-1, 0, 1)]
    return [p for p in these - those
            if not any((p[0] + i, p[1] + j, p[2] + k) in those for i, j, k in near)]


def fail(msg):
    print(f"FAIL: {msg}", file=sys.stderr)
    sys.exit(1)


def bench_size(label, n, args, tmp):
    a = os.path.join(tmp, f"A_{n}.stl")
    b = os.path.join(tmp, f"B_{n}.stl")
    t0 = time.monotonic()
    b_lo, b_hi = ((0.0, 0.0), (4.0, 4.0)) if args.same_grid else (B_LO, B_HI)
    # Written by a child process: a child's peak memory (ru_maxrss) starts at this
    # process's own high-water mark, which must stay small.
    subprocess.run([sys.executable, os.path.abspath(__file__), "--write-meshes", str(n), a, b,
                    "same" if args.same_grid else "offset"], check=True)
    (ax, ay), (bx, by) = grid_lines(n, (0.0, 0.0), (4.0, 4.0)), grid_lines(n, b_lo, b_hi)
    shared = len(ax & bx) + len(ay & by)
    if shared and not args.same_grid:
        print(f"WARNING [{label}]: {shared} grid line(s) of B in the vertical plane of one of A "
              f"(edge-edge contacts where the curve crosses them)", file=sys.stderr)
    print(f"[{label}] n={n}: 2 x {2 * n * n} triangles written in {time.monotonic() - t0:.1f} s",
          file=sys.stderr)

    rjson = os.path.join(tmp, f"r_{n}.json")
    dump = os.path.join(tmp, f"cgal_{n}.json")
    vcmd = [args.vericad, "ssi", a, b, "--threads", "1", "--out", rjson, "--json"]
    ccmd = [args.cgal, a, b]

    # Warm-up (untimed): the results compared below come from these runs.
    code, wall, _, _, err = run_timed(vcmd, False)
    if code not in (0, 3):
        fail(f"vericad exited {code} on size {label}: {err.strip()[-1000:]}")
    code, wall, _, out, err = run_timed(ccmd + ["--dump", dump], True)
    if code != 0:
        fail(f"cgal_ssi exited {code} on size {label}: {err.strip()[-1000:]}")
    with open(rjson) as fh:
        r = json.load(fh)
    s = r["summary"]
    branches = [br for pair in r.get("pairs", []) for br in pair.get("branches", [])]
    v_points = [key(p) for br in branches for p in br["points"]]
    with open(dump) as fh:
        polylines = json.load(fh)
    c_points = [key(p) for pl in polylines for p in pl]
    res = {
        "label": label, "n": n, "triangles": 2 * n * n,
        "v_branches": s["branches"], "v_points": s["points"], "v_distinct": len(set(v_points)),
        "v_exit": code,
        "c_polylines": len(polylines), "c_points": len(c_points), "c_distinct": len(set(c_points)),
    }
    if s["branches"] == 0 or not branches:
        fail(f"vericad found no intersection on size {label}")
    if not polylines:
        fail(f"CGAL found no intersection on size {label}")
    vs, cs = set(v_points), set(c_points)
    res["only_v"], res["only_c"] = len(unmatched(vs, cs)), len(unmatched(cs, vs))
    if s["branches"] != len(polylines):
        print(f"WARNING [{label}]: vericad {s['branches']} branches, CGAL {len(polylines)} "
              f"polylines", file=sys.stderr)
    if s["points"] != len(c_points) or res["only_v"] or res["only_c"]:
        print(f"WARNING [{label}]: points differ: vericad {s['points']} ({len(vs)} distinct), "
              f"CGAL {len(c_points)} ({len(cs)} distinct); {len(vs - cs)} distinct points only "
              f"in vericad, {len(cs - vs)} only in CGAL", file=sys.stderr)
    del r, branches, v_points, polylines, c_points, vs, cs
    if not args.keep:
        os.remove(dump)

    v_wall, v_own, v_peak, c_wall, c_own, c_read, c_peak, ratios = [], [], [], [], [], [], [], []
    for i in range(args.runs):
        code, wall, peak, _, err = run_timed(vcmd, False)
        if code not in (0, 3):
            fail(f"vericad exited {code} on size {label}: {err.strip()[-1000:]}")
        with open(rjson) as fh:
            sec = json.load(fh)["summary"].get("seconds")
        v_wall.append(wall)
        v_peak.append(peak)
        if sec is not None:
            v_own.append(sec)
        code, cwall, cpeak, out, err = run_timed(ccmd, True)
        if code != 0:
            fail(f"cgal_ssi exited {code} on size {label}: {err.strip()[-1000:]}")
        line = json.loads(out.strip().splitlines()[-1])
        c_wall.append(cwall)
        c_peak.append(cpeak)
        c_own.append(line["intersection_ms"] / 1000.0)
        c_read.append(line["read_ms"] / 1000.0)
        ratios.append(wall / cwall)
        print(f"[{label}] run {i + 1}/{args.runs}: vericad {wall:.2f} s (own {sec}), "
              f"CGAL {cwall:.2f} s (intersection {line['intersection_ms'] / 1000:.2f} s)",
              file=sys.stderr)
    med = statistics.median
    res.update({
        "v_wall": med(v_wall), "v_own": med(v_own) if v_own else None, "v_peak": max(v_peak),
        "c_wall": med(c_wall), "c_own": med(c_own), "c_read": med(c_read), "c_peak": max(c_peak),
        "ratio": med(ratios),
        "ratio_own": (med(v_own) / med(c_own)) if v_own and med(c_own) > 0 else None,
    })
    if not args.keep:
        for f in (a, b, rjson):
            os.remove(f)
    return res


def fmt_s(x):
    return "–" if x is None else f"{x:.2f} s" if x >= 0.1 else f"{x * 1000:.1f} ms"


def main():
    if len(sys.argv) == 6 and sys.argv[1] == "--write-meshes":  # internal: see bench_size
        n, a, b, grid = int(sys.argv[2]), sys.argv[3], sys.argv[4], sys.argv[5]
        write_height_field_stl(a, surface_a, n, (0.0, 0.0), (4.0, 4.0))
        b_lo, b_hi = ((0.0, 0.0), (4.0, 4.0)) if grid == "same" else (B_LO, B_HI)
        write_height_field_stl(b, surface_b, n, b_lo, b_hi)
        return 0
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", default="100k,1m",
                    help="triangles per mesh, comma separated (100k, 1m, 250000, ...)")
    ap.add_argument("--vericad", default=DEFAULT_VERICAD, help="vericad binary")
    ap.add_argument("--cgal", default=DEFAULT_CGAL,
                    help="cgal_ssi binary; built here by build.sh when missing or stale")
    ap.add_argument("--runs", type=int, default=3, help="timed runs of each side per size")
    ap.add_argument("--same-grid", action="store_true",
                    help="B on A's lattice: every curve/grid-line crossing is an edge-edge contact")
    ap.add_argument("--keep", metavar="DIR", help="write the meshes here and keep them")
    args = ap.parse_args()
    if not os.access(args.vericad, os.X_OK):
        fail(f"no vericad binary at {args.vericad} (cargo build --release, or --vericad PATH)")
    args.cgal = ensure_cgal(args.cgal)
    sizes = [parse_size(s) for s in args.sizes.split(",") if s.strip()]

    tmp = args.keep or tempfile.mkdtemp(prefix="cgal_mesh_ssi_")
    os.makedirs(tmp, exist_ok=True)
    rows = []
    try:
        for label, n in sizes:
            rows.append(bench_size(label, n, args, tmp))
    finally:
        if not args.keep:
            shutil.rmtree(tmp, ignore_errors=True)

    import resource
    floor = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print(f"\nvericad mesh mode (--threads 1) vs CGAL {cgal_version()} "
          f"Polygon_mesh_processing::surface_intersection (Epick), "
          f"{'same lattice (edge-edge contacts)' if args.same_grid else 'offset lattices'}; "
          f"medians of {args.runs} runs; peak = largest max RSS (cannot read below this "
          f"script's own {floor:.0f} MiB)\n")
    print("| triangles per mesh | vericad branches / points | CGAL polylines / points "
          "| vericad whole | vericad own | CGAL whole | CGAL intersection | "
          "vericad/CGAL whole | vericad/CGAL own | peak vericad | peak CGAL |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        own = "–" if r["ratio_own"] is None else f"{r['ratio_own']:.2f}"
        print(f"| {r['triangles']:,} (n={r['n']}) | {r['v_branches']} / {r['v_points']:,} "
              f"| {r['c_polylines']} / {r['c_points']:,} | {fmt_s(r['v_wall'])} "
              f"| {fmt_s(r['v_own'])} | {fmt_s(r['c_wall'])} | {fmt_s(r['c_own'])} "
              f"| {r['ratio']:.2f} | {own} | {r['v_peak']:.0f} MiB | {r['c_peak']:.0f} MiB |")
    print()
    for r in rows:
        same = (r["v_branches"] == r["c_polylines"] and r["only_v"] == 0 and r["only_c"] == 0)
        print(f"- {r['label']}: curves {'agree' if r['v_branches'] == r['c_polylines'] else 'DIFFER'}"
              f" ({r['v_branches']} vs {r['c_polylines']}); distinct points {r['v_distinct']:,} vs "
              f"{r['c_distinct']:,}, {r['only_v']} only in vericad, {r['only_c']} only in CGAL"
              f"{'' if same else ' (see warnings)'}; CGAL reading {fmt_s(r['c_read'])}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
