#!/usr/bin/env python3
"""vericad coons beside Open CASCADE's own constructions on the same four boundary curves.

For every case (a model file and a boundary file, scripts/data/coons/):

1. `vericad coons MODEL --boundary B.json --tol T --out patch.igs` — the projected Coons
   patch with multiquadric gap filling (Hamann & Jean §3); the IGES surface is read back
   with OCCT.
2. OCCT Coons: each boundary polyline (the same vertices vericad tabulates) is fitted by
   `GeomAPI_PointsToBSpline` (degree 3..8, C2, 3D tolerance T/10), its end poles set to
   the polyline's ends so that the corners meet exactly, the four curves put end to end in
   loop order and given to `GeomFill_BSplineCurves(c1, c2, c3, c4, GeomFill_CoonsStyle)`.
   The Coons patch sees only the boundary, never the original faces.
3. OCCT Plate, twice: `GeomPlate_BuildPlateSurface` (degree 3, 3 iterations) with the four
   fitted curves as G0 curve constraints (a) alone, (b) plus point constraints: the
   closest points on the original faces (`BRepExtrema_DistShapeShape`) of the interior
   points of an (M + 1) × (N + 1) lattice of the OCCT Coons patch — as many points as
   vericad's final grid has interior points — points over a gap (see below) dropped; then
   `GeomPlate_MakeApprox` (tolerance T, C1, at most 32 segments of degree 8,
   dmax = max(T, 10 × G0 error), criterion order 0).

Every result surface is measured the same way: the 33 × 33 cell centres of its parameter
square, `((i + ½)/33, (j + ½)/33)` — apart from the centre lines `½`, neither vericad's grid
points nor its error samples (17) — (for Plate: those inside the boundary's polygon in the
plate's own parameter plane, `Curves2d`; its approximation covers the enlarged bounding
rectangle), each point's distance to the original faces by `BRepExtrema_DistShapeShape`:
a measurement — evidence, not a bound; the true maximum can lie between samples. A sample
whose closest point lies on an edge or vertex of the originals (not inside a face),
farther than T and more than GAP_ANGLE (5°) off that face's normal, is *over a gap or
beyond the originals*: skipped and counted; on the sphere cases the analytic distance
`|‖p‖ − 1|` of those samples is reported instead (how well the gap is bridged). Also:
control points (poles u × v) and the wall time of building — vericad: the whole `vericad
coons` process (reading the STEP file, triangulating, refining, writing IGES and report;
its own figure in the notes); OCCT: fitting the curves and building the surface, without
reading the file; Plate (b): including the point projections. One run's times.

Units: OCCT converts lengths to millimetres when reading STEP and IGES; vericad keeps the
file's unit. Boundary points are scaled to millimetres for OCCT, and every distance is
divided back: the table is in the model's unit (fuselage: feet).

Usage:
  cargo build --release && python3 scripts/occt_coons_fill.py            # all cases, table
  python3 scripts/occt_coons_fill.py --write-data   # regenerate scripts/data/coons/
Environment: VERICAD (path of the binary; default target/release/vericad).
"""
import json, math, os, subprocess, sys, tempfile, time

import OCP.OCP as o

from occt_io import MM_PER_UNIT, from_json, read_iges_surface, read_step_faces

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..")
DATA = os.path.join(HERE, "data", "coons")
VERICAD = os.environ.get("VERICAD", os.path.join(ROOT, "target", "release", "vericad"))
LATTICE = 33      # measuring lattice (cell centres) per direction
GAP_ANGLE = 5.0   # degrees: a closest point on an edge farther from the normal than this is a gap


def unit_sphere(p):
    """Analytic distance to the unit sphere (the sphere models are in mm, radius 1)."""
    return abs(math.sqrt(p.X() ** 2 + p.Y() ** 2 + p.Z() ** 2) - 1.0)


CASES = [
    # (label, model, boundary, tol in model units, analytic distance for the gap samples)
    ("fuselage, 4 patches", "tests/data/public/occt-bug28366_fuselage.stp", "scripts/data/coons/fuselage-top.json", 1e-5, None),
    ("sphere piece (Fig. 8)", "scripts/data/coons/sphere-one.step", "scripts/data/coons/sphere.json", 1e-4, unit_sphere),
    ("two sphere pieces, gap 0.2 rad (Fig. 9)", "scripts/data/coons/sphere-gap.step", "scripts/data/coons/sphere.json", 1e-4, unit_sphere),
]


# ---------------------------------------------------------------- data (--write-data)

def write_data():
    """The boundary files and the sphere models. Fuselage: the boundary of
    tests/common/coons.rs `fuselage_top` — iso-curves of surfaces 0, 1, 4, 5 (vericad's
    order), 40 segments per patch, evaluated from the surfaces as `vericad convert` writes
    them to JSON. Spheres: the unit sphere between longitudes 0..1.6 (or 0..0.65 and
    0.85..1.6: a gap of 0.2 rad) and latitudes ±0.6, as rational B-spline faces written
    by OCCT; boundary: latitudes ±0.4 and meridians 0.2, 1.3, 64 segments each (the
    situations of tests/coons.rs, Figures 8 and 9)."""
    os.makedirs(DATA, exist_ok=True)
    tmp = tempfile.mkdtemp()
    js = os.path.join(tmp, "fuselage.json")
    subprocess.run([VERICAD, "convert", os.path.join(ROOT, CASES[0][1]), js], check=True)
    model = json.load(open(js))

    def surface(k):
        s = model["surfaces"][k]
        assert "weights" not in s
        return from_json(s)

    surf = {k: surface(k) for k in (0, 1, 4, 5)}

    def iso(k, a, b):
        pts = []
        for i in range(41):
            t = i / 40
            p = surf[k].Value(a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]))
            pts.append([p.X(), p.Y(), p.Z()])
        return pts

    def joined(a, b):
        return a[:-1] + b

    sides = [
        joined(iso(0, (2.5, 0.5), (3.0, 0.5)), iso(4, (0.0, 0.5), (0.5, 0.5))),
        joined(iso(4, (0.5, 0.5), (0.5, 1.0)), iso(5, (0.5, 0.0), (0.5, 0.5))),
        joined(iso(5, (0.5, 0.5), (0.0, 0.5)), iso(1, (3.0, 0.5), (2.5, 0.5))),
        joined(iso(1, (2.5, 0.5), (2.5, 0.0)), iso(0, (2.5, 1.0), (2.5, 0.5))),
    ]
    with open(os.path.join(DATA, "fuselage-top.json"), "w") as f:
        json.dump({"curves": [{"polyline": s} for s in sides]}, f)

    def sph(lon, lat):
        return [math.cos(lat) * math.cos(lon), math.cos(lat) * math.sin(lon), math.sin(lat)]

    n = 64
    lat = lambda phi, a0, a1: [sph(a0 + (a1 - a0) * i / n, phi) for i in range(n + 1)]
    mer = lambda a, p0, p1: [sph(a, p0 + (p1 - p0) * i / n) for i in range(n + 1)]
    sides = [lat(-0.4, 0.2, 1.3), mer(1.3, -0.4, 0.4), lat(0.4, 1.3, 0.2), mer(0.2, 0.4, -0.4)]
    with open(os.path.join(DATA, "sphere.json"), "w") as f:
        json.dump({"curves": [{"polyline": s, "name": n} for s, n in zip(sides, ["south", "east", "north", "west"])]}, f)

    ss = o.Geom.Geom_SphericalSurface(o.gp.gp_Ax3(), 1.0)
    for name, pieces in [("one", [(0.0, 1.6)]), ("gap", [(0.0, 0.65), (0.85, 1.6)])]:
        comp = o.TopoDS.TopoDS_Compound()
        b = o.BRep.BRep_Builder()
        b.MakeCompound(comp)
        for a0, a1 in pieces:
            bs = o.GeomConvert.GeomConvert.SurfaceToBSplineSurface_s(
                o.Geom.Geom_RectangularTrimmedSurface(ss, a0, a1, -0.6, 0.6))
            b.Add(comp, o.BRepBuilderAPI.BRepBuilderAPI_MakeFace(bs, 1e-9).Face())
        w = o.STEPControl.STEPControl_Writer()
        w.Transfer(comp, o.STEPControl.STEPControl_StepModelType.STEPControl_AsIs)
        w.Write(os.path.join(DATA, f"sphere-{name}.step"))


# ---------------------------------------------------------------- OCCT helpers

def pnt(p, scale):
    return o.gp.gp_Pnt(p[0] * scale, p[1] * scale, p[2] * scale)


class Originals:
    """The original faces (OCCT's reading of the model file) and the distance to them."""

    def __init__(self, path):
        self.compound = read_step_faces(path)
        self.surfaces = []
        ex = o.TopExp.TopExp_Explorer(self.compound, o.TopAbs.TopAbs_ShapeEnum.TopAbs_FACE)
        while ex.More():
            self.surfaces.append(o.BRep.BRep_Tool.Surface_s(o.TopoDS.TopoDS.Face(ex.Current())))
            ex.Next()

    def perpendicular(self, p, foot):
        """Does p lie on the normal line of a face through the foot (within GAP_ANGLE)?"""
        w = o.gp.gp_Vec(foot, p)
        for s in self.surfaces:
            pr = o.GeomAPI.GeomAPI_ProjectPointOnSurf(foot, s)
            if pr.NbPoints() == 0 or pr.LowerDistance() > 1e-6 * max(1.0, w.Magnitude()):
                continue
            u, v = pr.LowerDistanceParameters()
            props = o.GeomLProp.GeomLProp_SLProps(s, u, v, 1, 1e-12)
            if props.IsNormalDefined():
                n = props.Normal()
                if abs(w.Dot(o.gp.gp_Vec(n.XYZ()))) >= math.cos(math.radians(GAP_ANGLE)) * w.Magnitude():
                    return True
        return False

    def distance(self, p, tol):
        """(distance in OCCT's unit, foot point, over a gap?) for gp_Pnt p. Over a gap: the
        closest point lies on an edge or vertex, farther than tol, and p is not on a face's
        normal through it (within GAP_ANGLE) — the originals end there."""
        dss = o.BRepExtrema.BRepExtrema_DistShapeShape(o.BRepBuilderAPI.BRepBuilderAPI_MakeVertex(p).Vertex(), self.compound)
        if not dss.IsDone() or dss.NbSolution() == 0:
            return None, None, True
        d, foot = dss.Value(), dss.PointOnShape2(1)
        if d <= tol or any(dss.SupportTypeShape2(k) == o.BRepExtrema.BRepExtrema_SupportType.BRepExtrema_IsInFace
                           for k in range(1, dss.NbSolution() + 1)):
            return d, foot, False
        return d, foot, not self.perpendicular(p, foot)


def fit_side(points, scale, tol_mm):
    """GeomAPI_PointsToBSpline through the polyline's vertices; ends pinned to its ends."""
    arr = o.collections.Array1_gp_Pnt(1, len(points))
    for i, p in enumerate(points):
        arr.SetValue(i + 1, pnt(p, scale))
    c = o.GeomAPI.GeomAPI_PointsToBSpline(arr, 3, 8, o.GeomAbs.GeomAbs_Shape.GeomAbs_C2, tol_mm).Curve()
    c.SetPole(1, arr.Value(1))
    c.SetPole(c.NbPoles(), arr.Value(len(points)))
    # how far the fitted curve strays from the polyline's vertices (local projection)
    dev = max(o.GeomAPI.GeomAPI_ProjectPointOnCurve(arr.Value(i), c).LowerDistance() for i in range(1, len(points) + 1))
    return c, dev


def loop_order(sides):
    """Orient the polylines as vericad does: side 0 towards the end nearer side 1, every later
    side starting at the end nearer the previous side's end."""
    d = lambda a, b: math.dist(a, b)
    s0, s1 = sides[0], sides[1]
    if min(d(s0[0], s1[0]), d(s0[0], s1[-1])) < min(d(s0[-1], s1[0]), d(s0[-1], s1[-1])):
        s0 = s0[::-1]
    out = [s0]
    for s in sides[1:]:
        out.append(s if d(s[0], out[-1][-1]) <= d(s[-1], out[-1][-1]) else s[::-1])
    return out


def point_in_polygon(x, y, poly):
    inside = False
    for (x0, y0), (x1, y1) in zip(poly, poly[1:] + poly[:1]):
        if (y0 > y) != (y1 > y) and x < x0 + (y - y0) * (x1 - x0) / (y1 - y0):
            inside = not inside
    return inside


def measure(surface, originals, scale, tol, keep=None, truth=None):
    """Distances (model unit) at the LATTICE × LATTICE cell centres of the surface's parameter
    square to the originals: (max, rms, kept samples, samples over a gap, samples outside
    `keep`, largest `truth` over the gap samples)."""
    u0, u1, v0, v1 = surface.Bounds()
    ds, gap, outside, bridge = [], 0, 0, None
    for i in range(LATTICE):
        for j in range(LATTICE):
            u, v = u0 + (u1 - u0) * (i + 0.5) / LATTICE, v0 + (v1 - v0) * (j + 0.5) / LATTICE
            if keep is not None and not keep(u, v):
                outside += 1
                continue
            p = surface.Value(u, v)
            dist, _, over_gap = originals.distance(p, tol * scale)
            if over_gap:
                gap += 1
                if truth is not None:
                    bridge = max(bridge or 0.0, truth(p))
                continue
            ds.append(dist / scale)
    rms = math.sqrt(sum(d * d for d in ds) / len(ds)) if ds else float("nan")
    return max(ds) if ds else float("nan"), rms, len(ds), gap, outside, bridge


def plate(curves, points, tol_mm):
    """GeomPlate through the boundary curves (G0) and optional points; approximated."""
    b = o.GeomPlate.GeomPlate_BuildPlateSurface(3, 15, 3, 1e-5, tol_mm / 10)
    for c in curves:
        b.Add(o.GeomPlate.GeomPlate_CurveConstraint(o.GeomAdaptor.GeomAdaptor_Curve(c), 0, 40, tol_mm / 10))
    for p in points:
        b.Add(o.GeomPlate.GeomPlate_PointConstraint(p, 0, tol_mm / 10))
    b.Perform()
    if not b.IsDone():
        raise RuntimeError("GeomPlate_BuildPlateSurface failed")
    dmax = max(tol_mm, 10 * b.G0Error())
    ap = o.GeomPlate.GeomPlate_MakeApprox(b.Surface(), tol_mm, 32, 8, dmax, 0, o.GeomAbs.GeomAbs_Shape.GeomAbs_C1)
    s = ap.Surface()
    # the boundary's polygon in the plate's parameter plane, to keep samples inside it
    poly = []
    c2 = b.Curves2d()
    for k in range(c2.Lower(), c2.Upper() + 1):
        c = c2.Value(k)
        t0, t1 = c.FirstParameter(), c.LastParameter()
        for i in range(64):
            q = c.Value(t0 + (t1 - t0) * i / 64)
            poly.append((q.X(), q.Y()))
    return s, b.G0Error(), poly


# ---------------------------------------------------------------- one case

def run_case(label, model, boundary, tol, truth, rows):
    model, boundary = os.path.join(ROOT, model), os.path.join(ROOT, boundary)
    tmp = tempfile.mkdtemp()
    out, rep = os.path.join(tmp, "patch.igs"), os.path.join(tmp, "report.json")
    t0 = time.perf_counter()
    r = subprocess.run([VERICAD, "coons", model, "--boundary", boundary, "--tol", str(tol),
                        "--out", out, "--report", rep], capture_output=True, text=True)
    t_vericad = time.perf_counter() - t0
    if not os.path.exists(rep):
        print(r.stdout, r.stderr)
        raise RuntimeError(f"vericad coons failed on {label} (exit {r.returncode})")
    report = json.load(open(rep))
    unit = report.get("unit") or "mm"
    scale = MM_PER_UNIT[unit]
    tol_mm = tol * scale
    faces = Originals(model)
    sv = read_iges_surface(out, bspline=True)
    mx, rms, n, gap, _, bridge = measure(sv, faces, scale, tol, truth=truth)
    ap = report["approximant"]
    rows.append((label, f"vericad coons, {ap['m']} × {ap['n']} (exit {r.returncode})",
                 sv.NbUPoles(), sv.NbVPoles(), t_vericad, mx, rms, n, gap, bridge,
                 f"its own samples (17): max {ap['evidence']['max_error']:.3e}, {ap['evidence']['skipped_gap']} over gaps; "
                 f"{ap['fill']['filled']} artificial points; {seconds(ap['seconds'])} inside"))

    sides = loop_order([c["polyline"] for c in json.load(open(boundary))["curves"]])
    t0 = time.perf_counter()
    fitted = [fit_side(s, scale, tol_mm / 10) for s in sides]
    curves = [c for c, _ in fitted]
    coons = o.GeomFill.GeomFill_BSplineCurves(*curves, o.GeomFill.GeomFill_FillingStyle.GeomFill_CoonsStyle).Surface()
    t_coons = time.perf_counter() - t0
    fit_dev = max(d for _, d in fitted) / scale
    mx, rms, n, gap, _, bridge = measure(coons, faces, scale, tol, truth=truth)
    rows.append((label, "OCCT GeomFill Coons", coons.NbUPoles(), coons.NbVPoles(), t_coons, mx, rms, n, gap, bridge,
                 f"curve fit ≤ {fit_dev:.2g} from the polyline vertices"))

    for with_points in (False, True):
        name = "OCCT GeomPlate (b), curves + points" if with_points else "OCCT GeomPlate (a), curves"
        t0 = time.perf_counter()
        pts = []
        if with_points:
            # as many points as vericad's final grid has interior points, (M − 1) × (N − 1)
            u0, u1, v0, v1 = coons.Bounds()
            for i in range(1, ap["m"]):
                for j in range(1, ap["n"]):
                    p = coons.Value(u0 + (u1 - u0) * i / ap["m"], v0 + (v1 - v0) * j / ap["n"])
                    _, foot, over_gap = faces.distance(p, tol_mm)
                    if not over_gap:
                        pts.append(foot)
        t_project = time.perf_counter() - t0
        try:
            s, g0, poly = plate(curves, pts, tol_mm)
        except Exception as e:  # report, do not fake
            rows.append((label, name, 0, 0, time.perf_counter() - t0, float("nan"), float("nan"), 0, 0, None, f"failed: {e}"))
            continue
        t_plate = time.perf_counter() - t0
        mx, rms, n, gap, outside, bridge = measure(s, faces, scale, tol, keep=lambda u, v: point_in_polygon(u, v, poly), truth=truth)
        note = f"G0 error {g0 / scale:.2g}; {outside} lattice points outside the boundary"
        if with_points:
            note = f"{len(pts)} point constraints (projecting them: {t_project:.2f} s); " + note
        rows.append((label, name, s.NbUPoles(), s.NbVPoles(), t_plate, mx, rms, n, gap, bridge, note))
    return unit


def seconds(t):
    return f"{t:.2f} s" if t >= 0.1 else f"{t * 1000:.2g} ms"


def main():
    try:
        from importlib.metadata import version
        print(f"OCP (Open CASCADE) {version('cadquery-ocp-novtk')}; vericad {VERICAD}\n")
    except Exception:
        pass
    rows, units = [], {}
    for label, model, boundary, tol, truth in CASES:
        units[label] = (run_case(label, model, boundary, tol, truth, rows), tol)
    print("| case (unit, tol) | surface | poles u × v | build time | max distance | RMS | samples | over a gap | analytic, over the gap | notes |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for label, name, nu, nv, t, mx, rms, n, gap, bridge, note in rows:
        unit, tol = units[label]
        b = "—" if bridge is None else f"{bridge:.2e}"
        print(f"| {label} ({unit}, {tol:g}) | {name} | {nu} × {nv} = {nu * nv} | {seconds(t)} | {mx:.3e} | {rms:.2e} | {n} | {gap} | {b} | {note} |")


if __name__ == "__main__":
    if sys.argv[1:] == ["--write-data"]:
        write_data()
    else:
        main()
