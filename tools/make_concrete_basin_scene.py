#!/usr/bin/env python3
"""Writes scenes/concrete_basin.obj byte for byte (docs/scenes.md, "concrete_basin").

A 25 x 12 m concrete test basin, 4 m deep: x 0..25 m East, y 0..12 m North, vertical walls from
the floor (z = -4 m) to 0.5 m above the surface; a floating pontoon 10 x 2 m (x 4..14 m,
y 9.5..11.5 m) drawing 0.6 m; two vertical pipes 0.3 m across (12-sided) standing on the floor at
(18, 2.5) and (21, 9) m. Every face a triangle, counter-clockwise seen from the water.

Usage: tools/make_concrete_basin_scene.py OUT.obj
"""
import math
import sys

HEADER = """\
# A 25 x 12 m concrete test basin, 4 m deep, as a new user with a small vehicle would describe the
# tank they test in (issue 47, item 4: a closed, four-walled basin is not ambiguous): x 0..25 m East,
# y 0..12 m North, vertical walls from the floor (z = -4 m) to 0.5 m above the surface; a floating
# pontoon 10 x 2 m (x 4..14 m, y 9.5..11.5 m) drawing 0.6 m; two vertical pipes 0.3 m across
# standing on the floor, at (18, 2.5) and (21, 9) m (12-sided). Metres, z up, surface at z = 0;
# every face a triangle, counter-clockwise seen from the water. Groups: walls, floor, pontoon,
# pipes. Written by tools/make_concrete_basin_scene.py (docs/scenes.md, "concrete_basin")."""


class Mesh:
    def __init__(self):
        self.vertices = []
        self.groups = []

    def vertex(self, x, y, z):
        self.vertices.append((x, y, z))
        return len(self.vertices)  # OBJ indices start at 1

    def group(self, name, faces):
        self.groups.append((name, faces))


def box(mesh, x0, y0, x1, y1, z0, z1):
    """A closed box, faces facing out."""
    c = [mesh.vertex(x0, y0, z0), mesh.vertex(x1, y0, z0), mesh.vertex(x1, y1, z0),
         mesh.vertex(x0, y1, z0), mesh.vertex(x0, y0, z1), mesh.vertex(x1, y0, z1),
         mesh.vertex(x1, y1, z1), mesh.vertex(x0, y1, z1)]
    quads = [(0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7), (4, 5, 6, 7), (3, 2, 1, 0)]
    faces = []
    for q in quads:
        a, b, cc, d = (c[i] for i in q)
        faces += [(a, b, cc), (a, cc, d)]
    return faces


def pipe(mesh, cx, cy, radius, z0, z1, sides=12):
    """An open vertical prism, sides facing out."""
    ring = [(cx + radius * math.cos(2 * math.pi * k / sides),
             cy + radius * math.sin(2 * math.pi * k / sides)) for k in range(sides)]
    low = [mesh.vertex(x, y, z0) for x, y in ring]
    high = [mesh.vertex(x, y, z1) for x, y in ring]
    faces = []
    for k in range(sides):
        n = (k + 1) % sides
        faces += [(low[k], low[n], high[n]), (low[k], high[n], high[k])]
    return faces


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    mesh = Mesh()
    f = [mesh.vertex(0, 0, -4), mesh.vertex(25, 0, -4), mesh.vertex(25, 12, -4),
         mesh.vertex(0, 12, -4)]
    t = [mesh.vertex(0, 0, 0.5), mesh.vertex(25, 0, 0.5), mesh.vertex(25, 12, 0.5),
         mesh.vertex(0, 12, 0.5)]
    walls = []
    for k in range(4):  # south, east, north, west, facing the water
        n = (k + 1) % 4
        walls += [(f[k], t[n], f[n]), (f[k], t[k], t[n])]
    floor = [(f[0], f[1], f[2]), (f[0], f[2], f[3])]
    pontoon = box(mesh, 4, 9.5, 14, 11.5, -0.6, 0.4)
    pipes = pipe(mesh, 18, 2.5, 0.15, -4, 0.5) + pipe(mesh, 21, 9, 0.15, -4, 0.5)
    for name, faces in (("walls", walls), ("floor", floor), ("pontoon", pontoon), ("pipes", pipes)):
        mesh.group(name, faces)
    lines = [HEADER]
    lines += ["v %g %g %g" % tuple(round(c, 4) for c in v) for v in mesh.vertices]
    for name, faces in mesh.groups:
        lines.append("g " + name)
        lines += ["f %d %d %d" % face for face in faces]
    with open(sys.argv[1], "w", encoding="ascii") as out:
        out.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
