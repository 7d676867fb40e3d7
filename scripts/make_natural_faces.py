#!/usr/bin/env python3
"""Constructed STEP faces on closed surfaces whose class is known from their construction:
*natural* (the face is its surface's whole parameter rectangle: every point of the closed
surface between the two end circles) or *trimmed* (a part of it). Each file holds one face in
an open shell, in a rotated placement (frames from scripts/make_seam_faces.py); the class is
the file name's first word. Written to tests/data/constructed/natural/ (or the directory
given); used by tests/natural_faces.rs and checked with Open CASCADE by
scripts/occt_natural_faces.py.

  natural-cylinder-two-circles   a cylinder between two whole circles, one loop each, no seam
                                 edge, the circles' vertices at 2.0 and 4.5 rad (away from
                                 the seam the NURBS form starts at)
  natural-cylinder-seam-edge     a cylinder bounded by one loop: circle, seam line, circle
                                 backwards, seam line backwards
  natural-cone-two-circles       a cone between two whole circles, vertices at 1.0 and 5.0 rad
  trimmed-cylinder-partial       a cylinder between two arcs 0.3 .. 2.0 rad and two lines
  trimmed-cylinder-across-seam   the same from -1 to 1 rad (across the seam)
  trimmed-cylinder-almost-whole  the same from 0.5 to 0.5 + 2 pi - 0.01 rad
  trimmed-cylinder-wavy-top      a whole circle below; above, a closed polyline on the
                                 cylinder whose every other vertex lies on the top circle and
                                 the others 0.2 below it (the edge touches the border only at
                                 its vertices)
  trimmed-cylinder-hole          two whole circles and a hole between them
  natural-sphere-seam            a whole sphere bounded by one pole-to-pole meridian used twice
                                 (as Open CASCADE writes a sphere)
  natural-sphere-vnorth, -vboth  a whole sphere bounded by vertex loops at one pole or both
  trimmed-sphere-cap             a cap above a circle of latitude
  natural-cone-vapex, -seam      a cone from its apex (a vertex loop there, or a seam line
                                 through it) to a circle
  natural-cone-circle            the same bounded by the circle alone (radius 2 + tan 0.3 at
                                 height 1, half-angle 0.3: area pi r s, s = r / sin 0.3)
  natural-torus-seams            a whole torus bounded by its two seam circles
  trimmed-torus-hole             the same with a hole

Usage: python3 scripts/make_natural_faces.py [DIR]
"""
import importlib.util, math, os, sys

HERE = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("seam", os.path.join(HERE, "make_seam_faces.py"))
seam = importlib.util.module_from_spec(spec)
spec.loader.exec_module(seam)


def revolved(kind, seed, h0, h1, a0, a1, seam_edge=False, r=2.0, half_angle=0.3):
    """One face on a cylinder (`kind` "cylinder") or cone ("cone", radius r at height 0,
    widening by tan(half_angle) per unit height) about a rotated axis, bounded by the circles
    at heights h0 < h1 (whole, their vertices at angles a0 and a1 about the placement's x), or
    with `seam_edge` by one loop through the seam line at angle 0."""
    w = seam.W()
    x, y, z = seam.rot(seed)
    o = [0.3, -0.2, 0.1]
    rad = lambda h: r + (h * math.tan(half_angle) if kind == "cone" else 0.0)
    P = lambda a, h: [o[k] + rad(h) * (math.cos(a) * x[k] + math.sin(a) * y[k]) + h * z[k] for k in range(3)]
    surf = (w.add("CYLINDRICAL_SURFACE('',#%d,%r)" % (w.ax(o, z, x), r)) if kind == "cylinder"
            else w.add("CONICAL_SURFACE('',#%d,%r,%r)" % (w.ax(o, z, x), r, half_angle)))

    def circle(h, a):
        # The circle's own placement turned by `a`, so its vertex (at its start) lies there.
        xa = [math.cos(a) * x[k] + math.sin(a) * y[k] for k in range(3)]
        c = w.add("CIRCLE('',#%d,%r)" % (w.ax([o[k] + h * z[k] for k in range(3)], z, xa), rad(h)))
        v = w.vtx(P(a, h))
        return w.add("EDGE_CURVE('',#%d,#%d,#%d,.T.)" % (v, v, c)), v

    if seam_edge:
        # The loop circle h0 (+), line up (+), circle h1 (-), line down (-): the vertices are
        # shared, so both circles start at angle 0.
        v0, v1 = w.vtx(P(0.0, h0)), w.vtx(P(0.0, h1))
        c0 = w.add("EDGE_CURVE('',#%d,#%d,#%d,.T.)" % (v0, v0, w.add("CIRCLE('',#%d,%r)" % (
            w.ax([o[k] + h0 * z[k] for k in range(3)], z, x), rad(h0)))))
        c1 = w.add("EDGE_CURVE('',#%d,#%d,#%d,.T.)" % (v1, v1, w.add("CIRCLE('',#%d,%r)" % (
            w.ax([o[k] + h1 * z[k] for k in range(3)], z, x), rad(h1)))))
        d = [P(0.0, h1)[k] - P(0.0, h0)[k] for k in range(3)]
        n = math.sqrt(sum(t * t for t in d))
        line = w.add("LINE('',#%d,#%d)" % (w.pt(P(0.0, h0)), w.add("VECTOR('',#%d,1.)" % w.dr([t / n for t in d]))))
        s = w.add("EDGE_CURVE('',#%d,#%d,#%d,.T.)" % (v0, v1, line))
        oes = [w.add("ORIENTED_EDGE('',*,*,#%d,%s)" % (e, f)) for e, f in ((c0, ".T."), (s, ".T."), (c1, ".F."), (s, ".F."))]
        loop = w.add("EDGE_LOOP('',(%s))" % ",".join("#%d" % e for e in oes))
        bounds = [w.add("FACE_OUTER_BOUND('',#%d,.T.)" % loop)]
    else:
        (e0, _), (e1, _) = circle(h0, a0), circle(h1, a1)
        # Material above the lower circle (run forwards) and below the upper one (backwards).
        l0 = w.add("EDGE_LOOP('',(#%d))" % w.add("ORIENTED_EDGE('',*,*,#%d,.T.)" % e0))
        l1 = w.add("EDGE_LOOP('',(#%d))" % w.add("ORIENTED_EDGE('',*,*,#%d,.F.)" % e1))
        bounds = [w.add("FACE_OUTER_BOUND('',#%d,.T.)" % l0), w.add("FACE_BOUND('',#%d,.T.)" % l1)]
    face = w.add("ADVANCED_FACE('',(%s),#%d,.T.)" % (",".join("#%d" % b for b in bounds), surf))
    return seam.finish(w, [face], product=True)


# Faces on spheres, cones and tori, and cylinders with edges that only touch the border at
# their vertices or holes inside, in one rotated frame (seed 21).
x, y, z = seam.rot(21)
o = [0.3, -0.2, 0.1]


def add(p, *terms):
    r = list(p)
    for c, v in terms:
        for k in range(3): r[k] += c * v[k]
    return r
neg = lambda v: [-t for t in v]

def circle_edge(w, centre, axis, xdir, r, a=None):
    c = w.add("CIRCLE('',#%d,%r)" % (w.ax(centre, axis, xdir), r))
    ydir = [axis[1]*xdir[2]-axis[2]*xdir[1], axis[2]*xdir[0]-axis[0]*xdir[2], axis[0]*xdir[1]-axis[1]*xdir[0]]
    v = w.vtx(add(centre, (r, xdir)))
    return w.add("EDGE_CURVE('',#%d,#%d,#%d,.T.)" % (v, v, c)), v

def bspline1_edge(w, pts, closed=True):
    n = len(pts)
    ids = ",".join("#%d" % w.pt(p) for p in pts)
    mult = [2] + [1] * (n - 2) + [2]
    knots = list(range(n))
    c = w.add("B_SPLINE_CURVE_WITH_KNOTS('',1,(%s),.UNSPECIFIED.,%s,.F.,(%s),(%s),.UNSPECIFIED.)" % (
        ids, ".T." if closed else ".F.", ",".join(map(str, mult)), ",".join("%d." % k for k in knots)))
    v0 = w.vtx(pts[0]); v1 = v0 if closed else w.vtx(pts[-1])
    return w.add("EDGE_CURVE('',#%d,#%d,#%d,.T.)" % (v0, v1, c))

def loop(w, oes, outer=False):
    l = w.add("EDGE_LOOP('',(%s))" % ",".join("#%d" % w.add("ORIENTED_EDGE('',*,*,#%d,%s)" % (e, ".T." if f else ".F.")) for e, f in oes))
    return w.add("%s('',#%d,.T.)" % ("FACE_OUTER_BOUND" if outer else "FACE_BOUND", l))

def face(w, bounds, surf):
    ids = ",".join("#%d" % b for b in bounds)
    return seam.finish(w, [w.add("ADVANCED_FACE('',(%s),#%d,.T.)" % (ids, surf))], product=True)

R = 2.0
P = lambda a, h, r=R: add(o, (r*math.cos(a), x), (r*math.sin(a), y), (h, z))

def cyl(kind):
    w = seam.W()
    surf = w.add("CYLINDRICAL_SURFACE('',#%d,%r)" % (w.ax(o, z, x), R))
    e0, _ = circle_edge(w, add(o, (0.0, z)), z, x, R)
    b = [loop(w, [(e0, True)], outer=True)]
    if kind == "wavy":
        # top: degree-1 closed polygon through 16 points alternately at h=1 and h=0.8, all on the cylinder
        pts = [P(i*math.pi/8, 1.0 if i % 2 == 0 else 0.8) for i in range(17)]
        pts[16] = pts[0]
        b.append(loop(w, [(bspline1_edge(w, pts), False)]))
    elif kind == "hole":
        e1, _ = circle_edge(w, add(o, (1.0, z)), z, x, R)
        b.append(loop(w, [(e1, False)]))
        pts = [P(2.0 + 0.2*math.cos(t), 0.5 + 0.2*math.sin(t)) for t in [i*2*math.pi/12 for i in range(13)]]
        pts[12] = pts[0]
        b.append(loop(w, [(bspline1_edge(w, pts), False)]))
    elif kind == "partialtop":
        # top: an open arc only (0 .. pi) -- invalid loop
        c = w.add("CIRCLE('',#%d,%r)" % (w.ax(add(o, (1.0, z)), z, x), R))
        va, vb = w.vtx(P(0.0, 1.0)), w.vtx(P(math.pi, 1.0))
        e1 = w.add("EDGE_CURVE('',#%d,#%d,#%d,.T.)" % (va, vb, c))
        b.append(loop(w, [(e1, False)]))
    return face(w, b, surf)

def sphere(kind):
    w = seam.W()
    surf = w.add("SPHERICAL_SURFACE('',#%d,%r)" % (w.ax(o, z, x), R))
    S, N = add(o, (-R, z)), add(o, (R, z))
    if kind == "seam":
        c = w.add("CIRCLE('',#%d,%r)" % (w.ax(o, neg(y), x), R))
        vs, vn = w.vtx(S), w.vtx(N)
        e = w.add("EDGE_CURVE('',#%d,#%d,#%d,.T.)" % (vs, vn, c))
        b = [loop(w, [(e, True), (e, False)], outer=True)]
    elif kind in ("vnorth", "vboth", "vequator"):
        pts = {"vnorth": [N], "vboth": [N, S], "vequator": [P(0.7, 0.0)]}[kind]
        b = [w.add("FACE_OUTER_BOUND('',#%d,.T.)" % w.add("VERTEX_LOOP('',#%d)" % w.vtx(p))) for p in pts]
    elif kind == "cap":
        # circle at latitude h=1: trimmed
        r = math.sqrt(R*R - 1)
        e, _ = circle_edge(w, add(o, (1.0, z)), z, x, r)
        b = [loop(w, [(e, True)], outer=True)]
    return face(w, b, surf)

def cone(kind):
    w = seam.W()
    al = 0.3
    surf = w.add("CONICAL_SURFACE('',#%d,%r,%r)" % (w.ax(o, z, x), R, al))
    ha = -R / math.tan(al)
    apex = add(o, (ha, z))
    rt = R + 1.0*math.tan(al)
    e, vt = circle_edge(w, add(o, (1.0, z)), z, x, rt)
    if kind == "vapex":
        b = [loop(w, [(e, True)], outer=True), w.add("FACE_BOUND('',#%d,.T.)" % w.add("VERTEX_LOOP('',#%d)" % w.vtx(apex)))]
    elif kind == "seam":
        top = P(0.0, 1.0, rt)
        d = [top[k]-apex[k] for k in range(3)]; n = math.sqrt(sum(t*t for t in d))
        line = w.add("LINE('',#%d,#%d)" % (w.pt(apex), w.add("VECTOR('',#%d,1.)" % w.dr([t/n for t in d]))))
        va = w.vtx(apex)
        s = w.add("EDGE_CURVE('',#%d,#%d,#%d,.T.)" % (va, vt, line))
        b = [loop(w, [(s, True), (e, True), (s, False)], outer=True)]
    elif kind == "circle":
        # The circle alone, run so that the face lies between it and the apex.
        b = [loop(w, [(e, False)], outer=True)]
    return face(w, b, surf)

def torus(kind):
    w = seam.W()
    Rm, rm = 3.0, 1.0
    surf = w.add("TOROIDAL_SURFACE('',#%d,%r,%r)" % (w.ax(o, z, x), Rm, rm))
    v = w.vtx(add(o, (Rm + rm, x)))
    eq = w.add("EDGE_CURVE('',#%d,#%d,#%d,.T.)" % (v, v, w.add("CIRCLE('',#%d,%r)" % (w.ax(o, z, x), Rm + rm))))
    tube = w.add("EDGE_CURVE('',#%d,#%d,#%d,.T.)" % (v, v, w.add("CIRCLE('',#%d,%r)" % (w.ax(add(o, (Rm, x)), neg(y), x), rm))))
    b = [loop(w, [(eq, True), (tube, True), (eq, False), (tube, False)], outer=True)]
    if kind == "hole":
        pts = [add(o, ((Rm + rm*math.cos(1.0+0.2*math.cos(t)))*math.cos(2.0+0.2*math.sin(t)), x), ((Rm + rm*math.cos(1.0+0.2*math.cos(t)))*math.sin(2.0+0.2*math.sin(t)), y), (rm*math.sin(1.0+0.2*math.cos(t)), z)) for t in [i*2*math.pi/12 for i in range(13)]]
        pts[12] = pts[0]
        b.append(loop(w, [(bspline1_edge(w, pts), False)]))
    elif kind == "eqonly":
        b = [loop(w, [(eq, True)], outer=True)]
    return face(w, b, surf)


def cases():
    tau = 2 * math.pi
    yield "natural-cylinder-two-circles", revolved("cylinder", 11, 0.5, 2.5, 2.0, 4.5)
    yield "natural-cylinder-seam-edge", revolved("cylinder", 12, -1.0, 1.5, 0.0, 0.0, seam_edge=True)
    yield "natural-cone-two-circles", revolved("cone", 13, 0.2, 1.7, 1.0, 5.0)
    for name, (a0, a1), seed in (("partial", (0.3, 2.0), 14), ("across-seam", (-1.0, 1.0), 15),
                                 ("almost-whole", (0.5, 0.5 + tau - 0.01), 16)):
        yield "trimmed-cylinder-" + name, seam.cyl_face(a0=a0, a1=a1, rot=seam.rot(seed), product=True)[0]
    yield "trimmed-cylinder-wavy-top", cyl("wavy")
    yield "trimmed-cylinder-hole", cyl("hole")
    yield "natural-sphere-seam", sphere("seam")
    yield "natural-sphere-vnorth", sphere("vnorth")
    yield "natural-sphere-vboth", sphere("vboth")
    yield "trimmed-sphere-cap", sphere("cap")
    yield "natural-cone-vapex", cone("vapex")
    yield "natural-cone-seam", cone("seam")
    yield "natural-cone-circle", cone("circle")
    yield "natural-torus-seams", torus("seams")
    yield "trimmed-torus-hole", torus("hole")


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "..", "tests", "data", "constructed", "natural")
    os.makedirs(out, exist_ok=True)
    for name, text in cases():
        with open(os.path.join(out, name + ".step"), "w") as f:
            f.write(text)
        print(name + ".step")
