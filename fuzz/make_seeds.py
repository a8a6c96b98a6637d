#!/usr/bin/env python3
"""Write the committed seed corpus of the fuzz targets (fuzz/corpus/stl, fuzz/corpus/surface).

Small valid inputs that reach deep: every one is read (or decoded) and prepared without error
and has node rings (tests/fuzz/test_fuzz_regressions.cpp checks it), so the fuzzer starts from
meshes that pass every check and mutates them into ones that do not. The soup format is
documented at decode_soup in fuzz/fuzz_surface.cpp.
    python3 fuzz/make_seeds.py [OUT_DIR]   (default: fuzz/corpus)
"""
import os
import struct
import sys

out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus")

# ---------------------------------------------------------------------------------------- shapes
TETRA_POINTS = [(0, 0, 0), (3, 0, 0), (0, 3, 0), (0, 0, 3)]
TETRA_FACES = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
# Cube [0,3]^3: node x + 2y + 4z of the unit cube, scaled by 3; quads outward.
CUBE_POINTS = [(3 * (i & 1), 3 * ((i >> 1) & 1), 3 * ((i >> 2) & 1)) for i in range(8)]
CUBE_QUADS = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]


def triangles(quads):
    return [t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))]


def write(name, data):
    path = os.path.join(out, name)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data)


# ------------------------------------------------------------------------------------------- STL
def ascii_stl(solids, newline="\n", bom=False, upper=False):
    """solids: [(name, points, faces)]"""
    kw = (lambda s: s.upper()) if upper else (lambda s: s)
    lines = []
    for name, pts, faces in solids:
        lines.append(kw("solid") + " " + name)
        for f in faces:
            lines.append("  " + kw("facet normal") + " 0 0 0")
            lines.append("    " + kw("outer loop"))
            for v in f:
                x, y, z = pts[v]
                lines.append("      %s %s %s %s" % (kw("vertex"), repr(float(x)), "%.6E" % y, ("+%g" if z >= 0 else "%g") % z))
            lines.append("    " + kw("endloop"))
            lines.append("  " + kw("endfacet"))
        lines.append(kw("endsolid") + " " + name)
    text = newline.join(lines) + newline
    return (b"\xef\xbb\xbf" if bom else b"") + text.encode()


def binary_stl(points, faces, header):
    data = header.encode().ljust(80, b" ")[:80] + struct.pack("<I", len(faces))
    for f in faces:
        data += struct.pack("<3f", 0, 0, 0)
        for v in f:
            data += struct.pack("<3f", *points[v])
        data += struct.pack("<H", 0)
    return data


def offset(points, d):
    return [(x + d, y + d, z + d) for x, y, z in points]


write("stl/tetra_ascii.stl", ascii_stl([("tetra", TETRA_POINTS, TETRA_FACES)]))
write("stl/tetra_binary.stl", binary_stl(TETRA_POINTS, TETRA_FACES, "binary tetra"))
# A binary file whose header starts with "solid": told apart from ASCII by its size.
write("stl/cube_binary_solid_header.stl", binary_stl(CUBE_POINTS, triangles(CUBE_QUADS), "solid cube"))
# Byte-order mark, CRLF, upper-case keywords, two solids sharing the nodes of one closed cube.
cube_tris = triangles(CUBE_QUADS)
write("stl/cube_two_solids_crlf_bom.stl",
      ascii_stl([("side", CUBE_POINTS, cube_tris[:6]), ("top", CUBE_POINTS, cube_tris[6:])], "\r\n", True, True))
# A farfield box round a tetrahedron: orientation inward for the box, outward for the body.
box = [(3 * x - 3, 3 * y - 3, 3 * z - 3) for x, y, z in CUBE_POINTS]
write("stl/tetra_in_farfield_box.stl",
      ascii_stl([("farfield", box, cube_tris), ("body", offset(TETRA_POINTS, 0.5), TETRA_FACES)]))
# An open surface: two triangles of a square, one boundary loop.
write("stl/open_square.stl", ascii_stl([("", CUBE_POINTS, [(0, 1, 3), (0, 3, 2)])]))


# ---------------------------------------------------------------------------------------- soups
def g(p):
    """Grid byte of a point of the 4x4x4 lattice."""
    x, y, z = p
    return x | (y << 2) | (z << 4)


def soup(points, faces, flags=0, patches=None, node_bytes=None):
    """faces: tuples of 3 or 4 node ids; patches: a patch (0-3) per face."""
    data = bytes([flags, len(points)])
    data += bytes(node_bytes) if node_bytes is not None else bytes(g(p) for p in points)
    for i, f in enumerate(faces):
        patch = patches[i] if patches else 0
        data += bytes([(1 if len(f) == 4 else 0) | (patch << 1)] + list(f))
    return data


write("surface/tetrahedron", soup(TETRA_POINTS, TETRA_FACES))
write("surface/cube_quads", soup(CUBE_POINTS, CUBE_QUADS))
# Mixed: the cube with three sides split into triangles, on two patches, internal flow.
mixed = CUBE_QUADS[:3] + triangles(CUBE_QUADS[3:])
write("surface/cube_mixed_internal_flow", soup(CUBE_POINTS, mixed, flags=0x01 | 0x10, patches=[0, 1] * 4 + [1]))
# A 3 x 3 grid of quads in z = 0 (open, one boundary loop), node i = x + 4y.
grid_points = [(x, y, 0) for y in range(4) for x in range(4)]
grid_quads = [(x + 4 * y, x + 1 + 4 * y, x + 5 + 4 * y, x + 4 + 4 * y) for y in range(3) for x in range(3)]
write("surface/open_grid_quads", soup(grid_points, grid_quads))
# The tetrahedron exploded (3 nodes per face, copies 1e-10 apart: byte 0x40 | grid), merged back.
exploded = [TETRA_POINTS[v] for f in TETRA_FACES for v in f]
write("surface/tetrahedron_exploded",
      soup(exploded, [(3 * i, 3 * i + 1, 3 * i + 2) for i in range(4)],
           node_bytes=[g(p) | (0x40 if i % 2 else 0) for i, p in enumerate(exploded)]))
# A pyramid with one side given as a quad that repeats a node (a, b, c, c): made a triangle by
# remove_collapsed_faces, and the surface is closed.
pyramid_points = [(0, 0, 0), (3, 0, 0), (3, 3, 0), (0, 3, 0), (1, 1, 3)]
pyramid = [(0, 3, 2, 1), (0, 1, 4, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)]
write("surface/pyramid_collapsed_quad", soup(pyramid_points, pyramid))
# A farfield cube (patch 1) round a tetrahedron in a half-grid offset, tolerance 1e-3.
inner = [(1, 1, 1), (2, 1, 1), (1, 2, 1), (1, 1, 2)]
write("surface/tetra_in_farfield_cube",
      soup(CUBE_POINTS + inner, CUBE_QUADS + [tuple(8 + v for v in f) for f in TETRA_FACES], flags=0x04 | 0x10,
           patches=[1] * 6 + [0] * 4))
