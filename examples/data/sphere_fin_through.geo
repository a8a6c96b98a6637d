SetFactory("OpenCASCADE");
// Strata test case (written for this repository; issue 9): a sphere of radius 0.5 with a fin
// passing through it, as two overlapping solids to be fused into one (--fuse). The fin is a
// flat plate 0.02 thick, thinner than the layers of the issue's two settings (30 layers from
// 1e-4 at growth 1.2: 0.118; 10 from 1e-3: 0.026), chord 0.4, reaching 0.3 beyond the sphere
// on both sides; its edges are square (90 degrees) and end on the sphere at concave junctions.
Sphere(1) = {0, 0, 0, 0.5};
Box(2) = {-0.2, -0.01, -0.8, 0.4, 0.02, 1.6};
