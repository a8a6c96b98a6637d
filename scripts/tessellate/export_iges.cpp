// export_iges: a CAD file (STEP or BREP) written as IGES the way most CAD tools write it, with
// OpenCASCADE's IGESControl_Writer in its default "faces" mode: trimmed surfaces without
// topology, so each face has its own edges, which reading sews (CadParams::sew_tolerance).
// Not part of Strata; built with tessellate_cad (build.sh) when OpenCASCADE's headers are
// installed. For test data such as tests/data/cad_nose_trimmed_faces.igs.
//   export_iges IN.step|IN.brep OUT.igs [UNIT]      (UNIT: MM (default), M, IN, ...)

#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <TopoDS_Shape.hxx>

#include "read_shape.h"

#include <cstdio>
#include <string>

int main(int argc, char** argv) {
    if (argc < 3 || argc > 4) {
        std::fprintf(stderr, "usage: %s IN.step|IN.brep OUT.igs [UNIT]\n", argv[0]);
        return 2;
    }
    const std::string in = argv[1];
    TopoDS_Shape shape;
    if (!read_shape(in, shape)) return 1;
    IGESControl_Controller::Init();
    IGESControl_Writer writer(argc == 4 ? argv[3] : "MM", 0);  // 0: faces (trimmed surfaces), 1: BRep
    writer.AddShape(shape);
    writer.ComputeModel();
    if (!writer.Write(argv[2])) {
        std::fprintf(stderr, "%s: cannot write the IGES file\n", argv[2]);
        return 1;
    }
    return 0;
}
