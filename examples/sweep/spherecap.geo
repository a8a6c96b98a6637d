// A sphere of radius 0.5 through a plate 2 x 2 x 0.05, its centre 0.45 below the plate's top
// (`--fuse`): a cap 0.05 high shows above the plate, where the walls meet at 154 degrees, and
// beneath it the sphere meets the plate's underside at 37 degrees, an acute concave junction
// round a circle of radius 0.3.
SetFactory("OpenCASCADE");
Box(1) = {-1, -1, -0.05, 2, 2, 0.05};
Sphere(2) = {0, 0, -0.45, 0.5};
BooleanUnion{ Volume{1}; Delete; }{ Volume{2}; Delete; }
