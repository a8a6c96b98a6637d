"""Source of cad_half_model_nose_twice_shell.brep and cad_half_model_nose_twice_loose.brep
(tests/surface/test_cad.cpp, tests/app/test_cli.cpp, tests/CMakeLists.txt).

A wind-tunnel half model as CAD tools export it: the air in a box (x -1..3, y 0..1.5, z
-1.5..1.5) round half a blunted cone-cylinder body on the symmetry plane y = 0, whose small flat
nose face is held twice: once as the plane it is, once remade on the same edges as a B-spline
filling (geometry of its own, so Gmsh meshes the two differently and three faces meet on each
edge round the nose). "shell": the solid's shell lists both; "loose": the copy lies beside the
solid, bounding none. Gmsh's OpenCASCADE kernel:
    /usr/bin/python3 cad_half_model_nose_twice.py shell cad_half_model_nose_twice_shell.brep
    /usr/bin/python3 cad_half_model_nose_twice.py loose cad_half_model_nose_twice_loose.brep
Surfaces as read back (shell): 6 the symmetry plane, 5 and 7-10 the box's other faces.
"""
import sys

import gmsh

mode, out = sys.argv[1], sys.argv[2]
gmsh.initialize()
gmsh.option.setNumber("General.Verbosity", 1)
o = gmsh.model.occ
cone = o.addCone(-0.5, 0, 0, 0.5, 0, 0, 0.05, 0.25)
cylinder = o.addCylinder(0, 0, 0, 2, 0, 0, 0.25)
body, _ = o.fuse([(3, cone)], [(3, cylinder)])
half, _ = o.cut(body, [(3, o.addBox(-2, -2, -2, 6, 2, 4))])
air, _ = o.cut([(3, o.addBox(-1, 0, -1.5, 4, 1.5, 3))], half)
o.synchronize()
faces = gmsh.model.getBoundary(air, oriented=False)


def at_nose(face):
    box = gmsh.model.getBoundingBox(*face)
    return abs(box[0] + 0.5) < 1e-3 and abs(box[3] + 0.5) < 1e-3


nose = [f for f in faces if at_nose(f)][0]
curves = [abs(c) for _, c in gmsh.model.getBoundary([nose], oriented=False)]
copy = o.addSurfaceFilling(o.addCurveLoop(curves))
if mode == "shell":
    o.remove(air, recursive=False)
    o.addVolume([o.addSurfaceLoop([t for _, t in faces] + [copy])])
o.synchronize()
gmsh.write(out)
gmsh.finalize()
