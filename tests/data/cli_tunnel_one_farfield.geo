SetFactory("OpenCASCADE");
// A short wind tunnel over a road with a bump on it: the fluid is the box minus a sphere sunk
// halfway into the road. The road and the bump are walls; the tunnel's other five faces are ONE
// physical group "farfield", not one plane, and the road's layers end on four of them.
Box(1) = {0, -1, 0, 4, 2, 1};
Sphere(2) = {1.5, 0, 0, 0.4};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
eps = 1e-6;
road() = Surface In BoundingBox{-eps, -1 - eps, -eps, 4 + eps, 1 + eps, eps};
far() = Surface In BoundingBox{-eps, -1 - eps, -eps, eps, 1 + eps, 1 + eps};
far() += Surface In BoundingBox{4 - eps, -1 - eps, -eps, 4 + eps, 1 + eps, 1 + eps};
far() += Surface In BoundingBox{-eps, -1 - eps, -eps, 4 + eps, -1 + eps, 1 + eps};
far() += Surface In BoundingBox{-eps, 1 - eps, -eps, 4 + eps, 1 + eps, 1 + eps};
far() += Surface In BoundingBox{-eps, -1 - eps, 1 - eps, 4 + eps, 1 + eps, 1 + eps};
bump() = Surface{:};
bump() -= road();
bump() -= far();
Physical Surface("road") = road();
Physical Surface("bump") = bump();
Physical Surface("farfield") = far();
