"""Source of cad_box_loose_faces_1e-7.brep and cad_box_loose_faces_3e-5.brep (tests/surface/test_cad.cpp).

A 1 x 0.5 x 0.3 box written as six separate faces, each with its own edges, whose corners are
moved by up to GAP in each coordinate (a surface model as CAD tools export it: faces that miss
their neighbours by the tool's tolerance). Gmsh's OpenCASCADE kernel, filling surfaces.
    /usr/bin/python3 cad_box_loose_faces.py 1e-7 cad_box_loose_faces_1e-7.brep
    /usr/bin/python3 cad_box_loose_faces.py 3e-5 cad_box_loose_faces_3e-5.brep
Also the source of cad_sphere_face_only.brep: the face of a sphere of radius 0.5 without its
solid, a loose face that closes on itself (its seam bounds it twice, its poles are degenerate
edges), which sewing must leave alone:
    /usr/bin/python3 cad_box_loose_faces.py sphere cad_sphere_face_only.brep
And of cad_solid_and_loose_face.brep: a unit cube, a loose unit square beside it (x = 2..3) and
a free line (construction geometry), in one file: the square must be read, the line ignored.
    /usr/bin/python3 cad_box_loose_faces.py mixed cad_solid_and_loose_face.brep
And of cad_cylinder_and_profile.step: a cylinder and the rectangle a revolve was made from,
lying beside it (a STEP with a solid and a loose face), and of cad_sphere_in_box_faces.brep: a
sphere solid inside six loose faces of a box (a closed group of faces bounding no solid):
    /usr/bin/python3 cad_box_loose_faces.py profile cad_cylinder_and_profile.step
    /usr/bin/python3 cad_box_loose_faces.py boxed cad_sphere_in_box_faces.brep
And of cad_box_face_written_twice.brep: the six faces of the box, exact, the first written twice.
    /usr/bin/python3 cad_box_loose_faces.py twice cad_box_face_written_twice.brep
"""
import random
import sys

import gmsh

out = sys.argv[2]
gmsh.initialize()
gmsh.option.setNumber("General.Verbosity", 1)
o = gmsh.model.occ


def finish():
    o.synchronize()
    gmsh.write(out)
    gmsh.finalize()
    sys.exit(0)


if sys.argv[1] == "mixed":
    o.addBox(0, 0, 0, 1, 1, 1)
    o.addRectangle(2, 0, 0, 1, 1)
    o.addLine(o.addPoint(0, 3, 0), o.addPoint(1, 3, 0))
    finish()
if sys.argv[1] == "profile":
    o.addCylinder(0, 0, 0, 1, 0, 0, 0.3)
    o.addRectangle(0, 0.5, 0, 1, 0.3)  # the profile a revolve was made from, left beside it
    finish()
if sys.argv[1] == "boxed":
    o.addSphere(0, 0, 0, 0.5)
    o.addBox(-2, -2, -2, 4, 4, 4)
    box = [e for e in o.getEntities(3) if e[1] != 1]
    o.copy([f for f in o.getEntities(2) if f[1] > 1])
    o.remove(box, recursive=False)
    o.remove([(2, t) for t in range(2, 8)], recursive=True)
    finish()
if sys.argv[1] == "twice":
    o.addBox(0, 0, 0, 1, 0.5, 0.3)
    box_faces = o.getEntities(2)
    o.copy(box_faces)
    o.copy(box_faces[:1])
    o.remove(o.getEntities(3), recursive=True)
    finish()
if sys.argv[1] == "sphere":
    o.addSphere(0, 0, 0, 0.5)
    o.copy(o.getEntities(2))
    o.remove(o.getEntities(3), recursive=True)
    finish()
gap = float(sys.argv[1])
random.seed(1)
faces = [[(0, 0, 0), (1, 0, 0), (1, 0.5, 0), (0, 0.5, 0)], [(0, 0, 0.3), (1, 0, 0.3), (1, 0.5, 0.3), (0, 0.5, 0.3)],
         [(0, 0, 0), (1, 0, 0), (1, 0, 0.3), (0, 0, 0.3)], [(0, 0.5, 0), (1, 0.5, 0), (1, 0.5, 0.3), (0, 0.5, 0.3)],
         [(0, 0, 0), (0, 0.5, 0), (0, 0.5, 0.3), (0, 0, 0.3)], [(1, 0, 0), (1, 0.5, 0), (1, 0.5, 0.3), (1, 0, 0.3)]]
for f in faces:
    p = [o.addPoint(*(c + random.uniform(-gap, gap) for c in corner)) for corner in f]
    lines = [o.addLine(p[i], p[(i + 1) % 4]) for i in range(4)]
    o.addSurfaceFilling(o.addCurveLoop(lines))
finish()
