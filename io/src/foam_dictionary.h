#pragma once
// The text OpenFOAM's own utilities put round a dictionary or field file: the banner, the
// FoamFile header and the closing line, for the polyMesh writer and the case writer alike.

#include <string>
#include <string_view>

namespace strata {

/// The banner and FoamFile header of an OpenFOAM file: \p cls ("dictionary", "volScalarField",
/// "faceList", ...), \p location ("system", "0", "constant/polyMesh"), \p object (its name);
/// \p note, if not empty, as the header's note.
inline std::string foam_header(std::string_view cls, std::string_view location, std::string_view object,
                               std::string_view note = {}) {
    std::string s =
        "/*--------------------------------*- C++ -*----------------------------------*\\\n"
        "  Written by Strata, a near-body hybrid mesh generator, for OpenFOAM\n"
        "\\*---------------------------------------------------------------------------*/\n"
        "FoamFile\n{\n    version     2.0;\n    format      ascii;\n    class       ";
    s.append(cls).append(";\n");
    if (!note.empty()) s.append("    note        \"").append(note).append("\";\n");
    s.append("    location    \"").append(location).append("\";\n    object      ").append(object);
    s.append(
        ";\n}\n"
        "// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n\n");
    return s;
}

/// The line that ends every OpenFOAM file.
constexpr std::string_view kFoamFooter =
    "// ************************************************************************* //\n";

}  // namespace strata
