#!/usr/bin/env python3
"""The analytic meshes of the boolean set (boolean_set.sh): a sphere, a box and a torus around
the origin, the size of the unit-scale meshes of ../shared/data (fandisk, knot1, ...), written
as OBJ into the folder given (default: /tmp/strata_boolean_set)."""
import math
import os
import sys


def write_obj(path, vertices, faces):
    with open(path, "w") as f:
        for v in vertices:
            f.write("v %.9g %.9g %.9g\n" % v)
        for t in faces:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))


def icosphere(radius, levels):
    t = (1.0 + math.sqrt(5.0)) / 2.0
    verts = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
             (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    verts = [tuple(c / math.sqrt(sum(x * x for x in v)) for c in v) for v in verts]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(levels):
        cache = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                m = [(verts[a][k] + verts[b][k]) / 2 for k in range(3)]
                n = math.sqrt(sum(x * x for x in m))
                verts.append(tuple(x / n for x in m))
                cache[key] = len(verts) - 1
            return cache[key]

        new = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            new += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = new
    return [tuple(radius * x for x in v) for v in verts], faces


def box(side):
    h = side / 2
    verts = [(x, y, z) for z in (-h, h) for y in (-h, h) for x in (-h, h)]
    # corners: index = x + 2y + 4z; outward counter-clockwise quads
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    faces = []
    for a, b, c, d in quads:
        faces += [(a, b, c), (a, c, d)]
    return verts, faces


def torus(major, minor, around, across):
    verts, faces = [], []
    for i in range(around):
        u = 2 * math.pi * i / around
        for j in range(across):
            v = 2 * math.pi * j / across
            r = major + minor * math.cos(v)
            verts.append((r * math.cos(u), r * math.sin(u), minor * math.sin(v)))
    for i in range(around):
        for j in range(across):
            a = i * across + j
            b = ((i + 1) % around) * across + j
            c = ((i + 1) % around) * across + (j + 1) % across
            d = i * across + (j + 1) % across
            faces += [(a, b, c), (a, c, d)]
    return verts, faces


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else "/tmp/strata_boolean_set"
    os.makedirs(folder, exist_ok=True)
    write_obj(os.path.join(folder, "sphere.obj"), *icosphere(0.42, 4))
    write_obj(os.path.join(folder, "box.obj"), *box(0.62))
    write_obj(os.path.join(folder, "torus.obj"), *torus(0.33, 0.12, 96, 48))


if __name__ == "__main__":
    main()
