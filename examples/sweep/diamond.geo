// A body of revolution 2 long with a wing of diamond section through it (written for Strata's
// sweep, 2026-12-02), as on a missile: sharp leading and trailing edges (8.6° wedges, a 171°
// turn) ending on the body at concave junctions, and flat tips whose edges close their chains
// (`--fuse`).
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, 0, 2, 0, 0, 0.15};
Point(100) = {0.6, 0, -0.7}; Point(101) = {1.0, 0.03, -0.7}; Point(102) = {1.4, 0, -0.7}; Point(103) = {1.0, -0.03, -0.7};
Line(100) = {100,101}; Line(101) = {101,102}; Line(102) = {102,103}; Line(103) = {103,100};
Curve Loop(100) = {100:103}; Plane Surface(100) = {100};
v() = Extrude {0, 0, 1.4} { Surface{100}; };
BooleanUnion{ Volume{1}; Delete; }{ Volume{v(1)}; Delete; }
