// write_foam_case and the case's texts: each patch kind's conditions in every field (exact
// entries), the flow's numbers (nu from the Reynolds number, k and omega of the freestream),
// byte-identical reruns; a case made from nothing, a case whose files the user edited (kept, and
// 0/ made again from 0.orig/), the warnings, and nothing left by a bad path or a cancellation.
// (OpenFOAM itself runs a case: tests/openfoam/run_simplefoam.sh.)

#include "core/box_mesh.h"
#include "test_support.h"

#include <strata/core/error.h>
#include <strata/io/openfoam_case.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace strata;
using strata::test::CancelAt;
using strata::test::ScratchDir;
using strata::test::slurp;
namespace fs = std::filesystem;

namespace {

/// Two cubes whose six sides are a wall, a farfield, a symmetry plane, an inlet, an outlet and
/// an outflow plane named neither (kind other).
VolumeMesh every_kind_box() {
    VolumeMesh m = test::BoxMesh(2, 1, 1).build();
    const std::vector<std::pair<std::string, PatchKind>> patches = {
        {"body", PatchKind::Wall},        {"far", PatchKind::Farfield}, {"mirror", PatchKind::Symmetry},
        {"Main_Inlet", PatchKind::Other}, {"outlet", PatchKind::Other}, {"cut", PatchKind::Other}};
    for (std::size_t i = 0; i < patches.size(); ++i) {
        m.boundary.patches[i].name = patches[i].first;
        m.boundary.patches[i].kind = patches[i].second;
    }
    return m;
}

std::vector<PolyPatch> every_kind_patches() {
    return {{"body", PatchKind::Wall, 0, 1},       {"far", PatchKind::Farfield, 1, 1},
            {"mirror", PatchKind::Symmetry, 2, 1}, {"Main_Inlet", PatchKind::Other, 3, 1},
            {"outlet", PatchKind::Other, 4, 1},    {"cut", PatchKind::Other, 5, 1}};
}

/// The text of \p file among \p files.
std::string text_of(const std::vector<FoamCaseFile>& files, const std::string& file) {
    for (const FoamCaseFile& f : files)
        if (f.path == file) return f.text;
    ADD_FAILURE() << "no " << file;
    return "";
}

/// The entries of \p patch in the field text \p text ("type noSlip;" ...), one line each, trimmed.
std::string entry(const std::string& text, const std::string& patch) {
    const std::size_t at = text.find("\n    " + patch + "\n    {\n");
    if (at == std::string::npos) return "(none)";
    const std::size_t begin = text.find("{\n", at) + 2, end = text.find("    }\n", begin);
    std::string out, line;
    std::istringstream lines(text.substr(begin, end - begin));
    while (std::getline(lines, line)) {
        const std::size_t key_end = line.find_first_of(' ', 8);
        const std::size_t value = line.find_first_not_of(' ', key_end);
        if (!out.empty()) out += ' ';
        out.append(line, 8, key_end - 8).append(" ").append(line, value);
    }
    return out;
}

const std::vector<std::string> kCaseFiles = {"system/controlDict",
                                             "system/fvSchemes",
                                             "system/fvSolution",
                                             "constant/transportProperties",
                                             "constant/turbulenceProperties",
                                             "0.orig/U",
                                             "0.orig/p",
                                             "0.orig/k",
                                             "0.orig/omega",
                                             "0.orig/nut"};

}  // namespace

TEST(FoamCase, PathsOfTheCaseAndItsMesh) {
    EXPECT_EQ(foam_case_directory("run/case"), "run/case");
    EXPECT_EQ(foam_case_directory("run/case/"), "run/case");
    EXPECT_EQ(foam_case_directory("run/case/constant/polyMesh"), "run/case");
    EXPECT_EQ(foam_case_directory("run/case/constant/polyMesh/"), "run/case");
    EXPECT_EQ(foam_case_directory("constant/polyMesh"), ".");
    EXPECT_EQ(foam_case_directory("polyMesh"), "polyMesh");  // a case named so
    EXPECT_EQ(foam_polymesh_path("run/case/"), "run/case/constant/polyMesh");
}

TEST(FoamCase, EveryPatchKindGetsItsConditionsInEveryField) {
    const std::vector<FoamCaseFile> files = foam_case_files(every_kind_patches(), FoamCaseParams{});
    std::vector<std::string> paths;
    for (const FoamCaseFile& f : files) paths.push_back(f.path);
    EXPECT_EQ(paths, kCaseFiles);
    const std::string u = text_of(files, "0.orig/U"), p = text_of(files, "0.orig/p"), k = text_of(files, "0.orig/k"),
                      omega = text_of(files, "0.orig/omega"), nut = text_of(files, "0.orig/nut");
    EXPECT_EQ(entry(u, "body"), "type noSlip;");
    EXPECT_EQ(entry(p, "body"), "type zeroGradient;");
    EXPECT_EQ(entry(k, "body"), "type kqRWallFunction; value uniform $kinf;");
    EXPECT_EQ(entry(omega, "body"), "type omegaWallFunction; value uniform $omegainf;");
    EXPECT_EQ(entry(nut, "body"), "type nutkWallFunction; value uniform 0;");
    EXPECT_EQ(entry(u, "far"), "type freestreamVelocity; freestreamValue uniform $Uinf;");
    EXPECT_EQ(entry(p, "far"), "type freestreamPressure; freestreamValue uniform 0;");
    EXPECT_EQ(entry(k, "far"), "type inletOutlet; inletValue uniform $kinf; value uniform $kinf;");
    for (const std::string& f : {u, p, k, omega, nut}) EXPECT_EQ(entry(f, "mirror"), "type symmetry;");
    // Kind other: an inlet and an outlet where the name says so (any case), else an outflow plane.
    EXPECT_EQ(entry(u, "Main_Inlet"), "type surfaceNormalFixedValue; refValue uniform $Uin; value uniform $Uinf;");
    EXPECT_EQ(entry(p, "Main_Inlet"), "type zeroGradient;");
    EXPECT_EQ(entry(omega, "Main_Inlet"), "type fixedValue; value uniform $omegainf;");
    for (const char* out : {"outlet", "cut"}) {
        EXPECT_EQ(entry(u, out), "type inletOutlet; inletValue uniform (0 0 0); value uniform $Uinf;");
        EXPECT_EQ(entry(p, out), "type fixedValue; value uniform 0;");
        EXPECT_EQ(entry(nut, out), "type calculated; value uniform 0;");
    }
    EXPECT_NE(u.find("name it so (--patch NAME=other:inlet)"), std::string::npos);
    // The variables the entries use, and the header OpenFOAM reads.
    EXPECT_NE(u.find("\nUinf            (1 0 0);"), std::string::npos);
    EXPECT_NE(u.find("\nUin             -1;"), std::string::npos);
    EXPECT_NE(u.find("class       volVectorField;\n    location    \"0\";\n    object      U;\n"), std::string::npos);
    EXPECT_NE(p.find("dimensions      [0 2 -2 0 0 0 0];\n\ninternalField   uniform 0;"), std::string::npos);
    // Without an inlet, no inlet speed.
    const std::string wall_only = text_of(foam_case_files({{"body", PatchKind::Wall, 0, 1}}, {}), "0.orig/U");
    EXPECT_EQ(wall_only.find("Uin "), std::string::npos);
}

TEST(FoamCase, TheFlowsNumbersFromTheReynoldsNumber) {
    FoamCaseParams params;
    params.velocity = Vec3(0, 2, 0);
    params.reynolds = 4e5;
    params.reference_length = 0.5;
    params.first_height = 1e-3;
    params.yplus = 12.3;
    params.iterations = 250;
    EXPECT_DOUBLE_EQ(foam_viscosity(params), 2 * 0.5 / 4e5);
    const std::vector<FoamCaseFile> files = foam_case_files(every_kind_patches(), params);
    EXPECT_NE(text_of(files, "constant/transportProperties").find("\nnu              2.5e-06;\n"), std::string::npos);
    EXPECT_NE(text_of(files, "constant/turbulenceProperties").find("RASModel        kOmegaSST;"), std::string::npos);
    // k = 1.5 (0.01 * 2)^2 = 6e-4; omega = k / (nu * 10) = 24.
    EXPECT_NE(text_of(files, "0.orig/k").find("\nkinf            0.0006;"), std::string::npos);
    EXPECT_NE(text_of(files, "0.orig/omega").find("\nomegainf        24;"), std::string::npos);
    EXPECT_NE(text_of(files, "0.orig/U").find("\nUinf            (0 2 0);"), std::string::npos);
    EXPECT_NE(text_of(files, "0.orig/U").find("\nUin             -2;"), std::string::npos);
    const std::string control = text_of(files, "system/controlDict");
    EXPECT_NE(control.find("\napplication     simpleFoam;\n"), std::string::npos);
    EXPECT_NE(control.find("\nendTime         250;\n"), std::string::npos);
    EXPECT_NE(control.find("Re = |Uinf| L / nu = 400000 on the reference length L = 0.5"), std::string::npos);
    EXPECT_NE(control.find("First layer height 0.001: y+ about 12.3"), std::string::npos);
    // The same bytes every time.
    const std::vector<FoamCaseFile> again = foam_case_files(every_kind_patches(), params);
    for (std::size_t i = 0; i < files.size(); ++i) EXPECT_TRUE(files[i].text == again[i].text) << files[i].path;

    for (auto bad : {+[](FoamCaseParams& p) { p.reynolds = 0; }, +[](FoamCaseParams& p) { p.reference_length = -1; },
                     +[](FoamCaseParams& p) { p.velocity = Vec3::Zero(); }}) {
        FoamCaseParams p;
        bad(p);
        test::expect_error<InputError>([&] { foam_case_files(every_kind_patches(), p); },
                                       {"cannot write an OpenFOAM case", "FoamCaseParams::"});
    }
}

TEST(WriteFoamCase, ACaseFromNothingThenTheUsersEditsKept) {
    ScratchDir dir("foam_case");
    const VolumeMesh m = every_kind_box();
    const std::string c = dir.file("case");
    FoamCaseWritten w = write_foam_case(m, c, {});
    EXPECT_EQ(w.written, kCaseFiles);
    EXPECT_TRUE(w.kept.empty());
    EXPECT_TRUE(w.warnings.empty());
    EXPECT_EQ(test::dir_entries(c), (std::vector<std::string>{"0", "0.orig", "constant", "system"}));
    EXPECT_EQ(test::dir_entries(c + "/constant"),
              (std::vector<std::string>{"polyMesh", "transportProperties", "turbulenceProperties"}));
    EXPECT_NE(slurp(c + "/constant/polyMesh/boundary").find("Main_Inlet"), std::string::npos);
    const std::vector<FoamCaseFile> texts = foam_case_files(every_kind_patches(), {});
    for (const FoamCaseFile& f : texts) EXPECT_TRUE(slurp(c + "/" + f.path) == f.text) << f.path;
    for (const char* f : {"U", "p", "k", "omega", "nut"}) EXPECT_EQ(slurp(c + "/0/" + f), slurp(c + "/0.orig/" + f));

    // The user edits the numerics and the velocity; a solver writes into 0/; the mesh is written again.
    std::ofstream(c + "/system/fvSchemes") << "mine";
    const std::string u = slurp(c + "/0.orig/U");
    std::ofstream(c + "/0.orig/U") << u.substr(0, u.find("Uinf ")) + "Uinf (0 0 3);" +
                                          u.substr(u.find(";", u.find("Uinf ")) + 1);
    std::ofstream(c + "/0.orig/nuTilda") << "body far mirror Main_Inlet outlet cut";
    std::ofstream(c + "/0/phi") << "of the earlier mesh";
    std::ofstream(c + "/0/U") << "potentialFoam's";
    fs::create_directory(c + "/250");
    w = write_foam_case(m, c, {});
    EXPECT_EQ(w.kept, (std::vector<std::string>{"system/fvSchemes", "0.orig/U"}));
    EXPECT_TRUE(w.written.empty());
    EXPECT_EQ(w.unchanged.size(), kCaseFiles.size() - 2);  // Strata's as they were
    EXPECT_EQ(slurp(c + "/system/fvSchemes"), "mine");
    EXPECT_EQ(slurp(c + "/0/U"), slurp(c + "/0.orig/U"));
    EXPECT_NE(slurp(c + "/0/U").find("Uinf (0 0 3);"), std::string::npos);
    EXPECT_EQ(test::dir_entries(c + "/0"), (std::vector<std::string>{"U", "k", "nuTilda", "nut", "omega", "p"}));
    ASSERT_EQ(w.warnings.size(), 1u);
    EXPECT_NE(w.warnings[0].find("earlier run (times 250)"), std::string::npos) << w.warnings[0];
    EXPECT_NE(w.warnings[0].find("foamListTimes -case " + c + " -rm"), std::string::npos);

    // A kept field without one of the mesh's patches is said.
    fs::remove(c + "/250");
    std::ofstream(c + "/0.orig/p") << "boundaryField { body {} far {} mirror {} outlet {} cut {} }";
    w = write_foam_case(m, c, {});
    ASSERT_EQ(w.warnings.size(), 1u);
    EXPECT_NE(w.warnings[0].find("0.orig/p' (kept: the case's own) has no entry for the patch 'Main_Inlet'"),
              std::string::npos)
        << w.warnings[0];
}

TEST(WriteFoamCase, BadPathsAndCancellingLeaveNothing) {
    ScratchDir dir("foam_case_bad");
    const VolumeMesh m = every_kind_box();
    test::expect_error<InputError>([&] { write_foam_case(m, dir.file("missing/case"), {}); },
                                   {"cannot write the OpenFOAM case", "missing' does not exist"});
    fs::create_directory(dir.file("case"));
    std::ofstream(dir.file("case/system")) << "a file";
    test::expect_error<InputError>([&] { write_foam_case(m, dir.file("case"), {}); },
                                   {"case/system' is a file, not a directory"});
    fs::remove(dir.file("case/system"));
    fs::create_directories(dir.file("case/0.orig/U"));
    test::expect_error<InputError>([&] { write_foam_case(m, dir.file("case"), {}); },
                                   {"case/0.orig/U' is a directory, not a file"});
    fs::remove_all(dir.file("case"));
    EXPECT_TRUE(test::dir_entries(dir.path()).empty());
    // Cancelled while the polyMesh is written: not even the case's directory is left.
    for (double at : {0.5, 1.0}) {
        CancelAt cancel(at);
        EXPECT_THROW(write_foam_case(m, dir.file("case"), {}, &cancel), Cancelled) << at;
        EXPECT_TRUE(test::dir_entries(dir.path()).empty()) << at;
    }
    // In an existing case nothing changes: the user's file stays, no directory is added.
    fs::create_directories(dir.file("case/system"));
    std::ofstream(dir.file("case/system/controlDict")) << "mine";
    CancelAt cancel(1.0);
    EXPECT_THROW(write_foam_case(m, dir.file("case"), {}, &cancel), Cancelled);
    EXPECT_EQ(test::dir_entries(dir.file("case")), std::vector<std::string>{"system"});
    EXPECT_EQ(test::dir_entries(dir.file("case/system")), std::vector<std::string>{"controlDict"});
}
