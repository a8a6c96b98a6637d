// Source of cad_nose_trimmed_faces.igs (tests/geometry/test_cad.cpp): half of a cylinder of
// radius 0.2 and length 1 with a quarter-sphere nose, cut by the plane z = 0 (the body of
// bl3d_5_body_fin_in_box.brep), written as IGES in faces mode, as CAD tools write it: trimmed
// surfaces, each face with its own edges.
//   /usr/bin/python3 -c "import gmsh; gmsh.initialize(); gmsh.open('cad_nose_trimmed_faces.geo'); gmsh.write('nose.brep')"
//   scripts/tessellate/export_iges nose.brep cad_nose_trimmed_faces.igs   (OpenCASCADE 7.6)
// Sewn alone, its nose keeps a degenerate edge at the pole and Gmsh aborts meshing it; sewn
// with the small edges fixed it is one closed solid.
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, 0, 1, 0, 0, 0.2};
Sphere(2) = {0, 0, 0, 0.2};
BooleanUnion{ Volume{1}; Delete; }{ Volume{2}; Delete; }
Box(3) = {-1, -1, 0, 3, 2, 1};
BooleanIntersection{ Volume{1}; Delete; }{ Volume{3}; Delete; }
