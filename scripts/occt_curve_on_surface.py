#!/usr/bin/env python3
"""Yang et al. Table 2 data through Open CASCADE's Approx_CurveOnSurface, beside vericad.

OCCT approximates S(D(t)) by a B-spline *near* the surface within a requested 3D tolerance;
vericad's segments lie *on* S exactly with a proven Hausdorff bound. Prints degree, segments,
control points, OCCT's reported MaxError3d, the distance of OCCT's curve to S measured at
samples (GeomAPI_ProjectPointOnSurf), and wall time.
Usage: cargo build --release && python3 scripts/occt_curve_on_surface.py
"""
import json, os, subprocess, time

import OCP.OCP as o

HERE = os.path.dirname(os.path.abspath(__file__))
VERICAD = os.environ.get("VERICAD") or os.path.join(HERE, "..", "target", "release", "vericad")
MODEL = os.path.join(HERE, "..", "src", "models", "yang-table2.json")

P = [[(0, 2, -1), (2.5, 1, 0), (1, 0, 1.5)],
     [(1, 1, -2), (1, 0, -0.5), (2.5, -1, 0)],
     [(1, 0, -3), (1, -1, -2), (-0.51, -2, -1)]]
D = [(0.1, 0.1), (0.5, 1.8), (0.8, 0.1)]


def arr1d(vals):
    a = o.collections.Array1_double(1, len(vals))
    for i, v in enumerate(vals, 1):
        a.SetValue(i, float(v))
    return a


def arr1i(vals):
    a = o.collections.Array1_int(1, len(vals))
    for i, v in enumerate(vals, 1):
        a.SetValue(i, int(v))
    return a


def surface():
    poles = o.collections.Array2_gp_Pnt(1, 3, 1, 3)
    for i in range(3):
        for j in range(3):
            poles.SetValue(i + 1, j + 1, o.gp.gp_Pnt(*P[i][j]))
    return o.Geom.Geom_BSplineSurface(poles, arr1d([0, 1]), arr1d([0, 1]), arr1i([3, 3]), arr1i([3, 3]), 2, 2)


def domain_curve():
    poles = o.collections.Array1_gp_Pnt2d(1, 3)
    for i, (u, v) in enumerate(D, 1):
        poles.SetValue(i, o.gp.gp_Pnt2d(u, v))
    return o.Geom2d.Geom2d_BSplineCurve(poles, arr1d([0, 1]), arr1i([3, 3]), 2)


def occt(tol):
    s, c = surface(), domain_curve()
    t0 = time.perf_counter()
    app = o.Approx.Approx_CurveOnSurface(o.Geom2dAdaptor.Geom2dAdaptor_Curve(c), o.GeomAdaptor.GeomAdaptor_Surface(s),
                                         0.0, 1.0, tol, o.GeomAbs.GeomAbs_Shape.GeomAbs_C1, 8, 100, True, False)
    ms = (time.perf_counter() - t0) * 1e3
    if not app.IsDone() or not app.HasResult():
        return None
    r = app.Curve3d()
    # Distance of OCCT's curve to S (evidence: projection at 200 samples).
    worst = 0.0
    for k in range(201):
        p = r.Value(r.FirstParameter() + (r.LastParameter() - r.FirstParameter()) * k / 200)
        proj = o.GeomAPI.GeomAPI_ProjectPointOnSurf(p, s)
        worst = max(worst, proj.LowerDistance())
    return dict(degree=r.Degree(), segments=r.NbKnots() - 1, control_points=r.NbPoles(),
                max_error_3d=app.MaxError3d(), distance_to_S=worst, ms=ms)


def vericad(tol):
    out = subprocess.run([VERICAD, "curve-on-surface", "--surface", MODEL, "--curve", MODEL, "--tol", str(tol), "--angle", "10", "--evidence", "--json"],
                         capture_output=True, text=True, check=True).stdout
    r = json.loads(out)
    return dict(degree=r["bspline"]["degree"], segments=r["num_segments"], control_points=r["num_control_points"],
                bound=r["certificate"]["hausdorff_bound"], measured=r["evidence"]["max_distance_sampled"], ms=r["elapsed_ms"])


if __name__ == "__main__":
    print(f"{'tol':>8} | {'OCCT deg':>8} {'segs':>5} {'poles':>6} {'MaxError3d':>11} {'dist to S':>10} {'ms':>7} | "
          f"{'vericad deg':>11} {'segs':>5} {'pts':>5} {'proven':>10} {'measured':>10} {'ms':>7}")
    for tol in (1e-2, 1e-3, 1e-4):
        a, b = occt(tol), vericad(tol)
        if a is None:
            print(f"{tol:>8} | OCCT did not converge")
            continue
        print(f"{tol:>8} | {a['degree']:>8} {a['segments']:>5} {a['control_points']:>6} {a['max_error_3d']:>11.3e} {a['distance_to_S']:>10.3e} {a['ms']:>7.2f} | "
              f"{b['degree']:>11} {b['segments']:>5} {b['control_points']:>5} {b['bound']:>10.3e} {b['measured']:>10.3e} {b['ms']:>7.1f}")
