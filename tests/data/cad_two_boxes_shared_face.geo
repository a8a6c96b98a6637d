// Source of cad_two_boxes_shared_face.igs (tests/app/test_cli.cpp): two unit boxes sharing
// the face x = 1 (one copy of it, as BooleanFragments leaves an assembly that conforms), written
// as IGES in faces mode: sewn, three faces meet at each edge round the shared one, which no
// solid can be made of.
//   /usr/bin/python3 -c "import gmsh; gmsh.initialize(); gmsh.open('cad_two_boxes_shared_face.geo'); gmsh.write('boxes.brep')"
//   scripts/tessellate/export_iges boxes.brep cad_two_boxes_shared_face.igs   (OpenCASCADE 7.6)
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {1, 0, 0, 1, 1, 1};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
