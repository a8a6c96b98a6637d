// Tests for io/geo_script.h: a .geo script with Macros read more than once in one process, and
// the scan that refuses a script reaching outside Gmsh's model.

#include <strata/core/error.h>
#include <strata/io/geo_script.h>
#include <strata/io/gmsh_session.h>

#include <gmsh.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "test_support.h"

using namespace strata;

namespace {

// Gmsh's tutorial t5 in miniature: a Macro that adds a sphere, called twice.
constexpr const char* kScript =
    "SetFactory(\"OpenCASCADE\");\n"
    "// Call Bore inside a comment is renamed too, harmlessly\n"
    "Macro Bore\n"
    "  Sphere(newv) = {x, 0, 0, 0.1};\n"
    "Return\n"
    "Function \"Old\"\n"
    "  y = 1;\n"
    "Return\n"
    "x = 0;\n"
    "Call Bore;\n"
    "x = 1;\n"
    "Call \"Bore\";\n"
    "Call Old;\n"
    "Bores = 2; CallBore = 3;\n";

}  // namespace

TEST(GeoScript, MacroNamesAreThoseDefinedBareOrQuoted) {
    EXPECT_EQ(geo_macro_names(kScript), (std::vector<std::string>{"Bore", "Old"}));
    EXPECT_TRUE(geo_macro_names("MyMacro Foo;\nx = 1;\n").empty());  // part of a longer word
}

TEST(GeoScript, RenamingTouchesTheDefinitionsAndCallsOnly) {
    const std::string r = rename_geo_macros(kScript, "_s1");
    test::expect_contains(
        r, {"Macro Bore_s1\n", "Function \"Old_s1\"\n", "Call Bore_s1;\nx = 1;\nCall \"Bore_s1\";\nCall Old_s1;\n"});
    EXPECT_NE(r.find("Bores = 2; CallBore = 3;"), std::string::npos) << r;  // other words stay
    EXPECT_EQ(rename_geo_macros("Call Other;\n", "_s1"), "Call Other;\n");  // another script's Macro
}

TEST(GeoScript, AScriptWithMacrosIsReadTwiceInOneProcess) {
    // Gmsh 4.8 keeps Macros for the life of the process: gmsh::merge of the same script a
    // second time failed with "Redefinition of function Bore".
    test::ScratchDir dir("geo_script_twice");
    const std::string path = dir.file("holes.geo");
    std::ofstream(path) << kScript;
    for (int round = 0; round < 3; ++round) {
        GmshSession session("geo_script_test");
        gmsh_call("reading " + path, [&] { merge_geo_script(path, false); });
        gmsh::model::occ::synchronize();
        gmsh::vectorpair volumes;
        gmsh::model::getEntities(volumes, 3);
        EXPECT_EQ(volumes.size(), 2u) << "round " << round;
    }
    // The renamed copies beside the script are gone.
    int files = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir.path())) files += e.is_regular_file() ? 1 : 0;
    EXPECT_EQ(files, 1);
}

// ---------------------------------------------------------------------------------------
// A .geo script is a program: the statements that reach outside Gmsh's model.

namespace {

/// "line command" of each hazard of \p text, in order.
std::vector<std::string> hazards_of(const std::string& text) {
    std::vector<std::string> out;
    for (const GeoHazard& h : scan_geo_text(text).hazards) out.push_back(std::to_string(h.line) + " " + h.command);
    return out;
}

}  // namespace

TEST(GeoScriptScan, EachCommandThatReachesOutsideTheModelIsFoundOnItsLine) {
    const std::string text =
        "Point(1) = {0, 0, 0, 1};\n"
        "SystemCall \"touch a\";\n"
        "System \"touch b\";\n"
        "NonBlockingSystemCall \"sleep 10\";\n"
        "OnelabRun(\"client\", \"./solver\");\n"
        "CreateDir \"out\";\n"
        "Save \"model.msh\";\n"
        "Print \"model.png\";\n"
        "Save View[0] \"view.pos\";\n"
        "SendToServer View[0] \"v\";\n"
        "Printf(\"x\") > \"log.txt\";\n"
        "Printf(\"x = %g\", (1 + 2)) >> Str(\"log.txt\");\n"
        "Plugin(Bubbles).Run;\n"
        "Include StrCat(\"part\", \".geo\");\n"
        "Merge Sprintf(\"fin%g.geo\", 1);\n"
        "Exit;\n";
    EXPECT_EQ(
        hazards_of(text),
        (std::vector<std::string>{"2 SystemCall", "3 System", "4 NonBlockingSystemCall", "5 OnelabRun", "6 CreateDir",
                                  "7 Save", "8 Print", "9 Save", "10 SendToServer", "11 Printf(...) >",
                                  "12 Printf(...) >>", "13 Plugin(Bubbles).Run", "14 Include", "15 Merge", "16 Exit"}));
    const GeoHazard first = scan_geo_text(text).hazards.front();
    EXPECT_EQ(first.what, "runs a shell command");
    EXPECT_TRUE(first.file.empty());
    // The command as a statement however it is spaced: across lines, a comment between.
    EXPECT_EQ(hazards_of("SystemCall\n\"touch a\";\nSystemCall/* x */Str(\"touch b\");\nSave f;\n"),
              (std::vector<std::string>{"1 SystemCall", "3 SystemCall", "4 Save"}));
}

TEST(GeoScriptScan, CommentsStringsAndOtherUsesOfTheWordsAreNotCommands) {
    const std::string text =
        "// SystemCall \"touch a\";\n"
        "/* Save \"x.msh\";\n"
        "   Exit; */\n"
        "Printf(\"SystemCall 'touch b'; Exit;\");\n"  // a string: not run
        "Physical Surface(\"Save\") = {1};\n"
        "s = 'Include \"x.geo\"; OnelabRun';\n"
        "Print.Width = 800;\n"       // an option
        "General.Print = 1;\n"       // a word after a dot
        "Save = 1; x = Save + 1;\n"  // a variable
        "SystemCallX \"a\"; MySave \"b\";\n"
        "SystemCall~{2} \"c\";\n"  // Gmsh's name SystemCall_2: an unknown command
        "Printf(\"x = %g\", x);\n"
        "Printf(\"a\"); y = 2 > 1;\n"
        "Plugin(CutPlane).A = 1;\n"
        "exit; systemcall \"d\"; SYSTEMCALL \"e\";\n";  // keywords are case-sensitive
    EXPECT_EQ(hazards_of(text), std::vector<std::string>{});
    EXPECT_TRUE(scan_geo_text(text).reads.empty());
}

TEST(GeoScriptScan, LineNumbersCountTheLinesOfCommentsAndStrings) {
    EXPECT_EQ(hazards_of("/* one\ntwo\nthree */ x = 1;\ns = \"four\nfive\";\n\n\tSave \"m.msh\";\n"),
              std::vector<std::string>{"7 Save"});
    // An unterminated string or comment runs to the end, as in Gmsh's lexer: nothing after it.
    EXPECT_EQ(hazards_of("Save \"a.msh\";\ns = \"open;\nSave \"b.msh\";\n"), std::vector<std::string>{"1 Save"});
    EXPECT_EQ(hazards_of("/* open\nExit;\n"), std::vector<std::string>{});
}

TEST(GeoScriptScan, ScriptsReadByAPlainNameAreListedForTheFileCheck) {
    const GeoScan s = scan_geo_text("Include \"a.geo\";\nMerge 'b.step';\nMergeWithBoundingBox \"c.txt\";\n");
    ASSERT_EQ(s.reads.size(), 3u);
    EXPECT_EQ(s.reads[0].line, 1);
    EXPECT_EQ(s.reads[0].command, "Include");
    EXPECT_EQ(s.reads[0].path, "a.geo");
    EXPECT_EQ(s.reads[1].path, "b.step");
    EXPECT_EQ(s.reads[2].command, "MergeWithBoundingBox");
    EXPECT_TRUE(s.hazards.empty());
}

TEST(GeoScriptScan, MergeRunsAScriptUnlessGmshHasAReaderForTheFile) {
    test::ScratchDir dir("geo_script_merged");
    for (const char* name : {"a.step", "a.STEP", "a.stp", "a.igs", "a.brep", "a.BRP", "a.stl", "a.py", "a.pro"})
        EXPECT_FALSE(merged_as_script(dir.file(name))) << name;
    // Gmsh compares the extensions as spelled: another case, or none it knows, is parsed.
    for (const char* name : {"a.geo", "a.txt", "a.Step", "a.BREP", "a.PRO", "a", "a.pos"})
        EXPECT_TRUE(merged_as_script(dir.file(name))) << name;
    std::ofstream(dir.file("m.msh")) << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
    std::ofstream(dir.file("s.msh")) << "SystemCall \"touch x\";\n";
    EXPECT_FALSE(merged_as_script(dir.file("m.msh")));
    EXPECT_TRUE(merged_as_script(dir.file("s.msh")));
}

TEST(GeoScriptCheck, IncludedAndMergedScriptsAreScannedRelativeToTheScriptReadingThem) {
    test::ScratchDir dir("geo_script_nested");
    std::filesystem::create_directories(dir.path() / "parts");
    std::ofstream(dir.file("main.geo")) << "Point(1) = {0, 0, 0, 1};\n"
                                           "Include \"parts/wing.geo\";\n"
                                           "Merge \"parts/body.step\";\n"      // a reader of its own
                                           "Include \"parts/missing.geo\";\n"  // Gmsh fails on it
                                           "Include \"main.geo\";\n";          // scanned once
    std::ofstream(dir.file("parts/wing.geo")) << "Point(2) = {1, 0, 0, 1};\nMerge \"tip.txt\";\n";
    std::ofstream(dir.file("parts/body.step")) << "SystemCall \"touch not_a_script\";\n";
    std::ofstream(dir.file("parts/tip.txt")) << "\n\nSave \"tip.msh\";\n";
    const std::vector<GeoHazard> found = geo_script_hazards(dir.file("main.geo"));
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].file, (dir.path() / "parts" / "tip.txt").string());
    EXPECT_EQ(found[0].line, 3);
    EXPECT_EQ(found[0].command, "Save");
    EXPECT_EQ(found[0].read_from, (dir.path() / "parts" / "wing.geo").string() + ", line 2");
    test::expect_error<InputError>([&] { check_geo_script(dir.file("main.geo")); },
                                   {"tip.txt, line 3: `Save` writes a file", "a script read by", "wing.geo, line 2",
                                    "a .geo file is a program", "CadParams::trust_geo = true"});
}

TEST(GeoScriptCheck, TheMessageNamesTheFirstStatementAndListsTheOthers) {
    test::ScratchDir dir("geo_script_message");
    const std::string path = dir.file("evil.geo");
    std::ofstream(path) << "Point(1) = {0, 0, 0, 1};\nSystemCall \"touch pwned\";\nSave \"a.msh\";\nExit;\n";
    test::expect_error<InputError>(
        [&] { check_geo_script(path); },
        {path + ", line 2: `SystemCall` runs a shell command (and 2 more such statements: line 3 `Save`, line 4 "
                "`Exit`); a .geo file is a program: if you trust its author, give CadParams::trust_geo = true"});
    std::ofstream(dir.file("fine.geo")) << "Point(1) = {0, 0, 0, 1};\n";
    EXPECT_NO_THROW(check_geo_script(dir.file("fine.geo")));
}

TEST(GeoScriptCheck, AnUntrustedScriptIsRefusedBeforeGmshRunsIt) {
    test::ScratchDir dir("geo_script_refused");
    const std::string path = dir.file("evil.geo");
    const std::string pwned = dir.file("pwned");
    std::ofstream(path) << "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\nSystemCall \"touch '" + pwned +
                               "'\";\n";
    {
        GmshSession session("geo_script_refused");
        EXPECT_THROW(gmsh_call("reading " + path, [&] { merge_geo_script(path, false); }), InputError);
    }
    EXPECT_FALSE(std::filesystem::exists(pwned));
    GmshSession session("geo_script_trusted");
    gmsh_call("reading " + path, [&] { merge_geo_script(path, true); });
    EXPECT_TRUE(std::filesystem::exists(pwned));  // trusted, it runs as Gmsh runs it
}

TEST(GeoScriptCheck, TheBundledScriptsPassTheCheck) {
    // Ours: no example or test script needs CadParams::trust_geo.
    namespace fs = std::filesystem;
    const fs::path examples = fs::path(STRATA_EXAMPLES_DATA).parent_path();
    int scripts = 0;
    for (const fs::path& root : {examples, fs::path(STRATA_TEST_DATA)})
        for (const auto& e : fs::recursive_directory_iterator(root)) {
            if (e.path().extension() != ".geo") continue;
            ++scripts;
            for (const GeoHazard& h : geo_script_hazards(e.path().string()))
                ADD_FAILURE() << h.file << ", line " << h.line << ": " << h.command << " " << h.what;
        }
    EXPECT_GT(scripts, 40);
}
