SetFactory("OpenCASCADE");
// Strata test case (written for this repository): two spheres of radius 0.5 with a gap of 0.0118 (1/10 of 30 layers at growth 1.2 from 1e-4).
Sphere(1) = {0, 0, 0, 0.5};
Sphere(2) = {1.0118, 0, 0, 0.5};
