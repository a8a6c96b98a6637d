// A model Gmsh 4.8 cannot mesh, for tests/app/test_cli.cpp: the half body of
// cad_nose_trimmed_faces.igs sewn by Gmsh's own import option (sewing alone, without fixing its
// small edges), whose nose keeps a degenerate edge at its pole: Gmsh's surface mesher throws
// "The 1D mesh seems not to be forming a closed loop" out of an OpenMP region, which ends the
// process through std::terminate. Strata must say so on one line and exit 1.
SetFactory("OpenCASCADE");
Geometry.OCCSewFaces = 1;
Merge "cad_nose_trimmed_faces.igs";
