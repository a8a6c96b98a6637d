"""Source of vessel_three_cuts.stl (issue 56's open vessel): a tube of radius 0.5 along x
(0 to 4) with a branch of radius 0.3 leaving it at x = 2 along y, fused, its three end discs
removed: a wall open at three planar cuts (an inlet and two outlets), as a segmentation of an
artery leaves it. Meshed by Gmsh (size 0.12) and written as one STL solid "vessel", seven digits.
    /usr/bin/python3 vessel_three_cuts.py vessel_three_cuts.stl
"""
import sys

import gmsh

gmsh.initialize()
gmsh.option.setNumber("General.Verbosity", 1)
o = gmsh.model.occ
main = o.addCylinder(0, 0, 0, 4, 0, 0, 0.5)
branch = o.addCylinder(2, 0, 0, 0, 2, 0, 0.3)
o.fuse([(3, main)], [(3, branch)])
o.synchronize()
# The end discs: the planar faces whose normal runs along a tube's axis at its ends.
ends = []
for dim, tag in gmsh.model.getEntities(2):
    if gmsh.model.getType(dim, tag) != "Plane":
        continue
    x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(dim, tag)
    if abs(x1 - x0) < 1e-6 or abs(y1 - y0) < 1e-6:
        ends.append(tag)
gmsh.option.setNumber("Mesh.MeshSizeMax", 0.12)
walls = [t for d, t in gmsh.model.getEntities(2) if t not in ends]
group = gmsh.model.addPhysicalGroup(2, walls)
gmsh.model.setPhysicalName(2, group, "vessel")
gmsh.model.mesh.generate(2)
gmsh.option.setNumber("Mesh.Binary", 0)
gmsh.write(sys.argv[1])
gmsh.finalize()
# Seven significant digits and the solid named "vessel": a smaller file, the same surface.
lines = []
for line in open(sys.argv[1]):
    words = line.split()
    if words and words[0] == "vertex":
        line = "   vertex %.7g %.7g %.7g\n" % tuple(float(w) for w in words[1:4])
    elif words and words[0] in ("solid", "endsolid"):
        line = words[0] + " vessel\n"
    elif words and words[0] == "facet":
        line = " facet normal 0 0 0\n"
    lines.append(line)
open(sys.argv[1], "w").writelines(lines)
