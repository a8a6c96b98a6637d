SetFactory("OpenCASCADE");
// Two blades of blade_sharp_edge.geo's section (sharp edges at x = 1), one above the other,
// 0.0125 apart: sharp edges next to a gap narrower than 20 layers of 1e-3 at growth 1.2.
Wedge(1) = {0, 0, -0.0875, 1, 2, 0.175, 0};
Wedge(2) = {0, 0, 0.1, 1, 2, 0.175, 0};
