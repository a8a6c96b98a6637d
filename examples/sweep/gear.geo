// A spur gear 1 across and 0.1 thick (written for Strata's sweep, 2026-12-02): sixteen box teeth
// fused on a disc, concave 90° roots 0.06 apart at their narrowest and convex tips: the layers
// asked are thicker than the gaps between the teeth (`--fuse`).
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, 0, 0, 0, 0.1, 0.4};
For i In {0:15}
  Box(2+i) = {0.35, -0.04, 0, 0.15, 0.08, 0.1};
  Rotate {{0,0,1},{0,0,0}, i*2*Pi/16} { Volume{2+i}; }
EndFor
BooleanUnion{ Volume{1}; Delete; }{ Volume{2:17}; Delete; }
