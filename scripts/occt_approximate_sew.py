#!/usr/bin/env python3
"""vericad approximate (layouts of connected Coons approximants) read back and sewn by Open CASCADE.

For every case (a model file and a layout file, scripts/data/coons/layout-*):

1. `vericad approximate MODEL --layout L --tol T --out X.igs --report R.json`, and again with
   `--out X.step` (same inputs; the report of each run is kept). vericad writes the
   approximants as one open shell (STEP `SHELL_BASED_SURFACE_MODEL` / `OPEN_SHELL` of
   `ADVANCED_FACE`s; IGES 514 / 510 / 508 / 504 / 502); its report's `shell` counts faces,
   shared, free and other edges.
2. Open CASCADE reads the file (IGESControl_Reader / STEPControl_Reader, `OneShape()`; OCCT
   converts lengths to millimetres). Every edge of every face is matched to the layout
   curve it runs along: 5 interior points of the edge (divided back to the model's unit), the
   layout curve whose polyline (or densely sampled model curve) is nearest to all 5 — the
   largest of those 5 distances is reported as the matching distance (`match`), a check of
   the units and of the geometry; each face is matched to the approximant whose four sides
   its four edges are.
3. As read, no sewing: the shape type; shells and faces (TopExp_Explorer); distinct edges
   and vertices; edge -> faces (TopExp::MapShapesAndAncestors): edges on one, two, more
   faces; the edges on two faces matched to curves and compared with the report's shared
   curves (each on the faces of the two approximants sharing it, used once FORWARD and once
   REVERSED), those on one face with `open_curves`; `BRepCheck_Analyzer(shape).IsValid()`;
   ShapeAnalysis_FreeBounds (closed / open free wires, their edges); ShapeAnalysis_Shell
   (CheckOrientedShells with free edges, FreeEdges); the largest edge and vertex tolerance;
   vericad's `shell` beside it.
4. Per shared curve of the layout (vericad's report `shared`), on the shape as read: are the
   two faces' edges along it one OCCT edge (`IsSame`); the largest distance, at 201 common
   parameters, between its 3D curve and its curve on each face (pcurve on the surface), and
   between the two curves on surface; is the edge's 3D curve a boundary iso-curve of each
   face's surface with the same poles, weights and knots bit for bit (`poles identical`).
   Should the edges be two (no shell read), the old comparison: `BRepExtrema_DistShapeShape`
   from 201 points of each edge to the other, and the two edge curves bit for bit.
5. Secondary: `BRepBuilderAPI_Sewing` of the faces as read (at tol: nothing should be left to
   join), and of the faces taken apart (each copied alone with BRepBuilderAPI_Copy, so that
   no edge is shared), at the layout's tol converted to millimetres (`sewing tol`), and
   again at a tight tolerance, 1e-12 × the diagonal of the faces' bounding box. Reported:
   faces and shells in the sewn shape, `NbFreeEdges`, `NbContigousEdges`,
   `NbMultipleEdges`, `NbDegeneratedShapes`; the free edges and the contiguous edges matched
   to layout curves as in 2 and compared with vericad's report (`open_curves`, the curves of
   `shared`); the edge -> face count of the sewn shape (edges on one face, on two); the largest
   edge tolerance (`BRep_Tool.Tolerance`) of the faces as read and of the sewn shape;
   `BRepCheck_Analyzer(sewn).IsValid()`.
6. Control for the tight sewing: of the faces taken apart, the last approximant's face, moved
   by 1e-9 … 1e-6 mm perpendicular to one of its shared edges (`BRepBuilderAPI_Transform`),
   sewn at the tight tolerance again — does the tight sewing still join what no longer
   coincides?
7. Per shared curve also: the largest distance (41 points per edge, both edges) of the edges
   to the layout curve they replace and to the original surface — analytic for the sphere
   (`|‖p‖ − 1|`) and the bicubic graph (`|z − f(x, y)|`), OCCT's distance to the STEP file's
   faces for the fuselage.

All distances in the tables are in the model's unit (OCCT's millimetres divided back); the
sewing tolerances are given in both. Nothing here is a proof: the edge distances are
measurements at finitely many points; the topology counts and the bit-for-bit pole
comparison are exact but only of what OCCT read.

Usage:
  cargo build --release
  python3 scripts/occt_approximate_sew.py
  python3 scripts/occt_approximate_sew.py --write-data   # regenerate scripts/data/coons/layout-*
Environment: VERICAD (path of the binary; default target/release/vericad).
"""
import json, math, os, subprocess, sys, tempfile

import OCP.OCP as o

from occt_io import MM_PER_UNIT, from_json

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..")
DATA = os.path.join(HERE, "data", "coons")
VERICAD = os.environ.get("VERICAD", os.path.join(ROOT, "target", "release", "vericad"))
FUSELAGE = "tests/data/public/occt-bug28366_fuselage.stp"
EDGE_SAMPLES = 201   # points per edge for the edge-to-edge distance
TIGHT = 1e-12        # tight sewing tolerance, relative to the bounding-box diagonal
CONTROL_SHIFTS = (1e-9, 1e-8, 1e-7, 1e-6)   # mm: a face moved off its neighbour, sewn at TIGHT

def unit_sphere(p):
    return abs(math.sqrt(p[0] ** 2 + p[1] ** 2 + p[2] ** 2) - 1.0)


def graph_vertical(p):
    return abs(p[2] - _graph(p[0], p[1]))


def original_faces(path):
    """Distance (model unit) to the model file's faces as OCCT reads them (STEP)."""
    rd = o.STEPControl.STEPControl_Reader()
    rd.ReadFile(os.path.join(ROOT, path))
    rd.TransferRoots()
    comp = o.TopoDS.TopoDS_Compound()
    b = o.BRep.BRep_Builder()
    b.MakeCompound(comp)
    for f in subshapes(rd.OneShape(), FACE):
        b.Add(comp, f)

    def dist(p, scale):
        v = o.BRepBuilderAPI.BRepBuilderAPI_MakeVertex(o.gp.gp_Pnt(*(x * scale for x in p))).Vertex()
        return o.BRepExtrema.BRepExtrema_DistShapeShape(v, comp).Value() / scale
    return dist


CASES = [
    # (label, model, layout, tol in model units, truth: distance of a point (model unit) to
    #  the original surface — analytic, or OCCT's distance to the model file's faces)
    ("two sphere pieces, gap 0.2 rad, 2 × 1 (left asks N = 16)",
     "scripts/data/coons/layout-sphere-model.json", "scripts/data/coons/layout-sphere.json", 1e-4,
     ("analytic |‖p‖ − 1|", lambda: lambda p, scale: unit_sphere(p))),
    ("bicubic graph, 2 × 2, 4 shared polylines",
     "scripts/data/coons/layout-bicubic-model.json", "scripts/data/coons/layout-bicubic.json", 1e-4,
     ("vertical |z − f(x, y)|", lambda: lambda p, scale: graph_vertical(p))),
    ("bicubic graph, 2 × 2, tol 3e-5 (rebuild)",
     "scripts/data/coons/layout-bicubic-model.json", "scripts/data/coons/layout-bicubic.json", 3e-5,
     ("vertical |z − f(x, y)|", lambda: lambda p, scale: graph_vertical(p))),
    ("fuselage, 2 × 1 sharing the section joint",
     FUSELAGE, "scripts/data/coons/layout-fuselage.json", 1e-5,
     ("OCCT distance to the STEP faces", lambda: original_faces(FUSELAGE))),
]


# ---------------------------------------------------------------- data (--write-data)
# The constructions of tests/coons_layout.rs and src/spline/construct.rs (`arc`,
# `revolve_curve_range`), step by step in the same floating-point operations, so that the
# model files hold the test's control points bit for bit (checked against a Rust program
# calling vericad's own functions when this was written).

def _add(a, b): return [a[i] + b[i] for i in range(3)]
def _sub(a, b): return [a[i] - b[i] for i in range(3)]
def _scale(a, s): return [a[i] * s for i in range(3)]


def _dot(a, b):
    s = 0.0
    for i in range(3):
        s = s + a[i] * b[i]
    return s


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


WORLD = dict(o=[0.0, 0.0, 0.0], x=[1.0, 0.0, 0.0], y=[0.0, 1.0, 0.0], z=[0.0, 0.0, 1.0])


def _at(f, a, b, c):
    return _add(_add(_add(f["o"], _scale(f["x"], a)), _scale(f["y"], b)), _scale(f["z"], c))


def _cartesian(p, w):
    """What vericad stores and writes: the homogeneous point p·w divided by w again."""
    return [(p[i] * w) / w for i in range(3)]


def _arc(f, r, a0, a1):
    sweep = min(max(a1 - a0, 1e-300), 2 * math.pi)
    n = int(max(math.ceil(sweep / (math.pi / 2) - 1e-12), 1.0))
    d = sweep / n
    w1 = math.cos(d / 2.0)
    pts, ws, knots = [_at(f, r * math.cos(a0), r * math.sin(a0), 0.0)], [1.0], [0.0] * 3
    for k in range(n):
        s, e = a0 + k * d, a0 + (k + 1) * d
        m = (s + e) / 2.0
        pts.append(_at(f, r / w1 * math.cos(m), r / w1 * math.sin(m), 0.0))
        ws.append(w1)
        pts.append(_at(f, r * math.cos(e), r * math.sin(e), 0.0))
        ws.append(1.0)
        if k + 1 < n:
            knots += [(k + 1) / n] * 2
    knots += [1.0] * 3
    return dict(degree=2, knots=knots, control_points=[_cartesian(p, w) for p, w in zip(pts, ws)], weights=ws)


def _revolve_range(o_, z, c, a0, a1):
    circ = _arc(WORLD, 1.0, a0, a1)
    rows, wrows = [], []
    for cp, wc in zip(circ["control_points"], circ["weights"]):
        row, wr = [], []
        for p, wp in zip(c["control_points"], c["weights"]):
            rel = _sub(p, o_)
            h = _dot(rel, z)
            radial = _sub(rel, _scale(z, h))
            y = _cross(z, radial)
            q = _add(_add(_add(o_, _scale(z, h)), _scale(radial, cp[0])), _scale(y, cp[1]))
            w = wc * wp
            row.append(_cartesian(q, w))
            wr.append(w)
        rows.append(row)
        wrows.append(wr)
    return dict(degree_u=2, degree_v=c["degree"], knots_u=circ["knots"], knots_v=c["knots"],
                control_points=rows, weights=wrows)


def _sphere_piece(a0, a1):
    meridian_plane = dict(o=[0.0] * 3, x=[1.0, 0.0, 0.0], y=[0.0, 0.0, 1.0], z=[0.0, -1.0, 0.0])
    return _revolve_range([0.0] * 3, [0.0, 0.0, 1.0], _arc(meridian_plane, 1.0, -0.6, 0.6), a0, a1)


def _latitude(phi, a0, a1):
    return _arc(dict(WORLD, o=[0.0, 0.0, math.sin(phi)]), math.cos(phi), a0, a1)


def _meridian(a, p0, p1):
    x, y = [math.cos(a), math.sin(a), 0.0], [0.0, 0.0, 1.0]
    return _arc(dict(o=[0.0] * 3, x=x, y=y, z=_cross(x, y)), 1.0, p0, p1)


def _model(surfaces, curves):
    return {"format": "vericad-model", "version": 1, "unit": None, "curves": curves,
            "surfaces": surfaces, "patch_sets": []}


SPHERE_LAYOUT = """{"curves": {"sw": {"curve": 0}, "se": {"curve": "south east"}, "nw": {"curve": 2},
            "ne": {"curve": 3}, "w": {"curve": 4}, "mid": {"curve": 5}, "e": {"curve": 6}},
           "approximants": [
             {"name": "left", "n": 16, "sides": [{"curve": "sw"}, {"curve": "mid"}, {"curve": "nw"}, {"curve": "w"}]},
             {"name": "right", "sides": [{"curve": "se"}, {"curve": "e"}, {"curve": "ne"}, {"curve": "mid"}]}
           ]}
"""

Z = [[0.0, 0.1, -0.05, 0.0], [0.1, 0.2, 0.1, -0.1], [0.0, -0.1, 0.15, 0.05], [0.05, 0.0, 0.1, 0.0]]


def _bernstein(t):
    s = 1.0 - t
    return [s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t]


def _graph(x, y):
    """z = f(x, y) of the test's bicubic patch, summed in the test's order (no compensated sum)."""
    bu, bv = _bernstein(x / 2.0), _bernstein(y / 2.0)
    total = 0.0
    for i in range(4):
        row = 0.0
        for j in range(4):
            row = row + bu[i] * bv[j] * Z[i][j]
        total = total + row
    return total


def _grid_layout():
    def line(a, b):
        pts = []
        for k in range(65):
            t = k / 64.0
            x, y = a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])
            pts.append([x, y, _graph(x, y)])
        return {"polyline": pts}
    xs = [0.2, 1.0, 1.8]
    curves = {}
    for r, y in enumerate(xs):
        for c in range(2):
            curves[f"h{r}{c}"] = line([xs[c], y], [xs[c + 1], y])
    for c, x in enumerate(xs):
        for r in range(2):
            curves[f"v{c}{r}"] = line([x, xs[r]], [x, xs[r + 1]])
    aps = []
    for r in range(2):
        for c in range(2):
            aps.append({"name": f"q{r}{c}", "sides": [{"curve": f"h{r}{c}"}, {"curve": f"v{c + 1}{r}"},
                                                       {"curve": f"h{r + 1}{c}"}, {"curve": f"v{c}{r}"}]})
    return {"curves": curves, "approximants": aps}


def _fuselage_layout(tmp):
    """The boundary of fuselage-top.json (scripts/occt_coons_fill.py; tests/common/coons.rs
    `fuselage_top`) cut in two along the joint of the front and rear sections: sides 0 and 2
    split at their vertex 40 (where they cross the joint), and the joint itself — vericad's
    surface 0 at u = 3 for v 0.5..1 followed by surface 1 at u = 3 for v 0..0.5, 40 segments
    each (evaluated by OCCT from the surfaces as `vericad convert` writes them)."""
    top = json.load(open(os.path.join(DATA, "fuselage-top.json")))["curves"]
    s0, s1, s2, s3 = (c["polyline"] for c in top)
    js = os.path.join(tmp, "fuselage.json")
    subprocess.run([VERICAD, "convert", os.path.join(ROOT, FUSELAGE), js], check=True, capture_output=True)
    model = json.load(open(js))

    def surface(k):
        s = model["surfaces"][k]
        assert "weights" not in s
        return from_json(s)

    def iso(srf, a, b):
        pts = []
        for i in range(41):
            t = i / 40
            p = srf.Value(a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]))
            pts.append([p.X(), p.Y(), p.Z()])
        return pts
    f0, f1 = surface(0), surface(1)
    joint = iso(f0, (3.0, 0.5), (3.0, 1.0))[:-1] + iso(f1, (3.0, 0.0), (3.0, 0.5))
    # the joint's ends are the split vertices of sides 0 and 2 (distances, model unit)
    ends = (math.dist(joint[0], s0[40]), math.dist(joint[-1], s2[40]))
    curves = {
        "south front": {"polyline": s0[:41]}, "south rear": {"polyline": s0[40:]},
        "east": {"polyline": s1},
        "north rear": {"polyline": s2[:41]}, "north front": {"polyline": s2[40:]},
        "west": {"polyline": s3}, "joint": {"polyline": joint},
    }
    aps = [
        {"name": "front", "sides": [{"curve": "south front"}, {"curve": "joint"}, {"curve": "north front"}, {"curve": "west"}]},
        {"name": "rear", "sides": [{"curve": "south rear"}, {"curve": "east"}, {"curve": "north rear"}, {"curve": "joint"}]},
    ]
    return {"curves": curves, "approximants": aps}, ends


def write_data():
    os.makedirs(DATA, exist_ok=True)
    pieces = [dict(name=f"piece {k}", **_sphere_piece(a0, a1)) for k, (a0, a1) in enumerate([(0.0, 0.65), (0.85, 1.6)])]
    curves = [dict(name=n, **c) for n, c in [
        ("south west", _latitude(-0.4, 0.2, 0.75)), ("south east", _latitude(-0.4, 0.75, 1.3)),
        ("north west", _latitude(0.4, 0.2, 0.75)), ("north east", _latitude(0.4, 0.75, 1.3)),
        ("west", _meridian(0.2, -0.4, 0.4)), ("middle", _meridian(0.75, -0.4, 0.4)),
        ("east", _meridian(1.3, -0.4, 0.4))]]
    with open(os.path.join(DATA, "layout-sphere-model.json"), "w") as f:
        json.dump(_model(pieces, curves), f, indent=1)
    with open(os.path.join(DATA, "layout-sphere.json"), "w") as f:
        f.write(SPHERE_LAYOUT)
    pts = [[[2.0 * i / 3.0, 2.0 * j / 3.0, z] for j, z in enumerate(row)] for i, row in enumerate(Z)]
    k = [0.0] * 4 + [1.0] * 4
    bicubic = dict(name="bicubic", degree_u=3, degree_v=3, knots_u=k, knots_v=k, control_points=pts)
    with open(os.path.join(DATA, "layout-bicubic-model.json"), "w") as f:
        json.dump(_model([bicubic], []), f, indent=1)
    with open(os.path.join(DATA, "layout-bicubic.json"), "w") as f:
        json.dump(_grid_layout(), f)
    tmp = tempfile.mkdtemp()
    lay, ends = _fuselage_layout(tmp)
    print(f"fuselage joint: its ends are {ends[0]:.3g} and {ends[1]:.3g} (foot) from the split vertices")
    with open(os.path.join(DATA, "layout-fuselage.json"), "w") as f:
        json.dump(lay, f)


# ---------------------------------------------------------------- the layout's curves, as points

def _nurbs_point(c, t):
    """Rational de Boor on homogeneous points (model curves of the JSON model)."""
    p, U = c["degree"], c["knots"]
    P, W = c["control_points"], c.get("weights") or [1.0] * len(c["control_points"])
    n = len(P) - 1
    k = p
    while k < n and not (U[k] <= t < U[k + 1]):
        k += 1
    d = [[P[j][0] * W[j], P[j][1] * W[j], P[j][2] * W[j], W[j]] for j in range(k - p, k + 1)]
    for r in range(1, p + 1):
        for j in range(p, r - 1, -1):
            i = j + k - p
            den = U[i + p - r + 1] - U[i]
            a = 0.0 if den == 0 else (t - U[i]) / den
            d[j] = [(1 - a) * d[j - 1][m] + a * d[j][m] for m in range(4)]
    return [d[p][0] / d[p][3], d[p][1] / d[p][3], d[p][2] / d[p][3]]


def layout_curves(model_path, layout):
    """{curve id: list of points (model unit)} — polylines' vertices; model curves sampled at
    1024 parameters (JSON models only)."""
    model = None
    out = {}
    for cid, e in layout["curves"].items():
        if "polyline" in e:
            out[cid] = e["polyline"]
            continue
        if model is None:
            model = json.load(open(model_path))
        ref = e["curve"]
        c = model["curves"][ref] if isinstance(ref, int) else next(c for c in model["curves"] if c["name"] == ref)
        U = c["knots"]
        a, b = U[c["degree"]], U[-c["degree"] - 1]
        out[cid] = [_nurbs_point(c, a + (b - a) * i / 1024) for i in range(1024)] + [_nurbs_point(c, b - 1e-15 * (b - a))]
    return out


def _seg_dist(p, a, b):
    ab = [b[i] - a[i] for i in range(3)]
    L = sum(x * x for x in ab)
    t = 0.0 if L == 0 else max(0.0, min(1.0, sum((p[i] - a[i]) * ab[i] for i in range(3)) / L))
    return math.dist(p, [a[i] + t * ab[i] for i in range(3)])


def _poly_dist(p, poly):
    return min(_seg_dist(p, a, b) for a, b in zip(poly, poly[1:]))


# ---------------------------------------------------------------- OCCT helpers

FACE, EDGE, SHELL = (o.TopAbs.TopAbs_ShapeEnum.TopAbs_FACE, o.TopAbs.TopAbs_ShapeEnum.TopAbs_EDGE,
                     o.TopAbs.TopAbs_ShapeEnum.TopAbs_SHELL)
WIRE, VERTEX = o.TopAbs.TopAbs_ShapeEnum.TopAbs_WIRE, o.TopAbs.TopAbs_ShapeEnum.TopAbs_VERTEX


def subshapes(shape, kind):
    m = o.collections.IndexedMap_TopoDS_Shape_TopTools_ShapeMapHasher()
    o.TopExp.TopExp.MapShapes_s(shape, kind, m)
    return [m.FindKey(i) for i in range(1, m.Extent() + 1)]


def read(path):
    """(the shape OCCT reads — `OneShape()` after `TransferRoots()` —, its faces)."""
    rd = o.IGESControl.IGESControl_Reader() if path.endswith(".igs") else o.STEPControl.STEPControl_Reader()
    if rd.ReadFile(path) != o.IFSelect.IFSelect_ReturnStatus.IFSelect_RetDone:
        raise RuntimeError(f"OCCT cannot read {path}")
    rd.TransferRoots()
    shape = rd.OneShape()
    return shape, [o.TopoDS.TopoDS.Face(f) for f in subshapes(shape, FACE)]


def explore(shape, kind):
    """How many sub-shapes of `kind` TopExp_Explorer visits (occurrences, not distinct)."""
    ex, n = o.TopExp.TopExp_Explorer(shape, kind), 0
    while ex.More():
        n += 1
        ex.Next()
    return n


def shape_name(shape):
    return str(shape.ShapeType()).split(".")[-1].replace("TopAbs_", "")


def edge_faces(shape):
    """[(edge, [faces it lies on])] over the distinct edges of `shape`
    (TopExp::MapShapesAndAncestors edge -> face)."""
    m = o.collections.IndexedDataMap_TopoDS_Shape_List_TopoDS_Shape_TopTools_ShapeMapHasher()
    o.TopExp.TopExp.MapShapesAndAncestors_s(shape, EDGE, FACE, m)
    return [(o.TopoDS.TopoDS.Edge(m.FindKey(i)), [o.TopoDS.TopoDS.Face(f) for f in m.FindFromIndex(i)])
            for i in range(1, m.Extent() + 1)]


def orientation_in(edge, face):
    """The orientations (FORWARD / REVERSED ...) with which `face` uses `edge`."""
    out, ex = [], o.TopExp.TopExp_Explorer(face, EDGE)
    while ex.More():
        if ex.Current().IsSame(edge):
            out.append(ex.Current().Orientation())
        ex.Next()
    return out


def as_read(shape, faces, curves, scale, report, face_of):
    """What OCCT reads, before any sewing: shells and faces, edges on one / two / more faces,
    those edges matched to layout curves, validity, free bounds, shell orientation."""
    ef = edge_faces(shape)
    on1 = [e for e, fs in ef if len(fs) == 1]
    on2 = [(e, fs) for e, fs in ef if len(fs) == 2]
    on3 = [e for e, fs in ef if len(fs) > 2]
    free_ids = sorted(match_edge(e, curves, scale)[0] for e in on1)
    shared_ids = sorted(match_edge(e, curves, scale)[0] for e, _ in on2)
    want_shared = sorted(s["curve"] for s in report["shared"])
    # each edge on two faces lies on the faces of the two approximants that share its curve

    def face_index(f):
        return next(k for k, g in enumerate(faces) if g.IsSame(f))
    pairs_ok = True
    for e, fs in on2:
        cid = match_edge(e, curves, scale)[0]
        s = next((s for s in report["shared"] if s["curve"] == cid), None)
        want = None if s is None else {face_of.get(a) for a in s["approximants"]}
        if want is None or {face_index(f) for f in fs} != want:
            pairs_ok = False
    # a shared edge used once FORWARD and once REVERSED (as the faces lie in the shell)
    opposite = sum(1 for e, fs in on2
                   if sorted(str(x) for f in fs for x in orientation_in(e, f)) ==
                   sorted([str(o.TopAbs.TopAbs_Orientation.TopAbs_FORWARD), str(o.TopAbs.TopAbs_Orientation.TopAbs_REVERSED)]))
    fb = o.ShapeAnalysis.ShapeAnalysis_FreeBounds(shape)
    closed, opened = fb.GetClosedWires(), fb.GetOpenWires()
    sa = o.ShapeAnalysis.ShapeAnalysis_Shell()
    sa.LoadShells(shape)
    bad_orient = sa.CheckOrientedShells(shape, True)
    edges = [e for e, _ in ef]
    return dict(
        type=shape_name(shape), shells=explore(shape, SHELL), faces=explore(shape, FACE),
        distinct_faces=len(faces), edges=len(ef), vertices=len(subshapes(shape, VERTEX)),
        on1=len(on1), on2=len(on2), on3=len(on3),
        free_ok=free_ids == sorted(report["open_curves"]), n_open=len(report["open_curves"]),
        shared_ok=shared_ids == want_shared, n_shared=len(want_shared), pairs_ok=pairs_ok, opposite=opposite,
        valid=o.BRepCheck.BRepCheck_Analyzer(shape).IsValid(),
        fb_closed=(explore(closed, WIRE), explore(closed, EDGE)), fb_open=(explore(opened, WIRE), explore(opened, EDGE)),
        sa_loaded=sa.NbLoaded(), sa_bad=bad_orient, sa_free=explore(sa.FreeEdges(), EDGE) if sa.HasFreeEdges() else 0,
        max_edge_tol=max(o.BRep.BRep_Tool.Tolerance_s(e) for e in edges) if edges else float("nan"),
        max_vertex_tol=max(o.BRep.BRep_Tool.Tolerance_s(o.TopoDS.TopoDS.Vertex(v)) for v in subshapes(shape, VERTEX))
        if subshapes(shape, VERTEX) else float("nan"),
        vericad=report.get("shell"))


def edge_points(edge, n):
    c = o.BRepAdaptor.BRepAdaptor_Curve(edge)
    a, b = c.FirstParameter(), c.LastParameter()
    return [c.Value(a + (b - a) * i / (n - 1)) for i in range(n)]


def match_edge(edge, curves, scale):
    """(curve id, matching distance in model unit): the layout curve nearest to 5 interior
    points of the edge."""
    pts = edge_points(edge, 7)[1:-1]
    pts = [[p.X() / scale, p.Y() / scale, p.Z() / scale] for p in pts]
    best = None
    for cid, poly in curves.items():
        d = max(_poly_dist(p, poly) for p in pts)
        if best is None or d < best[1]:
            best = (cid, d)
    return best


def edge_distance(e1, e2):
    """Largest distance (OCCT's unit) from EDGE_SAMPLES points of each edge to the other edge."""
    mx = 0.0
    for a, b in ((e1, e2), (e2, e1)):
        for p in edge_points(a, EDGE_SAMPLES):
            v = o.BRepBuilderAPI.BRepBuilderAPI_MakeVertex(p).Vertex()
            d = o.BRepExtrema.BRepExtrema_DistShapeShape(v, b)
            mx = max(mx, d.Value())
    return mx


def bspline_of(edge):
    c = o.BRepAdaptor.BRepAdaptor_Curve(edge)
    if c.GetType() != o.GeomAbs.GeomAbs_CurveType.GeomAbs_BSplineCurve:
        return None
    return c.BSpline()


def same_bits(e1, e2):
    """(poles, knots): are the two edges' 3D B-spline curves' poles and weights the same bit
    for bit, in the same or the reverse order; are their knot vectors (values and
    multiplicities) the same bit for bit? None when either is no B-spline."""
    c1, c2 = bspline_of(e1), bspline_of(e2)
    if c1 is None or c2 is None:
        return None

    def data(c):
        poles = [(c.Pole(i).X(), c.Pole(i).Y(), c.Pole(i).Z(), c.Weight(i)) for i in range(1, c.NbPoles() + 1)]
        knots = [(c.Knot(i), c.Multiplicity(i)) for i in range(1, c.NbKnots() + 1)]
        return poles, knots, c.Degree()
    p1, k1, d1 = data(c1)
    p2, k2, d2 = data(c2)
    return (d1 == d2 and (p1 == p2 or p1 == p2[::-1])), k1 == k2


def on_surface_deviation(edge, faces):
    """Largest distance (OCCT's unit), at EDGE_SAMPLES common parameters, between the edge's
    3D curve and its curve on each face (pcurve on the face's surface), and between the
    curves on the two faces: how far the shared edge's three representations are apart."""
    c3 = o.BRepAdaptor.BRepAdaptor_Curve(edge)
    cs = [o.BRepAdaptor.BRepAdaptor_Curve(edge, f) for f in faces]
    a, b = c3.FirstParameter(), c3.LastParameter()
    to3d, between = 0.0, 0.0
    for i in range(EDGE_SAMPLES):
        t = a + (b - a) * i / (EDGE_SAMPLES - 1)
        p = c3.Value(t)
        q = [c.Value(t) for c in cs]
        to3d = max([to3d] + [p.Distance(x) for x in q])
        between = max([between] + [q[0].Distance(x) for x in q[1:]])
    return to3d, between


def _curve_data(c):
    poles = [(c.Pole(i).X(), c.Pole(i).Y(), c.Pole(i).Z(), c.Weight(i)) for i in range(1, c.NbPoles() + 1)]
    knots = [(c.Knot(i), c.Multiplicity(i)) for i in range(1, c.NbKnots() + 1)]
    return poles, knots, c.Degree()


def boundary_bits(edge, face):
    """(poles, knots): is the edge's 3D B-spline curve one of the four boundary iso-curves of
    the face's B-spline surface (UIso/VIso at the surface's bounds), poles and weights bit for
    bit (same or reverse order); and, for that iso-curve, are the knots the same bit for bit?
    None when the edge curve or the surface is no B-spline."""
    c = bspline_of(edge)
    ad = o.BRepAdaptor.BRepAdaptor_Surface(face)
    if c is None or ad.GetType() != o.GeomAbs.GeomAbs_SurfaceType.GeomAbs_BSplineSurface:
        return None
    srf = ad.BSpline()
    u0, u1, v0, v1 = srf.Bounds()
    isos = [srf.UIso(u0), srf.UIso(u1), srf.VIso(v0), srf.VIso(v1)]
    pe, ke, de = _curve_data(c)
    best = (False, False)
    for iso in isos:
        pi, ki, di = _curve_data(iso)   # a Geom_BSplineCurve (pybind11 gives the dynamic type)
        if di == de and (pi == pe or pi == pe[::-1]):
            best = (True, ki == ke)
            if ki == ke:
                break
    return best


def sew(faces, tol):
    sw = o.BRepBuilderAPI.BRepBuilderAPI_Sewing(tol)
    for f in faces:
        sw.Add(f)
    sw.Perform()
    shape = sw.SewedShape()
    free = [o.TopoDS.TopoDS.Edge(sw.FreeEdge(i)) for i in range(1, sw.NbFreeEdges() + 1)]
    contig = [o.TopoDS.TopoDS.Edge(sw.ContigousEdge(i)) for i in range(1, sw.NbContigousEdges() + 1)]
    # edge -> face counts in the sewn shape
    m = o.collections.IndexedDataMap_TopoDS_Shape_List_TopoDS_Shape_TopTools_ShapeMapHasher()
    o.TopExp.TopExp.MapShapesAndAncestors_s(shape, EDGE, FACE, m)
    per_edge = [m.FindFromIndex(i).Size() for i in range(1, m.Extent() + 1)]
    edges = subshapes(shape, EDGE)
    max_tol = max(o.BRep.BRep_Tool.Tolerance_s(o.TopoDS.TopoDS.Edge(e)) for e in edges) if edges else float("nan")
    return dict(
        shape_type=str(shape.ShapeType()).split(".")[-1].replace("TopAbs_", ""),
        faces=len(subshapes(shape, FACE)), shells=len(subshapes(shape, SHELL)),
        free=free, contig=contig, multiple=sw.NbMultipleEdges(), degenerated=sw.NbDegeneratedShapes(),
        on1=sum(1 for k in per_edge if k == 1), on2=sum(1 for k in per_edge if k == 2),
        on3=sum(1 for k in per_edge if k > 2), max_tol=max_tol,
        valid=o.BRepCheck.BRepCheck_Analyzer(shape).IsValid())


def moved_copy(face, edge, delta):
    """The face translated by `delta` (OCCT's unit) perpendicular to `edge` at its middle,
    and the translated edge."""
    c = o.BRepAdaptor.BRepAdaptor_Curve(edge)
    p, t = o.gp.gp_Pnt(), o.gp.gp_Vec()
    c.D1((c.FirstParameter() + c.LastParameter()) / 2, p, t)
    t.Normalize()
    axes = [o.gp.gp_Vec(1, 0, 0), o.gp.gp_Vec(0, 1, 0), o.gp.gp_Vec(0, 0, 1)]
    a = min(axes, key=lambda v: abs(v.Dot(t)))
    n = t.Crossed(a)
    n.Normalize()
    tr = o.gp.gp_Trsf()
    tr.SetTranslation(n.Multiplied(delta))
    mk = o.BRepBuilderAPI.BRepBuilderAPI_Transform(face, tr, True)
    return o.TopoDS.TopoDS.Face(mk.Shape()), o.TopoDS.TopoDS.Edge(mk.ModifiedShape(edge))


def compound(shapes):
    c = o.TopoDS.TopoDS_Compound()
    b = o.BRep.BRep_Builder()
    b.MakeCompound(c)
    for s in shapes:
        b.Add(c, s)
    return c


def bbox_diagonal(faces):
    box = o.Bnd.Bnd_Box()
    for f in faces:
        o.BRepBndLib.BRepBndLib.Add_s(f, box)
    return box.CornerMin().Distance(box.CornerMax())


# ---------------------------------------------------------------- one case

def run_case(label, model, layout_path, tol, truth, read_rows, rows, shared_rows, control_rows):
    model, layout_path = os.path.join(ROOT, model), os.path.join(ROOT, layout_path)
    layout = json.load(open(layout_path))
    truth_name, truth_fn = truth[0], truth[1]()
    tmp = tempfile.mkdtemp()
    for ext in ("igs", "step"):
        out, rep = os.path.join(tmp, f"surfaces.{ext}"), os.path.join(tmp, f"report-{ext}.json")
        r = subprocess.run([VERICAD, "approximate", model, "--layout", layout_path, "--tol", repr(tol),
                            "--out", out, "--report", rep], capture_output=True, text=True)
        if not os.path.exists(rep) or not os.path.exists(out):
            print(r.stdout, r.stderr)
            raise RuntimeError(f"vericad approximate failed on {label} (exit {r.returncode})")
        report = json.load(open(rep))
        info = subprocess.run([VERICAD, "info", out, "--json"], capture_output=True, text=True, check=True)
        out_unit = json.loads(info.stdout).get("unit") or "mm"
        unit = report.get("unit") or "mm"
        scale = MM_PER_UNIT[out_unit]
        curves = layout_curves(model, layout)
        shape, faces = read(out)

        # edges of the read faces -> layout curves; faces -> approximants
        match_max = 0.0
        face_edges = []   # per face: {curve id: edge}
        for f in faces:
            em = {}
            for e in subshapes(f, EDGE):
                cid, d = match_edge(o.TopoDS.TopoDS.Edge(e), curves, scale)
                match_max = max(match_max, d)
                em[cid] = o.TopoDS.TopoDS.Edge(e)
            face_edges.append(em)
        aps = layout["approximants"]
        face_of = {}
        for k, ap in enumerate(aps):
            want = {s["curve"] for s in ap["sides"]}
            hits = [i for i, em in enumerate(face_edges) if set(em) == want]
            face_of[k] = hits[0] if len(hits) == 1 else None
        faces_ok = sum(1 for v in face_of.values() if v is not None)
        read_rows.append(dict(label=label, unit=unit, tol=tol, ext=ext, exit=r.returncode, scale=scale,
                              faces_ok=faces_ok, n_aps=len(aps), match=match_max,
                              **as_read(shape, faces, curves, scale, report, face_of)))

        # per shared curve: the two faces' edges, measured by OCCT
        for s in report["shared"]:
            a, b = s["approximants"]
            fa, fb = face_of.get(a), face_of.get(b)
            if fa is None or fb is None or s["curve"] not in face_edges[fa] or s["curve"] not in face_edges[fb]:
                dist, bits, to_curve, to_truth = float("nan"), None, float("nan"), float("nan")
                one, dev, iso = None, (float("nan"), float("nan")), (None, None)
            else:
                ea, eb = face_edges[fa][s["curve"]], face_edges[fb][s["curve"]]
                # one edge of both faces (as the shell read should have it), or two edges
                one = ea.IsSame(eb)
                dist, bits = (0.0, None) if one else (edge_distance(ea, eb) / scale, same_bits(ea, eb))
                d3, dab = on_surface_deviation(ea, [faces[fa], faces[fb]]) if one else (float("nan"), float("nan"))
                dev = (d3 / scale, dab / scale)
                iso = (boundary_bits(ea, faces[fa]), boundary_bits(eb, faces[fb]))
                to_curve = max(_poly_dist([p.X() / scale, p.Y() / scale, p.Z() / scale], curves[s["curve"]])
                               for e in (ea, eb) for p in edge_points(e, 41))
                to_truth = max(truth_fn([p.X() / scale, p.Y() / scale, p.Z() / scale], scale)
                               for e in (ea, eb) for p in edge_points(e, 41))
            shared_rows.append((label, ext, s["curve"], f"{aps[a]['name']}–{aps[b]['name']}", s["count"],
                                s["gap"], s["moved"], s["status"], s["identical"], one, dist, bits, dev, iso,
                                to_curve, to_truth, truth_name))

        diag = bbox_diagonal(faces)
        # the sewing below works on the faces taken apart: each face copied alone
        # (BRepBuilderAPI_Copy), so that no edge is shared any more and sewing has to find the
        # shared edges from the geometry again (sewing the faces as read finds nothing to join:
        # their shared edges are already one edge; that is reported as `as read` below)
        sep, sep_edges = [], []
        for f, em in zip(faces, face_edges):
            cp = o.BRepBuilderAPI.BRepBuilderAPI_Copy(f)
            sep.append(o.TopoDS.TopoDS.Face(cp.Shape()))
            sep_edges.append({cid: o.TopoDS.TopoDS.Edge(cp.ModifiedShape(e)) for cid, e in em.items()})
        as_is = sew(faces, tol * scale)
        tol_read = max(o.BRep.BRep_Tool.Tolerance_s(o.TopoDS.TopoDS.Edge(e)) for f in faces for e in subshapes(f, EDGE))
        # control for the tight sewing: the last approximant's face moved off its neighbour by
        # CONTROL_SHIFTS (mm) perpendicular to a shared edge, sewn at the tight tolerance
        last = len(aps) - 1
        s0 = next((s for s in report["shared"] if last in s["approximants"]), None)
        if s0 is not None and face_of.get(last) is not None and face_of.get(s0["approximants"][0]) is not None:
            fl, fo = face_of[last], face_of[[a for a in s0["approximants"] if a != last][0]]
            ctl = []
            for delta in CONTROL_SHIFTS:
                mf, me = moved_copy(sep[fl], sep_edges[fl][s0["curve"]], delta)
                fs = sep[:fl] + [mf] + sep[fl + 1:]
                d = edge_distance(me, sep_edges[fo][s0["curve"]])
                sw = sew(fs, TIGHT * diag)
                ctl.append((delta, d, len(sw["contig"]), len(sw["free"])))
            control_rows.append((label, ext, aps[last]["name"], s0["curve"], TIGHT * diag, len(report["shared"]), ctl))
        open_set = set(report["open_curves"])
        shared_set = {s["curve"] for s in report["shared"]}
        for which, stol in (("tol", tol * scale), ("tight", TIGHT * diag)):
            sw = sew(sep, stol)
            free_ids = sorted(match_edge(e, curves, scale)[0] for e in sw["free"])
            contig_ids = sorted(match_edge(e, curves, scale)[0] for e in sw["contig"])
            mn = sorted({f"{ap['m']}×{ap['n']}" for ap in report["approximants"]})
            rows.append(dict(
                label=label, unit=unit, tol=tol, ext=ext, exit=r.returncode, mn=", ".join(mn),
                rebuilds=report["rebuilds"], read=len(faces), faces_ok=faces_ok, n_aps=len(aps),
                match=match_max, scale=scale, tol_read=tol_read, which=which, stol_mm=stol, stol_unit=stol / scale, sw=sw,
                free_ok=sorted(free_ids) == sorted(open_set), n_open=len(open_set),
                contig_ok=sorted(contig_ids) == sorted(shared_set), n_shared=len(shared_set),
                separated_on1=sum(1 for _, fs in edge_faces(compound(sep)) if len(fs) == 1),
                as_is=as_is))


def g(x):
    return "—" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.2e}"


def main():
    try:
        from importlib.metadata import version
        print(f"OCP (Open CASCADE) {version('cadquery-ocp-novtk')}; vericad {VERICAD}\n")
    except Exception:
        pass
    read_rows, rows, shared_rows, control_rows = [], [], [], []
    for label, model, layout, tol, truth in CASES:
        run_case(label, model, layout, tol, truth, read_rows, rows, shared_rows, control_rows)

    # 1. what OCCT reads, no sewing
    same = lambda ok, n, what: (f"the {n} {what}" if ok else f"NOT the {n} {what}")
    print("As read (no sewing):\n")
    print("| case (unit, tol) | file | vericad exit | OneShape type; shells, faces (TopExp_Explorer) | faces matched to approximants "
          "| distinct edges, vertices | edges on 1 / 2 / more faces | edges on 2 faces: along which curves; on the sharing approximants' faces; "
          "used FORWARD + REVERSED | edges on 1 face: along which curves | BRepCheck valid | ShapeAnalysis_FreeBounds: closed wires (edges), open wires (edges) "
          "| ShapeAnalysis_Shell: shells, bad orientation, free edges | max edge / vertex tol (model unit) "
          "| vericad `shell`: faces, shared, free, other; tolerance | OCCT = vericad |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for x in read_rows:
        v = x["vericad"] or {}
        agree = (v.get("faces") == x["faces"] == x["distinct_faces"] and v.get("shared_edges") == x["on2"]
                 and v.get("free_edges") == x["on1"] and v.get("other_edges") == x["on3"])
        print(f"| {x['label']} ({x['unit']}, {x['tol']:g}) | {x['ext']} | {x['exit']} "
              f"| {x['type']}; {x['shells']}, {x['faces']} | {x['faces_ok']} of {x['n_aps']} (edges ≤ {x['match']:.1e} from their curves) "
              f"| {x['edges']}, {x['vertices']} | {x['on1']} / {x['on2']} / {x['on3']} "
              f"| {same(x['shared_ok'], x['n_shared'], 'shared curves' if x['n_shared'] != 1 else 'shared curve')}; "
              f"{'yes' if x['pairs_ok'] else 'NO'}; {x['opposite']} of {x['on2']} "
              f"| {same(x['free_ok'], x['n_open'], 'open curves')} | {'yes' if x['valid'] else 'no'} "
              f"| {x['fb_closed'][0]} ({x['fb_closed'][1]}), {x['fb_open'][0]} ({x['fb_open'][1]}) "
              f"| {x['sa_loaded']}, {'yes' if x['sa_bad'] else 'no'}, {x['sa_free']} "
              f"| {x['max_edge_tol'] / x['scale']:.1e} / {x['max_vertex_tol'] / x['scale']:.1e} "
              f"| {v.get('faces')}, {v.get('shared_edges')}, {v.get('free_edges')}, {v.get('other_edges')}; "
              f"{g(v.get('tolerance'))} | {'yes' if agree else 'NO'} |")
    print()
    print("Sewn (secondary): BRepBuilderAPI_Sewing of the faces read, as they are (at tol)\n")
    print("| case | file | sewn shape: faces, shells | contiguous, free, multiple edges | edges on 1 / 2 faces | BRepCheck valid |")
    print("|---|---|---|---|---|---|")
    for x in rows:
        if x["which"] != "tol":
            continue
        a = x["as_is"]
        print(f"| {x['label']} | {x['ext']} | {a['shape_type']}: {a['faces']}, {a['shells']} "
              f"| {len(a['contig'])}, {len(a['free'])}, {a['multiple']} | {a['on1']} / {a['on2']} | {'yes' if a['valid'] else 'no'} |")
    print()
    print("and of the faces taken apart (each copied alone: edges on 1 face before sewing in every row: "
          + ", ".join(str(x["separated_on1"]) for x in rows if x["which"] == "tol") + "):\n")
    print("| case (unit, tol) | file | vericad exit, M × N | faces read (matched to approximants) | sewing tol (model unit; mm) "
          "| sewn shape: faces, shells | free edges: along which curves | contiguous edges: along which curves "
          "| multiple, degenerated | edges on 1 / 2 faces | max edge tol, read → sewn | BRepCheck valid |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for x in rows:
        sw = x["sw"]
        same = lambda ok, n, what: (f"the {n} {what}" if ok else f"NOT the {n} {what}")
        stol = ("tol " if x["which"] == "tol" else "tight ") + f"{x['stol_unit']:.1e}; {x['stol_mm']:.1e}"
        print(f"| {x['label']} ({x['unit']}, {x['tol']:g}) | {x['ext']} | {x['exit']}, {x['mn']}"
              f"{', ' + str(x['rebuilds']) + ' rebuild' + ('s' if x['rebuilds'] != 1 else '') if x['rebuilds'] else ''} "
              f"| {x['read']} ({x['faces_ok']} of {x['n_aps']}; edges ≤ {x['match']:.1e} from their curves) | {stol} "
              f"| {sw['shape_type']}: {sw['faces']}, {sw['shells']} "
              f"| {len(sw['free'])}: {same(x['free_ok'], x['n_open'], 'open curves')} "
              f"| {len(sw['contig'])}: {same(x['contig_ok'], x['n_shared'], 'shared curves' if x['n_shared'] != 1 else 'shared curve')} "
              f"| {sw['multiple']}, {sw['degenerated']} | {sw['on1']} / {sw['on2']}{' / ' + str(sw['on3']) + ' on more' if sw['on3'] else ''} "
              f"| {x['tol_read'] / x['scale']:.1e} → {sw['max_tol'] / x['scale']:.1e} | {'yes' if sw['valid'] else 'no'} |")
    print()
    print("| case | file | shared curve | approximants | count | vericad gap before join | vericad moved | status "
          "| vericad identical | OCCT: one edge of both faces | OCCT: 3D curve to each face's curve on surface; between the two "
          "| OCCT: edge curve = boundary iso of face a, of face b (bits) | edges to the layout curve "
          "| edges to the original surface |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    bitstr = lambda b: "—" if b is None else f"poles {'yes' if b[0] else 'no'}, knots {'yes' if b[1] else 'no'}"
    for (label, ext, curve, aps, count, gap, moved, status, ident, one, dist, bits, dev, iso,
         to_curve, to_truth, tn) in shared_rows:
        if one:
            onecell = "yes"
        elif one is None:
            onecell = "—"
        else:   # two edges: the old comparison of the two faces' edges
            onecell = f"NO: two edges, {'0' if dist == 0.0 else g(dist)} apart, {bitstr(bits)}"
        print(f"| {label} | {ext} | {curve} | {aps} | {count} | {g(gap)} | {g(moved)} | {status} | {ident} | "
              f"{onecell} | {g(dev[0])}; {g(dev[1])} | {bitstr(iso[0])}; {bitstr(iso[1])} "
              f"| {g(to_curve)} | {g(to_truth)} ({tn.replace('|', chr(92) + '|')}) |")
    print()
    print("| case | file | face moved (along shared curve) | tight sewing tol (mm) | "
          + " | ".join(f"moved {d:g} mm: edge distance, contiguous / free" for d in CONTROL_SHIFTS) + " |")
    print("|---|---|---|---|" + "---|" * len(CONTROL_SHIFTS))
    for label, ext, name, curve, ttol, n_shared, ctl in control_rows:
        cells = " | ".join(f"{d:.1e} mm, {c} / {f}" for _, d, c, f in ctl)
        print(f"| {label} | {ext} | {name} ({curve}) | {ttol:.1e} | {cells} |")


if __name__ == "__main__":
    if sys.argv[1:] == ["--write-data"]:
        write_data()
    else:
        main()
