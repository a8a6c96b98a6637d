SetFactory("OpenCASCADE");
// A sounding rocket 2.65 long (written for Strata's sweep, 2026-11-27): a conical nose, a body
// of radius 0.1, a boat tail with a nozzle cavity in its base, and four fins 8 mm thick at the
// tail (--fuse). Its STL export (rocket_brepmesh.stl) is the case: BRepMesh writes each facet of
// the body as one triangle pair along its whole length, and the fins' roots cut them into needles.
Cylinder(1) = {0, 0, 0, 2, 0, 0, 0.1};
Cone(2) = {-0.5, 0, 0, 0.5, 0, 0, 0, 0.1};
Cone(3) = {2, 0, 0, 0.15, 0, 0, 0.1, 0.08};
Cone(4) = {2.0, 0, 0, 0.15, 0, 0, 0.03, 0.06};
BooleanUnion(5) = {Volume{1}; Delete;}{Volume{2,3}; Delete;};
BooleanDifference(6) = {Volume{5}; Delete;}{Volume{4}; Delete;};
For i In {0:3}
  Box(10 + i) = {1.7, -0.004, 0.05, 0.3, 0.008, 0.2};
  Rotate {{1, 0, 0}, {0, 0, 0}, i * Pi / 2} { Volume{10 + i}; }
EndFor
