#!/usr/bin/env python3
"""STEP topology round trip with Open CASCADE as the independent reader: every STEP file with
topology (default: those in tests/data/public) is converted by `vericad convert IN OUT.step`,
and Open CASCADE (pip install cadquery-ocp-novtk, module OCP.OCP) reads both the original and
vericad's file. Compared per file: distinct solids, shells, faces, wires, edges and vertices
(TopExp::MapShapes), BRepCheck_Analyzer validity, total face area (BRepGProp surface
properties) and total volume of the solids (BRepGProp volume properties), both at relative
precision 1e-9, in mm (Open CASCADE converts lengths to millimetres on reading).

Prints a Markdown table; exits 1 when a count or validity differs, an area or volume differs by
more than TOLERANCE (relative), or nothing was compared.

A second table (for information, not a pass/fail check) has Open CASCADE read vericad's IGES
output of the same files in both forms beside the original STEP file: B-rep entities
(`vericad convert IN OUT.igs`: 186/514/510/508/504/502) and trimmed surfaces
(`--format iges-faces`: 144/142 over 128).

Usage: cargo build --release && python3 scripts/occt_brep_roundtrip.py [FILES...]
"""
import glob, os, subprocess, sys, tempfile

import OCP.OCP as o

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..")
TARGET = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
VERICAD = os.path.join(TARGET, "release", "vericad")
T = o.TopAbs.TopAbs_ShapeEnum
TOLERANCE = 1e-6
KINDS = [
    ("solids", T.TopAbs_SOLID),
    ("shells", T.TopAbs_SHELL),
    ("faces", T.TopAbs_FACE),
    ("wires", T.TopAbs_WIRE),
    ("edges", T.TopAbs_EDGE),
    ("vertices", T.TopAbs_VERTEX),
]


def shapes(shape, kind):
    m = o.collections.IndexedMap_TopoDS_Shape_TopTools_ShapeMapHasher()
    o.TopExp.TopExp.MapShapes_s(shape, kind, m)
    return m


def read(path):
    if path.lower().endswith((".igs", ".iges")):
        o.IGESControl.IGESControl_Controller.Init_s()
        rd = o.IGESControl.IGESControl_Reader()
        if rd.ReadFile(path) != o.IFSelect.IFSelect_ReturnStatus.IFSelect_RetDone:
            raise RuntimeError(f"Open CASCADE cannot read {path}")
        rd.TransferRoots()
        return rd.OneShape()
    rd = o.STEPControl.STEPControl_Reader()
    if rd.ReadFile(path) != o.IFSelect.IFSelect_ReturnStatus.IFSelect_RetDone:
        raise RuntimeError(f"Open CASCADE cannot read {path}")
    rd.TransferRoots()
    return rd.OneShape()


def measure(path):
    s = read(path)
    r = {k: shapes(s, kind).Extent() for k, kind in KINDS}
    r["valid"] = o.BRepCheck.BRepCheck_Analyzer(s).IsValid()
    faces = shapes(s, T.TopAbs_FACE)
    area = 0.0
    for i in range(1, faces.Extent() + 1):
        g = o.GProp.GProp_GProps()
        o.BRepGProp.BRepGProp.SurfaceProperties_s(faces.FindKey(i), g, 1e-9)
        area += g.Mass()
    solids = shapes(s, T.TopAbs_SOLID)
    volume = 0.0
    for i in range(1, solids.Extent() + 1):
        g = o.GProp.GProp_GProps()
        o.BRepGProp.BRepGProp.VolumeProperties_s(solids.FindKey(i), g, 1e-9)
        volume += g.Mass()
    r["area"], r["volume"] = area, volume
    return r


def has_topology(path):
    text = open(path, encoding="latin-1").read().upper()
    return "ADVANCED_FACE" in text or "FACE_SURFACE" in text


def counts(r):
    return ", ".join(f"{r[k]} {k}" for k, _ in KINDS)


def rel(a, b):
    return abs(a - b) / max(abs(a), abs(b), 1e-300)


def main(files):
    if not os.path.exists(VERICAD):
        sys.exit(f"{VERICAD} not found: cargo build --release first")
    rows, failures, iges_rows = [], [], []
    with tempfile.TemporaryDirectory() as tmp:
        for path in files:
            name = os.path.basename(path)
            if not has_topology(path):
                print(f"{name}: no topology in the file, skipped", file=sys.stderr)
                continue
            out = os.path.join(tmp, name + ".vericad.step")
            c = subprocess.run([VERICAD, "convert", path, out], capture_output=True, text=True)
            if c.returncode != 0:
                failures.append(f"{name}: vericad convert failed: {c.stderr.strip()}")
                continue
            a, b = measure(path), measure(out)
            bad = [k for k, _ in KINDS if a[k] != b[k]]
            if a["valid"] != b["valid"]:
                bad.append("validity")
            da, dv = rel(a["area"], b["area"]), rel(a["volume"], b["volume"])
            if da > TOLERANCE:
                bad.append("area")
            if dv > TOLERANCE:
                bad.append("volume")
            if bad:
                failures.append(f"{name}: differs in {', '.join(bad)}")
            rows.append((name, a, b, da, dv, bad))
            for form, extra in (("186", []), ("144", ["--format", "iges-faces"])):
                igs = os.path.join(tmp, f"{name}.vericad-{form}.igs")
                c = subprocess.run([VERICAD, "convert", path, igs, *extra], capture_output=True, text=True)
                if c.returncode == 0:
                    g = measure(igs)
                    iges_rows.append((f"{name} ({form})", a, g, rel(a["area"], g["area"]), rel(a["volume"], g["volume"])))
    print("| file | Open CASCADE reads the original | Open CASCADE reads vericad's STEP | valid (orig / vericad) | face area mm² (orig / vericad, rel. diff) | solid volume mm³ (orig / vericad, rel. diff) |")
    print("|---|---|---|---|---|---|")
    for name, a, b, da, dv, _ in rows:
        print(
            f"| {name} | {counts(a)} | {'same' if counts(a) == counts(b) else counts(b)} | "
            f"{a['valid']} / {b['valid']} | {a['area']:.10g} / {b['area']:.10g} ({da:.1e}) | "
            f"{a['volume']:.10g} / {b['volume']:.10g} ({dv:.1e}) |"
        )
    print()
    print("| file (IGES form) | Open CASCADE reads vericad's IGES | valid | face area mm² (rel. diff to the STEP original) | solid volume mm³ (rel. diff) |")
    print("|---|---|---|---|---|")
    for name, a, g, da, dv in iges_rows:
        print(
            f"| {name} | {counts(g)} | {g['valid']} | {g['area']:.10g} ({da:.1e}) | "
            f"{g['volume']:.10g} ({dv:.1e}) |"
        )
    for f in failures:
        print("FAIL:", f, file=sys.stderr)
    if not rows:
        print("FAIL: nothing compared", file=sys.stderr)
    return 1 if failures or not rows else 0


if __name__ == "__main__":
    args = sys.argv[1:] or sorted(
        glob.glob(os.path.join(ROOT, "tests/data/public/*.st*p"))
    )
    sys.exit(main(args))
