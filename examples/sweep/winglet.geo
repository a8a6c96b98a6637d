SetFactory("OpenCASCADE");
// thin wing with a tilted winglet, fused: sharp edges, concave junction
Box(1) = {0, 0, -0.03, 1, 3, 0.06};
Box(2) = {0.3, 2.95, -0.03, 0.7, 0.06, 0.6};
Rotate {{1,0,0},{0.3,2.98,0}, -0.3} { Volume{2}; }
