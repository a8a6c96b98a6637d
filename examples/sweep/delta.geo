SetFactory("OpenCASCADE");
// A delta wing 1 long and 1.2 wide (written for Strata's sweep, 2026-11-27): sharp leading
// edges swept 59 degrees, each bevelled about 7 degrees on both sides (a 166-degree turn), a
// flat top and bottom 0.02 apart, and a blunt base. The two leading edges meet at the apex at
// 62 degrees; the base's edges close their fans' chain.
Point(1) = {0, 0, 0}; Point(2) = {1, -0.6, 0}; Point(3) = {1, 0.6, 0};
Point(4) = {0.16, 0, 0.01}; Point(5) = {1, -0.48, 0.01}; Point(6) = {1, 0.48, 0.01};
Point(7) = {0.16, 0, -0.01}; Point(8) = {1, -0.48, -0.01}; Point(9) = {1, 0.48, -0.01};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 1};
Line(4) = {4, 5}; Line(5) = {5, 6}; Line(6) = {6, 4};
Line(7) = {7, 8}; Line(8) = {8, 9}; Line(9) = {9, 7};
Curve Loop(1) = {1, 2, 3}; Curve Loop(2) = {4, 5, 6}; Curve Loop(3) = {7, 8, 9};
Ruled ThruSections(1) = {3, 1, 2};
