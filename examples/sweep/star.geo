// A six-pointed star prism 1 across and 0.2 thick (written for Strata's sweep, 2026-12-02): its
// tips are 60° wedges (faces turning 120°, under the default fan angle, over --sharp-edge-stop),
// its notches acute concave corners, its end faces' 90° edges closing the tips' chains.
SetFactory("OpenCASCADE");
n = 6;
For i In {0:2*n-1}
  r = (i % 2 == 0) ? 0.5 : 0.22;
  Point(i+1) = {r*Cos(i*Pi/n), r*Sin(i*Pi/n), 0};
EndFor
For i In {0:2*n-1}
  Line(i+1) = {i+1, (i+1)%(2*n)+1};
EndFor
Curve Loop(1) = {1:2*n}; Plane Surface(1) = {1};
Extrude {0,0,0.2} { Surface{1}; }
