// cad_content.h: every real CAD file of the project passes the check of its format; a file
// holding something else is refused, saying what it looks like.

#include "test_support.h"

#include <strata/core/error.h>
#include <strata/io/cad_content.h>
#include <strata/io/files.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

using namespace strata;
using strata::test::ScratchDir;
namespace fs = std::filesystem;

namespace {

std::optional<CadContent> content_of(const std::string& path) {
    const std::string ext = lower_extension(path);
    if (ext == ".step" || ext == ".stp") return CadContent::Step;
    if (ext == ".iges" || ext == ".igs") return CadContent::Iges;
    if (ext == ".brep" || ext == ".brp") return CadContent::Brep;
    return std::nullopt;
}

/// An IGES start record: \p text padded to 72 columns, then the section letter and number.
std::string record(const std::string& text, char section, int number) {
    std::string r = text + std::string(72 - text.size(), ' ') + section;
    const std::string n = std::to_string(number);
    return r + std::string(7 - n.size(), '0') + n;
}

std::string write(const ScratchDir& dir, const std::string& name, const std::string& bytes) {
    std::ofstream(dir.file(name), std::ios::binary) << bytes;
    return dir.file(name);
}

}  // namespace

TEST(CadContent, EveryProjectCadFilePasses) {
    std::vector<std::string> dirs = {STRATA_EXAMPLES_DATA, STRATA_TEST_DATA};
    if (fs::is_directory("/work/shared/data")) dirs.push_back("/work/shared/data");
    int step = 0, iges = 0, brep = 0;
    for (const std::string& dir : dirs)
        for (const auto& e : fs::recursive_directory_iterator(dir)) {
            const std::optional<CadContent> kind = content_of(e.path().string());
            if (!kind || !e.is_regular_file()) continue;
            SCOPED_TRACE(e.path().string());
            EXPECT_NO_THROW(check_cad_content(e.path().string(), *kind));
            (*kind == CadContent::Step ? step : *kind == CadContent::Iges ? iges : brep)++;
        }
    // examples/data and tests/data alone: 3 STEP, 5 IGES, 7 BREP.
    EXPECT_GE(step, 3);
    EXPECT_GE(iges, 5);
    EXPECT_GE(brep, 7);
}

TEST(CadContent, StepVariants) {
    for (const char* head : {"ISO-10303-21;\nHEADER;", "\xEF\xBB\xBFISO-10303-21;\r\nHEADER;",
                             "\n\n  ISO-10303-21 ;\nHEADER;", "/* written by hand */\nISO-10303-21;", "iso-10303-21;"})
        EXPECT_TRUE(holds_cad_content(head, CadContent::Step)) << head;
    for (const char* head : {"", "ISO-10303-21", "ISO-10303-28;", "HEADER;\nISO-10303-21;", "/* unterminated"})
        EXPECT_FALSE(holds_cad_content(head, CadContent::Step)) << head;
}

TEST(CadContent, IgesVariants) {
    const std::string start = record("", 'S', 1), global = record(",,31HOpen CASCADE IGES processor", 'G', 1);
    for (const std::string& head : {
             start + "\n" + global + "\n",              // the usual
             start + "\r\n" + global + "\r\n",          // CRLF
             "\n\r\n" + start + "\n",                   // blank lines first
             global + "\n",                             // no start section
             record("", 'C', 1) + "\n" + start + "\n",  // compressed ASCII: the flag section
             record("", 'F', 1) + "\n" + start + "\n",
             std::string("a start line S      1\n"),  // a record that lost its padding
             record("", 'S', 1) + "   \n",            // trailing blanks
         })
        EXPECT_TRUE(holds_cad_content(head, CadContent::Iges)) << head;
    for (const std::string& head :
         {std::string(""), std::string("hello\n"), record("", 'D', 1) + "\n", record("", 'S', 1).substr(0, 73) + "x\n",
          std::string(200, ' ') + "S1\n", std::string("G17 G90\n"), std::string("text G      2\n"),
          std::string("ISO-10303-21;\n")})
        EXPECT_FALSE(holds_cad_content(head, CadContent::Iges)) << head;
}

TEST(CadContent, BrepVariants) {
    for (const char* head :
         {"DBRep_DrawableShape\n\nCASCADE Topology V1, (c) Matra-Datavision\n",
          "CASCADE Topology V3, (c) Open Cascade\nLocations 0\n", "\nCASCADE Topology V1, (c) Matra-Datavision\n"})
        EXPECT_TRUE(holds_cad_content(head, CadContent::Brep)) << head;
    for (const char* head : {"", "Locations 0\nCASCADE Topology V1", "ISO-10303-21;"})
        EXPECT_FALSE(holds_cad_content(head, CadContent::Brep)) << head;
}

TEST(CadContent, WrongContentIsNamed) {
    ScratchDir dir("cad_content_wrong");
    const std::string png = write(dir, "x.iges", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16));
    test::expect_error<InputError>(
        [&] { check_cad_content(png, CadContent::Iges); },
        {"'" + png +
         "' is not an IGES file: it looks like a PNG image; export the model again as IGES, or give the "
         "file the extension of its format (.step, .iges, .brep)"});
    const std::string step = write(dir, "wing.brep", "ISO-10303-21;\nHEADER;\n");
    test::expect_error<InputError>([&] { check_cad_content(step, CadContent::Brep); },
                                   {"is not a BREP file: it looks like a STEP file"});
    const std::string text = write(dir, "notes.step", "meeting notes\n");
    test::expect_error<InputError>([&] { check_cad_content(text, CadContent::Step); },
                                   {"is not a STEP file: it starts with the text 'meeting notes'"});
    const std::string empty = write(dir, "empty.igs", "");
    test::expect_error<InputError>([&] { check_cad_content(empty, CadContent::Iges); },
                                   {"is not an IGES file: it is empty"});
}
