#!/usr/bin/env python3
"""The faces repair (trims kept) beside Open CASCADE, which also serves as an independent
oracle. Needs `pip install cadquery-ocp-novtk` and `cargo build --release`.

1. **A faulty part written by Open CASCADE.** The unit cube (in mm) is built as six separate
   faces, each with its own edges and vertices. The top is lifted by DELTA = 1e-4 and written
   to STEP. On that file:
   - Open CASCADE's `BRepBuilderAPI_Sewing` runs at each tolerance u1;
   - `vericad repair --faces` runs at the same u1.
   Free edges are counted on both sides. vericad's repaired STEP is read back by Open CASCADE,
   which counts the edges used by one face (`TopExp::MapShapesAndAncestors`) and checks the
   shell with `BRepCheck_Analyzer`.
2. **The public files** that `vericad repair` gives the faces repair. For each, the repaired
   STEP is read back by Open CASCADE and its free edges are counted, beside the input's.

Prints a table for docs/repair.md. Exits 1 when nothing was compared, and when a check fails.
`--write-cube PATH` also writes the lifted cube there (the tests' copy is
tests/data/public/occt-written/occt-lifted-cube.step)."""
import json, os, subprocess, sys, tempfile, time
import OCP.OCP as o

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.environ.get("VERICAD", os.path.join(ROOT, "target", "release", "vericad"))
DATA = os.path.join(ROOT, "tests", "data", "public")
DELTA = 1e-4


def face(corners):
    poly = o.BRepBuilderAPI.BRepBuilderAPI_MakePolygon()
    for c in corners:
        poly.Add(o.gp.gp_Pnt(*c))
    poly.Close()
    return o.BRepBuilderAPI.BRepBuilderAPI_MakeFace(poly.Wire(), True).Face()


def lifted_cube(path):
    z = 1.0 + DELTA
    quads = [
        [(0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 0, 0)],
        [(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)],
        [(1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1)],
        [(1, 1, 0), (0, 1, 0), (0, 1, 1), (1, 1, 1)],
        [(0, 1, 0), (0, 0, 0), (0, 0, 1), (0, 1, 1)],
        [(0, 0, z), (1, 0, z), (1, 1, z), (0, 1, z)],
    ]
    builder = o.BRep.BRep_Builder()
    comp = o.TopoDS.TopoDS_Compound()
    builder.MakeCompound(comp)
    for q in quads:
        builder.Add(comp, face(q))
    w = o.STEPControl.STEPControl_Writer()
    w.Transfer(comp, o.STEPControl.STEPControl_StepModelType.STEPControl_AsIs)
    if w.Write(path) != o.IFSelect.IFSelect_ReturnStatus.IFSelect_RetDone:
        raise SystemExit(f"cannot write {path}")


def read(path):
    """The file's shape: IGES by its extension, STEP otherwise."""
    iges = path.lower().endswith((".igs", ".iges"))
    r = o.IGESControl.IGESControl_Reader() if iges else o.STEPControl.STEPControl_Reader()
    if r.ReadFile(path) != o.IFSelect.IFSelect_ReturnStatus.IFSelect_RetDone:
        raise SystemExit(f"Open CASCADE cannot read {path}")
    r.TransferRoots()
    return r.OneShape()


def faces_of(shape):
    ex = o.TopExp.TopExp_Explorer(shape, o.TopAbs.TopAbs_ShapeEnum.TopAbs_FACE)
    out = []
    while ex.More():
        out.append(ex.Current())
        ex.Next()
    return out


def free_edges(shape):
    """Edges of `shape` used once in all the faces' wires (a seam is used twice by its face).
    Edges are told apart by `IsSame` (quadratic; the files are small)."""
    edges, users = [], []
    for f in faces_of(shape):
        ex = o.TopExp.TopExp_Explorer(f, o.TopAbs.TopAbs_ShapeEnum.TopAbs_EDGE)
        while ex.More():
            e = o.TopoDS.TopoDS.Edge(ex.Current())
            ex.Next()
            if o.BRep.BRep_Tool.Degenerated_s(e):
                continue
            k = next((i for i, x in enumerate(edges) if x.IsSame(e)), None)
            if k is None:
                edges.append(e)
                users.append(0)
                k = len(edges) - 1
            users[k] += 1
    return sum(1 for n in users if n == 1)


def occt_sewing(shape, tol):
    sw = o.BRepBuilderAPI.BRepBuilderAPI_Sewing(tol)
    for f in faces_of(shape):
        sw.Add(f)
    t = time.perf_counter()
    sw.Perform()
    return sw.NbFreeEdges(), time.perf_counter() - t


MM = {"mm": 1.0, "m": 1000.0, "cm": 10.0, "km": 1e6, "um": 1e-3, "inch": 25.4, "foot": 304.8,
      "mile": 1609344.0, "mil": 0.0254}


def unit_mm(path):
    """The file's length unit in millimetres (vericad keeps the file's unit; Open CASCADE reads
    every file in millimetres, so a tolerance in the file's unit is scaled by this for it)."""
    out = subprocess.run([EXE, "info", path, "--json"], capture_output=True, text=True, check=True)
    unit = json.loads(out.stdout).get("unit") or "mm"
    if unit not in MM:
        raise SystemExit(f"{path}: unit {unit!r} has no millimetre factor here")
    return MM[unit]


def best(f, n=5):
    """The best of `n` runs of `f` (each returns (value, seconds)): the value and the time."""
    runs = [f() for _ in range(n)]
    return runs[0][0], min(t for _, t in runs)


def vericad(path, u1, out, *extra):
    r = subprocess.run([EXE, "repair", path, *extra, "--u1", str(u1), "--u2", "1e-3", "--out", out,
                        "--json"], capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f"vericad repair {path}: exit {r.returncode}: {r.stderr}")
    return json.loads(r.stdout)


def main():
    failed, compared = [], 0
    tmp = os.environ.get("KEEP") or tempfile.mkdtemp(prefix="occt-repair-faces-")
    cube = os.path.join(tmp, "lifted-cube.step")
    lifted_cube(cube)
    if "--write-cube" in sys.argv:
        # The copy the tests read (tests/data/public/occt-written/occt-lifted-cube.step).
        dest = sys.argv[sys.argv.index("--write-cube") + 1]
        with open(cube, "rb") as a, open(dest, "wb") as b:
            b.write(a.read())
    print(f"Lifted cube (written by Open CASCADE, top lifted {DELTA:g} mm), u2 = 1e-3:\n")
    print("| u1 | OCCT sewing: free edges | vericad: free edges before → after | vericad sewn pairs | "
          "vericad's repaired STEP read by OCCT: free edges, valid | vericad / OCCT time |")
    print("|---|---|---|---|---|---|")
    for u1 in [1e-3, 5e-5]:
        shape = read(cube)
        free_o, t_o = occt_sewing(shape, u1)
        out = os.path.join(tmp, f"repaired-{u1:g}.step")
        rep = vericad(cube, u1, out, "--faces")
        back = read(out)
        free_back = free_edges(back)
        valid = o.BRepCheck.BRepCheck_Analyzer(back).IsValid()
        print(f"| {u1:g} | {free_o} | {rep['free_edges_before']} → {rep['free_edges_after']} | "
              f"{len(rep['sewing']['edges_sewn'])} | {free_back}, {'valid' if valid else 'NOT valid'} | "
              f"{rep['seconds'] / t_o:.2f}× |")
        compared += 1
        if free_o != rep["free_edges_after"]:
            failed.append(f"cube u1={u1}: OCCT {free_o} free edges, vericad {rep['free_edges_after']}")
        if free_back != rep["free_edges_after"]:
            failed.append(f"cube u1={u1}: OCCT reads {free_back} free edges back, vericad says "
                          f"{rep['free_edges_after']}")
    print("\nPublic files (`vericad repair FILE`, u1 = u2 = 1e-3 in the file's unit), the repaired "
          "STEP read back by Open CASCADE; beside it Open CASCADE's `BRepBuilderAPI_Sewing` on the "
          "file's faces at the same tolerance in millimetres (best of 5; vericad's `seconds`, the "
          "repair with its proven gaps, best of 5):\n")
    print("| file | faces (trimmed) | OCCT free edges: input / vericad's output | vericad free edges after "
          "| OCCT sewing: free edges | vericad | OCCT sewing | vericad / OCCT |")
    print("|---|---|---|---|---|---|---|---|")
    for name in ["abc-0000.step", "gmsh-t20_data.step", "gmsh-periodic_u_cst.step",
                 "gmsh-cube1000.igs"]:
        p = os.path.join(DATA, name)
        out = os.path.join(tmp, name + ".repaired.step")
        rep = vericad(p, 1e-3, out)
        if rep.get("mode") != "faces":
            continue
        t_v = min([rep["seconds"]] + [vericad(p, 1e-3, out)["seconds"] for _ in range(4)])
        shape = read(p)
        src = free_edges(shape) if name.endswith(".step") else "—"
        back = free_edges(read(out))
        free_o, t_o = best(lambda: occt_sewing(shape, 1e-3 * unit_mm(p)))
        print(f"| {name} | {rep['faces']} ({len(rep['trimmed_faces'])}) | {src} / {back} | "
              f"{rep['free_edges_after']} | {free_o} | {t_v * 1e3:.1f} ms | {t_o * 1e3:.2f} ms | "
              f"{t_v / t_o:.0f}× |")
        compared += 1
        if back != rep["free_edges_after"]:
            failed.append(f"{name}: OCCT reads {back} free edges back, vericad says {rep['free_edges_after']}")
    if compared == 0:
        print("nothing compared", file=sys.stderr)
        return 1
    for f in failed:
        print("FAILED:", f, file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
