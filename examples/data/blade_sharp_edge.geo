SetFactory("OpenCASCADE");
// A blade: its section a thin triangle (10 degrees at the sharp edge, which runs along y at
// x = 1, z = 0), 1 deep and 2 long, closed by flat ends: a sharp edge that turns 170 degrees,
// ending in corners where it meets the ends' 90-degree edges.
Wedge(1) = {0, 0, -0.0875, 1, 2, 0.175, 0};
