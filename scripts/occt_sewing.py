#!/usr/bin/env python3
"""Patch connectivity: vericad `repair` beside Open CASCADE's BRepBuilderAPI_Sewing on the same
patch sets at the same tolerance: free edges and time. Needs `pip install cadquery-ocp-novtk`
and `cargo build --release`. Prints a table for BENCHMARKS.md.

Units: Open CASCADE converts lengths to millimetres on reading; vericad keeps the file's unit.
The tolerance is given in the file's unit and converted for Open CASCADE by the unit's factor
(fuselage: feet, 304.8 mm). Exits 1 when nothing was compared."""
import json, os, subprocess, sys, time
import OCP.OCP as o

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.environ.get("VERICAD", os.path.join(ROOT, "target", "release", "vericad"))
DATA = os.path.join(ROOT, "tests", "data", "public")
MM = {"mm": 1.0, "m": 1000.0, "cm": 10.0, "km": 1e6, "um": 1e-3, "inch": 25.4, "foot": 304.8,
      "mile": 1609344.0, "mil": 0.0254}


def unit_mm(path):
    out = subprocess.run([EXE, "info", path, "--json"], capture_output=True, text=True, check=True)
    unit = json.loads(out.stdout).get("unit") or "mm"
    if unit not in MM:
        raise SystemExit(f"{path}: unit {unit!r} has no millimetre factor here")
    return MM[unit]


def faces(path):
    r = o.STEPControl.STEPControl_Reader()
    r.ReadFile(path)
    r.TransferRoots()
    ex = o.TopExp.TopExp_Explorer(r.OneShape(), o.TopAbs.TopAbs_ShapeEnum.TopAbs_FACE)
    out = []
    while ex.More():
        f = o.TopoDS.TopoDS.Face(ex.Current())
        s = o.BRep.BRep_Tool.Surface_s(f)
        # Untrimmed patches, as vericad sees them: a face on the whole surface.
        out.append(o.BRepBuilderAPI.BRepBuilderAPI_MakeFace(s, 1e-7).Face())
        ex.Next()
    return out


def occt(fs, tol, repeat=5):
    best, free = float("inf"), None
    for _ in range(repeat):
        t = time.perf_counter()
        sw = o.BRepBuilderAPI.BRepBuilderAPI_Sewing(tol)
        for f in fs:
            sw.Add(f)
        sw.Perform()
        best = min(best, time.perf_counter() - t)
        free = sw.NbFreeEdges()
    return best, free


def vericad(path, tol, repeat=5):
    best, rep = float("inf"), None
    for _ in range(repeat):
        out = subprocess.run([EXE, "repair", path, "--patches", "--u1", str(tol), "--u2", str(tol), "--json"],
                             capture_output=True, text=True, check=True)
        rep = json.loads(out.stdout)
        best = min(best, rep["seconds"])
    return best, rep


def main():
    tol = 1e-3
    print("| patch set | patches | vericad free edges | vericad time | OCCT free edges | OCCT time | vericad / OCCT |")
    print("|---|---|---|---|---|---|---|")
    compared = 0
    for name in ["occt-bug28366_fuselage.stp", "gmsh-t20_data.step", "abc-0000.step"]:
        p = os.path.join(DATA, name)
        t_o, free_o = occt(faces(p), tol * unit_mm(p))
        t_v, rep = vericad(p, tol)
        print(f"| {name} | {rep['patches_in']} | {rep['free_edges']} | {t_v * 1e3:.1f} ms | {free_o} | {t_o * 1e3:.1f} ms | {t_v / t_o:.2f}× |")
        compared += 1
    if compared == 0:
        print("nothing compared", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
