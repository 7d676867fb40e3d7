#!/usr/bin/env python3
"""B-rep counts of vericad beside Open CASCADE's for STEP files (default: every STEP file in
tests/data/public). Prints a Markdown table and exits 1 when a count disagrees or nothing
was compared.

Open CASCADE (pip install cadquery-ocp-novtk, module OCP.OCP) heals the shape it reads: it
splits closed edges where they cross a surface seam (a new vertex and edge), adds seam edges
that join two loops of a closed surface into one wire, and adds degenerate edges at poles
(for vertex loops and at surface poles). vericad keeps the file's topology. Compared:
  faces        equal;
  components   boundary components without seams: per face, the connected pieces (at shared
               vertices) of the edges its wires use once, degenerate edges left out; summed
               (unchanged by the three healing operations);
  E - V        (edges - seam edges - degenerate edges) - vertices (splitting an edge at a new
               vertex changes both by one; adding seams or degenerate edges is discounted);
  raw          where Open CASCADE added no seam or degenerate edge and split nothing
               (as many vertices as the file's vertex_points), wires == loops,
               edges == edges and vertices == vertices.
Files without topology (bare patch sets) compare faces with vericad's surfaces only.

Trimmed areas: each face's area from `vericad info --json` (converted to mm^2) beside Open
CASCADE's BRepGProp surface area (adaptive, relative precision 1e-9), faces matched by their
order in the file's shells (the order Open CASCADE builds them in). The largest relative
difference per file is printed; above AREA_TOLERANCE it is a failure.

Usage: cargo build --release && python3 scripts/occt_brep_counts.py [FILES...]
"""
import glob, json, os, re, subprocess, sys

import OCP.OCP as o

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..")
TARGET = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
VERICAD = os.path.join(TARGET, "release", "vericad")
T = o.TopAbs.TopAbs_ShapeEnum
AREA_TOLERANCE = 2e-4
MM2 = {"m": 1e6, "mm": 1.0, "cm": 100.0, "inch": 645.16, "foot": 92903.04}


def shapes(shape, kind):
    m = o.collections.IndexedMap_TopoDS_Shape_TopTools_ShapeMapHasher()
    o.TopExp.TopExp.MapShapes_s(shape, kind, m)
    return m


def occt_counts(path):
    rd = o.STEPControl.STEPControl_Reader()
    if rd.ReadFile(path) != o.IFSelect.IFSelect_ReturnStatus.IFSelect_RetDone:
        raise RuntimeError(f"Open CASCADE cannot read {path}")
    rd.TransferRoots()
    s = rd.OneShape()
    faces, wires = shapes(s, T.TopAbs_FACE), shapes(s, T.TopAbs_WIRE)
    edges, verts = shapes(s, T.TopAbs_EDGE), shapes(s, T.TopAbs_VERTEX)
    tool = o.BRep.BRep_Tool
    degenerate, seams, components = set(), set(), 0
    for fi in range(1, faces.Extent() + 1):
        face = o.TopoDS.TopoDS.Face(faces.FindKey(fi))
        uses = {}
        fe = o.TopExp.TopExp_Explorer(face, T.TopAbs_EDGE)
        while fe.More():
            e = o.TopoDS.TopoDS.Edge(fe.Current())
            k = edges.FindIndex(e)
            if tool.Degenerated_s(e):
                degenerate.add(k)
            elif tool.IsClosed_s(e, face):
                seams.add(k)
            else:
                uses[k] = uses.get(k, 0) + 1
            fe.Next()
        parent = {}

        def root(x):
            while parent.setdefault(x, x) != x:
                x = parent[x]
            return x

        for k, n in uses.items():
            if n != 1:
                continue
            e = o.TopoDS.TopoDS.Edge(edges.FindKey(k))
            a = verts.FindIndex(o.TopExp.TopExp.FirstVertex_s(e))
            b = verts.FindIndex(o.TopExp.TopExp.LastVertex_s(e))
            parent[root(a)] = root(b)
        components += len({root(v) for v in list(parent)})
    areas = []
    for fi in range(1, faces.Extent() + 1):
        g = o.GProp.GProp_GProps()
        o.BRepGProp.BRepGProp.SurfaceProperties_s(faces.FindKey(fi), g, 1e-9)
        areas.append(g.Mass())
    return {
        "areas": areas,
        "solids": shapes(s, T.TopAbs_SOLID).Extent(),
        "shells": shapes(s, T.TopAbs_SHELL).Extent(),
        "faces": faces.Extent(),
        "wires": wires.Extent(),
        "edges": edges.Extent(),
        "vertices": verts.Extent(),
        "degenerate": len(degenerate),
        "seams": len(seams),
        "components": components,
    }


def shell_face_order(path):
    text = re.sub(r"\s+", " ", open(path, encoding="latin-1").read())
    order = []
    for faces in re.findall(r"(?:CLOSED|OPEN)_SHELL\s*\(\s*'[^']*'\s*,\s*\(([^)]*)\)", text):
        order += ["#" + x for x in re.findall(r"#(\d+)", faces)]
    return order


def vertex_points_in_file(path):
    text = open(path, encoding="latin-1").read()
    return len(re.findall(r"=\s*VERTEX_POINT\s*\(", text))


def vericad_info(path):
    r = subprocess.run([VERICAD, "info", "--json", path], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"vericad info {path}: {r.stderr.strip()}")
    return json.loads(r.stdout)


def main(files):
    if not os.path.exists(VERICAD):
        sys.exit(f"{VERICAD} not found: cargo build --release first")
    rows, failures, compared = [], [], 0
    for path in files:
        name = os.path.basename(path)
        oc = occt_counts(path)
        info = vericad_info(path)
        t = info.get("topology")
        checks = []
        if t is None:
            checks.append(("faces", len(info["surfaces"]), oc["faces"]))
            v = "— (no topology in the file: %d surfaces)" % len(info["surfaces"])
        else:
            checks.append(("faces", t["faces"], oc["faces"]))
            checks.append(("components", t["boundary_components"], oc["components"]))
            checks.append((
                "E - V",
                t["edges"] - t["seam_edges"] - t["vertices"],
                oc["edges"] - oc["seams"] - oc["degenerate"] - oc["vertices"],
            ))
            healed = oc["seams"] > 0 or oc["degenerate"] > 0 or oc["vertices"] != vertex_points_in_file(path)
            if not healed:
                checks.append(("loops/wires", t["loops"], oc["wires"]))
                checks.append(("edges", t["edges"], oc["edges"]))
                checks.append(("vertices", t["vertices"], oc["vertices"]))
            v = "%d faces, %d loops (%d vertex loops), %d edges (%d seams), %d vertices, %d components" % (
                t["faces"], t["loops"], t["vertex_loops"], t["edges"], t["seam_edges"],
                t["vertices"], t["boundary_components"])
        occ = "%d faces, %d wires, %d edges (%d seams, %d degenerate), %d vertices, %d components" % (
            oc["faces"], oc["wires"], oc["edges"], oc["seams"], oc["degenerate"], oc["vertices"],
            oc["components"])
        area = "—"
        if t is not None and info.get("face_areas"):
            va = {a["face"]: a["area"] for a in info["face_areas"]}
            scale = MM2.get(info.get("unit") or "mm", 1.0)
            worst = 0.0
            for f, ao in zip(shell_face_order(path), oc["areas"]):
                av = va.get(f)
                rel = abs(av * scale - ao) / ao if av is not None else float("inf")
                if rel > worst:
                    worst, worst_face = rel, f
            total = sum(a for a in va.values() if a is not None) * scale
            area = "%.10g vs %.10g mm²; largest face difference %.1e (%s)" % (
                total, sum(oc["areas"]), worst, worst_face)
            if worst > AREA_TOLERANCE:
                failures.append(f"{name}: face {worst_face} area differs by {worst:.1e}")
            compared += 1
        bad = [f"{k} {a} vs {b}" for k, a, b in checks if a != b]
        compared += len(checks)
        failures += [f"{name}: {b}" for b in bad]
        rows.append((name, v, occ, ", ".join(k for k, _, _ in checks), "DIFFERS: " + "; ".join(bad) if bad else "equal", area))
    print("| file | vericad | Open CASCADE 8 | counts compared | counts | trimmed area (vericad vs Open CASCADE) |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        print("| " + " | ".join(r) + " |")
    if compared == 0:
        sys.exit("nothing compared")
    if failures:
        print("\n".join(failures), file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    args = sys.argv[1:] or sorted(
        glob.glob(os.path.join(ROOT, "tests", "data", "public", "*.st*p"))
    )
    main(args)
