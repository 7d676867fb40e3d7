#!/usr/bin/env python3
"""Write the STEP assemblies of this directory with Open CASCADE 8.0.1 (pip install
cadquery-ocp-novtk; XCAF document, STEPCAFControl_Writer, AP214, millimetres) and print what
Open CASCADE reads back from each file (STEPControl_Reader, the solids of OneShape): per solid
its area (BRepGProp surface properties, adaptive, relative precision 1e-9) and its tight
bounding box (BRepBndLib::AddOptimal without triangulation or tolerances), in mm.

  occt-assembly-boxes.step     one box part (10 x 20 x 30) placed twice: rotated 90 deg about
                               z and moved by (100, 0, 0); rotated 30 deg about (1, 1, 0) and
                               moved by (0, 50, 10)
  occt-assembly-nested.step    a sub-assembly "pair" of a plate (40 x 30 x 5, not moved) and a
                               peg (5 x 5 x 20, rotated 45 deg about z, moved by (10, 10, 5)),
                               placed twice in the top assembly: rotated 90 deg about x; rotated
                               -60 deg about (0, 1, 1) and moved by (200, 0, 50)
  occt-assembly-cylinder.step  a cylinder part (radius 7, height 25) rotated 35 deg about
                               (1, 0, 1) and moved by (5, -20, 3)

Usage: python3 make_assemblies.py [--read-only]   (from this directory)
"""
import math, os, sys

import OCP.OCP as o

HERE = os.path.dirname(os.path.abspath(__file__))
g = o.gp


def name(label, text):
    o.TDataStd.TDataStd_Name.Set_s(label, o.TCollection.TCollection_ExtendedString(text))


def placement(axis, degrees, move):
    t = g.gp_Trsf()
    t.SetRotation(g.gp_Ax1(g.gp_Pnt(0, 0, 0), g.gp_Dir(*axis)), math.radians(degrees))
    t.SetTranslationPart(g.gp_Vec(*move))
    return o.TopLoc.TopLoc_Location(t)


def document():
    app = o.XCAFApp.XCAFApp_Application.GetApplication_s()
    doc = o.TDocStd.TDocStd_Document(o.TCollection.TCollection_ExtendedString("MDTV-XCAF"))
    app.InitDocument(doc)
    return doc, o.XCAFDoc.XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())


def part(st, shape, text):
    label = st.AddShape(shape, False, True)
    name(label, text)
    return label


def write(doc, st, file):
    st.UpdateAssemblies()
    w = o.STEPCAFControl.STEPCAFControl_Writer()
    w.Transfer(doc, o.STEPControl.STEPControl_StepModelType.STEPControl_AsIs)
    if w.Write(os.path.join(HERE, file)) != o.IFSelect.IFSelect_ReturnStatus.IFSelect_RetDone:
        raise RuntimeError(f"cannot write {file}")


def boxes():
    doc, st = document()
    box = part(st, o.BRepPrimAPI.BRepPrimAPI_MakeBox(10.0, 20.0, 30.0).Shape(), "box")
    top = st.NewShape()
    name(top, "two boxes")
    st.AddComponent(top, box, placement((0, 0, 1), 90, (100, 0, 0)))
    st.AddComponent(top, box, placement((1, 1, 0), 30, (0, 50, 10)))
    write(doc, st, "occt-assembly-boxes.step")


def nested():
    doc, st = document()
    plate = part(st, o.BRepPrimAPI.BRepPrimAPI_MakeBox(40.0, 30.0, 5.0).Shape(), "plate")
    peg = part(st, o.BRepPrimAPI.BRepPrimAPI_MakeBox(5.0, 5.0, 20.0).Shape(), "peg")
    pair = st.NewShape()
    name(pair, "pair")
    st.AddComponent(pair, plate, o.TopLoc.TopLoc_Location())
    st.AddComponent(pair, peg, placement((0, 0, 1), 45, (10, 10, 5)))
    top = st.NewShape()
    name(top, "two pairs")
    st.AddComponent(top, pair, placement((1, 0, 0), 90, (0, 0, 0)))
    st.AddComponent(top, pair, placement((0, 1, 1), -60, (200, 0, 50)))
    write(doc, st, "occt-assembly-nested.step")


def cylinder():
    doc, st = document()
    ax = g.gp_Ax2(g.gp_Pnt(0, 0, 0), g.gp_Dir(0, 0, 1))
    cyl = part(st, o.BRepPrimAPI.BRepPrimAPI_MakeCylinder(ax, 7.0, 25.0).Shape(), "cylinder")
    top = st.NewShape()
    name(top, "placed cylinder")
    st.AddComponent(top, cyl, placement((1, 0, 1), 35, (5, -20, 3)))
    write(doc, st, "occt-assembly-cylinder.step")


def read(file):
    rd = o.STEPControl.STEPControl_Reader()
    if rd.ReadFile(os.path.join(HERE, file)) != o.IFSelect.IFSelect_ReturnStatus.IFSelect_RetDone:
        raise RuntimeError(f"Open CASCADE cannot read {file}")
    rd.TransferRoots()
    shape = rd.OneShape()
    ex = o.TopExp.TopExp_Explorer(shape, o.TopAbs.TopAbs_ShapeEnum.TopAbs_SOLID)
    print(f"{file}:")
    while ex.More():
        s = ex.Current()
        props = o.GProp.GProp_GProps()
        o.BRepGProp.BRepGProp.SurfaceProperties_s(s, props, 1e-9)
        box = o.Bnd.Bnd_Box()
        o.BRepBndLib.BRepBndLib.AddOptimal_s(s, box, False, False)
        b = [box.GetXMin(), box.GetYMin(), box.GetZMin(), box.GetXMax(), box.GetYMax(), box.GetZMax()]
        gap = box.GetGap()
        print(f"  area {props.Mass():.9f} box " + " ".join(f"{x:.9f}" for x in b) + f" gap {gap:.1e}")
        ex.Next()


if __name__ == "__main__":
    if "--read-only" not in sys.argv:
        boxes()
        nested()
        cylinder()
    for f in ["occt-assembly-boxes.step", "occt-assembly-nested.step", "occt-assembly-cylinder.step"]:
        read(f)
