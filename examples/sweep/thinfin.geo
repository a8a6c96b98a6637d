SetFactory("OpenCASCADE");
// a cylinder with a very thin plate fin (1 mm) fused: layers much thicker than the fin
Cylinder(1) = {0, 0, 0, 3, 0, 0, 0.2};
Box(2) = {1, -0.0005, 0, 1, 0.001, 0.6};
