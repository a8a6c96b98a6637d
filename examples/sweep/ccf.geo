// A cone-cylinder-flare ballistic body 2.4 long (written for Strata's sweep, 2026-12-05, issue 54):
// a 9.5-degree cone with a nose blunted by a sphere of radius 0.005 tangent to it, a cylinder of
// radius 0.1, a 10-degree conical flare to radius 0.17 and a flat base (a body of revolution).
SetFactory("OpenCASCADE");
R = 0.1; Lc = 0.6; rn = 0.005;      // body radius, cone length (sharp apex at x = 0), nose radius
th = Atan(R / Lc);                  // cone half-angle
xc = rn / Sin(th);                  // the nose sphere's centre; it touches the cone at xt
xt = xc - rn * Sin(th);
Sphere(1) = {xc, 0, 0, rn};
Cone(2) = {xt, 0, 0, Lc - xt, 0, 0, rn * Cos(th), R};
Cylinder(3) = {Lc, 0, 0, 1.4, 0, 0, R};
Cone(4) = {Lc + 1.4, 0, 0, 0.4, 0, 0, R, R + 0.4 * Tan(10 * Pi / 180)};
BooleanUnion(5) = {Volume{1}; Delete;}{Volume{2:4}; Delete;};
