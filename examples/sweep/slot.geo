SetFactory("OpenCASCADE");
// two-element "airfoil" (ellipse sections) with a narrow slot, extruded spanwise
Disk(1) = {0, 0, 0, 0.5, 0.06};
Disk(2) = {0.62, -0.08, 0, 0.15, 0.025};
Rotate {{0,0,1},{0.62,-0.08,0}, -0.35} { Surface{2}; }
Extrude {0, 0, 1.5} { Surface{1,2}; }
