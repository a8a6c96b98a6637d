// The length unit a STEP or IGES file declares (io/cad_units.h): STEP units written the ways
// exporters write them, IGES global sections with their units flag, custom delimiters and
// Hollerith strings, and the names parse_length_unit knows.

#include <strata/core/error.h>
#include <strata/io/cad_units.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <fstream>
#include <string>

namespace strata {
namespace {

using test::example_data;
using test::test_data;

std::string write(const test::ScratchDir& dir, const std::string& name, const std::string& text) {
    const std::string path = dir.file(name);
    std::ofstream(path) << text;
    return path;
}

std::string step_with(const std::string& units) {
    return "ISO-10303-21;\nHEADER;\nFILE_NAME('x','',(''),(''),'','','');\nENDSEC;\nDATA;\n"
           "#1=CARTESIAN_POINT('',(0.,0.,0.));\n" +
           units + "\nENDSEC;\nEND-ISO-10303-21;\n";
}

/// An IGES file whose global section is \p global, cut into 72-column 'G' lines.
std::string iges_with(const std::string& global) {
    std::string out = std::string(72, ' ') + "S0000001\n";
    for (std::size_t i = 0, n = 1; i < global.size(); i += 72, ++n) {
        std::string line = global.substr(i, 72);
        line.resize(72, ' ');
        out += line + "G" + std::string(6 - std::to_string(n).size(), '0') + std::to_string(n) + "\n";
    }
    return out + std::string(72, ' ') + "T0000001\n";
}

TEST(CadUnits, StepDeclarationsAsExportersWriteThem) {
    test::ScratchDir dir("cad_units_step");
    struct Case {
        std::string units, expected;
    };
    for (const Case& c : {
             Case{"#12=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));", "mm"},
             Case{"#12 = ( LENGTH_UNIT ( ) NAMED_UNIT ( * ) SI_UNIT ( $, .METRE. ) ) ;", "m"},
             Case{"#7=(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.));\n#8=(LENGTH_UNIT()NAMED_UNIT(*)\n"
                  "SI_UNIT(.CENTI.,.METRE.));",
                  "cm"},
             Case{"#20=(CONVERSION_BASED_UNIT('INCH',#21)LENGTH_UNIT()NAMED_UNIT(#22));\n"
                  "#21=LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4),#23);\n"
                  "#23=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));",
                  "in"},
             Case{"#30=(CONVERSION_BASED_UNIT('FOOT',#31)LENGTH_UNIT()NAMED_UNIT(#32));", "ft"},
         }) {
        const auto u = declared_length_unit(write(dir, "part.step", step_with(c.units)));
        ASSERT_TRUE(u.has_value()) << c.units;
        EXPECT_EQ(u->name, c.expected) << c.units;
    }
    // None, or one Strata does not know: nothing.
    EXPECT_FALSE(declared_length_unit(write(dir, "none.stp", step_with(""))).has_value());
    EXPECT_FALSE(declared_length_unit(
                     write(dir, "deci.stp", step_with("#1=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.DECI.,.METRE.));")))
                     .has_value());
    // The shared example files.
    EXPECT_EQ(declared_length_unit(example_data("wing_fuselage.step"))->name, "m");
    EXPECT_EQ(declared_length_unit(example_data("onera_m6_sharp_te.stp"))->name, "mm");
}

TEST(CadUnits, IgesGlobalSectionUnitsFlag) {
    test::ScratchDir dir("cad_units_iges");
    // Default delimiters (the section starts ",,"): flag 6, metres.
    EXPECT_EQ(declared_length_unit(write(dir, "a.igs",
                                         iges_with(",,4Hpart,8Hpart.igs,3Hcad,3Hcad,32,308,15,308,15,4Hpart,1.,6,"
                                                   "1HM,1,0.01,15H20261121.224432,1E-07,2.,4Hroot,,11,0,"
                                                   "15H20261121.224432;")))
                  ->name,
              "m");
    // Custom delimiters, a Hollerith string holding them, flag 3 with the unit's name.
    EXPECT_EQ(declared_length_unit(
                  write(dir, "b.iges",
                        iges_with("1H/,1H#/7Ha/b#c,d/8Hpart.igs/3Hcad/3Hcad/32/308/15/308/15/4Hpart/1./3/"
                                  "4HINCH/1/0.01/15H20261121.224432/1E-07/2./4Hroot//11/0/15H20261121.224432#")))
                  ->name,
              "in");
    EXPECT_EQ(declared_length_unit(test_data("cad_box_with_hole.igs"))->name, "mm");
    // A global section too short to hold the flag: nothing.
    EXPECT_FALSE(declared_length_unit(write(dir, "c.igs", iges_with(",,4Hpart;"))).has_value());
}

TEST(CadUnits, NamesAndFailures) {
    EXPECT_EQ(parse_length_unit("Millimetre")->name, "mm");
    EXPECT_DOUBLE_EQ(parse_length_unit("INCH")->millimetres, 25.4);
    EXPECT_DOUBLE_EQ(parse_length_unit("ft")->millimetres, 304.8);
    EXPECT_DOUBLE_EQ(parse_length_unit("meters")->millimetres, 1000.0);
    EXPECT_FALSE(parse_length_unit("parsec").has_value());
    EXPECT_FALSE(parse_length_unit("").has_value());
    // STL, BREP, .geo: no declaration read.
    EXPECT_FALSE(declared_length_unit(example_data("sphere.stl")).has_value());
    EXPECT_THROW(declared_length_unit("no_such_file.step"), InputError);
}

}  // namespace
}  // namespace strata
