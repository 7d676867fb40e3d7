#!/usr/bin/env python3
"""Surface–surface intersection: vericad beside Open CASCADE's GeomAPI_IntSS, same surfaces,
same tolerance, one run. Needs `pip install cadquery-ocp-novtk` and a release build
(`cargo build --release`; or set VERICAD=/path/to/vericad). Prints a table for BENCHMARKS.md.

Cases: two cylinders (radii 1 and 0.6, perpendicular axes) as rational B-splines, written by
OCCT to IGES and read by vericad from that file; the faces of tests/data/public/gmsh-t20_data.step,
every pair whose boxes overlap (OCCT) / all pairs with net-box culling (vericad), the
untrimmed surfaces on both sides (`--untrimmed`)."""
import json, os, subprocess, sys, tempfile, time
import OCP.OCP as o

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.environ.get("VERICAD") or os.path.join(ROOT, "target", "release", "vericad")
DATA = os.path.join(ROOT, "tests", "data", "public")
TOL = 1e-6


def bspline(surface, u0, u1, v0, v1):
    t = o.Geom.Geom_RectangularTrimmedSurface(surface, float(u0), float(u1), float(v0), float(v1), True, True)
    return o.GeomConvert.GeomConvert.SurfaceToBSplineSurface_s(t)


def cylinders():
    ax_z = o.gp.gp_Ax3(o.gp.gp_Pnt(0, 0, 0), o.gp.gp_Dir(0, 0, 1))
    ax_x = o.gp.gp_Ax3(o.gp.gp_Pnt(-3, 0, 0), o.gp.gp_Dir(1, 0, 0))
    a = bspline(o.Geom.Geom_CylindricalSurface(ax_z, 1.0), 0, 6.283185307179586, -3, 3)
    b = bspline(o.Geom.Geom_CylindricalSurface(ax_x, 0.6), 0, 6.283185307179586, 0, 6)
    return [a, b]


def write_iges(surfaces, path):
    o.IGESControl.IGESControl_Controller.Init_s()
    w = o.IGESControl.IGESControl_Writer("MM", 0)
    for s in surfaces:
        w.AddShape(o.BRepBuilderAPI.BRepBuilderAPI_MakeFace(s, 1e-7).Face())
    w.ComputeModel()
    w.Write(path)


def read_step_faces(path):
    r = o.STEPControl.STEPControl_Reader()
    r.ReadFile(path)
    r.TransferRoots()
    shape = r.OneShape()
    ex = o.TopExp.TopExp_Explorer(shape, o.TopAbs.TopAbs_ShapeEnum.TopAbs_FACE)
    faces = []
    while ex.More():
        faces.append(o.TopoDS.TopoDS.Face(ex.Current()))
        ex.Next()
    return faces


def occt_pairs(surfaces, pairs, repeat):
    best = float("inf")
    lines = 0
    for _ in range(repeat):
        t = time.perf_counter()
        lines = 0
        for i, j in pairs:
            x = o.GeomAPI.GeomAPI_IntSS(surfaces[i], surfaces[j], TOL)
            if x.IsDone():
                lines += x.NbLines()
        best = min(best, time.perf_counter() - t)
    return best, lines


def vericad(path, repeat, extra=()):
    """Best in-process time (`summary.seconds`) of `vericad ssi`; exit 0 (certified) and 3
    (ran, not certified) are results, anything else an error."""
    best = float("inf")
    summary = None
    for _ in range(repeat):
        out = subprocess.run([EXE, "ssi", path, "--tol", str(TOL), "--json", "--threads", "1", *extra],
                             capture_output=True, text=True)
        if out.returncode not in (0, 3):
            raise SystemExit(f"vericad ssi {path} exited {out.returncode}: {out.stderr.strip()}")
        r = json.loads(out.stdout)
        best = min(best, r["summary"]["seconds"])
        summary = r["summary"]
    return best, summary


def certify_occt_lines(surfs, tmp):
    """vericad as the oracle: OCCT's intersection lines of the two cylinders, written to IGES
    by OCCT, checked by `vericad certify-ssi` against the two faces."""
    x = o.GeomAPI.GeomAPI_IntSS(surfs[0], surfs[1], TOL)
    o.IGESControl.IGESControl_Controller.Init_s()
    w = o.IGESControl.IGESControl_Writer("MM", 0)
    for i in range(1, x.NbLines() + 1):
        c = x.Line(i)
        w.AddShape(o.BRepBuilderAPI.BRepBuilderAPI_MakeEdge(c, c.FirstParameter(), c.LastParameter()).Edge())
    w.ComputeModel()
    lines = os.path.join(tmp, "occt_lines.igs")
    w.Write(lines)
    faces = []
    for k, s in enumerate(surfs):
        p = os.path.join(tmp, f"face{k}.igs")
        write_iges([s], p)
        faces.append(p)
    out = subprocess.run([EXE, "certify-ssi", faces[0], faces[1], "--curves", lines, "--tol", str(TOL), "--json"],
                         capture_output=True, text=True)
    # Exit 0: every curve certified within tol and nothing missing; 3: a curve not within tol,
    # partial or missing (the report says which); anything else is an error.
    if out.returncode not in (0, 3):
        print(f"certify-ssi failed (exit {out.returncode}):", out.stderr.strip())
        return
    print(f"certify-ssi exit {out.returncode}")
    r = json.loads(out.stdout)
    print(f"OCCT lines certified by vericad (tol {TOL}): {len(r['curves'])} curves")
    for c in r["curves"]:
        print(f"  curve {c['index']}: proven max distance {c['dist_a_max']:.2e} to A, {c['dist_b_max']:.2e} to B at {c['points_checked']} samples")
    print(f"  vericad branches: {len(r['branches'])}, missing from OCCT: {r['missing_branches']}, partly covered: {r['partial_branches']}")


def main():
    rows = []
    tmp = tempfile.mkdtemp()
    cyl = os.path.join(tmp, "cylinders.igs")
    write_iges(cylinders(), cyl)
    # OCCT on what it reads back from the same IGES file vericad reads.
    r = o.IGESControl.IGESControl_Reader()
    r.ReadFile(cyl)
    r.TransferRoots()
    ex = o.TopExp.TopExp_Explorer(r.OneShape(), o.TopAbs.TopAbs_ShapeEnum.TopAbs_FACE)
    surfs = []
    while ex.More():
        surfs.append(o.BRep.BRep_Tool.Surface_s(o.TopoDS.TopoDS.Face(ex.Current())))
        ex.Next()
    t_o, n_o = occt_pairs(surfs, [(0, 1)], 20)
    t_v, s_v = vericad(cyl, 5)
    rows.append(("two cylinders (IGES)", t_v, s_v["branches"], t_o, n_o))
    certify_occt_lines(surfs, tmp)

    t20 = os.path.join(DATA, "gmsh-t20_data.step")
    faces = read_step_faces(t20)
    surfs = [o.BRep.BRep_Tool.Surface_s(f) for f in faces]
    boxes = []
    for f in faces:
        b = o.Bnd.Bnd_Box()
        o.BRepBndLib.BRepBndLib.Add_s(f, b)
        boxes.append(b)
    pairs = [(i, j) for i in range(len(faces)) for j in range(i + 1, len(faces)) if not boxes[i].IsOut(boxes[j])]
    t_o, n_o = occt_pairs(surfs, pairs, 3)
    # The untrimmed surfaces, as OCCT's GeomAPI_IntSS takes them (vericad's default on a
    # B-rep works on the faces, trims and shared edges, which OCCT's call does not).
    t_v, s_v = vericad(t20, 3, ("--untrimmed",))
    rows.append((f"t20 faces ({len(pairs)} OCCT pairs, {s_v['pairs_intersected']} vericad pairs)",
                 t_v, s_v["branches"], t_o, n_o))

    print("| case | vericad (1 thread) | branches | OCCT GeomAPI_IntSS | lines | vericad / OCCT |")
    print("|---|---|---|---|---|---|")
    for name, tv, bv, to, lo in rows:
        print(f"| {name} | {tv * 1e3:.1f} ms | {bv} | {to * 1e3:.1f} ms | {lo} | {tv / to:.2f}× |")


if __name__ == "__main__":
    sys.exit(main())
