#!/usr/bin/env python3
"""vericad coons beside Open CASCADE: the approximant vericad writes (IGES) is read by OCCT
and its error samples (17) re-measured there — BRepExtrema_DistShapeShape from each sample
point to the original faces (trimmed, as OCCT reads them) — and compared with the distances
vericad measured (its local projection). Both are measurements (evidence), not bounds.

Prints, per run: samples compared, the largest vericad and OCCT distances, the largest
difference, and how many samples OCCT finds closer than vericad by more than 1e-9 (a
closest point vericad's local search missed).
Usage: cargo build --release && python3 scripts/occt_coons.py MODEL.step BOUNDARY.json [TOL [MAX_RESOLUTION]]
"""
import json, os, subprocess, sys, tempfile, time

import OCP.OCP as o

from occt_io import read_iges_surface, read_step_faces

HERE = os.path.dirname(os.path.abspath(__file__))
VERICAD = os.environ.get("VERICAD", os.path.join(HERE, "..", "target", "release", "vericad"))


def main(model, boundary, tol, max_resolution):
    tmp = tempfile.mkdtemp()
    out, rep = os.path.join(tmp, "patch.igs"), os.path.join(tmp, "report.json")
    t0 = time.time()
    r = subprocess.run([VERICAD, "coons", model, "--boundary", boundary, "--tol", str(tol),
                        "--max-resolution", str(max_resolution), "--out", out, "--report", rep], capture_output=True, text=True)
    t_vericad = time.time() - t0
    print(r.stdout, end="")
    if not os.path.exists(rep):
        print(r.stderr)
        return
    report = json.load(open(rep))
    # OCCT converts lengths to millimetres on reading; distances go back to the model's unit.
    mm_per_unit = {"mm": 1.0, "m": 1000.0, "cm": 10.0, "inch": 25.4, "foot": 304.8, "um": 1e-3, "km": 1e6}
    scale = 1.0 / mm_per_unit.get(report.get("unit") or "mm", 1.0)
    s = read_iges_surface(out)
    shape = read_step_faces(model)
    u0, u1, v0, v1 = s.Bounds()
    n, worst_v, worst_o, diff, closer = 0, 0.0, 0.0, 0.0, 0
    t0 = time.time()
    for xi, eta, d in report["samples"]:
        if d is None:
            continue
        p = s.Value(u0 + (u1 - u0) * xi, v0 + (v1 - v0) * eta)
        dss = o.BRepExtrema.BRepExtrema_DistShapeShape(o.BRepBuilderAPI.BRepBuilderAPI_MakeVertex(p).Vertex(), shape)
        if not dss.IsDone():
            continue
        do = dss.Value() * scale
        n += 1
        worst_v, worst_o = max(worst_v, d), max(worst_o, do)
        diff = max(diff, abs(d - do))
        closer += do < d - 1e-9
    print(f"vericad {t_vericad:.2f} s; OCCT re-measured {n} samples in {time.time() - t0:.2f} s: "
          f"max vericad {worst_v:.3e}, max OCCT {worst_o:.3e}, largest difference {diff:.3e}, "
          f"{closer} samples closer in OCCT")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], float(sys.argv[3]) if len(sys.argv) > 3 else 1e-3,
         int(sys.argv[4]) if len(sys.argv) > 4 else 128)
