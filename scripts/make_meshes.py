#!/usr/bin/env python3
"""Writes the OBJ models the project ships (no dependencies beyond Python 3):
  scenes/meshes/cup.obj    a cup: a closed solid (outer wall, bottom, rim, inner wall, inner floor),
                           radius 0.5, height 1, wall 0.15 thick, 48 segments; scale and place it in a scene
  tests/data/box_12.obj    the unit cube [0, 1]^3 as 12 triangles (tests: a mesh against the box shape)
Every triangle runs counter-clockwise seen from outside the solid (mesh.h)."""
import math, os, sys

def write(path, vertices, faces, comment):
    with open(path, "w") as f:
        f.write("# %s\n# written by scripts/make_meshes.py\n" % comment)
        for v in vertices:
            f.write("v %.9g %.9g %.9g\n" % v)
        for t in faces:
            f.write("f %d %d %d\n" % tuple(i + 1 for i in t))

def cup(n=48, radius=0.5, height=1.0, wall=0.15):
    inner = radius - wall
    rings = [(radius, 0.0), (radius, height), (inner, height), (inner, wall)]  # outer bottom .. inner floor
    v = []
    for r, y in rings:
        for k in range(n):
            a = 2 * math.pi * k / n
            v.append((r * math.cos(a), y, r * math.sin(a)))
    bottom_centre, floor_centre = len(v), len(v) + 1
    v += [(0.0, 0.0, 0.0), (0.0, wall, 0.0)]
    f = []
    ring = lambda i, k: i * n + k % n
    # Side bands between consecutive rings, outward from the solid: outer wall, rim, inner wall.
    for i in range(3):
        for k in range(n):
            a, b, c, d = ring(i, k), ring(i, k + 1), ring(i + 1, k + 1), ring(i + 1, k)
            f += [(a, d, c), (a, c, b)]
    for k in range(n):  # bottom faces down, inner floor faces up
        f.append((bottom_centre, ring(0, k), ring(0, k + 1)))
        f.append((floor_centre, ring(3, k + 1), ring(3, k)))
    return v, f

def box():
    v = [(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
    i = lambda x, y, z: x + 2 * y + 4 * z
    quads = [  # each counter-clockwise seen from outside
        (i(0, 0, 0), i(0, 0, 1), i(0, 1, 1), i(0, 1, 0)),  # x = 0
        (i(1, 0, 0), i(1, 1, 0), i(1, 1, 1), i(1, 0, 1)),  # x = 1
        (i(0, 0, 0), i(1, 0, 0), i(1, 0, 1), i(0, 0, 1)),  # y = 0
        (i(0, 1, 0), i(0, 1, 1), i(1, 1, 1), i(1, 1, 0)),  # y = 1
        (i(0, 0, 0), i(0, 1, 0), i(1, 1, 0), i(1, 0, 0)),  # z = 0
        (i(0, 0, 1), i(1, 0, 1), i(1, 1, 1), i(0, 1, 1)),  # z = 1
    ]
    f = []
    for a, b, c, d in quads:
        f += [(a, b, c), (a, c, d)]
    return v, f

if __name__ == "__main__":
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    write(os.path.join(root, "scenes/meshes/cup.obj"), *cup(), "a cup: radius 0.5, height 1, wall 0.15; a closed solid whose cavity opens at the top (y = 1)")
    write(os.path.join(root, "tests/data/box_12.obj"), *box(), "the unit cube [0, 1]^3 as 12 triangles")
