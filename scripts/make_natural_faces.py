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


def cases():
    tau = 2 * math.pi
    yield "natural-cylinder-two-circles", revolved("cylinder", 11, 0.5, 2.5, 2.0, 4.5)
    yield "natural-cylinder-seam-edge", revolved("cylinder", 12, -1.0, 1.5, 0.0, 0.0, seam_edge=True)
    yield "natural-cone-two-circles", revolved("cone", 13, 0.2, 1.7, 1.0, 5.0)
    for name, (a0, a1), seed in (("partial", (0.3, 2.0), 14), ("across-seam", (-1.0, 1.0), 15),
                                 ("almost-whole", (0.5, 0.5 + tau - 0.01), 16)):
        yield "trimmed-cylinder-" + name, seam.cyl_face(a0=a0, a1=a1, rot=seam.rot(seed), product=True)[0]


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "..", "tests", "data", "constructed", "natural")
    os.makedirs(out, exist_ok=True)
    for name, text in cases():
        with open(os.path.join(out, name + ".step"), "w") as f:
            f.write(text)
        print(name + ".step")
