SetFactory("OpenCASCADE");
// A car-like body on four wheels resting on the road (written for Strata's sweep, 2026-11-27):
// the fluid is a box over the road minus the body and wheels; each wheel sinks 1 % of its radius
// into the road, the usual way to give the contact patch a face. The road and the body are
// walls; the box's other faces are farfield (physical groups name them).
Box(1) = {-6, -4, 0, 18, 8, 5};
Box(2) = {0, -0.85, 0.25, 4.2, 1.7, 0.8};
e() = Unique(Abs(Boundary{ Boundary{ Volume{2}; } }));
f() = Fillet{2}{e()}{0.15};
Box(4) = {1.2, -0.75, 1.0, 2.0, 1.5, 0.5};
e() = Unique(Abs(Boundary{ Boundary{ Volume{4}; } }));
g() = Fillet{4}{e()}{0.12};
r = 0.32;
For i In {0:3}
  x = (i < 2) ? 0.8 : 3.4;
  y = (i % 2 == 0) ? -0.78 : 0.56;
  Cylinder(10 + i) = {x, y, r * 0.99, 0, 0.22, 0, r};
EndFor
BooleanDifference(20) = { Volume{1}; Delete; }{ Volume{f(0), g(0), 10:13}; Delete; };
eps = 1e-6;
road() = Surface In BoundingBox{-6 - eps, -4 - eps, -eps, 12 + eps, 4 + eps, eps};
far() = Surface In BoundingBox{-6 - eps, -4 - eps, -eps, -6 + eps, 4 + eps, 5 + eps};
far() += Surface In BoundingBox{12 - eps, -4 - eps, -eps, 12 + eps, 4 + eps, 5 + eps};
far() += Surface In BoundingBox{-6 - eps, -4 - eps, -eps, 12 + eps, -4 + eps, 5 + eps};
far() += Surface In BoundingBox{-6 - eps, 4 - eps, -eps, 12 + eps, 4 + eps, 5 + eps};
far() += Surface In BoundingBox{-6 - eps, -4 - eps, 5 - eps, 12 + eps, 4 + eps, 5 + eps};
body() = Surface{:};
body() -= road();
body() -= far();
Physical Surface("road") = road();
Physical Surface("body") = body();
Physical Surface("farfield") = far();
Physical Volume("fluid") = {20};
