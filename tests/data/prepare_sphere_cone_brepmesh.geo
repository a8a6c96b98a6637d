// Source of prepare_sphere_cone_brepmesh.stl (written for this repository): a sphere and a
// cone that overlap, as two solids. Exported to BREP by Gmsh and tessellated as a CAD tool
// exports STL: scripts/tessellate/tessellate_cad prepare_sphere_cone_brepmesh.brep OUT.stl 0.05 30
// (OpenCASCADE 7.6's BRepMesh_IncrementalMesh, StlAPI_Writer, binary).
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 0, 0.5};
Cone(4) = {0, 0, 0.4, 0.1, 0, 0.6, 0.15, 0.01};
