// A hypersonic lifting body 10 long (written for Strata's sweep, 2026-12-05, issue 54): lofted
// through cross-sections of a high rounded top and a slightly convex underside that meet at sharp
// chines along both sides (turning about 75 degrees at the nose, 105 at the base), the nose rounded
// by an ellipsoid, a flat base, and two canted fins with NACA sections whose sharp trailing edges
// end on the upper body ahead of the base (--fuse).
SetFactory("OpenCASCADE");

// The cross-section at station xq: chines at (xq, +-w, zc); the upper spline rises hu above them,
// z = zc + hu (1 - s^2)(1 + 0.9 s^2) with s = y / w; the lower one sags hl below, zc - hl (1 - s^2).
Macro ChineSection
  m = 12;
  For i In {0:m}
    s = Cos(Pi * i / m);
    pu[i] = newp; Point(pu[i]) = {xq, w * s, zc + hu * (1 - s^2) * (1 + 0.9 * s^2)};
  EndFor
  pl[0] = pu[m];
  For i In {1:m - 1}
    s = -Cos(Pi * i / m);
    pl[i] = newp; Point(pl[i]) = {xq, w * s, zc - hl * (1 - s^2)};
  EndFor
  pl[m] = pu[0];
  c1 = newc; Spline(c1) = {pu[{0:m}]};
  c2 = newc; Spline(c2) = {pl[{0:m}]};
  sec = newll; Wire(sec) = {c1, c2};
Return

X[] = {-0.2, 1.5, 3.5, 6.0, 8.0, 10.0};
W[] = {0.55, 1.0, 1.35, 1.45, 1.5, 1.5};
HU[] = {0.5, 0.8, 0.95, 1.0, 1.0, 1.0};
HL[] = {0.2, 0.22, 0.15, 0.12, 0.1, 0.1};
ZC[] = {0.25, 0.15, 0.05, 0.0, 0.0, 0.0};
For k In {0:#X[] - 1}
  xq = X[k]; w = W[k]; hu = HU[k]; hl = HL[k]; zc = ZC[k];
  Call ChineSection;
  sections[k] = sec;
EndFor
ThruSections(1) = {sections[]};

// The nose: the loft where it lies inside an ellipsoid (x semi-axis 2.5) joined to a block behind.
Sphere(2) = {2.5, 0, 0.3, 1};
Dilate {{2.5, 0, 0.3}, {2.5, 1.8, 1.2}} { Volume{2}; }
Box(3) = {2.5, -2, -1, 8, 4, 3};
BooleanUnion(4) = {Volume{2}; Delete;}{Volume{3}; Delete;};
BooleanIntersection(5) = {Volume{1}; Delete;}{Volume{4}; Delete;};

// Two fins canted outward, their roots inside the body, trailing edges at x = 9.7.
vertical = 1;
For side In {-1:1:2}
  c = 1.6; t = 0.08; x0 = 8.1; y0 = side * 1.15; z0 = 0.3;
  Include "naca_section.geo";
  f1 = sec;
  c = 0.8; t = 0.08; x0 = 9.1; y0 = side * 1.55; z0 = 1.5;
  Include "naca_section.geo";
  f2 = sec;
  ThruSections(10 + side) = {f1, f2};
EndFor
