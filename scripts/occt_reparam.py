#!/usr/bin/env python3
"""vericad reparam beside Open CASCADE's GeomAPI_PointsToBSplineSurface (chord-length
parameters, degree 3, C2) on the B-spline faces of a STEP file.

Both get as many points as vericad's final grid has lines: OCCT the points of S on a uniform
parameter grid of that size (what a user of GeomAPI_PointsToBSplineSurface would give it),
vericad its own grid. For each result: control points, the spacing ratio on a uniform 20 x 20
parameter grid (min..max, 1 = chord length), and the largest distance from 40 x 40 samples of
the result to S (GeomAPI_ProjectPointOnSurf: measured, evidence).
Usage: cargo build --release && python3 scripts/occt_reparam.py FILE.step [TOL]
"""
import json, math, os, subprocess, sys, tempfile

import OCP.OCP as o

HERE = os.path.dirname(os.path.abspath(__file__))
VERICAD = os.environ.get("VERICAD", os.path.join(HERE, "..", "target", "release", "vericad"))


def faces(path):
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


def deviation(r, s, n=40):
    u0, u1, v0, v1 = r.Bounds()
    worst = 0.0
    for i in range(n + 1):
        for j in range(n + 1):
            p = r.Value(u0 + (u1 - u0) * i / n, v0 + (v1 - v0) * j / n)
            pr = o.GeomAPI.GeomAPI_ProjectPointOnSurf(p, s)
            if pr.NbPoints() > 0:
                worst = max(worst, pr.LowerDistance())
    return worst


def occt_fit(s, nu, nv, tol):
    u0, u1, v0, v1 = s.Bounds()
    pts = o.collections.Array2_gp_Pnt(1, nu, 1, nv)
    for i in range(nu):
        for j in range(nv):
            pts.SetValue(i + 1, j + 1, s.Value(u0 + (u1 - u0) * i / (nu - 1), v0 + (v1 - v0) * j / (nv - 1)))
    api = o.GeomAPI.GeomAPI_PointsToBSplineSurface()
    api.Init(pts, o.Approx.Approx_ParametrizationType.Approx_ChordLength, 3, 8, o.GeomAbs.GeomAbs_Shape.GeomAbs_C2, tol)
    return api.Surface() if api.IsDone() else None


def main(path, tol):
    print(f"{path}, tol {tol}")
    print(f"{'face':>4}  {'who':<8} {'ctrl':>9} {'spacing':>17} {'max dist to S':>14}")
    tmp = tempfile.mkdtemp()
    for k, s in enumerate(faces(path)):
        if s.DynamicType().Name() != "Geom_BSplineSurface":
            continue
        rep = os.path.join(tmp, f"r{k}.json")
        subprocess.run([VERICAD, "reparam", f"{path}:{k}", "--tol", str(tol), "--report", rep],
                       capture_output=True, text=True)
        if not os.path.exists(rep):
            print(f"{k:>4}  vericad  not reparametrized")
            continue
        f = json.load(open(rep))["faces"][0]["result"]
        lo, hi = spacing(s)
        print(f"{k:>4}  {'given':<8} {s.NbUPoles():>4}x{s.NbVPoles():<4} {lo:>8.3f}..{hi:<7.3f}")
        sa = f["spacing_after"]
        print(f"{k:>4}  {'vericad':<8} {f['control_points_after'][0]:>4}x{f['control_points_after'][1]:<4} "
              f"{sa['min']:>8.3f}..{sa['max']:<7.3f} {f['deviation']['r_to_s']:>14.3e}")
        nu, nv = f["lines_final"]
        r = occt_fit(s, nu, nv, tol)
        if r is None:
            print(f"{k:>4}  {'OCCT':<8} failed")
            continue
        lo, hi = spacing(r)
        print(f"{k:>4}  {'OCCT':<8} {r.NbUPoles():>4}x{r.NbVPoles():<4} {lo:>8.3f}..{hi:<7.3f} {deviation(r, s):>14.3e}")


if __name__ == "__main__":
    main(sys.argv[1], float(sys.argv[2]) if len(sys.argv) > 2 else 1e-4)
