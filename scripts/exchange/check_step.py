#!/usr/bin/env python3
"""Checks a `capdiv surface --format step` file with OpenCascade (cadquery-ocp).

    check_step.py FILE.step FILE.json FILE.log [--mesh MESH.obj] [--f32]

FILE.json is `capdiv surface --format json` of the same mesh and options (the
patches, in the order the STEP faces are written, and the caps' limit
points; with --f32, of `--precision f32`: its shortest f32 digits are
read back as the f32 values the STEP file holds exactly); FILE.log is the summary the STEP run printed (its `step` line: the
face, edge and vertex counts, the shell, the volume capdiv computed by Gauss
quadrature over the patches). Checks, each failing with a one-line reason:

1. STEPControl_Reader reads the file (IFSelect_RetDone) and its load check
   (each entity instance's name and parameters read against OpenCascade's
   AP214 schema: known entity, parameter count and types) has neither a
   fail nor a warning; it transfers a shape;
2. BRepCheck_Analyzer says the shape is valid;
3. the faces, the (non-degenerate) edges and the vertices are as many as
   written;
4. each patch face's surface is a B-spline of the patch's degree and equals
   the JSON's Bézier patch (evaluated here by de Casteljau) at 7x7 parameter
   samples within 1e-9 of the model size (f64 round-off: the numbers are
   written exactly, both sides evaluate in f64 a few dozen operations);
5. each hole-fill face is ruled, `F(u, v) = (1 - v) F(u, 0) + v F(u, 1)`, its
   side v = 1 is one cap's limit point, and its side v = 0 is an edge of a
   patch (its midpoint is one of the JSON patches' edge midpoints), all
   within 1e-9 of the model size;
6. a closed shell (the log says so) is a solid with no free edge and no edge
   of more than two faces, and OpenCascade's volume (GProp, adaptive
   integration to 1e-9) equals capdiv's within 1e-9 relative (1e-6 for
   --f32);
7. an open shell: the free edges lie on the input's boundary limit curve,
   which for a boundary loop of smooth boundary vertices is the periodic
   uniform cubic B-spline of the loop's vertices (Catmull-Clark's boundary
   rule; built here as an OpenCascade Geom_BSplineCurve from --mesh), within
   1e-9 of the model size at 5 points per edge, and cover it: the free
   edges' total length equals the boundary curves' total length within 1e-7
   relative.

Prints one line of measured numbers; exit 1 on the first failed check.
"""

import json
import math
import re
import struct
import sys
import time

from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepGProp import BRepGProp
from OCP.GCPnts import GCPnts_AbscissaPoint
from OCP.Geom import Geom_BSplineCurve
from OCP.GeomAbs import GeomAbs_BSplineSurface
from OCP.GeomAdaptor import GeomAdaptor_Curve, GeomAdaptor_Surface
from OCP.GeomAPI import GeomAPI_ProjectPointOnCurve
from OCP.GProp import GProp_GProps
from OCP.gp import gp_Pnt
from OCP.IFSelect import IFSelect_RetDone
from OCP.STEPControl import STEPControl_Reader
from OCP.collections import (
    Array1_double,
    Array1_gp_Pnt,
    Array1_int,
    IndexedDataMap_TopoDS_Shape_List_TopoDS_Shape_TopTools_ShapeMapHasher as EdgeFaces,
    IndexedMap_TopoDS_Shape_TopTools_ShapeMapHasher as ShapeMap,
)
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_SOLID, TopAbs_VERTEX
from OCP.TopExp import TopExp, TopExp_Explorer
from OCP.TopoDS import TopoDS

SURFACE_TOL = 1e-9  # of the model size
VOLUME_TOL = 1e-9  # relative (f64: measured agreement 2e-13 or better)
VOLUME_TOL_F32 = 1e-6  # relative (f32 corners: gaps of f32 round-off)
LENGTH_TOL = 1e-7  # relative


def fail(msg):
    print(f"check_step: {sys.argv[1]}: {msg}")
    sys.exit(1)


def casteljau(pts, t):
    pts = [list(p) for p in pts]
    for r in range(len(pts) - 1, 0, -1):
        for k in range(r):
            pts[k] = [a + (b - a) * t for a, b in zip(pts[k], pts[k + 1])]
    return pts[0]


def bezier(patch, u, v):
    """JSON patch: points[(d+1)*j + i] = b_ij, i along u."""
    n = patch["degree"] + 1
    p = patch["points"]
    rows = [casteljau([p[n * j + i] for j in range(n)], v) for i in range(n)]
    return casteljau(rows, u)


def dist(a, b):
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)))


def xyz(p):
    return (p.X(), p.Y(), p.Z())


def shapes(shape, kind):
    m = ShapeMap()
    TopExp.MapShapes_s(shape, kind, m)
    return [m.FindKey(k) for k in range(1, m.Extent() + 1)]


def parse_log(path):
    text = open(path).read()
    m = re.search(
        r"^  step +(\d+) faces? \((\d+) patch(?:es)?, (\d+) hole fills?\), (\d+) edges?, "
        r"(\d+) vert(?:ex|ices); (closed|open) shell[^;]*(?:; volume ([^;]+))?;",
        text,
        re.M,
    )
    if not m:
        fail(f"no step line in {path}")
    return {
        "faces": int(m[1]),
        "patches": int(m[2]),
        "fills": int(m[3]),
        "edges": int(m[4]),
        "vertices": int(m[5]),
        "closed": m[6] == "closed",
        "volume": float(m[7]) if m[7] else None,
    }


def boundary_loops(obj_path):
    """The input's boundary loops (vertex positions in order) from an OBJ."""
    verts, faces = [], []
    for line in open(obj_path):
        w = line.split()
        if not w:
            continue
        if w[0] == "v":
            verts.append(tuple(float(x) for x in w[1:4]))
        elif w[0] == "f":
            faces.append([int(x.split("/")[0]) - 1 for x in w[1:]])
    count = {}
    for f in faces:
        for a, b in zip(f, f[1:] + f[:1]):
            k = (min(a, b), max(a, b))
            count[k] = count.get(k, 0) + 1
    nxt = {}
    for f in faces:
        for a, b in zip(f, f[1:] + f[:1]):
            if count[(min(a, b), max(a, b))] == 1:
                nxt[a] = b
    loops = []
    while nxt:
        start = next(iter(nxt))
        loop, v = [], start
        while v in nxt:
            loop.append(v)
            v = nxt.pop(v)
        loops.append([verts[i] for i in loop])
    return loops


def periodic_cubic(points):
    """The periodic uniform cubic B-spline with these control points."""
    n = len(points)
    poles = Array1_gp_Pnt(1, n)
    for k, p in enumerate(points):
        poles.SetValue(k + 1, gp_Pnt(*p))
    knots = Array1_double(1, n + 1)
    mults = Array1_int(1, n + 1)
    for k in range(n + 1):
        knots.SetValue(k + 1, float(k))
        mults.SetValue(k + 1, 1)
    return Geom_BSplineCurve(poles, knots, mults, 3, True)


def main():
    if len(sys.argv) < 4:
        print(__doc__)
        sys.exit(2)
    step_path, json_path, log_path = sys.argv[1:4]
    mesh = sys.argv[sys.argv.index("--mesh") + 1] if "--mesh" in sys.argv else None
    want = parse_log(log_path)
    surface = json.load(open(json_path))
    if "--f32" in sys.argv:
        f32 = lambda x: struct.unpack("f", struct.pack("f", x))[0]  # noqa: E731
        for q in surface["patches"]:
            q["points"] = [[f32(x) for x in p] for p in q["points"]]
        for c in surface["caps"]:
            c["limit"] = [f32(x) for x in c["limit"]]
    patches = surface["patches"]
    limits = [c["limit"] for c in surface["caps"]]
    if len(patches) != want["patches"]:
        fail(f"the JSON has {len(patches)} patches, the STEP run wrote {want['patches']}")
    lo = [min(p[k] for q in patches for p in q["points"]) for k in range(3)]
    hi = [max(p[k] for q in patches for p in q["points"]) for k in range(3)]
    size = max(h - l for h, l in zip(hi, lo))
    tol = SURFACE_TOL * size

    t0 = time.time()
    reader = STEPControl_Reader()
    if reader.ReadFile(step_path) != IFSelect_RetDone:
        fail("STEPControl_Reader could not read the file")
    checks = reader.WS().ModelCheckList()
    if not checks.IsEmpty(True):
        fail("the load check has fails (see reader.PrintCheckLoad)")
    if not checks.IsEmpty(False):
        fail("the load check has warnings (see reader.PrintCheckLoad)")
    if reader.TransferRoots() < 1:
        fail("no root transferred")
    shape = reader.OneShape()
    if shape.IsNull():
        fail("null shape")
    read_s = time.time() - t0

    # 2. validity
    if not BRepCheck_Analyzer(shape).IsValid():
        fail("BRepCheck_Analyzer: the shape is not valid")

    # 3. counts
    faces = []
    ex = TopExp_Explorer(shape, TopAbs_FACE)
    while ex.More():
        faces.append(TopoDS.Face(ex.Current()))
        ex.Next()
    edges = [e for e in shapes(shape, TopAbs_EDGE) if not BRep_Tool.Degenerated_s(TopoDS.Edge(e))]
    vertices = shapes(shape, TopAbs_VERTEX)
    got = (len(faces), len(edges), len(vertices))
    if got != (want["faces"], want["edges"], want["vertices"]):
        fail(f"faces, edges, vertices {got}, written {(want['faces'], want['edges'], want['vertices'])}")

    # 4. patch faces against the JSON patches
    params = [0.0, 0.125, 1 / 3, 0.5, 0.7, 0.875, 1.0]
    worst = 0.0
    for k, patch in enumerate(patches):
        s = BRep_Tool.Surface_s(faces[k])
        a = GeomAdaptor_Surface(s)
        d = patch["degree"]
        if a.GetType() != GeomAbs_BSplineSurface or a.UDegree() != d or a.VDegree() != d:
            fail(f"face {k}: not a B-spline surface of degree {d}")
        for u in params:
            for v in params:
                e = dist(xyz(s.Value(u, v)), bezier(patch, u, v))
                worst = max(worst, e)
        if worst > tol:
            fail(f"face {k}: surface differs from capdiv's patch by {worst:.3g} > {tol:.3g}")

    # 5. hole fills
    mids = []
    for patch in patches:
        n = patch["degree"] + 1
        p = patch["points"]
        b = lambda i, j: p[n * j + i]  # noqa: E731
        for edge in (
            [b(i, 0) for i in range(n)],
            [b(n - 1, j) for j in range(n)],
            [b(i, n - 1) for i in range(n)],
            [b(0, j) for j in range(n)],
        ):
            mids.append(casteljau(edge, 0.5))
    fill_worst = 0.0
    for k in range(want["patches"], want["faces"]):
        s = BRep_Tool.Surface_s(faces[k])
        top = [xyz(s.Value(u, 1.0)) for u in params]
        if not limits or min(max(dist(t, c) for t in top) for c in limits) > tol:
            fail(f"face {k}: a hole fill whose side v = 1 is no cap's limit point")
        for u in params:
            a0, a1 = xyz(s.Value(u, 0.0)), xyz(s.Value(u, 1.0))
            for v in params:
                ruled = [x + (y - x) * v for x, y in zip(a0, a1)]
                fill_worst = max(fill_worst, dist(xyz(s.Value(u, v)), ruled))
        m = xyz(s.Value(0.5, 0.0))
        if min(dist(m, q) for q in mids) > tol:
            fail(f"face {k}: a hole fill whose side v = 0 is no patch edge")
    if fill_worst > tol:
        fail(f"hole fills not ruled: {fill_worst:.3g} > {tol:.3g}")

    # 6, 7. shell
    ancestors = EdgeFaces()
    TopExp.MapShapesAndAncestors_s(shape, TopAbs_EDGE, TopAbs_FACE, ancestors)
    free = []
    for k in range(1, ancestors.Extent() + 1):
        e = TopoDS.Edge(ancestors.FindKey(k))
        if BRep_Tool.Degenerated_s(e):
            continue
        n = ancestors.FindFromIndex(k).Size()
        if n > 2:
            fail("an edge of more than two faces")
        if n == 1:
            free.append(e)
    extra = ""
    if want["closed"]:
        if shape.ShapeType() != TopAbs_SOLID:
            fail(f"a closed shell written, {shape.ShapeType()} read")
        if free:
            fail(f"{len(free)} free edges on a closed shell")
        props = GProp_GProps()
        BRepGProp.VolumeProperties_s(shape, props, 1e-9)
        occ = props.Mass()
        rel = abs(occ - want["volume"]) / abs(want["volume"])
        if rel > (VOLUME_TOL_F32 if "--f32" in sys.argv else VOLUME_TOL):
            fail(f"volume {occ!r} (OpenCascade) vs {want['volume']!r} (capdiv): {rel:.3g} relative")
        extra = f"; volume {occ:.12g} vs capdiv {want['volume']:.12g} ({rel:.2g} relative)"
    else:
        if mesh is None:
            fail("an open shell and no --mesh to find its boundary")
        loops = boundary_loops(mesh)
        curves = [periodic_cubic(loop) for loop in loops]
        if not free:
            fail("an open shell without free edges")
        on = 0.0
        length = 0.0
        for e in free:
            c = BRepAdaptor_Curve(e)
            length += GCPnts_AbscissaPoint.Length_s(c)
            a, b = c.FirstParameter(), c.LastParameter()
            for t in range(5):
                p = c.Value(a + (b - a) * t / 4)
                best = math.inf
                for g in curves:
                    proj = GeomAPI_ProjectPointOnCurve(p, g)
                    if proj.NbPoints() > 0:
                        best = min(best, proj.LowerDistance())
                on = max(on, best)
        if on > tol:
            fail(f"a free edge {on:.3g} off the input's boundary curve (> {tol:.3g})")
        total = sum(GCPnts_AbscissaPoint.Length_s(GeomAdaptor_Curve(g)) for g in curves)
        rel = abs(length - total) / total
        if rel > LENGTH_TOL:
            fail(f"free edges {length!r} long, the boundary curves {total!r}: {rel:.3g} relative")
        extra = (
            f"; {len(free)} free edges on {len(loops)} boundary loops, {on / size:.2g} of the size "
            f"off, length {rel:.2g} relative"
        )
    print(
        f"check_step: {step_path}: read {read_s:.2f} s, load check clean, valid; {len(faces)} faces, {len(edges)} edges, "
        f"{len(vertices)} vertices; patch error {worst / size:.2g}, fill error {fill_worst / size:.2g} "
        f"of size {size:.6g}{extra}"
    )


if __name__ == "__main__":
    main()
