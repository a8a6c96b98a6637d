SetFactory("OpenCASCADE");
// a torus round a sphere: the gap between them (0.08) narrower than the layers asked (0.31)
Torus(1) = {0, 0, 0, 1, 0.3};
Sphere(2) = {0, 0, 0, 0.62};
