// Unit box whose faces are partly in physical groups (tests/geometry/test_cad.cpp):
// "inlet" = {1}, "walls" = {3, 4}, an unnamed group 7 = {5}; faces 2 and 6 in no group.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Physical Surface("inlet", 1) = {1};
Physical Surface("walls", 2) = {3, 4};
Physical Surface(7) = {5};
