// Source of cad_two_boxes_trimmed_faces.igs (tests/geometry/test_cad.cpp): two boxes of
// 1 x 0.5 x 0.3 touching along the plane y = 0.5, written as IGES in faces mode, as CAD tools
// write an assembly: trimmed surfaces, each face with its own edges, both copies of the face
// between the boxes.
//   /usr/bin/python3 -c "import gmsh; gmsh.initialize(); gmsh.open('cad_two_boxes_trimmed_faces.geo'); gmsh.write('boxes.brep')"
//   scripts/tessellate/export_iges boxes.brep cad_two_boxes_trimmed_faces.igs   (OpenCASCADE 7.6)
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 0.5, 0.3};
Box(2) = {0, 0.5, 0, 1, 0.5, 0.3};
