SetFactory("OpenCASCADE");
// T-junction of two pipes (internal flow)
Cylinder(1) = {-1, 0, 0, 2, 0, 0, 0.2};
Cylinder(2) = {0, 0, 0, 0, 0, 0.8, 0.1};
BooleanUnion{ Volume{1}; Delete; }{ Volume{2}; Delete; }
