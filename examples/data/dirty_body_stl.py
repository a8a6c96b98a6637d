#!/usr/bin/env python3
"""Writes dirty_body.stl: a finned body as a CAD tool or a scan leaves it, for --wrap (issue 56).

A body of revolution (radius 0.1, 1 long, rounded nose, blunt tail) with four fins whose flat
roots sit on it and touch it along a line only (no overlap), a canopy (a sphere) pushed half
into it, a hole where three of its facets are missing, one facet written twice, and a loose
flap sharing one of its edges (a non-manifold edge). Each part is an STL solid of its own
(patches body, fins, canopy). Nothing here is repaired in place: the check stops on the first
defect it meets. Deterministic (no randomness): python3 dirty_body_stl.py OUT.stl
With --touching, the body and its fins only, each part closed and clean, the fins touching the
body along a line (fins_touching_body.stl: what --fuse must join):
python3 dirty_body_stl.py fins_touching_body.stl --touching
"""
import math
import sys


def body(n_around=32, n_along=40, radius=0.1, length=1.0, nose=0.2):
    """Rings along x: a nose of revolution over [0, nose], a cylinder, a flat tail cap."""
    rings = []
    for i in range(n_along + 1):
        x = length * i / n_along
        r = radius * math.sqrt(max(0.0, 1.0 - ((nose - x) / nose) ** 2)) if x < nose else radius
        rings.append((x, r))
    pts = [(0.0, 0.0, 0.0)]
    for x, r in rings[1:]:
        for j in range(n_around):
            t = 2 * math.pi * j / n_around
            pts.append((x, r * math.cos(t), r * math.sin(t)))
    tail = len(pts)
    pts.append((length, 0.0, 0.0))
    ring = lambda i, j: 1 + (i - 1) * n_around + j % n_around
    tris = [(0, ring(1, j + 1), ring(1, j)) for j in range(n_around)]
    for i in range(1, n_along):
        for j in range(n_around):
            a, b, c, d = ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j)
            tris += [(a, b, c), (a, c, d)]
    tris += [(tail, ring(n_along, j), ring(n_along, j + 1)) for j in range(n_around)]
    return pts, tris


def box(lo, hi, frame):
    """A box in local coordinates (u along x, v across, w out), placed by frame(u, v, w)."""
    c = [frame(u, v, w) for u in (lo[0], hi[0]) for v in (lo[1], hi[1]) for w in (lo[2], hi[2])]
    # Corner index: 4 u + 2 v + w; outward faces.
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    tris = []
    for a, b, c2, d in quads:
        tris += [(a, b, c2), (a, c2, d)]
    return c, tris


def sphere(centre, radius, n=12):
    pts = [(centre[0], centre[1], centre[2] + radius)]
    for i in range(1, n):
        phi = math.pi * i / n
        for j in range(2 * n):
            t = math.pi * j / n
            pts.append((centre[0] + radius * math.sin(phi) * math.cos(t),
                        centre[1] + radius * math.sin(phi) * math.sin(t), centre[2] + radius * math.cos(phi)))
    pts.append((centre[0], centre[1], centre[2] - radius))
    m = 2 * n
    at = lambda i, j: 1 + (i - 1) * m + j % m
    tris = [(0, at(1, j), at(1, j + 1)) for j in range(m)]
    for i in range(1, n - 1):
        for j in range(m):
            tris += [(at(i, j), at(i + 1, j), at(i + 1, j + 1)), (at(i, j), at(i + 1, j + 1), at(i, j + 1))]
    last = len(pts) - 1
    tris += [(last, at(n - 1, j + 1), at(n - 1, j)) for j in range(m)]
    return pts, tris


def main(out, clean=False):
    solids = []
    pts, tris = body()
    v = lambda k: pts[k]
    faces = [tuple(v(k) for k in t) for t in tris]
    hole = set() if clean else {600, 601, 602}
    flap_edge = faces[900][:2]
    faces = [f for i, f in enumerate(faces) if i not in hole]
    if not clean:
        faces.append(faces[500])  # written twice
        mid = tuple(0.5 * (a + b) for a, b in zip(*flap_edge))
        faces.append((flap_edge[0], flap_edge[1], (mid[0], mid[1] * 1.6, mid[2] * 1.6)))  # a flap: 3 faces on an edge
    solids.append(("body", faces))
    fins = []
    for k in range(4):  # roots on the cylinder's vertex lines at 0, 90, 180, 270 degrees
        t = math.pi / 2 * k
        ct, st = math.cos(t), math.sin(t)
        frame = lambda u, vv, w, ct=ct, st=st: (u, (0.1 + w) * ct - vv * st, (0.1 + w) * st + vv * ct)
        c, bt = box((0.72, -0.004, 0.0), (0.95, 0.004, 0.09), frame)
        fins += [tuple(c[i] for i in t3) for t3 in bt]
    solids.append(("fins", fins))
    if not clean:
        sp, stris = sphere((0.35, 0.0, 0.1), 0.06)
        solids.append(("canopy", [tuple(sp[i] for i in t) for t in stris]))
    with open(out, "w") as f:
        for name, faces in solids:
            f.write(f"solid {name}\n")
            for tri in faces:
                f.write(" facet normal 0 0 0\n  outer loop\n")
                for p in tri:
                    f.write("   vertex %.7g %.7g %.7g\n" % p)
                f.write("  endloop\n endfacet\n")
            f.write(f"endsolid {name}\n")


if __name__ == "__main__":
    # --touching: the body and its fins only, closed and clean (fins_touching_body.stl)
    main(sys.argv[1] if len(sys.argv) > 1 else "dirty_body.stl", "--touching" in sys.argv[2:])
