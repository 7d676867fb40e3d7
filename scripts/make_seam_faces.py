#!/usr/bin/env python3
"""Constructed STEP faces with a known trimmed area (tests/data/constructed): a face on a
CYLINDRICAL_SURFACE of radius r in a rotated placement, bounded by two circle arcs at heights
h0, h1 and two lines at angles a0, a1 (area r·(a1 − a0)·(h1 − h0) exactly). Writes cyl0..cyl3
in the current directory and prints each file's area; cyl2 (−1 .. 1 rad, spanning the
placement's x direction) is tests/data/constructed/cylinder-face-across-seam.step.

Usage: python3 scripts/make_seam_faces.py > areas.txt"""
import math
def step(entities):
    hdr = """ISO-10303-21;
HEADER;
FILE_DESCRIPTION(('truth'),'2;1');
FILE_NAME('t.step','2026-12-03T00:00:00',(''),(''),'','','');
FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));
ENDSEC;
DATA;
"""
    return hdr + "\n".join(f"#{i}={e};" for i, e in entities) + "\nENDSEC;\nEND-ISO-10303-21;\n"

class W:
    def __init__(s): s.e=[]; 
    def add(s, t): s.e.append((len(s.e)+1, t)); return len(s.e)
    def pt(s,p): return s.add("CARTESIAN_POINT('',(%r,%r,%r))"%tuple(p))
    def dr(s,d): return s.add("DIRECTION('',(%r,%r,%r))"%tuple(d))
    def ax(s,o,z,x): return s.add("AXIS2_PLACEMENT_3D('',#%d,#%d,#%d)"%(s.pt(o),s.dr(z),s.dr(x)))
    def vtx(s,p): return s.add("VERTEX_POINT('',#%d)"%s.pt(p))

def finish(w, faces, product=False):
    """The file of an open shell of `faces` (ids) in a millimetre context; with `product`,
    under a product definition (as Open CASCADE's reader needs to transfer it)."""
    S=w.add("OPEN_SHELL('',(%s))"%",".join("#%d"%f for f in faces))
    ctx=w.add("(GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNIT_ASSIGNED_CONTEXT((#%d,#%d,#%d)) REPRESENTATION_CONTEXT('',''))"%(
        w.add("(LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.))"),w.add("(NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.))"),w.add("(NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT())")))
    M=w.add("SHELL_BASED_SURFACE_MODEL('',(#%d))"%S)
    rep=w.add("MANIFOLD_SURFACE_SHAPE_REPRESENTATION('',(#%d),#%d)"%(M,ctx))
    if product:
        app=w.add("APPLICATION_CONTEXT('automotive design')")
        prod=w.add("PRODUCT('face','face','',(#%d))"%w.add("PRODUCT_CONTEXT('',#%d,'mechanical')"%app))
        pdf=w.add("PRODUCT_DEFINITION_FORMATION('','',#%d)"%prod)
        pd=w.add("PRODUCT_DEFINITION('design','',#%d,#%d)"%(pdf,w.add("PRODUCT_DEFINITION_CONTEXT('part definition',#%d,'design')"%app)))
        w.add("SHAPE_DEFINITION_REPRESENTATION(#%d,#%d)"%(w.add("PRODUCT_DEFINITION_SHAPE('','',#%d)"%pd),rep))
    return step(w.e)

def cyl_face(r=2.0, a0=0.3, a1=2.0, h0=0.5, h1=2.5, rot=None, product=False):
    w=W()
    # frame: rotated
    z=rot[2]; x=rot[0]; o=[0.3,-0.2,0.1]
    def P(rho,a,h): return [o[k]+rho*math.cos(a)*x[k]+rho*math.sin(a)*rot[1][k]+h*z[k] for k in range(3)]
    A=w.ax(o,z,x)
    surf=w.add("CYLINDRICAL_SURFACE('',#%d,%r)"%(A,r))
    V=[w.vtx(P(r,a0,h0)),w.vtx(P(r,a1,h0)),w.vtx(P(r,a1,h1)),w.vtx(P(r,a0,h1))]
    def circ(h):
        return w.add("CIRCLE('',#%d,%r)"%(w.ax([o[k]+h*z[k] for k in range(3)],z,x),r))
    def line(a):
        d=w.add("VECTOR('',#%d,1.)"%w.dr(z))
        return w.add("LINE('',#%d,#%d)"%(w.pt(P(r,a,0)),d))
    E=[w.add("EDGE_CURVE('',#%d,#%d,#%d,.T.)"%(V[0],V[1],circ(h0))),
       w.add("EDGE_CURVE('',#%d,#%d,#%d,.T.)"%(V[1],V[2],line(a1))),
       w.add("EDGE_CURVE('',#%d,#%d,#%d,.T.)"%(V[3],V[2],circ(h1))),
       w.add("EDGE_CURVE('',#%d,#%d,#%d,.T.)"%(V[0],V[3],line(a0)))]
    OE=[w.add("ORIENTED_EDGE('',*,*,#%d,%s)"%(e,f)) for e,f in zip(E,[".T.",".T.",".F.",".F."])]
    L=w.add("EDGE_LOOP('',(%s))"%",".join("#%d"%x for x in OE))
    B=w.add("FACE_OUTER_BOUND('',#%d,.T.)"%L)
    F=w.add("ADVANCED_FACE('',(#%d),#%d,.T.)"%(B,surf))
    return finish(w, [F], product), r*(a1-a0)*(h1-h0)

def rot(seed):
    import random; R=random.Random(seed)
    v=[R.gauss(0,1) for _ in range(3)]; n=math.sqrt(sum(t*t for t in v)); z=[t/n for t in v]
    u=[R.gauss(0,1) for _ in range(3)]; d=sum(a*b for a,b in zip(u,z)); x=[a-d*b for a,b in zip(u,z)]; n=math.sqrt(sum(t*t for t in x)); x=[t/n for t in x]
    y=[z[1]*x[2]-z[2]*x[1], z[2]*x[0]-z[0]*x[2], z[0]*x[1]-z[1]*x[0]]
    return [x,y,z]
if __name__ == "__main__":
    for k,(a0,a1) in enumerate([(0.3,2.0),(0.0,2.0),(-1.0,1.0),(0.5,5.5)]):
        t,area=cyl_face(a0=a0,a1=a1,rot=rot(k))
        open(f"cyl{k}.step","w").write(t); print(f"cyl{k}.step", repr(area))
