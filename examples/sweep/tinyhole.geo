SetFactory("OpenCASCADE");
// a block with a hole 1/500 of its size
Box(1) = {0, 0, 0, 1, 1, 0.2};
Cylinder(2) = {0.5, 0.5, -0.1, 0, 0, 0.4, 0.002};
BooleanDifference{ Volume{1}; Delete; }{ Volume{2}; Delete; }
