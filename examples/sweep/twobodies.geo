SetFactory("OpenCASCADE");
// two separate bodies 3 mm apart, not fused: a box and a cylinder
Box(1) = {0, 0, 0, 1, 1, 1};
Cylinder(2) = {1.303, 0.5, 0, 0, 0, 1, 0.3};
