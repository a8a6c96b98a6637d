SetFactory("OpenCASCADE");
// a body 2 mm above a ground plate inside a tunnel box (internal flow, every patch a wall)
Box(1) = {-2, -1, 0, 6, 2, 1.5};
Sphere(2) = {0.5, 0, 0.302, 0.3};
BooleanDifference{ Volume{1}; Delete; }{ Volume{2}; Delete; }
