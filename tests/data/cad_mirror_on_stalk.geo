SetFactory("OpenCASCADE");
// A body with a wing mirror on a thin stalk (written for Strata's tests, 2026-11-27): with
// quads at the default size, Gmsh 4.8's Blossom recombination crashes the process (a
// segmentation fault), where its simple recombination meshes it (--fuse).
Box(1) = {0, -0.5, 0, 2, 1, 0.6};
Cylinder(2) = {0.5, 0.45, 0.4, 0, 0.25, 0, 0.015};
Sphere(3) = {0.5, 0.78, 0.4, 0.08};
Dilate {{0.5, 0.78, 0.4}, {0.6, 1, 0.8}} { Volume{3}; }
