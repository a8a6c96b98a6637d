"""Writes halfbody.stl (binary): the half (y >= 0) of a sphere fused with a cylinder, its
surface open along the plane y = 0, as a half model is exported for a symmetry plane. Gmsh's
OpenCASCADE kernel, elements of 0.05. Run with python3 (python3-gmsh)."""
import gmsh

gmsh.initialize()
occ = gmsh.model.occ
body, _ = occ.fuse([(3, occ.addSphere(0, 0, 0, 0.5))], [(3, occ.addCylinder(0, 0, 0, 1.5, 0, 0, 0.3))])
occ.intersect(body, [(3, occ.addBox(-1, 0, -1, 4, 1, 2))])
occ.synchronize()
# Every surface but the cut at y = 0.
keep = [t for d, t in gmsh.model.getEntities(2) if abs(gmsh.model.getBoundingBox(d, t)[4]) > 1e-6]
gmsh.model.setPhysicalName(2, gmsh.model.addPhysicalGroup(2, keep), "body")
gmsh.option.setNumber("Mesh.MeshSizeMax", 0.05)
gmsh.model.mesh.generate(2)
gmsh.option.setNumber("Mesh.SaveAll", 0)
gmsh.option.setNumber("Mesh.Binary", 1)
gmsh.write("halfbody.stl")
gmsh.finalize()
