// Missile body for the five-part STL case (issue 10): a cylinder of radius 0.1 from x = 0.3 to
// 1.5 behind a conical nose from x = 0, one closed solid. scripts/missile_parts.sh writes it as
// body.stl with Gmsh.
SetFactory("OpenCASCADE");
Cone(1) = {0, 0, 0, 0.3, 0, 0, 0, 0.1};
Cylinder(2) = {0.3, 0, 0, 1.2, 0, 0, 0.1};
BooleanUnion{ Volume{1}; Delete; }{ Volume{2}; Delete; }
Mesh.MeshSizeMax = 0.04;
