SetFactory("OpenCASCADE");
// An airliner-like model, 10 long (written for Strata's sweep, 2026-11-27): a fuselage of a
// cylinder, a stretched-sphere nose and an upswept tail cone ending on a small flat face (lofted
// between sections across the fuselage's axis, so that it meets the cylinder all round its
// edge: a cone along its own tilted axis left a groove 4 mm deep on the cylinder's end); a
// swept wing with dihedral lofted through three NACA 00xx sections (sharp trailing edges);
// annular nacelles on pylons under the wings; a horizontal tail and a fin. Fused (--fuse).

// Fuselage.
Cylinder(1) = {1.5, 0, 0, 5.5, 0, 0, 0.5};
Sphere(2) = {1.5, 0, 0, 0.5};
Dilate {{1.5, 0, 0}, {3, 1, 1}} { Volume{2}; }
t1 = newc; Circle(t1) = {0, 0, 0, 0.5};
t2 = newc; Circle(t2) = {0, 0, 0, 0.08};
Rotate {{0, 1, 0}, {0, 0, 0}, Pi / 2} { Curve{t1, t2}; }
Translate {7, 0, 0} { Curve{t1}; }
Translate {10, 0, 0.25} { Curve{t2}; }
t3 = newll; Curve Loop(t3) = {t1};
t4 = newll; Curve Loop(t4) = {t2};
ThruSections(3) = {t3, t4};

// Wing, mirrored.
vertical = 0;
c = 2.2; t = 0.14; x0 = 3.2; y0 = 0; z0 = -0.15;
Include "naca_section.geo";
w1 = sec;
c = 2.0; t = 0.13; x0 = 3.45; y0 = 1; z0 = -0.1;
Include "naca_section.geo";
w2 = sec;
c = 0.8; t = 0.10; x0 = 5.6; y0 = 5; z0 = 0.2;
Include "naca_section.geo";
w3 = sec;
ThruSections(4) = {w1, w2, w3};
Symmetry {0, 1, 0, 0} { Duplicata { Volume{4}; } }

// Nacelles (rings) on pylons; airliner_tail.geo sets nacelles = 0 before it Includes this.
DefineConstant[ nacelles = 1 ];
If (nacelles)
  Cylinder(10) = {3, 1.8, -0.75, 1.4, 0, 0, 0.28};
  Cylinder(11) = {2.9, 1.8, -0.75, 1.6, 0, 0, 0.22};
  BooleanDifference(12) = { Volume{10}; Delete; }{ Volume{11}; Delete; };
  Box(13) = {3.5, 1.76, -0.5, 0.9, 0.08, 0.45};
  Symmetry {0, 1, 0, 0} { Duplicata { Volume{12, 13}; } }
EndIf

// Horizontal tail, mirrored, and fin.
c = 1.0; t = 0.10; x0 = 8.2; y0 = 0; z0 = 0.1;
Include "naca_section.geo";
h1 = sec;
c = 0.45; t = 0.09; x0 = 8.9; y0 = 1.8; z0 = 0.25;
Include "naca_section.geo";
h2 = sec;
ThruSections(20) = {h1, h2};
Symmetry {0, 1, 0, 0} { Duplicata { Volume{20}; } }
vertical = 1;
c = 1.3; t = 0.10; x0 = 8.0; y0 = 0; z0 = 0.2;
Include "naca_section.geo";
v1 = sec;
c = 0.55; t = 0.09; x0 = 9.0; y0 = 0; z0 = 1.7;
Include "naca_section.geo";
v2 = sec;
ThruSections(30) = {v1, v2};
