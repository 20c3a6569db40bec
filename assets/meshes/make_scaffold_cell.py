#!/usr/bin/env python3
"""Writes scaffold_cell.obj: one tile of the bone scaffold's porous core (a cubic strut lattice).

The tile is 14 x 12 x 34 mm, centred on the origin; 3 x 3 x 3 of them cover the 100 mm femur of
assets/scenes/bone_scaffold.strata.json. Struts of radius 0.4 mm run along x, y and z on a 2 mm
pitch, half a pitch in from the tile's faces, so that neighbouring tiles continue one lattice
(pores of 1.2 mm between struts); each strut reaches 0.3 mm past the faces, so the struts of
neighbouring tiles overlap instead of touching cap to cap.

Each strut is its own closed, outward-oriented 12-sided prism: the file is one mesh of 263
overlapping closed shells, which Strata samples as their union (engine/ldi/shared_math.h,
normalizeLeafRay: inside where the winding number is non-zero). No dependencies; run with no
arguments from this folder to rewrite the file (deterministic output).
"""
import math

SIZE = (14.0, 12.0, 34.0)  # tile extent, mm
PITCH = 2.0
RADIUS = 0.4
REACH = 0.3  # how far a strut runs past the tile's faces
SIDES = 12


def positions(extent):
    """Strut centre lines along one axis: half a pitch in from each face."""
    n = int(round(extent / PITCH))
    return [-extent / 2 + PITCH * (k + 0.5) for k in range(n)]


def prism(axis, u, v, length):
    """A closed prism along `axis` through (u, v) on the two other axes, outward oriented."""
    verts, tris = [], []
    for end in (-length / 2, length / 2):
        for k in range(SIDES):
            a = 2 * math.pi * k / SIDES
            p = [0.0, 0.0, 0.0]
            p[axis] = end
            p[(axis + 1) % 3] = u + RADIUS * math.cos(a)
            p[(axis + 2) % 3] = v + RADIUS * math.sin(a)
            verts.append(p)
    for k in range(SIDES):
        k1 = (k + 1) % SIDES
        a, b, c, d = k, k1, SIDES + k1, SIDES + k
        tris += [(a, b, c), (a, c, d)]  # side quad, normal pointing away from the axis
    for k in range(1, SIDES - 1):
        tris.append((0, k + 1, k))  # cap at -length/2, facing -axis
        tris.append((SIDES, SIDES + k, SIDES + k + 1))  # cap at +length/2, facing +axis
    return verts, tris


def main():
    verts, tris = [], []
    for axis in range(3):
        us = positions(SIZE[(axis + 1) % 3])
        vs = positions(SIZE[(axis + 2) % 3])
        for u in us:
            for v in vs:
                pv, pt = prism(axis, u, v, SIZE[axis] + 2 * REACH)
                base = len(verts)
                verts += pv
                tris += [(a + base, b + base, c + base) for a, b, c in pt]
    with open("scaffold_cell.obj", "w", newline="\n") as f:
        f.write("# scaffold_cell.obj: written by make_scaffold_cell.py (see its docstring)\n")
        for p in verts:
            f.write("v %.6f %.6f %.6f\n" % tuple(p))
        for a, b, c in tris:
            f.write("f %d %d %d\n" % (a + 1, b + 1, c + 1))
    print("scaffold_cell.obj: %d struts, %d vertices, %d triangles"
          % (len(verts) // (2 * SIDES), len(verts), len(tris)))


if __name__ == "__main__":
    main()
