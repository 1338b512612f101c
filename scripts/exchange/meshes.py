#!/usr/bin/env python3
"""Writes the generated test meshes of scripts/ci-step.sh into DIR (OBJ):

- tube.obj: an open cylinder, 8 around, 3 quads high (regular; two boundary
  loops of valence-3 vertices);
- bowl.obj: a pole of 6 triangles (a polar cap) over 3 rings of quads, open
  at the rim;
- open-box.obj: a cube without its top face (valence-3 extraordinary points
  at the bottom corners, one boundary loop);
- icosahedron.obj: 20 triangles, valence-5 vertices (closed);
- pole-sphere.obj: a UV sphere, 7 around, triangle fans at both poles (closed).

    meshes.py DIR
"""

import math
import os
import sys


def write(path, verts, faces):
    with open(path, "w") as f:
        for v in verts:
            f.write("v %r %r %r\n" % tuple(v))
        for face in faces:
            f.write("f " + " ".join(str(i + 1) for i in face) + "\n")


def ring(n, radius, z, phase=0.0):
    return [
        (radius * math.cos(2 * math.pi * (k + phase) / n), radius * math.sin(2 * math.pi * (k + phase) / n), z)
        for k in range(n)
    ]


def band(n, a, b):
    """Quads between rings starting at vertex a and b (n each), outward for
    a below b with counter-clockwise rings."""
    return [(a + k, a + (k + 1) % n, b + (k + 1) % n, b + k) for k in range(n)]


def tube():
    n = 8
    verts = [p for h in range(4) for p in ring(n, 1.0 + 0.1 * h, 0.5 * h)]
    faces = [q for h in range(3) for q in band(n, n * h, n * (h + 1))]
    return verts, faces


def bowl():
    n = 6
    verts = [(0.0, 0.0, 0.0)]
    for h in range(1, 5):
        verts += ring(n, 0.5 * h, 0.3 * h * h, 0.25 * h)
    # The fan and the bands face outward (down and away from the axis).
    faces = [(0, 1 + (k + 1) % n, 1 + k) for k in range(n)]
    for h in range(3):
        faces += band(n, 1 + n * h, 1 + n * (h + 1))
    return verts, faces


def open_box():
    v = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
    f = [(0, 3, 2, 1), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    return [tuple(float(x) for x in p) for p in v], f


def icosahedron():
    t = (1 + math.sqrt(5)) / 2
    v = [
        (-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0),
        (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
        (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1),
    ]
    f = [
        (0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11),
        (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8),
        (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
        (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1),
    ]
    return [tuple(float(x) for x in p) for p in v], f


def pole_sphere():
    n, rings = 7, 5
    verts = [(0.0, 0.0, -1.0)]
    for h in range(1, rings + 1):
        phi = math.pi * h / (rings + 1)
        verts += ring(n, math.sin(phi), -math.cos(phi))
    verts.append((0.0, 0.0, 1.0))
    top = len(verts) - 1
    faces = [(0, 1 + (k + 1) % n, 1 + k) for k in range(n)]
    for h in range(rings - 1):
        faces += band(n, 1 + n * h, 1 + n * (h + 1))
    last = 1 + n * (rings - 1)
    faces += [(last + k, last + (k + 1) % n, top) for k in range(n)]
    return verts, faces


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for name, make in [
        ("tube", tube),
        ("bowl", bowl),
        ("open-box", open_box),
        ("icosahedron", icosahedron),
        ("pole-sphere", pole_sphere),
    ]:
        write(os.path.join(out, name + ".obj"), *make())


if __name__ == "__main__":
    main()
