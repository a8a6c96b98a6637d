#pragma once
// Shared by tessellate_cad and export_iges: a STEP or BREP file read into one shape with
// OpenCASCADE, the failure said on stderr.

#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <STEPControl_Reader.hxx>
#include <TopoDS_Shape.hxx>

#include <cstdio>
#include <string>

/// \p in (.brep/.brp, anything else as STEP) into \p shape; false (and a message) if it cannot be read.
inline bool read_shape(const std::string& in, TopoDS_Shape& shape) {
    const std::string ext = in.substr(in.find_last_of('.') + 1);
    if (ext == "brep" || ext == "brp") {
        BRep_Builder builder;
        if (BRepTools::Read(shape, in.c_str(), builder)) return true;
        std::fprintf(stderr, "%s: cannot read the BREP file\n", in.c_str());
        return false;
    }
    STEPControl_Reader reader;
    if (reader.ReadFile(in.c_str()) != IFSelect_RetDone || reader.TransferRoots() == 0) {
        std::fprintf(stderr, "%s: cannot read the STEP file\n", in.c_str());
        return false;
    }
    shape = reader.OneShape();
    return true;
}
