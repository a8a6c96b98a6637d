SetFactory("OpenCASCADE");
// a box with filleted edges and a small chamfer-like step
Box(1) = {0, 0, 0, 2, 1, 0.5};
f() = Abs(Boundary{ Volume{1}; });
e() = Unique(Abs(Boundary{ Surface{f()}; }));
Fillet{1}{e()}{0.05}
