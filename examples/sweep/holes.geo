SetFactory("OpenCASCADE");
// plate with drilled holes and a boss
Box(1) = {0, 0, 0, 2, 1, 0.1};
Cylinder(2) = {0.3, 0.5, -0.1, 0, 0, 0.3, 0.08};
Cylinder(3) = {0.7, 0.5, -0.1, 0, 0, 0.3, 0.05};
Cylinder(4) = {1.1, 0.5, -0.1, 0, 0, 0.3, 0.02};
Cylinder(5) = {1.6, 0.5, 0.0, 0, 0, 0.4, 0.15};
BooleanDifference{ Volume{1}; Delete; }{ Volume{2,3,4}; Delete; }
