// tessellate_cad: a CAD file (STEP or BREP) tessellated as CAD tools export STL, with
// OpenCASCADE's own mesher (BRepMesh_IncrementalMesh) and STL writer (StlAPI_Writer): the
// coarse-deflection STL with needle triangles that issue 9 asks Strata to handle or refuse
// clearly. Not part of Strata; built when OpenCASCADE's headers are installed.
//   tessellate_cad IN.step|IN.brep OUT.stl DEFLECTION [ANGLE_DEG]
// DEFLECTION: largest distance from the surface, model units; ANGLE_DEG: largest angle
// between neighbouring triangles' normals (default 30). Writes binary STL.

#include <BRepMesh_IncrementalMesh.hxx>
#include <StlAPI_Writer.hxx>
#include <TopoDS_Shape.hxx>

#include <cmath>
#include "read_shape.h"

#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv) {
    if (argc < 4 || argc > 5) {
        std::fprintf(stderr, "usage: %s IN.step|IN.brep OUT.stl DEFLECTION [ANGLE_DEG]\n", argv[0]);
        return 2;
    }
    const std::string in = argv[1], out = argv[2];
    const double deflection = std::atof(argv[3]);
    const double angle = (argc == 5 ? std::atof(argv[4]) : 30.0) * M_PI / 180.0;
    if (!(deflection > 0.0) || !(angle > 0.0)) {
        std::fprintf(stderr, "%s: DEFLECTION and ANGLE_DEG must be positive\n", argv[0]);
        return 2;
    }
    TopoDS_Shape shape;
    if (!read_shape(in, shape)) return 1;
    BRepMesh_IncrementalMesh mesh(shape, deflection, Standard_False, angle, Standard_False);
    if (!mesh.IsDone()) {
        std::fprintf(stderr, "%s: BRepMesh_IncrementalMesh failed\n", in.c_str());
        return 1;
    }
    StlAPI_Writer writer;
    writer.ASCIIMode() = Standard_False;
    const std::string tmp = out + ".tmp";
    if (!writer.Write(shape, tmp.c_str()) || std::rename(tmp.c_str(), out.c_str()) != 0) {
        std::remove(tmp.c_str());
        std::fprintf(stderr, "%s: cannot write the STL file\n", out.c_str());
        return 1;
    }
    return 0;
}
