SetFactory("OpenCASCADE");
// The ONERA M6 wing (examples/data/onera_m6_sharp_te.stp, in mm, sharp trailing edge) as a half
// model on its symmetry plane, as it is meshed for CFD (written for Strata's sweep, 2026-11-28):
// the wing's root face lies in y = 0, and a box about 20 root chords across, whose plane y = 0 is the
// symmetry patch, is cut round it. The wing is meshed at 30 mm (its points' size), the box at up
// to 2000. Patches: wing, symmetry, farfield.
Merge "../data/onera_m6_sharp_te.stp";
Box(2) = {-8000, 0, -8000, 17000, 9000, 16000};
BooleanDifference(3) = { Volume{2}; Delete; }{ Volume{1}; Delete; };
sym() = Surface In BoundingBox{-8001, -1e-3, -8001, 9001, 1e-3, 8001};
wing() = Surface In BoundingBox{-1, -1, -41, 1147, 1219, 41};
wing() -= sym();
far() = Surface{:};
far() -= wing();
far() -= sym();
Physical Surface("wing") = wing();
Physical Surface("symmetry") = sym();
Physical Surface("farfield") = far();
Physical Volume("fluid") = {3};
Mesh.MeshSizeMax = 2000;
MeshSize{ PointsOf{ Surface{wing()}; } } = 30;
