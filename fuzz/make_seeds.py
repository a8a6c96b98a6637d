#!/usr/bin/env python3
"""Write the committed seed corpus of the fuzz targets (fuzz/corpus/<target>).

Small valid inputs that reach deep (tests/fuzz/test_fuzz_regressions.cpp checks it), so the
fuzzer starts from meshes that pass every check and mutates them into ones that do not: every
STL file and soup is read (or decoded) and prepared without error and has node rings; every
.msh file is read by read_msh or read_volume_msh; every volume soup is written by both writers.
The soup formats are documented at decode_soup in fuzz/fuzz_surface.cpp and decode_volume in
fuzz/volume_soup.cpp. The .msh files are Gmsh's own (its Python module, Debian's python3-gmsh).
    python3 fuzz/make_seeds.py [OUT_DIR]   (default: fuzz/corpus)
"""
import os
import struct
import sys

try:
    import gmsh
except ImportError:  # Debian's python3-gmsh is installed for the system's python3
    sys.path.append("/usr/lib/python3/dist-packages")
    import gmsh

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


# ------------------------------------------------------------------------------------ volume soups
# Cells in Gmsh order with positive volumes on the 4x4x4 lattice: a hex [0,1]^3, a pyramid on
# its top, the cube [1,2]x[0,1]^2 as two prisms, a tetrahedron on the first prism's top.
EVERY_TYPE_POINTS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1),
                     (0, 0, 2), (2, 0, 0), (2, 1, 0), (2, 0, 1), (2, 1, 1), (2, 0, 2)]
EVERY_TYPE_CELLS = [("tet", (5, 11, 12, 13)), ("pyramid", (4, 5, 6, 7, 8)),
                    ("prism", (1, 9, 10, 5, 11, 12)), ("prism", (1, 10, 2, 5, 12, 6)),
                    ("hex", (0, 1, 2, 3, 4, 5, 6, 7))]
CELL_CODE = {"tet": 0, "pyramid": 1, "prism": 2, "hex": 3}


def volume_soup(points, cells, faces=(), flags=0):
    """cells: (type, corners); faces: (patch, nodes) boundary faces listed before completion."""
    data = bytes([flags, len(points)]) + bytes(g(p) for p in points)
    for kind, corners in cells:
        data += bytes([CELL_CODE[kind]] + list(corners))
    for patch, nodes in faces:
        data += bytes([4 | (len(nodes) == 4) | (patch << 4)] + list(nodes))
    return data


COMPLETE = 0x08
write("writers/tetrahedron", volume_soup(TETRA_POINTS, [("tet", (0, 1, 2, 3))], flags=COMPLETE))
# The tetrahedron's faces listed outward (its cell_faces order), on patches 0, 1, 1, 0.
write("writers/tetrahedron_listed_faces",
      volume_soup(TETRA_POINTS, [("tet", (0, 1, 2, 3))], [(0, (0, 2, 1)), (1, (0, 1, 3)), (1, (0, 3, 2)), (0, (3, 1, 2))],
                  flags=0x01))
write("writers/hex", volume_soup(CUBE_POINTS, [("hex", (0, 1, 3, 2, 4, 5, 7, 6))], flags=COMPLETE | 0x02))
# Every type, four patches, kinds rotated by 1.
write("writers/every_type", volume_soup(EVERY_TYPE_POINTS, EVERY_TYPE_CELLS, flags=COMPLETE | 0x03 | 0x10))
# Every type with the awkward patch names (a CGNS section's name, '/' and a tab, blank, long).
write("writers/every_type_awkward_names",
      volume_soup(EVERY_TYPE_POINTS, EVERY_TYPE_CELLS, flags=COMPLETE | 0x03 | 0x04))
# Two patches with one name.
write("writers/every_type_one_name", volume_soup(EVERY_TYPE_POINTS, EVERY_TYPE_CELLS, flags=COMPLETE | 0x01 | 0x40))


# ------------------------------------------------------------------------------------------- MSH
GMSH_TYPE = {"tet": 4, "pyramid": 7, "prism": 6, "hex": 5}


def msh_files():
    """The every-type mesh (volume, two boundary physical groups) and a closed surface alone,
    as Gmsh writes them: MSH 4.1 and 2.2, ASCII and binary."""
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    scratch = os.path.join(out, "msh", "scratch.msh")
    os.makedirs(os.path.dirname(scratch), exist_ok=True)

    def save(name, version, binary):
        gmsh.option.setNumber("Mesh.MshFileVersion", version)
        gmsh.option.setNumber("Mesh.Binary", binary)
        gmsh.write(scratch)
        with open(scratch, "rb") as f:
            write("msh/" + name, f.read())
        os.remove(scratch)

    gmsh.model.add("every_type")
    gmsh.model.addDiscreteEntity(3, 1)
    gmsh.model.addDiscreteEntity(2, 1)
    gmsh.model.addDiscreteEntity(2, 2)
    gmsh.model.mesh.addNodes(3, 1, list(range(1, 15)), [c for p in EVERY_TYPE_POINTS for c in p])
    for tag, (kind, corners) in enumerate(EVERY_TYPE_CELLS, start=1):
        gmsh.model.mesh.addElementsByType(1, GMSH_TYPE[kind], [tag], [v + 1 for v in corners])
    # The hex's bottom (a quad) on "wall", the prisms' bottoms (triangles) on "floor".
    gmsh.model.mesh.addElementsByType(1, 3, [6], [1, 4, 3, 2])
    gmsh.model.mesh.addElementsByType(2, 2, [7, 8], [2, 11, 10, 2, 3, 11])
    for dim, tag, name in ((3, 1, "fluid"), (2, 1, "wall"), (2, 2, "floor")):
        group = gmsh.model.addPhysicalGroup(dim, [tag])
        gmsh.model.setPhysicalName(dim, group, name)
    for version in (4.1, 2.2):
        for binary in (0, 1):
            save("every_type_%s%s.msh" % (str(version).replace(".", ""), "_binary" if binary else ""), version, binary)
    gmsh.model.remove()

    gmsh.model.add("cube_surface")
    gmsh.model.addDiscreteEntity(2, 1)
    gmsh.model.mesh.addNodes(2, 1, list(range(1, 9)), [c for p in CUBE_POINTS for c in p])
    gmsh.model.mesh.addElementsByType(1, 3, [1, 2, 3], [v + 1 for q in CUBE_QUADS[:3] for v in q])
    gmsh.model.mesh.addElementsByType(1, 2, list(range(4, 10)), [v + 1 for t in triangles(CUBE_QUADS[3:]) for v in t])
    save("cube_surface_41.msh", 4.1, 0)
    save("cube_surface_22_binary.msh", 2.2, 1)
    gmsh.finalize()


msh_files()
