SetFactory("OpenCASCADE");
// car-like body: filleted box with four wheels partly inside it, fused
Box(1) = {0, -0.9, 0.3, 4.2, 1.8, 1.2};
Cylinder(2) = {0.8, -0.95, 0.33, 0, 1.9, 0, 0.33};
Cylinder(3) = {3.4, -0.95, 0.33, 0, 1.9, 0, 0.33};
Box(4) = {1.0, -0.8, 1.5, 2.2, 1.6, 0.5};
