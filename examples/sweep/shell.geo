SetFactory("OpenCASCADE");
// thin hemispherical shell (a cup), 0.01 thick: the layers of both sides meet at the rim
Sphere(1) = {0, 0, 0, 0.5, 0, Pi/2};
Sphere(2) = {0, 0, 0, 0.49, 0, Pi/2};
BooleanDifference{ Volume{1}; Delete; }{ Volume{2}; Delete; }
