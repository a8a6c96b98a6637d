SetFactory("OpenCASCADE");
// a sphere with three cones (sharp tips) fused on
Sphere(1) = {0, 0, 0, 0.5};
Cone(2) = {0.4, 0, 0, 0.6, 0, 0, 0.12, 0};
Cone(3) = {0, 0.4, 0, 0, 0.5, 0.1, 0.1, 0};
Cone(4) = {0, 0, 0.4, 0.1, 0, 0.6, 0.15, 0.01};
