// A rod through a plate at 15 degrees (`--fuse`): where the rod meets the plate on its acute
// side, the two walls meet at 15 degrees, and the first cells on either side of that junction
// lie stacked rather than side by side.
SetFactory("OpenCASCADE");
Box(1) = {-1, -1, 0, 2, 2, 0.05};
Cylinder(2) = {-0.9, 0, -0.24, 1.8, 0, 0.48, 0.05};
BooleanUnion{ Volume{1}; Delete; }{ Volume{2}; Delete; }
