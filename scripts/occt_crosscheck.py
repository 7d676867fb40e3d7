#!/usr/bin/env python3
"""Independent read-back of files written by vericad, with Open CASCADE.

For each input model (default: every IGES/STEP file in tests/data/public), vericad converts it
to IGES and to STEP; Open CASCADE (pip install cadquery-ocp-novtk, module OCP.OCP) reads
each written file, and every face's surface is evaluated at a 5x5 grid of parameters and
compared with vericad's own evaluation of the same surface (`vericad eval --json`); every
face's trimmed area as Open CASCADE computes it from the written file is compared with its
area from the original (adaptive integration at 1e-10; faces paired by centre and area).
Default inputs: tests/data/public and tests/data/public/occt-written.

Not part of the default test run (it needs the OCCT wheel). Usage:
    cargo build --release && python3 scripts/occt_crosscheck.py [FILES...]
Exit code 0 when every point agrees within 1e-9 relative to the model size.
"""
import glob, json, os, subprocess, sys, tempfile

import OCP.OCP as o

HERE = os.path.dirname(os.path.abspath(__file__))
VERICAD = os.environ.get("VERICAD") or os.path.join(
    os.environ.get("CARGO_TARGET_DIR", os.path.join(HERE, "..", "target")), "release", "vericad")


def vericad(*args):
    r = subprocess.run([VERICAD, *args], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"vericad {' '.join(args)}: {r.stderr.strip()}")
    return r.stdout


def occt_faces(path):
    if path.endswith(".igs"):
        o.IGESControl.IGESControl_Controller.Init_s()
        rd = o.IGESControl.IGESControl_Reader()
    else:
        rd = o.STEPControl.STEPControl_Reader()
    if rd.ReadFile(path) != o.IFSelect.IFSelect_ReturnStatus.IFSelect_RetDone:
        raise RuntimeError(f"OCCT cannot read {path}")
    rd.TransferRoots()
    shape = rd.OneShape()
    out = []
    ex = o.TopExp.TopExp_Explorer(shape, o.TopAbs.TopAbs_ShapeEnum.TopAbs_FACE)
    while ex.More():
        out.append(o.BRep.BRep_Tool.Surface_s(o.TopoDS.TopoDS.Face(ex.Current())))
        ex.Next()
    return out


def occt_face_areas(path):
    """Trimmed area and centre of mass of every face as Open CASCADE computes them (trims
    included), with its adaptive integration at relative 1e-10 (its default fixed-order rule
    is off by up to 1e-5 on rational faces)."""
    out = []
    ex = o.TopExp.TopExp_Explorer(occt_shape(path), o.TopAbs.TopAbs_ShapeEnum.TopAbs_FACE)
    while ex.More():
        props = o.GProp.GProp_GProps()
        o.BRepGProp.BRepGProp.SurfaceProperties_s(o.TopoDS.TopoDS.Face(ex.Current()), props, 1e-10)
        c = props.CentreOfMass()
        out.append((props.Mass(), (c.X(), c.Y(), c.Z())))
        ex.Next()
    return out


def occt_shape(path):
    if path.endswith((".igs", ".iges")):
        o.IGESControl.IGESControl_Controller.Init_s()
        rd = o.IGESControl.IGESControl_Reader()
    else:
        rd = o.STEPControl.STEPControl_Reader()
    rd.ReadFile(path)
    rd.TransferRoots()
    return rd.OneShape()


def worst_area_change(a, b):
    """Largest relative change of a face's area from `a` to `b` (lists of (area, centre)),
    faces paired greedily by centre distance plus area difference; None when the counts
    differ."""
    if len(a) != len(b) or not a:
        return None
    used, worst = set(), 0.0
    for area, c in a:
        j = min((j for j in range(len(b)) if j not in used),
                key=lambda j: sum((x - y) ** 2 for x, y in zip(b[j][1], c)) ** 0.5 + abs(b[j][0] - area))
        used.add(j)
        worst = max(worst, abs(b[j][0] - area) / max(abs(area), 1e-300))
    return worst


def match_by_centre(path, mine, theirs, scale):
    """Open CASCADE builds a B-rep's faces in an order of its own (a STEP file's in its shells'
    order, an IGES file's in neither the file's nor its shell's). Reorder its faces to vericad's by geometry: vericad's face k goes with the
    Open CASCADE face nearest to it at the centre of k's domain, evaluated at the same
    parameters (both keep the file's parametrization; `scale` turns vericad's length unit into
    Open CASCADE's millimetres). Kept as read unless the matching is one to one."""
    order = []
    for k, m in enumerate(mine):
        u0, u1, v0, v1 = m["domain"]
        u, v = 0.5 * (u0 + u1), 0.5 * (v0 + v1)
        p = json.loads(vericad("eval", path, "--surface", str(k), "--uv", f"{u!r},{v!r}", "--json"))["point"]

        def dist(g):
            try:
                q = g.Value(u, v)
            except Exception:  # noqa: BLE001 - a parameter outside that face
                return float("inf")
            return sum((a * scale - b) ** 2 for a, b in zip(p, (q.X(), q.Y(), q.Z())))

        order.append(min(range(len(theirs)), key=lambda i: dist(theirs[i])))
    if len(set(order)) != len(theirs) or len(mine) != len(theirs):
        return theirs
    return [theirs[i] for i in order]


def main(files):
    worst, checked, failures, areas = 0.0, 0, [], []
    tmp = tempfile.mkdtemp()
    for src in files:
        info = json.loads(vericad("info", src, "--json"))
        # OCCT converts lengths to millimetres on reading.
        scale = {"mm": 1.0, "m": 1000.0, "cm": 10.0, "inch": 25.4, "in": 25.4, "foot": 304.8, "ft": 304.8}.get(info["unit"] or "mm", 1.0)
        size = max(1.0, max(abs(c) for b in (info["bbox"] or [[1, 1, 1]]) for c in b))
        for ext in ("igs", "step"):
            out = os.path.join(tmp, os.path.basename(src) + "." + ext)
            vericad("convert", src, out)
            mine = json.loads(vericad("info", out, "--json"))["surfaces"]
            try:
                theirs = occt_faces(out)
            except Exception as e:  # noqa: BLE001 - report and continue
                failures.append(f"{out}: {e}")
                continue
            # Trims survive: OCCT's trimmed area of every face of the written file equals the
            # original's.
            w = worst_area_change(occt_face_areas(src), occt_face_areas(out))
            areas.append((os.path.basename(out), w))
            if w is None:
                failures.append(f"{out}: OCCT reads a different number of faces than from the original")
            elif w > 1e-9:
                failures.append(f"{out}: a face's OCCT trimmed area differs from the original's by {w:.2e} (relative)")
            theirs = match_by_centre(out, mine, theirs, scale)
            if len(theirs) != len(mine):
                failures.append(f"{out}: OCCT reads {len(theirs)} faces, vericad wrote {len(mine)}")
                continue
            for k, (s, g) in enumerate(zip(mine, theirs)):
                u0, u1, v0, v1 = s["domain"]
                for i in range(5):
                    for j in range(5):
                        # The last sample is the end itself (u0 + (u1 - u0) can round past u1).
                        u = u1 if i == 4 else u0 + (u1 - u0) * i / 4
                        v = v1 if j == 4 else v0 + (v1 - v0) * j / 4
                        p = json.loads(vericad("eval", out, "--surface", str(k), "--uv", f"{u!r},{v!r}", "--json"))["point"]
                        q = g.Value(u, v)
                        d = ((p[0] * scale - q.X()) ** 2 + (p[1] * scale - q.Y()) ** 2 + (p[2] * scale - q.Z()) ** 2) ** 0.5 / (size * scale)
                        worst = max(worst, d)
                        checked += 1
                        if d > 1e-9:
                            failures.append(f"{out} face {k} at ({u}, {v}): relative distance {d:.3e}")
    print(f"{checked} points compared, worst relative distance {worst:.3e}, {len(failures)} failure(s)")
    print("largest relative change of a face's trimmed area, Open CASCADE reading the original and the written file:")
    for name, w in areas:
        print(f"  {name}: " + ("face counts differ" if w is None else f"{w:.2e}"))
    for f in failures[:20]:
        print("  " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    data = os.path.join(HERE, "..", "tests", "data", "public")
    args = sys.argv[1:] or sorted(
        f for d in (data, os.path.join(data, "occt-written"))
        for f in glob.glob(os.path.join(d, "*.igs")) + glob.glob(os.path.join(d, "*.st*p")))
    sys.exit(main(args))
