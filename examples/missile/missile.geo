// The paper's second example (Thompson, Chalasani & Soni, section 5.2): a finned missile on a
// sting, half model, in a half-domain box. Notional, built from the paper's description and
// the usual wind-tunnel proportions (calibre D = 0.1 m, lengths in metres):
//   - a tangent-ogive nose 3 D long, blunted by a sphere of radius 0.05 D;
//   - a cylindrical body 7 D long (the missile is 1 m long);
//   - four trapezoidal fins in "+" (top, bottom and both sides), root chord 1.5 D, tip chord
//     0.75 D, span 1 D beyond the body, leading edge swept 45 deg, trailing edge 0.1 D ahead
//     of the base; a double-wedge section 0.06 D thick with 0.2 D long wedges (sharp edges);
//   - a sting of diameter 0.5 D from the base to the outflow plane, 4 D behind the base.
// The symmetry plane y = 0 runs through the top and bottom fins. The domain is a box 6 m
// ahead, above, below and beside the missile; its plane x = 1.4 m (the sting's aft end) is
// the outflow plane, where the layers' nodes stay (the paper's "constrained to lie in the
// x = constant plane at the aft end of the sting").
// Patches: nose, body, fins, sting, base (walls), symmetry, farfield, outflow (give it
// --patch outflow=other: not a wall, no layers grow from it).
SetFactory("OpenCASCADE");

D = 0.1; R = D / 2;
Ln = 3 * D;              // ogive length
L = 10 * D;              // missile length (nose tip to base)
rn = 0.05 * D;           // nose blunting radius
Rs = 0.25 * D;           // sting radius
Xend = L + 4 * D;        // aft end of the sting = outflow plane
Far = 6.0;               // box half-extent around the missile

// Tangent ogive of radius rho, tip at x = 0, base at (Ln, R); centre of the arc (Ln, R - rho).
rho = (R * R + Ln * Ln) / (2 * R);
// Spherical blunting: sphere on the axis, tangent to the ogive.
x0 = Ln - Sqrt((rho - rn) * (rho - rn) - (rho - R) * (rho - R));
yt = rn * (rho - R) / (rho - rn);
xt = x0 - Sqrt(rn * rn - yt * yt);

// Profile in the z = 0 plane (x, r = y), revolved about the x axis.
Point(1) = {x0 - rn, 0, 0};
Point(2) = {x0, 0, 0};        // sphere centre
Point(3) = {xt, yt, 0};
Point(4) = {Ln, R - rho, 0};  // ogive centre
Point(5) = {Ln, R, 0};
Point(6) = {L, R, 0};
Point(7) = {L, Rs, 0};
Point(8) = {Xend, Rs, 0};
Point(9) = {Xend, 0, 0};
Circle(1) = {1, 2, 3};
Circle(2) = {3, 4, 5};
Line(3) = {5, 6};
Line(4) = {6, 7};
Line(5) = {7, 8};
Line(6) = {8, 9};
Line(7) = {9, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7};
Plane Surface(1) = {1};
Extrude {{1, 0, 0}, {0, 0, 0}, 2 * Pi} { Surface{1}; }
body[] = Volume{:};  // the solid of revolution, the only volume yet
Recursive Delete { Surface{1}; }  // the profile, left over by the revolution

// One fin along +z: double-wedge sections at z = R/2 (inside the body) and at the tip.
cr = 1.5 * D; ct = 0.75 * D; span = D; t = 0.06 * D; w = 0.2 * D;
xte_root = L - 0.1 * D;
xle_root = xte_root - cr;
sweep = Tan(45 * Pi / 180);
// Leading and trailing edges as straight lines through the root (z = R) and the tip.
z0 = R / 2; z1 = R + span;
le0 = xle_root + (z0 - R) * sweep;  le1 = xle_root + span * sweep;
te1 = le1 + ct;
te0 = xte_root + (z0 - R) * (te1 - xte_root) / span;
p = 100;
Point(p + 1) = {le0, 0, z0};
Point(p + 2) = {le0 + w, t / 2, z0};
Point(p + 3) = {te0 - w, t / 2, z0};
Point(p + 4) = {te0, 0, z0};
Point(p + 5) = {te0 - w, -t / 2, z0};
Point(p + 6) = {le0 + w, -t / 2, z0};
Point(p + 11) = {le1, 0, z1};
Point(p + 12) = {le1 + w, t / 2, z1};
Point(p + 13) = {te1 - w, t / 2, z1};
Point(p + 14) = {te1, 0, z1};
Point(p + 15) = {te1 - w, -t / 2, z1};
Point(p + 16) = {le1 + w, -t / 2, z1};
For i In {0 : 5}
  Line(p + 1 + i) = {p + 1 + i, p + 1 + (i + 1) % 6};
  Line(p + 11 + i) = {p + 11 + i, p + 11 + (i + 1) % 6};
EndFor
Curve Loop(p + 1) = {p + 1 : p + 6};
Curve Loop(p + 2) = {p + 11 : p + 16};
ThruSections(11) = {p + 1, p + 2};
fin1[] = {11};
fin2[] = Rotate {{1, 0, 0}, {0, 0, 0}, Pi / 2} { Duplicata { Volume{fin1[0]}; } };
fin3[] = Rotate {{1, 0, 0}, {0, 0, 0}, Pi} { Duplicata { Volume{fin1[0]}; } };
fin4[] = Rotate {{1, 0, 0}, {0, 0, 0}, 3 * Pi / 2} { Duplicata { Volume{fin1[0]}; } };
missile[] = BooleanUnion{ Volume{body[0]}; Delete; }{ Volume{fin1[0], fin2[0], fin3[0], fin4[0]}; Delete; };

// The half domain y >= 0: a box minus the missile.
Box(1000) = {-Far, 0, -Far, Xend + Far, Far, 2 * Far};
fluid[] = BooleanDifference{ Volume{1000}; Delete; }{ Volume{missile[]}; Delete; };

// Patches, found by where their faces lie (e: a margin for OpenCASCADE's tolerances).
e = 1e-4;
sym[] = Surface In BoundingBox{-Far - e, -e, -Far - e, Xend + e, e, Far + e};
out[] = Surface In BoundingBox{Xend - e, -e, -Far - e, Xend + e, Far + e, Far + e};
nose[] = Surface In BoundingBox{-e, -e, -R - e, Ln + e, R + e, R + e};
base[] = Surface In BoundingBox{L - e, -e, -R - e, L + e, R + e, R + e};
sting[] = Surface In BoundingBox{L - e, -e, -Rs - e, Xend + e, Rs + e, Rs + e};
sting[] -= base[];
cyl[] = Surface In BoundingBox{Ln - e, -e, -R - e, L + e, R + e, R + e};
cyl[] -= base[];
cyl[] -= nose[];
// (OpenCASCADE bounds a fin face by its untrimmed surface, from the root section at z0.)
fins[] = Surface In BoundingBox{le0 - e, -e, z0 - e, te1 + e, t, z1 + e};      // top
fins[] += Surface In BoundingBox{le0 - e, z0 - e, -t, te1 + e, z1 + e, t};     // side
fins[] += Surface In BoundingBox{le0 - e, -e, -z1 - e, te1 + e, t, -z0 + e};   // bottom
all[] = Boundary{ Volume{fluid[]}; };
far[] = Abs(all[]);
far[] -= sym[]; far[] -= out[]; far[] -= nose[]; far[] -= base[]; far[] -= sting[];
far[] -= cyl[]; far[] -= fins[];
Physical Surface("nose") = nose[];
Physical Surface("body") = cyl[];
Physical Surface("fins") = fins[];
Physical Surface("base") = base[];
Physical Surface("sting") = sting[];
Physical Surface("symmetry") = sym[];
Physical Surface("outflow") = out[];
Physical Surface("farfield") = far[];
Physical Volume("fluid") = fluid[];

// Sizes: about 8,000 triangles on the missile (the paper's 7,934), coarse on the box.
Mesh.MeshSizeMax = 1.0;
Mesh.MeshSizeMin = 0.002;  // explicit: Strata floors curvature sizes at 1/20 of the maximum otherwise
Mesh.MeshSizeFromCurvature = 24;
MeshSize{ PointsOf{ Surface{nose[], cyl[], fins[], base[], sting[]}; } } = 0.0098;
MeshSize{ PointsOf{ Surface{far[]}; } } = 1.0;
