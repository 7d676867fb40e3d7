"""Shared by the Open CASCADE comparison scripts: reading STEP faces and an IGES surface with
OCCT, and a vericad-model JSON surface as an OCCT B-spline surface (the same data, exactly:
knots as distinct values with multiplicities, weights when the surface has them)."""
import OCP.OCP as o

# OCCT reads lengths in millimetres; vericad keeps the file's unit (its `unit` names it).
MM_PER_UNIT = {"mm": 1.0, "m": 1000.0, "cm": 10.0, "inch": 25.4, "foot": 304.8, "um": 1e-3, "km": 1e6}


def read_step_faces(path):
    """The file's faces as one compound (a solid would measure 0 inside its volume)."""
    rd = o.STEPControl.STEPControl_Reader()
    if rd.ReadFile(path) != o.IFSelect.IFSelect_ReturnStatus.IFSelect_RetDone:
        raise RuntimeError(f"OCCT cannot read {path}")
    rd.TransferRoots()
    comp = o.TopoDS.TopoDS_Compound()
    b = o.BRep.BRep_Builder()
    b.MakeCompound(comp)
    ex = o.TopExp.TopExp_Explorer(rd.OneShape(), o.TopAbs.TopAbs_ShapeEnum.TopAbs_FACE)
    while ex.More():
        b.Add(comp, ex.Current())
        ex.Next()
    return comp


def read_iges_surface(path, bspline=False):
    """The surface of the file's first face (converted to a B-spline surface if asked)."""
    rd = o.IGESControl.IGESControl_Reader()
    if rd.ReadFile(path) != o.IFSelect.IFSelect_ReturnStatus.IFSelect_RetDone:
        raise RuntimeError(f"OCCT cannot read {path}")
    rd.TransferRoots()
    ex = o.TopExp.TopExp_Explorer(rd.OneShape(), o.TopAbs.TopAbs_ShapeEnum.TopAbs_FACE)
    s = o.BRep.BRep_Tool.Surface_s(o.TopoDS.TopoDS.Face(ex.Current()))
    return o.GeomConvert.GeomConvert.SurfaceToBSplineSurface_s(s) if bspline else s


def distinct(knots):
    """A full knot vector as OCCT's distinct knots and multiplicities."""
    ks, ms = [], []
    for k in knots:
        if ks and k == ks[-1]:
            ms[-1] += 1
        else:
            ks.append(k)
            ms.append(1)
    a, b = o.collections.Array1_double(1, len(ks)), o.collections.Array1_int(1, len(ks))
    for i, (k, m) in enumerate(zip(ks, ms)):
        a.SetValue(i + 1, k)
        b.SetValue(i + 1, m)
    return a, b


def from_json(s, scale=1.0):
    """A vericad-model JSON surface as an OCCT B-spline surface, lengths times `scale`."""
    c = s["control_points"]
    nu, nv = len(c), len(c[0])
    poles = o.collections.Array2_gp_Pnt(1, nu, 1, nv)
    for i in range(nu):
        for j in range(nv):
            poles.SetValue(i + 1, j + 1, o.gp.gp_Pnt(*(scale * x for x in c[i][j][:3])))
    ku, mu = distinct(s["knots_u"])
    kv, mv = distinct(s["knots_v"])
    if s.get("weights"):
        w = o.collections.Array2_double(1, nu, 1, nv)
        for i in range(nu):
            for j in range(nv):
                w.SetValue(i + 1, j + 1, s["weights"][i][j])
        return o.Geom.Geom_BSplineSurface(poles, w, ku, kv, mu, mv, s["degree_u"], s["degree_v"])
    return o.Geom.Geom_BSplineSurface(poles, ku, kv, mu, mv, s["degree_u"], s["degree_v"])
