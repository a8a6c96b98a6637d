SetFactory("OpenCASCADE");
// A fuselage (cylinder r 0.1) and a thin elliptic wing whose lower surface is nearly tangent to the
// fuselage's top: OpenCASCADE's union leaves a long thin sliver region along the seam
Cylinder(1) = {-0.5, 0, 0, 1.5, 0, 0, 0.1};
Sphere(2) = {0.2, 0, 0.1, 1};
Dilate {{0.2, 0, 0.1}, {0.25, 0.8, 0.02}} { Volume{2}; }
BooleanUnion{ Volume{1}; Delete; }{ Volume{2}; Delete; }
