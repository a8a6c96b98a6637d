// Notional fighter, half model, with a chin inlet whose duct ends inside the aircraft, in a
// half-sphere air domain: the third example of Thompson, Chalasani & Soni, "Generation of
// volume meshes by extrusion from surface meshes of arbitrary topology" (section 5.3,
// "Fighter"; their surface had 4541 triangles). Notional, built from the paper's
// description (a fighter, symmetric, half model, an inlet under the forward fuselage that
// terminates inside the aircraft) with round public-ish numbers of a light single-engine
// fighter; not the shape of any real aircraft.
//
// Units: metres. x aft from the nose, y to starboard (the half model is y >= 0, the
// symmetry plane y = 0), z up.
//   fuselage   15.0 long, a body of revolution of radius 0.76 (a cubic B-spline profile: a
//              small rounded nose, a constant middle, a boattail to a flat base of radius
//              0.48 at x = 15), a canopy (a half-buried ellipsoid, 3.6 x 0.84 x 0.96) on top
//   inlet      a chin inlet: a fairing under the forward fuselage (lofted superellipse
//              sections, 1.1 wide at its mouth) whose duct (lofted, 0.92 x 0.66 at the mouth
//              at x = 4.2, turning up and aft into a circle of radius 0.40) ends at x = 9.0
//              in a flat engine face inside the aircraft; the lip rounded inside and out
//              (radius lip_r = 0.03, the lip 0.09-0.10 thick)
//   wing       trapezoidal, leading edge swept 40 degrees, semi-span 5.0 (span 10.0),
//              chord 5.2 at the centreline and 1.2 at the tip, NACA 0005 sections, sharp
//              trailing edge, mid fuselage (z = 0.05)
//   tails      horizontal: swept 40 degrees, semi-span 3.0, chords 2.4 / 0.8, NACA 0005, at
//              z = -0.05; vertical (on the centreline, cut in half by the symmetry plane):
//              swept 45 degrees, 3.25 high above its root, chords 3.0 / 1.1, NACA 0005 at
//              the root, 0010 at the tip
//   domain     a half sphere of radius 60 (4 lengths) centred at (7.5, 0, 0)
//
// Patches (physical surfaces): fuselage, canopy, inlet (the duct, its lip and the engine
// face), wing, htail, vtail (walls), symmetry, farfield (their names give their kinds).
// Mesh size: h on the aircraft (0.265: 4,486 triangles on the aircraft, the paper's
// resolution), h/3 along the leading edges, h/4 on the inlet lip, growing to h_far on the
// farfield. fighter_fine.geo sets h = 0.13 (14,540 triangles) and includes this file.
// Strata meshes it with the script's own sizes unless --size/--size-min/--curvature are
// given. Gmsh 4.8 (Debian 12); the Booleans and fillets take about 3 s.
SetFactory("OpenCASCADE");

If (!Exists(h))
  h = 0.265;     // aircraft surface size
EndIf
If (!Exists(lip_h))
  lip_h = h / 4; // inlet lip size
EndIf
If (!Exists(le_h))
  le_h = h / 3;  // leading-edge size
EndIf
h_far = 8;       // farfield size
lip_r = 0.03;    // inlet lip radius

Geometry.Tolerance = 1e-6;
Geometry.ToleranceBoolean = 1e-6;
Geometry.OCCBoundsUseStl = 1;  // tight bounding boxes for "In BoundingBox" (not the B-splines' control nets)

// ---------------------------------------------------------------- fuselage
// Profile r(x) as a cubic B-spline: its first leg is vertical, so the nose is round (no
// point). Drawn in the half plane 135 degrees from +y (below, on the side cut away) and
// revolved by 360 degrees about the x axis, so that the seam goes with the cut.
fp[] = {};
fx[] = {0, 0, 0.4, 1.8, 3.5, 7.0, 11.0, 13.2, 15.0};
fr[] = {0, 0.06, 0.30, 0.62, 0.76, 0.76, 0.76, 0.62, 0.48};
For k In {0:#fx[]-1}
  fp[] += newp; Point(newp) = {fx[k], -fr[k] * Sqrt(0.5), -fr[k] * Sqrt(0.5)};
EndFor
c_prof = newc; BSpline(c_prof) = fp[];
p_base = newp; Point(p_base) = {15.0, 0, 0};
c_base = newc; Line(c_base) = {fp[#fp[]-1], p_base};
c_axis = newc; Line(c_axis) = {p_base, fp[0]};
l_prof = 1; Curve Loop(l_prof) = {c_prof, c_base, c_axis};
s_prof = news; Plane Surface(s_prof) = {l_prof};
rev[] = Extrude {{1, 0, 0}, {0, 0, 0}, 2 * Pi} { Surface{s_prof}; };
v_fus = rev[1];
Recursive Delete { Surface{s_prof}; }  // the profile, a free surface now

// ---------------------------------------------------------------- canopy
v_can = newv; Sphere(v_can) = {0, 0, 0, 1};
Rotate {{0, 1, 0}, {0, 0, 0}, Pi / 2} { Volume{v_can}; }  // its poles fore and aft, inside the fuselage
Dilate {{0, 0, 0}, {1.8, 0.42, 0.48}} { Volume{v_can}; }
Translate {3.4, 0, 0.52} { Volume{v_can}; }

// ---------------------------------------------------------------- superellipse sections
// Macro Super: a closed spline through np points of |y/sa|^sn + |(z-sz)/sb|^sn = 1 in the
// plane x = sx, starting (its seam) at angle st from +y; its curve loop in sec.
np = 32;
// The sections' curves get tags from 3001 up, their curve loops from 8001 up, and every
// section is made before any loft (a loft's wires take the next free loop tags).
c_next = 3001;
ll_next = 8001;
Macro Super
  sp[] = {};
  For k In {0:np-1}
    t = st + 2 * Pi * k / np;
    c = Cos(t); s = Sin(t);
    sy = sa * c / (Fabs(c) + 1e-30) * Fabs(c)^(2 / sn);
    szz = sz + sb * s / (Fabs(s) + 1e-30) * Fabs(s)^(2 / sn);
    sp[] += newp; Point(newp) = {sx, sy, szz};
  EndFor
  sc = c_next; c_next += 1; Spline(sc) = {sp[], sp[0]};
  sec = ll_next; ll_next += 1; Curve Loop(sec) = {sc};
Return

// ---------------------------------------------------------------- inlet fairing and duct
// Fairing (outer): sections x, centre z, half width, half height, exponent; the lofted
// surface's seam on top, inside the fuselage (on the side it split the fairing into a
// strip that ended in a sliver where it met the fuselage).
st = Pi / 2;
fa_x[] = {4.2, 6.0, 8.0, 9.5, 11.5};
fa_z[] = {-0.95, -0.85, -0.65, -0.50, -0.20};
fa_a[] = {0.56, 0.60, 0.58, 0.55, 0.40};
fa_b[] = {0.65, 0.62, 0.55, 0.55, 0.40};
fa_n[] = {3.0, 3.0, 2.6, 2.4, 2.2};
fl[] = {};
For i In {0:#fa_x[]-1}
  sx = fa_x[i]; sz = fa_z[i]; sa = fa_a[i]; sb = fa_b[i]; sn = fa_n[i];
  Call Super;
  fl[] += sec;
EndFor

// Duct (the hole): from ahead of the mouth, turning up and aft to a round engine face; its
// seam along the side, mouth to engine face.
st = 0;
du_x[] = {4.0, 4.2, 6.0, 7.6, 9.0};
du_z[] = {-1.18, -1.18, -1.03, -0.78, -0.58};
du_a[] = {0.46, 0.46, 0.45, 0.42, 0.40};
du_b[] = {0.33, 0.33, 0.35, 0.38, 0.40};
du_n[] = {3.0, 3.0, 2.8, 2.4, 2.0};
dl[] = {};
For i In {0:#du_x[]-1}
  sx = du_x[i]; sz = du_z[i]; sa = du_a[i]; sb = du_b[i]; sn = du_n[i];
  Call Super;
  dl[] += sec;
EndFor

// ---------------------------------------------------------------- lifting surfaces
// Macro Foil: a NACA 00tt section (tt = 100 ft) of chord fc, leading edge at (fx0, fy0, fz0),
// in the plane y = fy0 (fo = 0: thickness along z, a wing) or z = fz0 (fo = 1: thickness
// along y, a fin). Two splines, the upper side from the sharp trailing edge to the leading
// edge and the lower side back (one face each: a face wrapped round the leading edge, much
// tighter than the mesh size, left Gmsh's mesher with invalid triangles); curve loop in
// sec. (Call a macro on a line of its own: Gmsh reads the rest of the line first.)
nf = 16;
Macro Foil
  up[] = {};
  lo[] = {};
  p_te = newp; Point(p_te) = {fx0 + fc, fy0, fz0};
  // upper side, trailing edge to leading edge (cosine spacing)
  For k In {1:nf}
    X = (1 + Cos(Pi * k / nf)) / 2;    // k = nf: X = 0 (leading edge)
    T = 5 * ft * (0.2969 * Sqrt(X) - 0.1260 * X - 0.3516 * X^2 + 0.2843 * X^3 - 0.1036 * X^4);
    up[] += newp; Point(newp) = {fx0 + fc * X, fy0 + fo * fc * T, fz0 + (1 - fo) * fc * T};
  EndFor
  // lower side, leading edge to trailing edge
  For k In {1:nf - 1}
    X = (1 - Cos(Pi * k / nf)) / 2;
    T = 5 * ft * (0.2969 * Sqrt(X) - 0.1260 * X - 0.3516 * X^2 + 0.2843 * X^3 - 0.1036 * X^4);
    lo[] += newp; Point(newp) = {fx0 + fc * X, fy0 - fo * fc * T, fz0 - (1 - fo) * fc * T};
  EndFor
  c_up = c_next; c_next += 1; Spline(c_up) = {p_te, up[]};
  c_lo = c_next; c_next += 1; Spline(c_lo) = {up[#up[]-1], lo[], p_te};
  sec = ll_next; ll_next += 1; Curve Loop(sec) = {c_up, c_lo};
Return

ft = 0.05;
// Wing: leading edge from (6.0, 0) swept 40 degrees; trailing edge from (11.2, 0) to (11.4, 5.0).
tan40 = Tan(40 * Pi / 180);
fo = 0; fz0 = 0.05;
fy0 = 0.35; fx0 = 6.0 + fy0 * tan40; fc = 11.2 + fy0 * 0.2 / 5.0 - fx0;
Call Foil;
w_root = sec;
fy0 = 5.0; fx0 = 6.0 + fy0 * tan40; fc = 1.2;
Call Foil;
w_tip = sec;

// Horizontal tail: leading edge from (12.15, 0) swept 40 degrees, chord 2.4 -> 0.8 at y = 3.0.
fo = 0; fz0 = -0.05;
fy0 = 0.30; fx0 = 12.15 + fy0 * tan40; fc = 2.4 - (2.4 - 0.8) * fy0 / 3.0;
Call Foil;
t_root = sec;
fy0 = 3.0; fx0 = 12.15 + fy0 * tan40; fc = 0.8;
Call Foil;
t_tip = sec;

// Vertical tail: leading edge from (10.8, z = 0.35) swept 45 degrees, chord 3.0 -> 1.1 at
// z = 3.6, NACA 0005 -> 0010 (a tip fairing): the half model's tip cap is half a section,
// whose corner at the trailing edge is half the edge's angle (3.3 degrees for 5 %, 6.6 for
// 10 %, as the wing tip's whole 5 % section).
fo = 1; fy0 = 0;
fz0 = 0.35; fx0 = 10.8; fc = 3.0;
Call Foil;
f_root = sec;
fz0 = 3.6; fx0 = 10.8 + (3.6 - 0.35); fc = 1.1; ft = 0.10;
Call Foil;
f_tip = sec;

// ---------------------------------------------------------------- lofts
v_fair = newv; ThruSections(v_fair) = fl[];
v_duct = newv; ThruSections(v_duct) = dl[];
v_wing = newv; ThruSections(v_wing) = {w_root, w_tip};
v_ht = newv; ThruSections(v_ht) = {t_root, t_tip};
v_vt = newv; ThruSections(v_vt) = {f_root, f_tip};
Recursive Delete { Curve{3001 : c_next - 1}; }  // the sections, free curves now

// ---------------------------------------------------------------- one solid, half model
// Fuselage and fairing fused, the duct cut out of them, the mouth's edges rounded, the rest
// fused on, and the whole cut at y = 0 (the half model).
// The inner edge: the one closed curve at x = 4.2 that stays below the fuselage.
body[] = BooleanUnion{ Volume{v_fus}; Delete; }{ Volume{v_fair}; Delete; };
body2[] = BooleanDifference{ Volume{body[]}; Delete; }{ Volume{v_duct}; Delete; };
lip[] = Curve In BoundingBox{4.17, -1, -1.6, 4.23, 1, -0.79};
body3[] = Fillet{body2[0]}{lip[]}{lip_r};
// the outer edge: the fairing's section at x = 4.2 below the fuselage (the curves at x = 4.2
// reaching below z = -1.55; the inner lip's stay above)
out1[] = Curve In BoundingBox{4.17, -1, -1.65, 4.23, 1, -0.2};
out2[] = Curve In BoundingBox{4.17, -1, -1.55, 4.23, 1, -0.2};
out1[] -= out2[];
body4[] = Fillet{body3[0]}{out1[]}{lip_r};
air[] = BooleanUnion{ Volume{body4[]}; Delete; }{ Volume{v_can, v_wing, v_ht, v_vt}; Delete; };
v_half = newv; Box(v_half) = {-1, 0, -2, 18, 6, 7};
half[] = BooleanIntersection{ Volume{air[]}; Delete; }{ Volume{v_half}; Delete; };

// ---------------------------------------------------------------- air domain
R = 60;
v_sph = newv; Sphere(v_sph) = {7.5, 0, 0, R};
v_hb = newv; Box(v_hb) = {7.5 - 1.1 * R, 0, -1.1 * R, 2.2 * R, 1.1 * R, 2.2 * R};
dom[] = BooleanIntersection{ Volume{v_sph}; Delete; }{ Volume{v_hb}; Delete; };
fluid[] = BooleanDifference{ Volume{dom[]}; Delete; }{ Volume{half[]}; Delete; };

// ---------------------------------------------------------------- patches
// By bounding boxes (Geometry.OCCBoundsUseStl, above: padded by about 0.01-0.04).
e = 0.05;
s_all[] = Surface "*";
s_air[] = Surface In BoundingBox{-1, -2 * e, -2, 17, 6, 5};
s_sym[] = Surface In BoundingBox{-2 * R, -e, -2 * R, 2 * R, e, 2 * R};
s_sym[] -= s_air[];
s_far[] = s_all[];
s_far[] -= s_sym[];
s_far[] -= s_air[];
s_wing[] = Surface In BoundingBox{6.0, 0.6, -0.3, 12.0, 5.0 + e, 0.4};
s_ht[] = Surface In BoundingBox{12.0, 0.4, -0.3, 15.6, 3.0 + e, 0.2};
s_vt[] = Surface In BoundingBox{10.5, -e, 0.45, 15.3, 0.1, 3.6 + e};
s_can[] = Surface In BoundingBox{1.5, -e, 0.4, 5.3, 0.5, 1.1};
s_in[] = Surface In BoundingBox{3.9, -e, -1.6, 9.1, 0.6, 0.0};
s_fus[] = s_air[];
s_fus[] -= s_wing[];
s_fus[] -= s_ht[];
s_fus[] -= s_vt[];
s_fus[] -= s_can[];
s_fus[] -= s_in[];
Physical Surface("fuselage") = s_fus[];
Physical Surface("canopy") = s_can[];
Physical Surface("inlet") = s_in[];
Physical Surface("wing") = s_wing[];
Physical Surface("htail") = s_ht[];
Physical Surface("vtail") = s_vt[];
Physical Surface("symmetry") = s_sym[];
Physical Surface("farfield") = s_far[];
Physical Volume("fluid") = fluid[];

// ---------------------------------------------------------------- mesh sizes
// Size fields only: h on the aircraft, lip_h at the inlet lip and le_h along the leading
// edges (graded from them), and on the symmetry plane and the farfield a size growing from
// h at the aircraft by 0.25 per unit of distance, up to h_far.
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeMax = h_far;
c_air[] = Unique(Abs(Boundary{ Surface{s_air[]}; }));
c_lip[] = Curve In BoundingBox{4.2 - 0.02, -e, -1.6, 4.2 + lip_r + 0.02, 0.7, -0.5};
Field[1] = MathEval;
Field[1].F = Sprintf("%g", h);
Field[2] = Restrict;
Field[2].InField = 1;
Field[2].SurfacesList = {s_air[]};
Field[2].CurvesList = {c_air[]};
Field[3] = Distance;
Field[3].CurvesList = {c_air[]};
Field[3].NumPointsPerCurve = 200;
Field[4] = Threshold;
Field[4].InField = 3;
Field[4].SizeMin = h;
Field[4].SizeMax = h_far;
Field[4].DistMin = 0;
Field[4].DistMax = (h_far - h) / 0.25;
Field[5] = Distance;
Field[5].CurvesList = {c_lip[]};
Field[5].NumPointsPerCurve = 200;
Field[6] = Threshold;
Field[6].InField = 5;
Field[6].SizeMin = lip_h;
Field[6].SizeMax = h_far;
Field[6].DistMin = 0.5 * lip_r;
Field[6].DistMax = 0.5 * lip_r + (h_far - lip_h) / 0.5;
// The leading edges of the wing and tails (their radius, 0.3-1.4 % of the chord, is far
// below h): le_h along them, graded to h over 2 h.
lec_w[] = Curve In BoundingBox{6.0, 0.6, -0.1, 10.3, 5.0 + e, 0.2};
lec_h[] = Curve In BoundingBox{12.3, 0.4, -0.2, 14.75, 3.0 + e, 0.1};
lec_h2[] = Curve In BoundingBox{12.3, 0.4, -0.2, 14.75, 0.66, 0.1};  // the root's junction
lec_h[] -= lec_h2[];
lec_v[] = Curve In BoundingBox{10.9, -e, 0.4, 14.1, 0.12, 3.6 + e};
lec_v2[] = Curve In BoundingBox{10.9, -e, 0.4, 14.1, 0.12, 0.75};    // the root's junction
lec_v[] -= lec_v2[];
Field[7] = Distance;
Field[7].CurvesList = {lec_w[], lec_h[], lec_v[]};
Field[7].NumPointsPerCurve = 400;
Field[8] = Threshold;
Field[8].InField = 7;
Field[8].SizeMin = le_h;
Field[8].SizeMax = h_far;
Field[8].DistMin = 0;
Field[8].DistMax = 2 * h * (h_far - le_h) / (h - le_h);  // h at 2 h from the edge
Field[9] = Min;
Field[9].FieldsList = {2, 4, 6, 8};
Background Field = 9;
