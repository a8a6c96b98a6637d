// Source of cad_box_with_hole.igs (tests/geometry/test_cad.cpp): a 2 x 1 x 0.5 box with a
// vertical hole of radius 0.25 through it, 7 faces. Made with Gmsh 4.8.4
// (gmsh cad_box_with_hole.geo -0 -o box.step) and written as IGES (BRep solid, mode 1, mm)
// by OpenCASCADE 7.6's IGESControl_Writer, as Gmsh 4.8 cannot write IGES.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1, 0.5};
Cylinder(2) = {1, 0.5, -0.1, 0, 0, 0.7, 0.25};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
