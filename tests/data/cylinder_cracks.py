"""Source of cylinder_cracks.stl (tests/surface/test_prepare.cpp, tests/app/test_cli.cpp): a closed
cylinder (radius 0.5, length 2 along x) as an exporter that tessellates each face alone writes
it: the side meshed with 32 nodes round each end circle, each flat end with 24 of its own, all
on the true circle, so that between the 8 nodes both sides share the end circles are cracks
(one side's nodes lie off the other side's chords by their sagitta, up to 0.0043).
    /usr/bin/python3 cylinder_cracks.py cylinder_cracks.stl
"""
import math
import sys

R, L, SIDE, END, RINGS = 0.5, 2.0, 32, 24, 8


def circle(x, n, r=R):
    return [(x, r * math.cos(2 * math.pi * k / n), r * math.sin(2 * math.pi * k / n)) for k in range(n)]


facets = []
rings = [circle(L * i / RINGS, SIDE) for i in range(RINGS + 1)]
for i in range(RINGS):  # the side, normals outward
    a, b = rings[i], rings[i + 1]
    for k in range(SIDE):
        k1 = (k + 1) % SIDE
        facets += [(a[k], b[k1], b[k]), (a[k], a[k1], b[k1])]
for x, outward in ((0.0, -1), (L, 1)):  # the ends: a fan round a ring at half the radius
    outer, inner, centre = circle(x, END), circle(x, END // 2, R / 2), (x, 0.0, 0.0)
    tris = []
    for k in range(END // 2):
        o0, o1, o2 = outer[2 * k], outer[2 * k + 1], outer[(2 * k + 2) % END]
        i0, i1 = inner[k], inner[(k + 1) % (END // 2)]
        tris += [(o0, o1, i0), (o1, i1, i0), (o1, o2, i1), (centre, i0, i1)]
    facets += [t if outward > 0 else (t[0], t[2], t[1]) for t in tris]


def normal(t):
    u = [t[1][i] - t[0][i] for i in range(3)]
    v = [t[2][i] - t[0][i] for i in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    s = math.sqrt(sum(c * c for c in n)) or 1.0
    return [c / s for c in n]


with open(sys.argv[1], "w") as f:
    f.write("solid cylinder\n")
    for t in facets:
        f.write("facet normal %.9g %.9g %.9g\nouter loop\n" % tuple(normal(t)))
        for p in t:
            f.write("vertex %.9g %.9g %.9g\n" % p)
        f.write("endloop\nendfacet\n")
    f.write("endsolid cylinder\n")
