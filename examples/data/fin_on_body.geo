SetFactory("OpenCASCADE");
// A fin on a body, to be fused (--fuse): a cylinder of radius 0.3 along x, and a wedge fin
// 0.06 thick at its root, 1 high, whose sharp edge runs up its top; the fin's edges end on
// the concave junction with the body.
Cylinder(1) = {-1, 0, 0, 4, 0, 0, 0.3};
Wedge(2) = {0, -0.03, 0, 1, 0.06, 1, 0};
