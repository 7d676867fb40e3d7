#!/usr/bin/env python3
"""Which faces are *natural* (bounded by their surface's own parameter rectangle: the faces a
patch-set repair may take as patches) by vericad, beside an independent decision made with
Open CASCADE. Prints a Markdown table and exits 1 when a face is classed differently or
nothing was compared.

vericad's classes: `vericad repair FILE --faces --report R` lists the trimmed faces
(`trimmed_faces`, STEP ids); every other face is natural (src/brep/natural.rs).

Open CASCADE's decision (pip install cadquery-ocp-novtk, module OCP.OCP), per face, matched
by the order of the file's shells (as scripts/occt_brep_counts.py does):
  fills      the face's area (BRepGProp, relative precision 1e-9) equals, within 1e-6
             relative, the area of its surface over the face's parameter bounding box
             (BRepTools::UVBounds; a face made of the surface and that box);
  rectangle  that box is the rectangle vericad gives the surface: a B-spline surface's own
             bounds; for the analytic surfaces vericad converts, the whole period in each
             closed direction (the circle of a cylinder, cone, sphere or torus, the meridian
             of a sphere from pole to pole, the torus's tube) — in the open directions vericad
             takes the face's own extent (planes, the axis of cylinders and cones).
A face is natural when both hold. Other surface kinds are listed as not compared.

Usage: cargo build --release && python3 scripts/occt_natural_faces.py [FILES...]
"""
import glob, importlib.util, json, math, os, subprocess, sys, tempfile

import OCP.OCP as o

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..")
TARGET = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
VERICAD = os.environ.get("VERICAD") or os.path.join(TARGET, "release", "vericad")
spec = importlib.util.spec_from_file_location("counts", os.path.join(HERE, "occt_brep_counts.py"))
counts = importlib.util.module_from_spec(spec)
spec.loader.exec_module(counts)
T = o.TopAbs.TopAbs_ShapeEnum
A = o.GeomAbs.GeomAbs_SurfaceType
AREA_REL = 1e-6
PARAM_REL = 1e-9


def area(face):
    g = o.GProp.GProp_GProps()
    o.BRepGProp.BRepGProp.SurfaceProperties_s(face, g, 1e-9)
    return g.Mass()


def occt_natural(face):
    """(natural, kind, why) of one face by the decision in the module comment."""
    u0, u1, v0, v1 = o.BRepTools.BRepTools.UVBounds_s(face)
    surf = o.BRep.BRep_Tool.Surface_s(face)
    kind = o.BRepAdaptor.BRepAdaptor_Surface(face).GetType()
    two_pi = 2 * math.pi
    full = lambda a, b, want: abs((b - a) - want) <= PARAM_REL * max(1.0, want)
    if kind == A.GeomAbs_BSplineSurface:
        bu0, bu1, bv0, bv1 = surf.Bounds()
        rect = all(abs(x - y) <= PARAM_REL * max(1.0, abs(bu1 - bu0), abs(bv1 - bv0))
                   for x, y in ((u0, bu0), (u1, bu1), (v0, bv0), (v1, bv1)))
        name = "bspline"
    elif kind == A.GeomAbs_Plane:
        rect, name = True, "plane"
    elif kind in (A.GeomAbs_Cylinder, A.GeomAbs_Cone):
        rect, name = full(u0, u1, two_pi), "cylinder" if kind == A.GeomAbs_Cylinder else "cone"
    elif kind == A.GeomAbs_Sphere:
        rect, name = full(u0, u1, two_pi) and full(v0, v1, math.pi), "sphere"
    elif kind == A.GeomAbs_Torus:
        rect, name = full(u0, u1, two_pi) and full(v0, v1, two_pi), "torus"
    else:
        return None, str(kind).split("_")[-1], "not compared"
    rect_face = o.BRepBuilderAPI.BRepBuilderAPI_MakeFace(surf, u0, u1, v0, v1, 1e-7).Face()
    af, ar = area(face), area(rect_face)
    fills = abs(af - ar) <= AREA_REL * max(ar, 1e-300)
    why = "fills its box" if fills else "area %.6g of box %.6g" % (af, ar)
    if not rect:
        why += "; box is not the surface's rectangle"
    return fills and rect, name, why


def vericad_trimmed(path):
    with tempfile.TemporaryDirectory() as d:
        rep = os.path.join(d, "r.json")
        r = subprocess.run([VERICAD, "repair", path, "--faces", "--report", rep],
                           capture_output=True, text=True)
        if not os.path.exists(rep):
            return None, (r.stderr.strip().splitlines() or ["exit %d" % r.returncode])[-1]
        return set(json.load(open(rep))["trimmed_faces"]), None


def main(files):
    rows, failures, compared = [], [], 0
    for path in files:
        name = os.path.basename(path)
        rd = o.STEPControl.STEPControl_Reader()
        if rd.ReadFile(path) != o.IFSelect.IFSelect_ReturnStatus.IFSelect_RetDone:
            rows.append((name, "Open CASCADE cannot read it", "", "", ""))
            continue
        rd.TransferRoots()
        faces = counts.shapes(rd.OneShape(), T.TopAbs_FACE)
        ids = counts.shell_face_order(path)
        if not ids and faces.Extent() == 0:
            continue  # no faces (bare surfaces, or a file Open CASCADE transfers nothing from)
        if len(ids) != faces.Extent():
            rows.append((name, f"{faces.Extent()} faces, {len(ids)} in the shells: not matched", "", "", ""))
            continue
        trimmed, err = vericad_trimmed(path)
        if trimmed is None:
            rows.append((name, str(len(ids)), "— (" + err + ")", "", "not compared"))
            continue
        agree, differ, skipped, nat_v, nat_o = 0, [], 0, 0, 0
        for fi, fid in enumerate(ids, start=1):
            nat, kind, why = occt_natural(o.TopoDS.TopoDS.Face(faces.FindKey(fi)))
            v = fid not in trimmed
            nat_v += v
            if nat is None:
                skipped += 1
                continue
            nat_o += nat
            compared += 1
            if nat == v:
                agree += 1
            else:
                differ.append(f"{fid} ({kind}: vericad {'natural' if v else 'trimmed'}, "
                              f"Open CASCADE {'natural' if nat else 'trimmed'}: {why})")
        failures += [f"{name}: {d}" for d in differ]
        rows.append((name, str(len(ids)), f"{nat_v}", f"{nat_o}" + (f" ({skipped} not compared)" if skipped else ""),
                     "equal" if not differ else "DIFFERS: " + "; ".join(differ)))
    print("| file | faces | natural, vericad | natural, Open CASCADE | classes |")
    print("|---|---|---|---|---|")
    for r in rows:
        print("| " + " | ".join(r) + " |")
    if compared == 0:
        print("nothing compared", file=sys.stderr)
        return 1
    for f in failures:
        print("DIFFERS:", f, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    files = sys.argv[1:] or sorted(glob.glob(os.path.join(ROOT, "tests", "data", "**", "*.st*p"), recursive=True))
    sys.exit(main(files))
