// Source of cad_capsule_trimmed_faces.igs (tests/geometry/test_cad.cpp): a capsule (a cylinder
// of radius 0.2 and length 1 with hemispherical ends), written as IGES in faces mode, as CAD
// tools write it: trimmed surfaces, each face with its own edges.
//   /usr/bin/python3 -c "import gmsh; gmsh.initialize(); gmsh.open('cad_capsule_trimmed_faces.geo'); gmsh.write('capsule.brep')"
//   scripts/tessellate/export_iges capsule.brep cad_capsule_trimmed_faces.igs   (OpenCASCADE 7.6)
// Healing its faces (fixing small edges) cuts its spherical ends to 40 % of their area: Strata
// must see that and mesh the faces unsewn, as they are.
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, 0, 1, 0, 0, 0.2};
Sphere(2) = {0, 0, 0, 0.2};
Sphere(3) = {1, 0, 0, 0.2};
BooleanUnion{ Volume{1}; Delete; }{ Volume{2, 3}; Delete; }
