#pragma once
/// \file
/// The length unit a CAD file declares. OpenCASCADE converts every STEP and IGES file to
/// millimetres on import, whatever unit the file declares; to read a file in its own unit
/// (a STEP in metres stays in metres), Strata reads the declaration here and scales back.
/// BREP files and Gmsh scripts carry no unit.

#include <optional>
#include <string>
#include <string_view>

namespace strata {

/// A length unit: Strata's short name ("mm", "cm", "m", "km", "in", "ft", "mi", "mil",
/// "um", "uin") and its length in millimetres.
struct LengthUnit {
    std::string name;
    double millimetres = 1.0;
};

/// The unit named \p name: a short name as above or a common spelling (case-insensitive:
/// "millimetre", "meter", "inch", "INCH", "MM", "micron", ...). Empty if unknown.
std::optional<LengthUnit> parse_length_unit(std::string_view name);

/// "mm, cm, m, km, in, ft, mi, mil, um, uin": the names parse_length_unit knows, for messages.
std::string_view length_unit_names();

/// The length unit \p path declares: for STEP (.step/.stp) the first LENGTH_UNIT of its data
/// section (an SI unit of metre, with or without a prefix, or a conversion-based inch, foot,
/// mile or mil); for IGES (.iges/.igs) the units flag of its global section (parameter 14; with
/// flag 3 the name in parameter 15). Empty if the file declares none Strata knows, or for any
/// other format. InputError if the file cannot be read.
std::optional<LengthUnit> declared_length_unit(const std::string& path);

}  // namespace strata
