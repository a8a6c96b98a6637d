// End-to-end tests of the `strata` program: real inputs succeed and write what they claim;
// every bad input gives one line on stderr, a non-zero exit and no output file.

#include <strata/geometry/topology.h>
#include <strata/hybrid/hybrid_mesh.h>
#include <strata/io/read_surface.h>
#include <strata/io/write_volume.h>
#include <strata/surface/prepare.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace strata {
namespace {

using test::closed_manifold;
using test::enclosed_volume;

namespace fs = std::filesystem;
using test::example_data;
using test::test_data;

using strata::test::slurp;
using test::CliResult;

/// Run the strata program with \p args (already shell-quoted) in \p dir, under \p wrapper (a
/// command prefix such as "timeout ... ").
CliResult strata_cli(const test::ScratchDir& dir, const std::string& args, const std::string& wrapper = "") {
    return test::run_program(dir, STRATA_CLI, args, wrapper);
}

/// `strata mesh` run in \p dir on \p shape of examples/sweep with the options \p args.
CliResult mesh_sweep(const test::ScratchDir& dir, const std::string& shape, const std::string& args) {
    return strata_cli(dir, "mesh '" + example_data("../sweep/" + shape) + "' " + args);
}

/// `strata mesh` on \p shape of examples/sweep with \p args, run in a scratch directory
/// \p scratch: it succeeds, its summary says each of \p says and that checkMesh passes the mesh.
void expect_sweep_passes(const std::string& scratch, const std::string& shape, const std::string& args,
                         std::vector<std::string> says) {
    test::ScratchDir dir(scratch);
    const CliResult r = mesh_sweep(dir, shape, args);
    ASSERT_EQ(r.code, 0) << r.err;
    says.push_back("checkMesh would say \"Mesh OK\"");
    test::expect_contains(r.out, says);
}

/// Files in \p dir (after the runner removed its own capture files).
std::vector<std::string> files_in(const test::ScratchDir& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir.path())) names.push_back(e.path().filename().string());
    return names;
}

/// `strata surface INPUT -o OUT EXTRA` in \p dir, which must succeed; the surface it wrote.
SurfaceMesh surface_via_cli(const test::ScratchDir& dir, const std::string& input, const std::string& out,
                            const std::string& extra = "", std::string* stdout_text = nullptr) {
    CliResult r = strata_cli(dir, "surface '" + input + "' -o " + out + " " + extra);
    EXPECT_EQ(r.code, 0) << r.err;
    if (stdout_text) *stdout_text = r.out;
    if (r.code != 0) return {};
    return read_msh(dir.file(out));
}

std::size_t lines(const std::string& s) {
    std::size_t n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

TEST(Cli, HelpAndVersion) {
    test::ScratchDir dir("cli_help");
    CliResult h = strata_cli(dir, "--help");
    EXPECT_EQ(h.code, 0);
    EXPECT_NE(h.out.find("surface"), std::string::npos);
    for (const char* format : {".cgr", ".cgns", "polyMesh", ".msh"}) EXPECT_NE(h.out.find(format), std::string::npos);
    CliResult hm = strata_cli(dir, "mesh --help");
    EXPECT_EQ(hm.code, 0);
    for (const char* format : {".cgr", ".cgns", "polyMesh", ".msh"}) EXPECT_NE(hm.out.find(format), std::string::npos);
    CliResult hs = strata_cli(dir, "surface --help");
    EXPECT_EQ(hs.code, 0);
    for (const char* opt : {"--size", "--quads", "--mixed", "--patch", "--fuse", "--curvature", "-o"})
        EXPECT_NE(hs.out.find(opt), std::string::npos) << opt;
    CliResult v = strata_cli(dir, "--version");
    EXPECT_EQ(v.code, 0);
    EXPECT_EQ(v.out.rfind("strata ", 0), 0u) << v.out;
    // The commit it was built from, as the reports' provenance gives it (40 hex digits, or
    // "unknown" outside a git checkout).
    const auto at = v.out.find("(commit ");
    ASSERT_NE(at, std::string::npos) << v.out;
    const std::string commit = v.out.substr(at + 8, v.out.find(')', at) - at - 8);
    EXPECT_TRUE(commit == "unknown" ||
                (commit.size() == 40 && commit.find_first_not_of("0123456789abcdef") == std::string::npos))
        << commit;
    CliResult none = strata_cli(dir, "");
    EXPECT_NE(none.code, 0);
}

TEST(Cli, SurfaceFromStl) {
    test::ScratchDir dir("cli_stl");
    const SurfaceMesh m = surface_via_cli(dir, example_data("sphere.stl"), "sphere.msh");
    EXPECT_EQ(m.num_triangles(), 606);
    EXPECT_EQ(m.num_points(), 305);  // closed genus-0 triangulation: V = F/2 + 2
    EXPECT_TRUE(closed_manifold(m));
    EXPECT_EQ(files_in(dir), std::vector<std::string>{"sphere.msh"});  // no temporary left behind
}

TEST(Cli, SurfaceFromQuadMsh) {
    test::ScratchDir dir("cli_quads");
    const SurfaceMesh m = surface_via_cli(dir, example_data("sphere_pyhyp_quads.msh"), "s.msh", "--msh-version 2.2");
    EXPECT_EQ(m.num_quads(), 1536);
    EXPECT_EQ(m.num_triangles(), 0);
    EXPECT_TRUE(closed_manifold(m));
    EXPECT_EQ(slurp(dir.file("s.msh")).rfind("$MeshFormat\n2.2", 0), 0u);
}

TEST(Cli, SurfaceFromMixedMshWithPatchKind) {
    test::ScratchDir dir("cli_mixed");
    const SurfaceMesh in = read_msh(example_data("onera_m6_mixed_quadtri.msh"));
    ASSERT_FALSE(in.patches.empty());
    const std::string name = in.patches.front().name;
    std::string out;
    const SurfaceMesh m = surface_via_cli(dir, example_data("onera_m6_mixed_quadtri.msh"), "m6.msh",
                                          "--patch '" + name + "=symmetry'", &out);
    EXPECT_NE(out.find("symmetry"), std::string::npos) << out;
    EXPECT_EQ(m.num_quads(), 7753);
    EXPECT_EQ(m.num_triangles(), 2588);
    EXPECT_TRUE(closed_manifold(m));
}

TEST(Cli, SurfaceFromStep) {
    test::ScratchDir dir("cli_step");
    const SurfaceMesh m = surface_via_cli(dir, example_data("onera_m6_sharp_te.stp"), "m6.msh", "--size 60");
    EXPECT_GT(m.num_triangles(), 500);
    EXPECT_EQ(m.patches.size(), 11u);
    EXPECT_TRUE(closed_manifold(m));
}

TEST(Cli, SeveralInputsAreOneSurface) {
    // The unit sphere and an IGES box (2 x 1 x 0.5 from the origin) that cuts into it: one
    // surface of two components for strata surface, which does not test for overlap; strata
    // mesh refuses it, saying where.
    test::ScratchDir dir("cli_several");
    CliResult r = strata_cli(
        dir, "surface '" + example_data("sphere.stl") + "' '" + test_data("cad_box_with_hole.igs") + "' -o both.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("2 connected components (2 closed)"), std::string::npos) << r.out;
    const SurfaceMesh m = read_msh((dir.path() / "both.msh").string());
    EXPECT_EQ(m.patches.size(), 8u);  // the STL's solid and the box's 7 faces
    r = strata_cli(dir, "mesh '" + example_data("sphere.stl") + "' '" + test_data("cad_box_with_hole.igs") +
                            "' -o both.cgr --layers 2 --first-height 0.01");
    EXPECT_NE(r.code, 0);
    EXPECT_NE(r.err.find("the surface intersects itself"), std::string::npos) << r.err;
}

TEST(Cli, FiveStlPartsThatOverlapAreFusedIntoOneBody) {
    // Issue 10's case: a missile body and four fins passing into it, five closed STL files
    // (examples/data/missile_parts, written by Gmsh). Without --fuse: refused, saying where and
    // what to do; with it: their union, each face keeping its file's patch, and a valid mesh.
    test::ScratchDir dir("cli_five_stl");
    std::string parts;
    for (const char* p : {"body", "fin1", "fin2", "fin3", "fin4"})
        parts += " '" + example_data(std::string("missile_parts/") + p + ".stl") + "'";
    const std::string layers = " --layers 5 --first-height 1e-3 --msh-version 2.2";
    CliResult r = strata_cli(dir, "mesh" + parts + " -o apart.msh" + layers);
    EXPECT_NE(r.code, 0);
    test::expect_contains(r.err, {"the surface intersects itself", "--fuse"});
    EXPECT_TRUE(files_in(dir).empty());
    r = strata_cli(dir, "mesh" + parts + " -o fused.msh --fuse" + layers);
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(
        r.out, {"fused: 5 overlapping components replaced by their union", "1 connected components (1 closed)"});
    const VolumeMesh m = read_volume_msh((dir.path() / "fused.msh").string());
    EXPECT_GT(m.prisms.size(), 0u);
    EXPECT_GT(m.tets.size(), 0u);
    for (const char* patch : {"Created_by_Gmsh", "Created_by_Gmsh_fin1.stl", "Created_by_Gmsh_fin4.stl"})
        EXPECT_NE(find_patch(m.boundary, patch), kNone) << patch;
}

TEST(Cli, HxtFillsTheSameMeshTwice) {
    // --tets hxt: Gmsh's HXT fills the domain (its points other than TetGen's), the same bytes on a
    // second run at the same thread count, validated like any mesh (where HXT stops, TetGen fills
    // it: HybridMesh.HxtFallsBackToTetGen). An unknown mesher is refused by name.
    test::ScratchDir dir("cli_hxt");
    const std::string args = "mesh '" + example_data("sphere.stl") + "' --layers 3 --first-height 1e-3 --threads 2 ";
    CliResult a = strata_cli(dir, args + "-o a.msh --tets hxt");
    ASSERT_EQ(a.code, 0) << a.err;
    const CliResult b = strata_cli(dir, args + "-o b.msh --tets hxt");
    ASSERT_EQ(b.code, 0) << b.err;
    const CliResult t = strata_cli(dir, args + "-o t.msh");
    ASSERT_EQ(t.code, 0) << t.err;
    test::expect_contains(a.out, {"valid: "});
    EXPECT_EQ(a.out.find("HXT"), std::string::npos) << a.out;
    EXPECT_EQ(slurp(dir.path() / "a.msh"), slurp(dir.path() / "b.msh"));
    EXPECT_NE(slurp(dir.path() / "a.msh"), slurp(dir.path() / "t.msh"));
    const CliResult bad = strata_cli(dir, args + "-o bad.msh --tets netgen");
    EXPECT_NE(bad.code, 0);
    test::expect_contains(bad.err, {"netgen", "tetgen", "hxt"});
}

TEST(Cli, BinaryMshHoldsTheSameMeshAsAscii) {
    // --binary: Gmsh's binary MSH, read back to the same cells and patches and the same nodes (to
    // the 16 digits ASCII keeps; binary keeps every bit); MSH 2.2 too. Asked of a format that is
    // not .msh: refused in one line before any work, nothing written.
    test::ScratchDir dir("cli_binary");
    const std::string args = "layers '" + example_data("sphere.stl") + "' --layers 3 --first-height 1e-3 -o ";
    for (const std::string version : {"4.1", "2.2"}) {
        const std::string ascii = "ascii" + version + ".msh", binary = "binary" + version + ".msh";
        CliResult r = strata_cli(dir, args + ascii + " --msh-version " + version);
        ASSERT_EQ(r.code, 0) << r.err;
        r = strata_cli(dir, args + binary + " --binary --msh-version " + version);
        ASSERT_EQ(r.code, 0) << r.err;
        const std::string bytes = slurp(dir.path() / binary);
        EXPECT_EQ(bytes.rfind("$MeshFormat\n" + version + " 1 8\n", 0), 0u) << bytes.substr(0, 30);
        const VolumeMesh a = read_volume_msh((dir.path() / ascii).string());
        const VolumeMesh b = read_volume_msh((dir.path() / binary).string());
        ASSERT_EQ(a.points.size(), b.points.size());
        for (std::size_t i = 0; i < a.points.size(); ++i)
            ASSERT_LT((a.points[i] - b.points[i]).norm(), 1e-14) << "node " << i;
        EXPECT_EQ(a.prisms, b.prisms);
        EXPECT_EQ(a.boundary.face_nodes, b.boundary.face_nodes);
        EXPECT_EQ(a.boundary.face_patch, b.boundary.face_patch);
        EXPECT_GT(b.prisms.size(), 0u);
    }
    const CliResult r = strata_cli(dir, args + "out.cgr --binary");
    EXPECT_NE(r.code, 0);
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    test::expect_contains(r.err, {"out.cgr", "--binary", ".msh"});
    EXPECT_FALSE(fs::exists(dir.path() / "out.cgr"));
}

TEST(Cli, SurfaceFromStepFused) {
    test::ScratchDir dir("cli_fuse");
    const SurfaceMesh m = surface_via_cli(dir, example_data("wing_fuselage.step"), "wf.msh", "--fuse --quads");
    EXPECT_GT(m.num_quads(), m.num_triangles());
    EXPECT_TRUE(closed_manifold(m));
    Index components = 0;
    face_components(m, &components);
    EXPECT_EQ(components, 1);
}

/// A bad input: non-zero exit, exactly one line on stderr naming \p must_name, nothing written.
void expect_clean_failure(const std::string& args, const std::string& must_name, const std::string& tag) {
    test::ScratchDir dir("cli_bad_" + tag);
    CliResult r = strata_cli(dir, args);
    EXPECT_NE(r.code, 0) << args;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("strata: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(must_name), std::string::npos) << r.err;
    EXPECT_TRUE(files_in(dir).empty()) << args;
}

TEST(Cli, ASewnSurfaceModelOfTouchingBodiesSaysToExportSolids) {
    // Two boxes sharing a face, written as IGES faces: sewn, the surface has edges of three
    // and four faces. The error says that sewing cannot tell an assembly's bodies apart and to
    // export them as solids.
    expect_clean_failure("surface '" + test_data("cad_two_boxes_shared_face.igs") + "' -o s.msh",
                         "this CAD file is a surface model: its 12 faces bound no solid and were sewn here",
                         "sewn_assembly");
}

TEST(Cli, UnitsAreStatedAndConvertedOnRequest) {
    // The STEP declares metres: read in metres, and the summary says so; --units mm converts;
    // --scale scales any input; --units on a surface mesh is refused.
    test::ScratchDir dir("cli_units");
    CliResult r = strata_cli(dir, "surface '" + example_data("wing_fuselage.step") + "' -o m.msh --fuse");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("units: m, as the file declares"), std::string::npos) << r.out;
    r = strata_cli(dir, "surface '" + example_data("wing_fuselage.step") + "' -o mm.msh --fuse --units mm");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("units: mm, converted from the file's m (--units)"), std::string::npos) << r.out;
    r = strata_cli(dir, "surface '" + example_data("sphere.stl") + "' -o s.msh --scale 1000");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("then scaled by 1000 (--scale)"), std::string::npos) << r.out;
    const SurfaceMesh s = read_msh((dir.path() / "s.msh").string());
    double far = 0.0;
    for (const Vec3& x : s.points) far = std::max(far, x.norm());
    EXPECT_NEAR(far, 1000.0, 1e-3);  // sphere.stl: radius 1
    expect_clean_failure("surface '" + example_data("sphere.stl") + "' -o s.msh --units m", "--units", "units_stl");
    expect_clean_failure("surface '" + example_data("wing_fuselage.step") + "' -o s.msh --units parsec", "parsec",
                         "units_unknown");
    expect_clean_failure("surface '" + example_data("sphere.stl") + "' -o s.msh --scale 0", "--scale", "scale");
}

TEST(Cli, BadInputsFailCleanly) {
    const std::string out = " -o out.msh";
    expect_clean_failure("surface /nonexistent/wing.step" + out, "/nonexistent/wing.step", "missing");
    expect_clean_failure("surface '" + test_data("cli_empty.stl") + "'" + out, "cli_empty.stl", "empty");
    expect_clean_failure("surface '" + test_data("cli_nan.stl") + "'" + out, "cli_nan.stl", "nan");
    expect_clean_failure("surface '" + test_data("cli_nonmanifold_edge.stl") + "'" + out, "shared by 4 faces",
                         "nonmanifold");
    // A flap on a closed body's edge is not refused: it hangs off the body and goes, said.
    test::ScratchDir flap("cli_flap");
    const CliResult r = strata_cli(flap, "surface '" + test_data("cli_nonmanifold.stl") + "'" + out);
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"repaired: 1 sheets of 1 faces hanging off the surface on edges of three or more",
                                  "(the first at (0.5, -0.333333, 0.166667))", "1 connected components (1 closed)"});
    expect_clean_failure("surface '" + test_data("cli_degenerate.stl") + "'" + out, "cli_degenerate.stl", "degenerate");
    expect_clean_failure("surface '" + test_data("cli_mobius.stl") + "'" + out, "orient", "mobius");
    expect_clean_failure("surface '" + test_data("cad_unit_sphere.geo") + "' -o out.xyz123", "out.xyz123", "badext");
    expect_clean_failure("surface '" + example_data("SOURCES.md") + "'" + out, "SOURCES.md", "unknowntype");
    expect_clean_failure("surface '" + example_data("sphere.stl") + "'" + out + " --quads", "sphere.stl", "quadsonstl");
    expect_clean_failure("surface '" + example_data("sphere.stl") + "'" + out + " --patch nosuch=wall", "nosuch",
                         "patch");
    expect_clean_failure("surface '" + example_data("sphere.stl") + "'" + out + " --patch wall=wobbly", "wobbly",
                         "kind");
    expect_clean_failure("surface '" + example_data("sphere.stl") + "' -o nodir/out.msh", "nodir", "nodir");
    expect_clean_failure("surface '" + example_data("sphere.stl") + "'", "output", "noout");
}

TEST(Cli, CorruptStepFailsCleanly) {
    test::ScratchDir src("cli_corrupt_src");
    { std::ofstream(src.file("broken.step")) << "ISO-10303-21;\nthis is not a STEP file\n"; }
    expect_clean_failure("surface '" + src.file("broken.step") + "' -o out.msh", "broken.step", "corrupt");
}

TEST(Cli, LayersOnQuadSphere) {
    test::ScratchDir dir("cli_layers");
    CliResult r = strata_cli(dir, "layers '" + example_data("sphere_pyhyp_quads.msh") +
                                      "' -o layers.msh --layers 8 --first-height 1e-3 --growth 1.2");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("12288 hexahedra"), std::string::npos) << r.out;  // 1536 quads × 8 layers
    EXPECT_NE(r.out.find("min SJ"), std::string::npos) << r.out;
    std::vector<std::string> files = files_in(dir);
    std::sort(files.begin(), files.end());
    EXPECT_EQ(files, (std::vector<std::string>{"layers.msh", "layers.msh.report.json"}));
    // The coverage report: the table on stdout, the same in JSON next to the mesh; nothing
    // limited a sphere's columns.
    EXPECT_NE(r.out.find("coverage: 8 layers asked"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("coverage: every layer on 100.0 % of 1538 wall nodes (100.0 % of the 1538 where no proximity "
                         "limit binds), 99.5 % of the thickness asked on average (99.5 % there); short: 0 for their "
                         "own reason, 0 "
                         "only because of a neighbour\n"),
              std::string::npos)
        << r.out;
    const std::string json = slurp(dir.file("layers.msh.report.json"));
    for (const char* key :
         {"\"layers\": 8", "\"nodes\": 289, \"full_nodes\": 289", "\"short_nodes\": []",
          "\"coverage\": {\"faces\": 1536, \"nodes\": 1538, \"full_nodes\": 1538, \"all_layers\": 1538"})
        EXPECT_NE(json.find(key), std::string::npos) << key << "\n" << json;
}

// Issue 9's last case: an STL as a CAD tool exports it (OpenCASCADE's BRepMesh at 2 mm
// deflection), 220 of its 1018 triangles needles: a valid mesh, and the summary names the
// sharpest needle and says to remesh. Ten of its edges are under 1 % of the edges around them
// (--collapse-edges): collapsed, they take 20 faces and 19 needles with them; the rest are
// slivers, not short edges.
TEST(Cli, WrapMeshesAnStlNothingRepairsInPlace) {
    // examples/data/dirty_body.stl: fins touching the body along a line, a canopy half inside
    // it, a hole, a facet written twice, a flap on one edge. Refused as it is (the copy and the
    // flap removed, the hole's loop touches another at a node), naming --wrap;
    // wrapped, a valid mesh checkMesh would pass, the wrap's distances in the summary and the
    // report, the same bytes twice.
    test::ScratchDir dir("cli_wrap");
    const std::string input = "'" + example_data("dirty_body.stl") + "'";
    const std::string layers = " --layers 10 --first-height 5e-4 --growth 1.2";
    const CliResult refused = strata_cli(dir, "mesh " + input + " -o no.msh" + layers);
    EXPECT_NE(refused.code, 0);
    test::expect_contains(refused.err, {"dirty_body.stl", "two boundary loops touch", "--wrap"});
    for (const char* out : {"a.msh", "b.msh"}) {
        const CliResult r = strata_cli(dir, "mesh --wrap " + input + " -o " + out + layers);
        ASSERT_EQ(r.code, 0) << r.err;
        test::expect_contains(r.out, {"wrapped: 3135 faces -> one watertight surface of ", "alpha 0.0113525",
                                      "checkMesh would say \"Mesh OK\"", "  fins ", "  canopy "});
    }
    EXPECT_TRUE(slurp(dir.file("a.msh")) == slurp(dir.file("b.msh")));
    const std::string json = slurp(dir.file("a.msh.report.json"));
    test::expect_contains(json, {"\"wrapped\": true", "\"wrap_to_input\"", "\"input_to_wrap\"", "\"hausdorff\""});
    // A size given: the narrowest gap the wrap follows.
    const CliResult sized = strata_cli(dir, "surface --wrap 0.02 " + input + " -o s.msh");
    ASSERT_EQ(sized.code, 0) << sized.err;
    test::expect_contains(sized.out, {"alpha 0.02, offset 0.000666667"});
    const CliResult negative = strata_cli(dir, "surface --wrap -1 " + input + " -o n.msh");
    EXPECT_NE(negative.code, 0);
    test::expect_contains(negative.err, {"--wrap", "'-1' is not a size", "a number >= 0"});
    EXPECT_FALSE(std::filesystem::exists(dir.file("n.msh")));
}

TEST(Cli, NeedleStlGivesAValidMeshAndSaysRemesh) {
    test::ScratchDir dir("cli_needles");
    CliResult r = strata_cli(dir, "mesh '" + example_data("onera_m6_brepmesh_needles.stl") +
                                      "' -o m6.cgr --layers 20 --first-height 0.1 --growth 1.2");
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(
        r.out, {"short edges: 10 collapsed", "201 of 998 wall faces are needles", "aspect ratio 496", "add --remesh"});
    EXPECT_NE(r.out.find("valid: "), std::string::npos);
    EXPECT_TRUE(fs::exists(dir.file("m6.cgr")));
}

/// The summary \p out has a remesh line "needle faces N -> M" with M under \p limit.
void expect_needles_after_remesh_below(const std::string& out, int limit) {
    const std::size_t at = out.find("needle faces ");
    const std::size_t arrow = at == std::string::npos ? at : out.find("-> ", at);
    ASSERT_NE(arrow, std::string::npos) << out;
    EXPECT_LT(std::atoi(out.c_str() + arrow + 3), limit) << out;
}

TEST(Cli, RemeshRebuildsANeedleStlIntoAValidMesh) {
    // Issue 10's case: OpenCASCADE's coarse tessellation of the M6 (220 of 1018 faces needles)
    // remeshed by Gmsh, then meshed: far fewer needles (9: the input's own 0.57 mm trailing edge
    // at the root and its tip strips), every wall node gets every layer (79 % without --remesh,
    // NeedleStlGivesAValidMeshAndSaysRemesh) and checkMesh would pass it. The asked feature
    // angle works: the trailing edge is cut apart (feature_cuts.h; before, 22.5 degrees left 31
    // needles and 222 highly skewed faces).
    test::ScratchDir dir("cli_remesh_needles");
    CliResult r = strata_cli(dir, "mesh --remesh '" + example_data("onera_m6_brepmesh_needles.stl") +
                                      "' -o m6.msh --layers 20 --first-height 0.1 --growth 1.2");
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"remeshed: 1018 faces -> ", "needle faces 220 -> "});
    expect_needles_after_remesh_below(r.out, 15);
    EXPECT_NE(r.out.find("feature angle 40 degrees;"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("valid: "), std::string::npos);
    EXPECT_NE(r.out.find("checkMesh would say \"Mesh OK\""), std::string::npos) << r.out;
    // The wall patch's row of the coverage table: its share of nodes with every layer.
    const std::size_t row = r.out.find("  onera_m6_brepmesh_needles ");
    ASSERT_NE(row, std::string::npos) << r.out;
    std::istringstream fields(r.out.substr(row, r.out.find('\n', row) - row));
    std::string name, full;
    int faces = 0, nodes = 0;
    fields >> name >> faces >> nodes >> full;
    EXPECT_GT(std::atof(full.c_str()), 99.9) << r.out;
    const VolumeMesh m = read_volume_msh(dir.file("m6.msh"));
    EXPECT_GT(m.prisms.size(), 0u);
    EXPECT_GT(m.tets.size(), 0u);
}

TEST(Cli, RemeshKeepsASharpTrailingEdgeWhoseSidesMeetRoundTheLeadingEdge) {
    // The same STL at a size of 10 mm, 10 times finer than its median edge. Its trailing edge is
    // one straight edge 1243 mm long between the upper and lower sides, which meet round the
    // leading edge: Gmsh's classification alone made no curve of it, and the new faces ran
    // across the thin wedge and folded (43 faces at 40 degrees, every feature angle failed).
    // feature_cuts splits the sides along the leading edge: the first angle works, and the
    // trailing edge is a line of new nodes about 10 mm apart.
    test::ScratchDir dir("cli_remesh_trailing_edge");
    std::string out;
    const SurfaceMesh m =
        surface_via_cli(dir, example_data("onera_m6_brepmesh_needles.stl"), "m6.msh", "--remesh 10", &out);
    ASSERT_GT(m.num_faces(), 0) << out;
    EXPECT_NE(out.find("size 10, feature angle 40 degrees;"), std::string::npos) << out;
    const Vec3 root(810.491, 0.0, 0.0), tip(1146.57, 1196.3, 0.0);  // the trailing edge's ends
    const Vec3 along = (tip - root).normalized();
    int on_edge = 0;
    for (const Vec3& q : m.points) {
        const double t = (q - root).dot(along);
        if (t > -1e-3 && t < (tip - root).norm() + 1e-3 && (q - root - t * along).norm() < 1e-3) ++on_edge;
    }
    EXPECT_GE(on_edge, 110) << out;
}

TEST(Cli, TouchingBodiesOfATessellatedStlAreJoinedAndRemeshed) {
    // Issue 10's case: OpenCASCADE's coarse tessellation of wing_fuselage.step, whose glider is
    // two halves touching at y = 0, each closed there by its own disc (64 faces back to back,
    // edges bounding four faces). Without --fuse: one line saying so; with it: one closed body
    // and a valid mesh (with the needle warning); with --remesh too: a valid mesh of a
    // remeshed surface (at the median edge Gmsh fails at every feature angle, at half of it
    // not).
    const std::string stl = "'" + example_data("wing_fuselage_brepmesh.stl") + "'";
    const std::string layers = " --layers 5 --first-height 0.1 --msh-version 2.2";
    expect_clean_failure("mesh " + stl + " -o wf.msh" + layers, "64 faces lie back to back", "touching");
    test::ScratchDir dir("cli_touching");
    CliResult r = strata_cli(dir, "mesh " + stl + " -o fused.msh --fuse" + layers);
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"fused: 64 faces removed where bodies touch back to back",
                                  "1 connected components (1 closed)", "add --remesh", "valid: "});
    r = strata_cli(dir, "mesh " + stl + " -o remeshed.msh --fuse --remesh" + layers);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("remeshed: 1860 faces -> "), std::string::npos) << r.out;
    expect_needles_after_remesh_below(r.out, 20);
    const VolumeMesh m = read_volume_msh(dir.file("remeshed.msh"));
    EXPECT_GT(m.prisms.size(), 0u);
    EXPECT_GT(m.tets.size(), 0u);
}

/// The report's smallest scaled Jacobian of \p type ("tetrahedron", ...); NaN if absent.
double report_min_quality(const std::string& json, const std::string& type) {
    const auto at = json.find("\"min_scaled_jacobian\"");
    if (at == std::string::npos) return std::nan("");
    const auto key = json.find("\"" + type + "\": ", at);
    if (key == std::string::npos) return std::nan("");
    return std::strtod(json.c_str() + key + type.size() + 4, nullptr);
}

/// A run with a setting at its default (on) and one with it off, and their JSON reports.
struct OnAndOff {
    CliResult on, off;
    std::string on_report, off_report;
};

/// `strata ARGS on.msh` and `strata ARGS off.msh OFF` run in \p dir (\p args ends with "-o "),
/// both of which must succeed.
OnAndOff mesh_on_and_off(const test::ScratchDir& dir, const std::string& args, const std::string& off) {
    OnAndOff r{strata_cli(dir, args + "on.msh"), strata_cli(dir, args + "off.msh " + off), {}, {}};
    EXPECT_EQ(r.on.code, 0) << r.on.err;
    EXPECT_EQ(r.off.code, 0) << r.off.err;
    r.on_report = slurp(dir.file("on.msh.report.json"));
    r.off_report = slurp(dir.file("off.msh.report.json"));
    return r;
}

TEST(Cli, ShortEdgesOfAFusedCadModelAreCollapsed) {
    // OpenCASCADE's union of wing_fuselage.step leaves curves of 3.5e-5 m where the wing's
    // leading edge meets the fuselage, among faces of 0.04 m: Gmsh gives each a mesh edge, the
    // faces on both sides are needles and the tetrahedra beside them flat (6.4e-9 at 30
    // layers). Collapsed (default --collapse-edges 0.01), the worst tetrahedron is 3.8e-5.
    test::ScratchDir dir("cli_short_edges");
    const std::string args = "mesh '" + example_data("wing_fuselage.step") +
                             "' --fuse --layers 30 --first-height 1e-4 --growth 1.2 --tet-improve 0 -o ";
    // (Without the tetrahedra improved after TetGen, which lift the uncollapsed worst to 3.4e-5
    // on their own: this is the collapse's part.)
    const OnAndOff r = mesh_on_and_off(dir, args, "--collapse-edges 0");
    EXPECT_NE(r.on.out.find("short edges: 4 collapsed"), std::string::npos) << r.on.out;
    EXPECT_GT(report_min_quality(r.on_report, "tetrahedron"), 1e-5) << r.on.out;
    EXPECT_EQ(r.off.out.find("short edges:"), std::string::npos) << r.off.out;
    EXPECT_LT(report_min_quality(r.off_report, "tetrahedron"), 1e-7) << r.off.out;
    expect_clean_failure(args + "x.msh --collapse-edges 0.7", "--collapse-edges", "collapse_range");
}

TEST(Cli, WallsAreMeshedFinerWhereTheLayersStepAtAGap) {
    // Two spheres 0.0118 apart (examples/data/two_spheres_narrow_gap.geo) under 12 layers from
    // 1e-3: the columns facing the gap have fewer layers, and the cells closing each step have
    // a corner of about its layer height over the wall spacing (0.017 at size 0.1). With
    // --step-quality (default 0.1) the walls there are meshed again finer: the faces grow and
    // the worst pyramid and tetrahedron rise above 0.03; with 0 the walls are kept.
    test::ScratchDir dir("cli_step_sizes");
    const std::string args = "mesh '" + example_data("two_spheres_narrow_gap.geo") +
                             "' --size 0.1 --layers 12 --first-height 1e-3 --growth 1.2 -o ";
    const OnAndOff runs = mesh_on_and_off(dir, args, "--step-quality 0");
    test::expect_contains(runs.on.out, {"steps: walls meshed again finer around ", "where the layers step low"});
    EXPECT_GT(report_min_quality(runs.on_report, "pyramid"), 0.03) << runs.on.out;
    EXPECT_GT(report_min_quality(runs.on_report, "tetrahedron"), 0.03) << runs.on.out;
    EXPECT_EQ(runs.off.out.find("steps:"), std::string::npos) << runs.off.out;
    EXPECT_LT(report_min_quality(runs.off_report, "pyramid"), 0.03) << runs.off.out;
    // The sizes go to the CAD in its own unit: the model scaled by 2 (--scale, and the first
    // height with it) gets the same walls.
    const auto faces = [](const std::string& out) {
        const auto at = out.find(" faces, so that a step's layer height");
        const auto from = out.rfind("-> ", at);
        return at == std::string::npos || from == std::string::npos ? std::string() : out.substr(from, at - from);
    };
    const std::string unscaled = faces(runs.on.out);
    const CliResult r =
        strata_cli(dir, "mesh '" + example_data("two_spheres_narrow_gap.geo") +
                            "' --size 0.1 --scale 2 --layers 12 --first-height 2e-3 --growth 1.2 -o scaled.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_FALSE(unscaled.empty());
    EXPECT_EQ(faces(r.out), unscaled) << r.out;
    expect_clean_failure(args + "x.msh --step-quality 1", "--step-quality = 1", "step_range");
}

TEST(Cli, NarrowCadFacesKeepTheLayerCellsOrthogonal) {
    // The README's M6 job: the STEP closes the sharp trailing edge with two strips 3.47 mm wide,
    // one row of slivers at size 30, and the prisms on them and the fan cells beside them have
    // faces nearly parallel to the line between their centres (3,000 above checkMesh's 70°).
    // Meshed at 4 times their width (--narrow-faces, default 4) few are left, at the tip,
    // where the CAD's faces are 0.23 mm wide.
    test::ScratchDir dir("cli_narrow_faces");
    const std::string args = "layers '" + example_data("onera_m6_sharp_te.stp") +
                             "' --size 30 --layers 20 --first-height 0.02 --growth 1.2 -o ";
    const OnAndOff r = mesh_on_and_off(dir, args, "--narrow-faces 0");
    const auto severe = [](const std::string& out) {
        const auto at = out.find(" faces above 70");
        const auto from = out.rfind(", ", at);
        return at == std::string::npos || from == std::string::npos ? -1 : std::stoi(out.substr(from + 2, at - from - 2));
    };
    test::expect_contains(r.on.out, {"size: 2 CAD faces narrower than the size over 4 (the narrowest 3.47 wide"});
    EXPECT_EQ(r.off.out.find("narrower than the size"), std::string::npos) << r.off.out;
    EXPECT_GT(severe(r.off.out), 2000) << r.off.out;
    EXPECT_GE(severe(r.on.out), 0) << r.on.out;
    EXPECT_LT(severe(r.on.out), severe(r.off.out) / 8) << r.on.out;
    expect_clean_failure(args + "x.msh --narrow-faces 0.5", "--narrow-faces = 0.5", "narrow_ratio");
    expect_clean_failure("mesh '" + example_data("sphere.stl") + "' --narrow-faces 2 --layers 5 --first-height 1e-3 -o x.msh",
                         "is a surface mesh: --narrow-faces sizes the narrow faces of a CAD model", "narrow_stl");
}

TEST(Cli, AWingNearlyTangentToAFuselageMeshesAfterItsFrontRounds) {
    // tests/data/cli_wingbody_tangent.stl: a thin wing nearly tangent to a fuselage, fused by
    // OpenCASCADE and tessellated by it (cli_wingbody_tangent.geo says how), 1171 of its 3416
    // faces needles. Its fronts made TetGen (Debian's libtet 1.5.0) stop on an internal check
    // (tetgen.cxx:7854, scount == 1) recovering a layer-top face near the wing root at one
    // setting or another until colliding columns lost their top layer first instead of half
    // their length (2026-12-05): since then none of 80 settings tried (10 to 30 layers, first
    // heights 8e-4 to 2.5e-3, growth 1.1 to 1.3, front slopes 0.25 to 4) does, and the lowering
    // round that follows such a stop is tested through TetGen's own trace on the piece of front
    // that stopped it (TetgenLibrary.InternalCheckIsLocatedAtTheFaceBeingRecovered). Here: the
    // case meshes once the front rounds have closed its collisions.
    test::ScratchDir dir("cli_tetgen_retry");
    const CliResult r = strata_cli(dir, "mesh '" + test_data("cli_wingbody_tangent.stl") +
                                            "' --layers 20 --first-height 1.5e-3 --front-slope 0.5 -o m.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"short edges: 6 collapsed", "front: ", "valid: "});
    const VolumeMesh m = read_volume_msh(dir.file("m.msh"));
    EXPECT_GT(m.prisms.size(), 10000u);
}

TEST(Cli, RemeshAfterFuseClearsTheCutsNeedles) {
    // The union of the missile's five parts cuts their triangles along the fin roots into 222
    // needles; remeshed, a handful are left and every part keeps its patch.
    test::ScratchDir dir("cli_remesh_fuse");
    std::string parts;
    for (const char* p : {"body", "fin1", "fin2", "fin3", "fin4"})
        parts += " '" + example_data(std::string("missile_parts/") + p + ".stl") + "'";
    CliResult r = strata_cli(dir, "mesh" + parts + " -o m.msh --fuse --remesh --layers 5 --first-height 1e-3");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("needle faces 222 -> "), std::string::npos) << r.out;
    expect_needles_after_remesh_below(r.out, 10);
    const VolumeMesh m = read_volume_msh(dir.file("m.msh"));
    for (const char* patch : {"Created_by_Gmsh", "Created_by_Gmsh_fin1.stl", "Created_by_Gmsh_fin4.stl"})
        EXPECT_NE(find_patch(m.boundary, patch), kNone) << patch;
}

TEST(Cli, RemeshTakesAnOptionalSize) {
    test::ScratchDir dir("cli_remesh_size");
    const std::string sphere = "'" + example_data("sphere.stl") + "'";
    std::string out;
    // A size after --remesh; a bare --remesh before the input leaves the input an input.
    SurfaceMesh fine = surface_via_cli(dir, example_data("sphere.stl"), "fine.msh", "--remesh 0.05", &out);
    EXPECT_NE(out.find("size 0.05,"), std::string::npos) << out;
    EXPECT_TRUE(closed_manifold(fine));
    CliResult r = strata_cli(dir, "surface --remesh " + sphere + " -o auto.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    const SurfaceMesh same = read_msh(dir.file("auto.msh"));
    r = strata_cli(dir, "surface " + sphere + " -o eq.msh --remesh=0.05 --quads");
    ASSERT_EQ(r.code, 0) << r.err;
    const SurfaceMesh quads = read_msh(dir.file("eq.msh"));
    EXPECT_GT(quads.num_quads(), 0);
    EXPECT_GT(fine.num_faces(), same.num_faces());  // sphere.stl's median edge is longer than 0.05
    EXPECT_NEAR(enclosed_volume(fine), enclosed_volume(same), 0.02 * enclosed_volume(same));
}

TEST(Cli, RemeshBadOptionsFailCleanly) {
    const std::string sphere = "surface '" + example_data("sphere.stl") + "' -o out.msh";
    expect_clean_failure(sphere + " --feature-angle 30", "--feature-angle", "angle_alone");
    expect_clean_failure(sphere + " --remesh --feature-angle 200", "feature angle", "angle_range");
    expect_clean_failure(sphere + " --remesh -1", "--remesh", "negative");
    expect_clean_failure(sphere + " --remesh 0.1 --size 0.2", "two sizes", "two_sizes");
    expect_clean_failure(sphere + " --remesh --mixed 1", "--mixed", "mixed");
}

TEST(Cli, LayersBadInputsFailCleanly) {
    const std::string in = "layers '" + example_data("sphere_pyhyp_quads.msh") + "' -o out.msh";
    expect_clean_failure(in + " --layers 0 --first-height 1e-3", "--layers", "nolayers");
    expect_clean_failure(in + " --layers 5 --first-height=-1e-3", "first layer height", "noheight");
    expect_clean_failure(in + " --layers 5 --first-height 1e-3 --yplus 1 --reynolds 1e6", "--yplus", "twoheights");
    expect_clean_failure(in + " --layers 5 --first-height 1e-3 --growth 1.2 --thickness 0.1", "--thickness",
                         "overdetermined");
    expect_clean_failure(in + " --layers 5 --first-height 1e-2 --thickness 0.01", "thickness", "thin");
    expect_clean_failure(in + " --layers 5 --first-height 1e-3 --normals sideways", "sideways", "normals");
    expect_clean_failure(in + " --layers 5 --first-height 1e-3 --min-quality 1.5", "--min-quality", "quality");
    expect_clean_failure(in + " --layers 5 --first-height 1e-3 --max-turn 0", "--max-turn", "turn");
    expect_clean_failure(in + " --layers 5 --first-height 1e-3 --fan-angle 200", "--fan-angle", "fan");
    expect_clean_failure(in + " --layers 5 --first-height 1e-3 --sharp-edge-stop 200", "--sharp-edge-stop", "sharp");
    expect_clean_failure(in + " --layers 5 --first-height 1e-3 --max-twist 0", "--max-twist", "twist");
    // Plain extrusion into the notched box's concave corner folds: with local stopping off,
    // reported, nothing written.
    expect_clean_failure("layers '" + example_data("bl3d_4_box_notch_concave_corner.brep") +
                             "' -o out.msh --layers 20 --first-height 5e-4 --growth 1.15 --sweeps 0 --max-sweeps 0 "
                             "--min-quality 0 "
                             "--patch surface_1=farfield --patch surface_2=farfield --patch surface_3=farfield "
                             "--patch surface_4=farfield --patch surface_6=farfield",
                         "would invert", "folds");
    // With the concave-region smoothing off, the message says how to turn it back on.
    expect_clean_failure("layers '" + example_data("bl3d_4_box_notch_concave_corner.brep") +
                             "' -o out.msh --layers 20 --first-height 5e-4 --growth 1.15 --sweeps 0 --max-sweeps 0 "
                             "--min-quality 0 --no-concave "
                             "--patch surface_1=farfield --patch surface_2=farfield --patch surface_3=farfield "
                             "--patch surface_4=farfield --patch surface_6=farfield",
                         "would invert", "(drop --no-concave)");
}

TEST(Cli, MeshSphereToCobaltAndMsh) {
    test::ScratchDir dir("cli_mesh");
    const std::string common = " --layers 6 --first-height 2e-3 --growth 1.2 --farfield box --farfield-size 8";
    CliResult r = strata_cli(dir, "mesh '" + example_data("sphere_pyhyp_quads.msh") + "' -o s.cgr" + common);
    ASSERT_EQ(r.code, 0) << r.err;
    for (const char* word : {"hexahedra", "pyramids", "tetrahedra", "min scaled Jacobian", "time:"})
        EXPECT_NE(r.out.find(word), std::string::npos) << word << "\n" << r.out;
    CliResult m = strata_cli(dir, "mesh '" + example_data("sphere.stl") + "' -o s.msh" + common);
    ASSERT_EQ(m.code, 0) << m.err;
    const std::vector<std::string> expected{"s.cgr", "s.cgr.bc", "s.cgr.report.json", "s.msh", "s.msh.report.json"};
    std::vector<std::string> got = files_in(dir);
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, expected);
}

TEST(Cli, MeshToOpenFoamPolyMeshAndCgns) {
    // The polyMesh directory is written straight into a case, byte-identical for 1 and 2 threads;
    // CGNS by extension; the report beside the directory, not in it.
    test::ScratchDir dir("cli_polymesh");
    const std::string common = " --layers 3 --first-height 2e-3 --farfield-size 6";
    std::vector<std::string> files{"boundary", "faces", "neighbour", "owner", "points"};
    for (const char* threads : {"1", "2"}) {
        const std::string c = std::string("case") + threads;
        fs::create_directories(dir.file(c + "/constant"));
        CliResult r = strata_cli(dir, "mesh '" + example_data("sphere.stl") + "' -o " + c + "/constant/polyMesh" +
                                          common + " --threads " + threads);
        ASSERT_EQ(r.code, 0) << r.err;
        EXPECT_NE(r.out.find("wrote " + c + "/constant/polyMesh and " + c + "/constant/polyMesh.report.json"),
                  std::string::npos)
            << r.out;
        std::vector<std::string> got;
        for (const auto& e : fs::directory_iterator(dir.file(c + "/constant/polyMesh")))
            got.push_back(e.path().filename().string());
        std::sort(got.begin(), got.end());
        EXPECT_EQ(got, files);
    }
    for (const std::string& f : files)
        EXPECT_TRUE(slurp(dir.file("case1/constant/polyMesh/" + f)) == slurp(dir.file("case2/constant/polyMesh/" + f)))
            << f << " differs between 1 and 2 threads";
    const std::string boundary = slurp(dir.file("case1/constant/polyMesh/boundary"));
    EXPECT_NE(boundary.find("type            wall;"), std::string::npos) << boundary;
    EXPECT_NE(boundary.find("type            patch;"), std::string::npos) << boundary;  // the farfield
    CliResult c = strata_cli(dir, "mesh '" + example_data("sphere.stl") + "' -o s.cgns" + common);
    ASSERT_EQ(c.code, 0) << c.err;
    EXPECT_GT(fs::file_size(dir.file("s.cgns")), 100000u);
    EXPECT_TRUE(fs::exists(dir.file("s.cgns.report.json")));
}

TEST(Cli, MeshToVtuAndVtmForParaView) {
    // .vtu and .vtm by extension, with their reports; the .vtm's blocks in s_blocks/ beside it, one
    // per patch and named after it; byte-identical for 1 and 2 threads. (Read back with VTK in
    // tests/io/test_vtk_xml.cpp.)
    test::ScratchDir dir("cli_vtk_xml");
    const std::string common = " --layers 3 --first-height 2e-3 --farfield-size 6";
    for (const char* threads : {"1", "2"}) {
        const std::string sub = std::string("t") + threads;
        fs::create_directories(dir.file(sub));
        for (const char* ext : {".vtu", ".vtm"}) {
            const CliResult r = strata_cli(
                dir, "mesh '" + example_data("sphere.stl") + "' -o " + sub + "/s" + ext + common + " --threads " + threads);
            ASSERT_EQ(r.code, 0) << r.err;
        }
    }
    std::vector<std::string> blocks;
    for (const auto& e : fs::directory_iterator(dir.file("t1/s_blocks"))) blocks.push_back(e.path().filename().string());
    std::sort(blocks.begin(), blocks.end());
    EXPECT_EQ(test::dir_entries(dir.file("t1")),
              (std::vector<std::string>{"s.vtm", "s.vtm.report.json", "s.vtu", "s.vtu.report.json", "s_blocks"}));
    const std::string vtm = slurp(dir.file("t1/s.vtm"));
    EXPECT_NE(vtm.find("name=\"volume\" file=\"s_blocks/volume.vtu\""), std::string::npos) << vtm;
    EXPECT_NE(vtm.find("<Block index=\"1\" name=\"boundary\">"), std::string::npos) << vtm;
    ASSERT_GE(blocks.size(), 3u);  // the volume, the sphere and the farfield
    for (const std::string& b : blocks) {
        EXPECT_NE(vtm.find("s_blocks/" + b), std::string::npos) << b;
        EXPECT_TRUE(slurp(dir.file("t1/s_blocks/" + b)) == slurp(dir.file("t2/s_blocks/" + b))) << b << " differs";
    }
    for (const char* f : {"s.vtu", "s.vtm"})
        EXPECT_TRUE(slurp(dir.file(std::string("t1/") + f)) == slurp(dir.file(std::string("t2/") + f))) << f;
    EXPECT_NE(slurp(dir.file("t1/s.vtu")).find("<VTKFile type=\"UnstructuredGrid\""), std::string::npos);
}

TEST(Cli, FoamCaseWritesACaseThatRunsAndKeepsTheUsersFiles) {
    // -o CASE --foam-case: the polyMesh, its report and the case made from nothing; the summary's
    // case: and run: lines; a rerun keeps an edited file, makes 0/ anew and says so; the same
    // bytes run after run. (OpenFOAM runs such a case: OpenFOAM.SimpleFoamHemisphereCylinderFoamCase.)
    test::ScratchDir dir("cli_foam_case");
    const std::string mesh =
        "mesh '" + example_data("sphere.stl") + "' --layers 3 --first-height 2e-3 --farfield-size 6";
    CliResult r = strata_cli(dir, mesh + " -o run/case --foam-case");
    EXPECT_NE(r.code, 0);
    EXPECT_NE(r.err.find("cannot write the OpenFOAM case 'run/case': directory 'run' does not exist"),
              std::string::npos)
        << r.err;
    EXPECT_TRUE(files_in(dir).empty());
    r = strata_cli(dir, mesh + " -o case --foam-case --reynolds 2e5");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("case: case, simpleFoam with k-omega SST: U (1 0 0), Re 200000 on L 1, nu 5e-06, first cells "
                         "at y+ about "),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("wrote system/controlDict system/fvSchemes system/fvSolution constant/transportProperties "
                         "constant/turbulenceProperties 0.orig/U 0.orig/p 0.orig/k 0.orig/omega 0.orig/nut 0/ (a copy "
                         "of 0.orig/)\nrun: potentialFoam -case case && simpleFoam -case case\n"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("wrote case/constant/polyMesh and case/constant/polyMesh.report.json"), std::string::npos)
        << r.out;
    const std::vector<std::string> texts = {"system/controlDict", "system/fvSolution", "0.orig/U", "0/nut",
                                            "constant/polyMesh/boundary", "constant/polyMesh/points"};
    std::vector<std::string> first;
    for (const std::string& f : texts) first.push_back(slurp(dir.file("case/" + f)));
    EXPECT_NE(first[2].find("type            freestreamVelocity;"), std::string::npos) << first[2];
    // The user edits the numerics; potentialFoam wrote 0/U; the mesh is written again, through
    // the polyMesh's own path this time (the same case).
    std::ofstream(dir.file("case/system/fvSchemes")) << "mine";
    std::ofstream(dir.file("case/0/U")) << "potentialFoam's";
    r = strata_cli(dir, mesh + " -o case/constant/polyMesh --foam-case --reynolds 2e5");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("; kept the case's own system/fvSchemes (delete one to have Strata's)"), std::string::npos)
        << r.out;
    EXPECT_EQ(slurp(dir.file("case/system/fvSchemes")), "mine");
    for (std::size_t i = 0; i < texts.size(); ++i)
        EXPECT_TRUE(slurp(dir.file("case/" + texts[i])) == first[i]) << texts[i] << " differs on the rerun";
    // A directory named without the flag: refused before any work, saying what to add.
    expect_clean_failure(mesh + " -o .", "it is a directory; for an OpenFOAM case there add --foam-case", "dir");
}

TEST(Cli, BadOutputPathsFailCleanly) {
    const std::string in = "mesh '" + example_data("sphere.stl") + "' --layers 3 --first-height 2e-3 -o ";
    expect_clean_failure(in + "nocase/constant/polyMesh", "directory 'nocase/constant' does not exist", "polymesh_dir");
    expect_clean_failure(in + "missing/mesh.cgns", "directory 'missing' does not exist", "cgns_dir");
    expect_clean_failure(in + "mesh.foam", "polyMesh (OpenFOAM", "unknown_ext");
    // An existing file where the polyMesh directory would go is refused, and left alone.
    test::ScratchDir dir("cli_bad_polymesh_file");
    std::ofstream(dir.file("polyMesh")) << "mine";
    CliResult r = strata_cli(dir, in + "polyMesh");
    EXPECT_NE(r.code, 0);
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("is a file, not a directory"), std::string::npos) << r.err;
    EXPECT_EQ(files_in(dir), std::vector<std::string>{"polyMesh"});
    EXPECT_EQ(slurp(dir.file("polyMesh")), "mine");
}

TEST(Cli, MeshBoxDomainRemeshesTheSidesTheLayersEndOn) {
    test::ScratchDir dir("cli_mesh_planes");
    CliResult r =
        strata_cli(dir, "mesh '" + example_data("bl3d_5_body_fin_in_box.brep") +
                            "' -o box.su2 --layers 10 --first-height 5e-4 --growth 1.15 --patch surface_1=farfield "
                            "--patch surface_2=farfield --patch surface_4=farfield --patch surface_6=farfield");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("planes re-meshed around the layers' sides: surface_1, surface_2, surface_4, surface_6"),
              std::string::npos)
        << r.out;
    std::vector<std::string> files = files_in(dir);
    std::sort(files.begin(), files.end());
    EXPECT_EQ(files, (std::vector<std::string>{"box.su2", "box.su2.report.json"}));
}

TEST(Cli, MeshInsideTheWallsWithInternal) {
    // A spherical tank: with --internal the sphere's inside is the fluid, the layers grow
    // inward and the tetrahedra fill the rest, no farfield; an open surface cannot hold a fluid.
    test::ScratchDir dir("cli_mesh_internal");
    CliResult r = strata_cli(dir, "mesh '" + example_data("sphere.stl") +
                                      "' -o tank.msh --msh-version 2.2 --layers 5 --first-height 2e-3 --internal");
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"domain: inside the walls (internal flow), no farfield generated",
                                  "flow: inside the walls (--internal)"});
    const VolumeMesh m = read_volume_msh((dir.path() / "tank.msh").string());
    EXPECT_GT(m.prisms.size(), 0u);
    EXPECT_GT(m.tets.size(), 0u);
    EXPECT_EQ(find_patch(m.boundary, "farfield"), kNone);
    double outermost = 0.0;
    for (const Vec3& p : m.points) outermost = std::max(outermost, p.norm());
    EXPECT_LE(outermost, 1.0 + 1e-6);  // nothing outside the tank (sphere.stl: radius 1)
    expect_clean_failure(
        "mesh '" + test_data("cli_open_bent.stl") + "' -o out.cgr --layers 2 --first-height 1e-3 --internal",
        "--internal", "internal_open");
}

/// The share (per cent) in column \p column (0: faces, 1: nodes, 2: full, 3: all L) of the
/// coverage table's row for \p patch; -1 if the row is missing.
double coverage_share(const std::string& out, const std::string& patch, int column) {
    const std::size_t row = out.find("\n  " + patch + " ");
    if (row == std::string::npos) return -1.0;
    std::istringstream fields(out.substr(row + 1, out.find('\n', row + 1) - row - 1));
    std::string name, value;
    fields >> name;
    for (int i = 0; i <= column; ++i) fields >> value;
    return std::atof(value.c_str());
}

/// The mean thickness reached, per cent of the thickness asked, from the summary's coverage line.
double wall_thickness(const std::string& out) {
    const std::size_t at = out.find(" % of the thickness asked on average");
    if (at == std::string::npos) return -1.0;
    const std::size_t from = out.rfind(' ', at - 1);
    return std::atof(out.substr(from + 1, at - from - 1).c_str());
}

TEST(Cli, FrontRoundsLowerTheLayersLocallyFirst) {
    // Where the layer top meets itself, the columns under it are lowered and the layers marched
    // again; each lowering spreads along the wall at 1 per unit of distance, halved where the
    // same columns must be lowered again (ProximityParams::front_slope), and the columns it
    // lowers keep every layer, capped (docs/ALGORITHM.md, "Capped columns"). The winglet of the
    // sweep, 30 layers from 2.4e-3 of its length (far thicker than its front is wide; from 6e-4
    // or 1.2e-3 its front no longer meets itself since columns that stop are capped there):
    // the layers reach 22 % of the thickness asked on average, 11 % when every lowering spread
    // at 0.25 per unit.
    test::ScratchDir dir("cli_front_slope");
    CliResult r = mesh_sweep(dir, "winglet.geo", "--fuse --layers 30 --growth 1.2 --first-height 2.4e-3 -o w.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("front: "), std::string::npos) << r.out;
    const double local = wall_thickness(r.out);
    r = mesh_sweep(dir, "winglet.geo",
                   "--fuse --layers 30 --growth 1.2 --first-height 2.4e-3 --front-slope 0.25 -o w25.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_GT(local, 1.5 * wall_thickness(r.out)) << r.out;
    // The plate with holes, tessellated and remeshed: its front still meets itself after local
    // lowerings, and the rounds that follow spread wider (0.5, then 0.25 per unit) until it
    // does not (at 1 per unit throughout it still did after 8 rounds).
    r = mesh_sweep(dir, "holes_brepmesh.stl", "--fuse --remesh --layers 30 --growth 1.2 --first-height 2e-4 -o p.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("valid: "), std::string::npos) << r.out;
    expect_clean_failure(
        "mesh '" + example_data("sphere.stl") + "' --layers 2 --first-height 1e-3 --front-slope 0 -o x.msh",
        "--front-slope = 0", "front_slope_range");
}

TEST(Cli, AWallQuadNoPyramidCanCapIsSplitIntoTwoTriangles) {
    // A wall quad bent so that it takes no pyramid on the layer top at any apex height, where
    // lowering its columns does not change that (the run stopped with "cannot be capped with a
    // pyramid" after 8 rounds), is split into two triangles, whose columns need no pyramid, and
    // the mesh is made. The sweep's rocket in quads, 15 layers from 2e-3, has one such quad. (It
    // was the pipe junction's, bent round the branch pipe's small radius, until the concave
    // terms kept to the spacing asked and its columns there rose less; then the rocket's from
    // 1e-3 until steps were judged against their own geometry.)
    test::ScratchDir dir("cli_split_quad");
    const CliResult r =
        mesh_sweep(dir, "rocket.geo", "--fuse --quads --layers 15 --growth 1.2 --first-height 2e-3 -o p.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    // (Its first "quads: " line says that Blossom's quads folded; the split's line is its own.)
    const auto at = r.out.find(" wall quads could take no pyramid on the layer top");
    ASSERT_NE(at, std::string::npos) << r.out;
    const auto line = r.out.rfind("quads: ", at);
    ASSERT_NE(line, std::string::npos) << r.out;
    EXPECT_GE(std::atoi(r.out.c_str() + line + 7), 1) << r.out;
    test::expect_contains(r.out, {"valid: ", "checkMesh would say \"Mesh OK\""});
    EXPECT_TRUE(fs::exists(dir.path() / "p.msh"));
}

/// The sweep's \p shape meshed with \p options in quads: no face whose pyramid to a cell's centre
/// is inverted, and checkMesh's "Mesh OK".
void expect_quads_pass_checkmesh(const std::string& scratch, const std::string& shape, const std::string& options) {
    test::ScratchDir dir(scratch);
    const CliResult r = mesh_sweep(dir, shape, "--quads " + options + " -o q.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out.find("pyramid to a cell centre is inverted"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("checkMesh would say \"Mesh OK\""), std::string::npos) << r.out;
}

TEST(Cli, AStepOverAQuadBentRoundALeadingEdgeIsSplitNotInverted) {
    // The slotted two-element wing of the sweep in quads, 15 layers from 7.5e-4: where two
    // adjacent columns of a quad bent round the main element's leading edge stop at the wall,
    // the prism lying on its side that closed the step had every corner positive but its
    // centre outside the wall quad's side, and checkMesh failed the mesh on 5 "incorrectly
    // oriented" faces. Such a quad is split through a stopped corner (a pyramid and a
    // tetrahedron over planar triangles) and the mesh passes.
    expect_quads_pass_checkmesh("cli_bent_quad_step", "slot.geo", "--layers 15 --growth 1.2 --first-height 7.5e-4");
}

TEST(Cli, HexahedraOverWarpedQuadsAreSplitIntoPrisms) {
    // The sweep's rocket in quads (20 layers from 2.5e-4): at the default size Gmsh's quads span
    // 72 degrees of its 0.1 radius, and hexahedra over them had every corner fair but 35 faces
    // whose pyramid to the cell's centre was inverted, which checkMesh fails. Such a quad is now
    // split into two prisms' triangles where they are sound.
    expect_quads_pass_checkmesh("cli_warped_quads", "rocket.geo",
                                "--fuse --layers 20 --growth 1.2 --first-height 2.5e-4");
}

TEST(Cli, ADeltaWingKeepsItsLeadingEdgeFansAndTheirWedgesPassCheckMesh) {
    // The sweep's delta wing, 30 layers from 1e-4: its sharp leading edges' fan chain turns 118
    // degrees at the apex, where shared columns twisted the wedges until checkMesh found them
    // skewed; that fan went and with it every leading-edge fan (their columns stopped at the
    // wall). The apex is now closed like a corner. The chain closes through the blunt base's 90
    // degree edges, whose wedges (edges of 0.074 under 1e-4) reached aspect ratio 2089: the
    // walls there are meshed again finer for them from the fans the layers build. Here under
    // the settings sweep's `fine` (25 layers from 5e-5 at 1.15): sized at the edges' ends only,
    // Gmsh's edges between came out up to twice as long and 80 wedges stayed at 1147.
    test::ScratchDir dir("cli_delta");
    const CliResult r = mesh_sweep(dir, "delta.geo", "--layers 25 --growth 1.15 --first-height 5e-5 -o d.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out.find("no fan at"), std::string::npos) << r.out;
    test::expect_contains(r.out, {"at the ends of fan edges and along them", "checkMesh would say \"Mesh OK\""});
    const std::string rep = slurp(dir.file("d.msh.report.json"));
    EXPECT_NE(rep.find("\"short_nodes\": []"), std::string::npos) << "every column has every layer";
    EXPECT_GT(report_min_quality(rep, "pyramid"), 0.1) << r.out;
    EXPECT_GT(report_min_quality(rep, "tetrahedron"), 0.02) << r.out;
}

TEST(Cli, CellsAboveCheckMeshsAspectRatioMeshTheWallsAgainFinerRoundThem) {
    // The sweep's propeller under the settings sweep's `fine` (25 layers from 5e-5 of its length
    // at 1.15) at its default size: its blades' trailing edges end on the spinner (fan
    // terminals, stopped at the wall), whose faces there are 0.12 long, and the pyramids
    // closing those steps reached aspect ratio 1210 under 1e-4, which checkMesh fails. The
    // walls are meshed again finer round such cells and the mesh made again.
    test::ScratchDir dir("cli_aspect_remesh");
    const CliResult r = mesh_sweep(dir, "propeller.geo", "--fuse --layers 25 --growth 1.15 --first-height 1e-4 -o p.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"aspect: the first mesh had ", "so the walls were meshed again finer round them",
                                  "0 such cells, kept", "checkMesh would say \"Mesh OK\""});
    const std::string rep = slurp(dir.file("p.msh.report.json"));
    EXPECT_NE(rep.find("\"cells_after\": 0"), std::string::npos) << rep.substr(0, 2000);
    // With the limit off (--max-aspect-ratio 0) nothing is meshed again, and the summary says
    // what checkMesh will find.
    const CliResult off =
        mesh_sweep(dir, "propeller.geo", "--fuse --layers 25 --growth 1.15 --first-height 1e-4 --max-aspect-ratio 0 -o q.msh");
    ASSERT_EQ(off.code, 0) << off.err;
    EXPECT_EQ(off.out.find("aspect: the first mesh"), std::string::npos) << off.out;
    test::expect_contains(off.out, {"cells with an aspect ratio above 1000"});
}

TEST(Cli, CellsStackedAcrossAnAcuteJunctionAreNotKeptSideBySide) {
    // The sweep's acute junctions, 30 layers from 2e-4 (1e-4 of their 2 m). A rod through a
    // plate at 15 degrees: the first prisms of plate and rod lay stacked across the junction,
    // the face between them skewed 4.15, which checkMesh fails; the columns of such an edge now
    // stop there. A sphere through a plate, meeting its underside at 37 degrees: 43 faces
    // between prisms up to 6.74; with that rule alone, 9 faces at 5.64 between the two pyramids
    // closing a step where one junction column had stopped and its neighbour went on, which
    // now stops too.
    for (const std::string shape : {"rodplate", "spherecap"}) {
        test::ScratchDir dir("cli_" + shape);
        const CliResult r =
            mesh_sweep(dir, shape + ".geo", "--fuse --layers 30 --growth 1.2 --first-height 2e-4 -o j.msh");
        ASSERT_EQ(r.code, 0) << shape << r.err;
        EXPECT_NE(r.out.find("(0 faces above 4)"), std::string::npos) << shape << r.out;
        EXPECT_NE(r.out.find("checkMesh would say \"Mesh OK\""), std::string::npos) << shape << r.out;
    }
}

TEST(Cli, ASharpTrailingEdgeOnASymmetryPlaneKeepsItsFan) {
    // The sweep's half wing: its sharp trailing edge (and its coarse leading edge, in the same
    // chain through the flat tip) runs from the symmetry plane to the tip. The chains end on
    // the plane, where each node's fan lies in the plane and the plane is re-meshed round the
    // fan's columns. Before, a chain had to close into a loop: the edge had no fan, 69 nodes
    // stopped at the wall and a pyramid at the root was 0.0013.
    test::ScratchDir dir("cli_half_wing");
    const CliResult r = mesh_sweep(dir, "halfwing.geo", "--layers 5 --first-height 1e-3 -o w.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out.find("note: no fan"), std::string::npos) << r.out;
    test::expect_contains(
        r.out, {"fans: 177 sharp convex edges, 177 wall nodes with a column per side and between (2 corners, 2 "
                "ending on a symmetry or other plane)",
                "100.0% 100.0%    5.0      5"});
    const std::string rep = slurp(dir.file("w.msh.report.json"));
    EXPECT_NE(rep.find("\"no_fan_nodes\": []"), std::string::npos) << rep.substr(0, 2000);
    const std::string valid = "valid: min scaled Jacobian ";
    const auto at = r.out.find(valid);
    ASSERT_NE(at, std::string::npos) << r.out;
    EXPECT_GE(std::stod(r.out.substr(at + valid.size())), 0.1) << r.out;
    EXPECT_NE(r.out.find("checkMesh would say \"Mesh OK\""), std::string::npos) << r.out;
}

TEST(Cli, AHalfModelStlFacingIntoTheBodyIsTurnedOutward) {
    // The sweep's half body STL with every triangle reversed, as a CAD tool writes the fluid's
    // boundary (normals into the body). Open along its symmetry plane, it kept the file's
    // orientation, grew its layers inside the body and stopped in TetGen ("points into the
    // region to fill"). Its cut closed by the plane, it is a body: turned outward, meshed.
    test::ScratchDir dir("cli_flipped_half_body");
    std::string stl = slurp(example_data("../sweep/halfbody.stl"));
    ASSERT_GT(stl.size(), 84u);
    std::uint32_t n = 0;
    std::memcpy(&n, stl.data() + 80, 4);
    ASSERT_EQ(stl.size(), 84u + 50u * n);
    for (std::uint32_t t = 0; t < n; ++t)  // swap each triangle's second and third vertices
        std::swap_ranges(stl.begin() + 84 + 50 * t + 24, stl.begin() + 84 + 50 * t + 36,
                         stl.begin() + 84 + 50 * t + 36);
    std::ofstream(dir.file("inward.stl"), std::ios::binary) << stl;
    const CliResult r = strata_cli(dir, "mesh inward.stl --layers 5 --first-height 1e-3 -o w.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find(std::to_string(n) + " faces re-oriented"), std::string::npos) << r.out;
    test::expect_contains(r.out, {"domain: a half model", "checkMesh would say \"Mesh OK\""});
}

TEST(Cli, AFanWhoseCellsCheckMeshFindsSkewedIsDropped) {
    // The wing-fuselage at its default size (426 wall faces), 10 layers from 1e-3 of its length:
    // the wing's leading edge (151 degrees on so coarse a wall) seeds a fan chain that closes
    // through the fuselage's coarse facets and its nose pole, where the chain doubles back and
    // two wedges share a face checkMesh found skewed 4.17 (6 faces). The fans there are dropped
    // and the layers marched again: the summary says where, and the mesh passes. (With its
    // narrow faces meshed at their width, the default, the chain no longer doubles back there.)
    test::ScratchDir dir("cli_skewed_fan");
    const CliResult r =
        strata_cli(dir, "mesh '" + example_data("wing_fuselage.step") +
                            "' --fuse --narrow-faces 0 --layers 10 --growth 1.3 --first-height 4.47e-4 -o w.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"where a fan's cells had faces OpenFOAM's checkMesh would fail as skewed",
                                  "checkMesh would say \"Mesh OK\""});
    std::ifstream json(dir.path() / "w.msh.report.json");
    const std::string text((std::istreambuf_iterator<char>(json)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("\"reason\": \"skewed\""), std::string::npos);
}

TEST(Cli, AFarfieldOfSeveralPlanesTheLayersEndOnIsMeshedPlaneByPlane) {
    // A wind tunnel whose inlet, outlet, sides and top are one physical group "farfield" (the
    // road and a bump on it walls): the road's layers end on four of its planes, and the run
    // stopped with "patch 'farfield' meets the walls, so the layers end on it, but it is not
    // planar". Each plane is now re-meshed round the layers as one, and the mesh keeps the
    // group as one patch.
    test::ScratchDir dir("cli_tunnel_one_farfield");
    const CliResult r = strata_cli(dir, "mesh '" + test_data("cli_tunnel_one_farfield.geo") +
                                            "' --layers 10 --growth 1.2 --first-height 1e-3 -o t.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"planes: patch 'farfield' is 5 planes", "checkMesh would say \"Mesh OK\""});
    std::ifstream msh(dir.path() / "t.msh");
    const std::string text((std::istreambuf_iterator<char>(msh)), std::istreambuf_iterator<char>());
    const auto names = text.find("$PhysicalNames");
    ASSERT_NE(names, std::string::npos);
    EXPECT_EQ(text.substr(names, text.find("$EndPhysicalNames") - names),
              "$PhysicalNames\n4\n2 1 \"road\"\n2 2 \"bump\"\n2 3 \"farfield\"\n3 1 \"fluid\"\n");
}

TEST(Cli, QuadsWhereBlossomWouldAbortTheProcess) {
    // The sweep's sphere with three cones in quads: Gmsh's Blossom recombination threw out of
    // Gmsh's OpenMP loop on a cone, and the run stopped with "Gmsh aborted the process
    // (Perfect Match failed in quadrangulation ...)". Tried first in a child, the surfaces are
    // recombined with Gmsh's simple algorithm instead, the summary says so, and the mesh passes.
    expect_sweep_passes("cli_blossom_aborts", "spiky.geo",
                        "--fuse --quads --layers 15 --growth 1.2 --first-height 8e-4 -o s.msh",
                        {"quads: Gmsh's Blossom recombination would have ended the process on this model (\"Perfect "
                         "Match failed"});
}

TEST(Cli, QuadsWhereBlossomsFoldAreMadeWithTheSimpleAlgorithm) {
    // The sweep's wing with a winglet, fused, in quads: Blossom's quads fold where the winglet
    // meets the wing (two faces of the surface intersect), and the run stopped with "the
    // surface intersects itself". Gmsh's simple recombination does not fold there: the surfaces
    // are made with it, the summary names the fold, and the mesh passes.
    expect_sweep_passes("cli_blossom_folds", "winglet.geo",
                        "--fuse --quads --layers 15 --growth 1.2 --first-height 1.5e-3 -o w.msh",
                        {"quads: Gmsh's Blossom quads folded where the surface nearly touches itself (face "});
}

TEST(Cli, RemeshedQuadsWhereBlossomsFoldAreMadeWithTheSimpleAlgorithm) {
    // The sweep's plate with holes as a CAD tool's STL, remeshed in quads: Blossom's quads fold
    // at a hole (two faces intersect) and the run stopped with "the surface intersects itself".
    // Remeshed with the simple recombination (RemeshParams::simple_recombination) it passes.
    expect_sweep_passes("cli_remesh_blossom_folds", "holes_brepmesh.stl",
                        "--remesh --quads --fuse --layers 15 --growth 1.2 --first-height 1e-3 -o p.msh",
                        {"quads: Gmsh's Blossom quads folded where the surface nearly touches itself (face "});
}

TEST(Cli, QuadsRoundATinyHoleWhereBlossomWouldAbort) {
    // The sweep's block with a hole of 1/500 in quads: Blossom aborts on it (the simple
    // algorithm then meshes it); and 18 quads bent round the hole that take no pyramid,
    // several per march of the layers, are all mended within the rounds allowed (they were
    // mended one per round, and the 8 rounds ran out). (Its walls were meshed again finer round
    // the layers' steps, where Gmsh crashed under the simple algorithm, until steps were judged
    // against their own geometry; that crash in a child: GmshSession's tests.)
    test::ScratchDir dir("cli_blossom_tiny_hole");
    const CliResult r =
        mesh_sweep(dir, "tinyhole.geo", "--quads --layers 15 --growth 1.2 --first-height 5e-4 -o h.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"quads: Gmsh's Blossom recombination would have ended the process"});
    test::expect_contains(r.out, {"were split into two triangles", "checkMesh would say \"Mesh OK\""});
}

/// The summary's smallest scaled Jacobian of \p type ("tetrahedron", ...); NaN if absent.
double summary_min_quality(const std::string& out, const std::string& type) {
    const auto at = out.find("  " + type + ":");
    if (at == std::string::npos) return std::nan("");
    const auto key = out.find("min scaled Jacobian ", at);
    return key == std::string::npos ? std::nan("") : std::strtod(out.c_str() + key + 20, nullptr);
}

TEST(Cli, TetrahedraAreImprovedAfterTetGen) {
    // The cup 0.01 thick of the sweep: TetGen leaves 562 tetrahedra below a scaled Jacobian of
    // 0.2, the worst 0.052; flips, edge removals and moved interior nodes leave 23, the worst
    // 0.118 (improve_tets). Its worst tetrahedron overall is a cell of a layer step (0.018).
    test::ScratchDir dir("cli_tet_improve");
    const std::string args =
        "mesh '" + example_data("../sweep/shell.geo") + "' --layers 30 --growth 1.2 --first-height 1e-4 ";
    CliResult r = strata_cli(dir, args + "-o c.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto at = r.out.find("tetrahedra improved: ");
    ASSERT_NE(at, std::string::npos) << r.out;
    long long below_before = -1, below_after = -1;
    double worst_before = 0.0, worst_after = 0.0;
    const std::string line = r.out.substr(at, r.out.find('\n', at) - at);
    ASSERT_EQ(std::sscanf(line.c_str() + line.find("0.2: "), "0.2: %lld -> %lld, the worst %lf -> %lf", &below_before,
                          &below_after, &worst_before, &worst_after),
              4)
        << line;
    EXPECT_GT(below_before, 200) << line;
    EXPECT_LT(below_after, below_before / 5) << line;
    EXPECT_GT(worst_after, 1.5 * worst_before) << line;
    r = strata_cli(dir, args + "--tet-improve 0 -o c0.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out.find("tetrahedra improved"), std::string::npos) << r.out;
    // The notched box: TetGen's worst are slivers over a shallow valley of the layer top, all four
    // corners on it (0.026 since the concave corner's columns keep every layer, capped where
    // they stopped; 0.017 before); a point inserted above each lifts them, and the mesh's worst
    // tetrahedron passes 0.02 (0.049).
    const std::string notch = "mesh '" + example_data("bl3d_4_box_notch_concave_corner.brep") +
                              "' --patch surface_1=farfield --patch surface_2=farfield --patch surface_3=farfield "
                              "--patch surface_4=farfield --patch surface_6=farfield --layers 30 --first-height 1e-4 "
                              "--growth 1.2 ";
    r = strata_cli(dir, notch + "-o n.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out.find(" 0 inserted;"), std::string::npos) << r.out;
    EXPECT_GE(summary_min_quality(r.out, "tetrahedron"), 0.02) << r.out;
    const double improved = summary_min_quality(r.out, "tetrahedron");
    r = strata_cli(dir, notch + "--tet-improve 0 -o n0.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_LT(summary_min_quality(r.out, "tetrahedron"), 0.75 * improved) << r.out;
    expect_clean_failure(
        "mesh '" + example_data("sphere.stl") + "' --layers 2 --first-height 1e-3 --tet-improve 1 -o x.msh",
        "--tet-improve = 1", "tet_improve_range");
}

// The paper's third example (examples/fighter, Thompson, Chalasani & Soni section 5.3): a
// notional fighter's half model (4486 wall triangles, the paper's resolution) in a half-sphere
// domain whose y = 0 face is the symmetry plane, with a chin inlet whose duct ends inside the
// aircraft. 10 layers instead of the example's 30 (same surface): the layers are prisms (no
// quads) but for the wedges of the fans at the sharp edges, whose chains end on the fuselage
// (terminals), they go into the duct and cover all of its wall, and the symmetry plane stays flat.
TEST(Cli, FighterHalfModelWithInletDuct) {
    test::ScratchDir dir("cli_fighter");
    const int layers = 10;
    CliResult r =
        strata_cli(dir, "mesh '" + example_data("../fighter/fighter.geo") +
                            "' -o fighter.msh --first-height 1e-3 --growth 1.2 --layers " + std::to_string(layers));
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"planes re-meshed around the layers' sides: symmetry", "valid: "});
    // Coverage, share of wall nodes with every layer (measured: inlet 100 %, fuselage 99.4 %,
    // wing 92.1 %; 84.3 % and 96.8 % before the sharp edges' fans could end on the fuselage;
    // the rest are at the sharp edges, whose columns stop at the wall: 57 of the wing's, the
    // fans' terminals and the edges under the fan angle, --sharp-edge-stop).
    EXPECT_GE(coverage_share(r.out, "inlet", 3), 98.0) << r.out;
    EXPECT_GE(coverage_share(r.out, "fuselage", 3), 98.0) << r.out;
    EXPECT_GE(coverage_share(r.out, "wing", 3), 90.0) << r.out;
    // With one direction at those edges, checkMesh found the faces between their two sides'
    // cells skewed (above 4); stopped at the wall, it passes the mesh.
    EXPECT_NE(r.out.find("checkMesh would say \"Mesh OK\""), std::string::npos) << r.out;

    const VolumeMesh m = read_volume_msh(dir.file("fighter.msh"));
    EXPECT_GT(m.tets.size(), 0u);
    EXPECT_FALSE(m.hexes.empty());                    // the fans' wedges
    EXPECT_LT(m.hexes.size(), m.prisms.size() / 20);  // else prisms, as the paper's
    // Prisms only in the layers: at most one per wall triangle and layer, and none away from
    // the aircraft (x 0..15.5, y 0..5, z -1.6..3.6; the layers are 0.026 thick).
    // (A mesh read back has patch names only: the walls are the patches other than these two.)
    const Index symmetry = find_patch(m.boundary, "symmetry"), farfield = find_patch(m.boundary, "farfield");
    ASSERT_NE(symmetry, kNone);
    ASSERT_NE(farfield, kNone);
    std::size_t wall_triangles = 0;
    for (Index f = 0; f < m.boundary.num_faces(); ++f)
        if (m.boundary.face_patch[f] != symmetry && m.boundary.face_patch[f] != farfield) {
            EXPECT_EQ(m.boundary.face_size(f), 3);
            ++wall_triangles;
        }
    EXPECT_EQ(wall_triangles, 4486u);  // the paper's 4541
    EXPECT_GT(m.prisms.size(), 0u);
    EXPECT_LE(m.prisms.size(), layers * wall_triangles);
    for (const auto& c : m.prisms)
        for (Index v : c) {
            const Vec3& q = m.points[v];
            ASSERT_TRUE(q.x() > -0.3 && q.x() < 15.8 && q.y() < 5.3 && q.z() > -1.9 && q.z() < 3.9)
                << "a prism node away from the aircraft at " << q.transpose();
        }
    // The symmetry plane held: its faces (the plane re-meshed, and the layers' side faces in
    // it) lie in y = 0, and nothing crosses it.
    double off_plane = 0.0, below = 0.0;
    for (Index f = 0; f < m.boundary.num_faces(); ++f)
        if (m.boundary.face_patch[f] == symmetry)
            for (const Index* v = m.boundary.face_begin(f); v != m.boundary.face_end(f); ++v)
                off_plane = std::max(off_plane, std::abs(m.points[*v].y()));
    for (const Vec3& q : m.points) below = std::min(below, q.y());
    EXPECT_LT(off_plane, 1e-9);
    EXPECT_GT(below, -1e-9);
}

// --max-aspect-ratio (CadParams::max_aspect_ratio): a unit box (its edges in sevenths) under a
// first layer of 5e-5 has prisms near 1900 in aspect ratio, which checkMesh fails. Its walls are
// meshed again finer, the summary says so, and the mesh passes; 0 keeps the surface; too many
// faces for the budget keeps it too, with a warning naming the size that would do.
TEST(Cli, WallsAreMeshedFinerForTheFirstLayersAspectRatio) {
    test::ScratchDir dir("cli_max_aspect");
    const std::string box = "mesh '" + test_data("cad_box_groups.geo") + "' --layers 3 --first-height 5e-5 ";
    CliResult r = strata_cli(dir, box + "-o fine.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"walls: meshed again finer (6 surfaces, 0 curves under fans; size 0.035)",
                                  "checkMesh would say \"Mesh OK\""});
    r = strata_cli(dir, box + "--max-aspect-ratio 0 -o coarse.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out.find("walls: "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("cells with an aspect ratio above 1000"), std::string::npos) << r.out;
    // A thousand times thinner: about 11 million faces, far over the budget.
    r = strata_cli(dir, "mesh '" + test_data("cad_box_groups.geo") + "' --layers 3 --first-height 5e-8 -o thin.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("more than Strata makes unasked (200000): give --size 3.5e-05"), std::string::npos) << r.out;
    expect_clean_failure(box + "-o out.msh --max-aspect-ratio 5", "--max-aspect-ratio", "aspect_small");
}

// A column on a 90-degree edge without a fan leans 45 degrees, its first cell only 0.71 of the
// first height off the face: the wall sizing predicts that cell, not a right prism. The winglet
// STL of the sweep, remeshed, under 3e-4: 955 predicted for a right prism, 1192 made (checkMesh
// failed it); now 1190 predicted, its walls meshed finer, and checkMesh passes.
TEST(Cli, WallSizingPredictsTheColumnsLeaningOverEdges) {
    expect_sweep_passes("cli_lean", "winglet_brepmesh.stl",
                        "--fuse --remesh --layers 30 --growth 1.2 --first-height 3e-4 -o w.msh",
                        {"walls: meshed again finer", "worst 1190 before"});
}

// A surface mesh is kept as it is: where its walls are too wide for the first layer the
// summary says so before the layers' checkMesh figures, naming the worst face, and points to
// --remesh; --max-aspect-ratio is the limit of that warning (0: none).
TEST(Cli, SurfaceMeshTooCoarseForTheFirstLayerIsForecast) {
    test::ScratchDir dir("cli_aspect_forecast");
    const std::string sphere = "layers '" + example_data("sphere.stl") + "' --layers 2 --first-height 1e-7 ";
    CliResult r = strata_cli(dir, sphere + "-o thin.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"wall faces are too wide for the first layer (1e-07 high)", "(on face ",
                                  "add --remesh to mesh it again", "cells with an aspect ratio above 1000",
                                  "the surface mesh was kept as it is: --remesh meshes it again"});
    r = strata_cli(dir, sphere + "--max-aspect-ratio 0 -o silent.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out.find("too wide for the first layer"), std::string::npos) << r.out;
    // Thick enough: no forecast, and checkMesh's aspect ratio passes.
    r = strata_cli(dir, "layers '" + example_data("sphere.stl") + "' --layers 2 --first-height 1e-3 -o thick.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out.find("too wide for the first layer"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("cells with an aspect ratio above 1000"), std::string::npos) << r.out;
}

TEST(Cli, AVesselsOpeningsAreCappedEachWithAPatchOfItsOwn) {
    // tests/data/vessel_three_cuts.stl: a tube with a branch, open at three planar cuts (an
    // inlet, two outlets), internal flow. --fill-holes alone closes them into the wall patch, so
    // layers grow from the openings and no inflow patch exists; with --caps each is a patch of
    // its own (kind other, named with --patch), the wall's layers meet it as an outflow plane.
    test::ScratchDir dir("cli_caps");
    const std::string vessel = "'" + test::test_data("vessel_three_cuts.stl") + "'";
    const std::string rest = " --internal --fill-holes 1000 --layers 5 --first-height 0.005 --growth 1.2";
    const CliResult r = strata_cli(dir, "mesh " + vessel + rest +
                                            " --caps --patch cap_1=other:inlet --patch cap_3=other:outlet_b -o v.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"caps: 3 openings closed each by a cap of its own", "  patch 2 inlet ",
                                  "  patch 3 cap_2 ", "  patch 4 outlet_b ", "checkMesh would say \"Mesh OK\""});
    const CliResult bad = strata_cli(dir, "surface " + vessel + rest.substr(0, rest.find(" --layers")) +
                                              " --caps --patch cap_4=other -o s.msh");
    EXPECT_NE(bad.code, 0);
    test::expect_contains(bad.err, {"no cap named 'cap_4'", "closed 3 loops"});
    const CliResult no_holes = strata_cli(dir, "surface " + vessel + " --caps -o s.msh");
    EXPECT_NE(no_holes.code, 0);
    test::expect_contains(no_holes.err, {"--caps closes the loops --fill-holes closes"});
}

TEST(Cli, TheUsersGmshOptionsFilesDoNotChangeTheMesh) {
    // A home whose ~/.gmsh-options saves another algorithm, a finer size factor, smoothing and a
    // random factor (as Gmsh's File > Save Options As Default does) and whose ~/.gmshrc is not
    // Gmsh's at all: the CAD model is meshed as in an empty home, byte for byte, and Gmsh says
    // nothing about them (read, they made Gmsh abort meshing this model, and the .gmshrc's
    // syntax errors were printed three times).
    test::ScratchDir dir("cli_gmsh_home");
    std::filesystem::create_directories(dir.file("plain"));
    std::filesystem::create_directories(dir.file("user"));
    std::ofstream(dir.file("user/.gmsh-options"))
        << "Mesh.Algorithm = 1;\nMesh.MeshSizeFactor = 0.5;\nMesh.Smoothing = 20;\nMesh.RandomFactor = 1e-3;\n";
    std::ofstream(dir.file("user/.gmshrc")) << "this is not a Gmsh file;\n";
    const std::string job = "mesh '" + example_data("hemisphere_cylinder_halfdomain.stp") +
                            "' --patch surface_1=farfield --patch surface_2=symmetry --patch surface_3=other "
                            "--layers 3 --first-height 0.01 -q -o ";
    for (const char* home : {"plain", "user"}) {
        const CliResult r = strata_cli(dir, job + home + ".msh", "HOME='" + dir.file(home) + "' ");
        ASSERT_EQ(r.code, 0) << home << ": " << r.err;
        EXPECT_EQ(r.err.find("gmsh"), std::string::npos) << home << ": " << r.err;
    }
    EXPECT_TRUE(slurp(dir.file("plain.msh")) == slurp(dir.file("user.msh")));
}

TEST(Cli, OnATerminalEachStagesBarSaysTheSecondsItHasTaken) {
    // Under a pseudo-terminal (script(1)), as a user at a shell sees it: each stage's bar ends with
    // its seconds so far; the surface, layers and tetrahedra each reach 100 %.
    test::ScratchDir dir("cli_progress_tty");
    const std::string cmd = "cd '" + dir.path().string() + "' && script -qec \"'" + std::string(STRATA_CLI) +
                            "' mesh '" + example_data("sphere.stl") +
                            "' -o s.msh --layers 5 --first-height 0.01\" /dev/null > tty.txt 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    const std::string tty = slurp(dir.file("tty.txt"));
    for (const char* stage : {"layers", "tetrahedra"}) {
        const std::regex done(std::string(stage) + R"re( *\[#{30}\] 100% +[0-9]+\.[0-9] s)re");
        EXPECT_TRUE(std::regex_search(tty, done)) << stage << " in:\n" << tty;
    }
    EXPECT_NE(tty.find("wrote s.msh"), std::string::npos) << tty;
}

/// The first height a run chose (its report's "automatic_first_height"), as the report wrote it.
std::string chosen_first_height(const std::string& report) {
    std::smatch m;
    const std::regex chosen(R"re("automatic_first_height": \{"first_height": ([-+.0-9eE]+))re");
    return std::regex_search(report, m, chosen) ? m[1].str() : std::string();
}

TEST(Cli, WithNoFirstHeightOneIsChosenFromTheWallsSaidAndTheSameAsAsked) {
    // No --layers, no --first-height: 20 layers whose first height makes them 2 % of the walls'
    // length thick, said in the summary and the report; the mesh is the one that height asked for
    // gives, byte for byte. The STL sphere (radius 1) as it is; the CAD hemisphere-cylinder in its
    // air domain, whose walls are sized for the layers (a first pass measures them) and meshed at
    // their own twentieth, not the domain's.
    test::ScratchDir dir("cli_automatic_first_height");
    const std::string sphere = "'" + example_data("sphere.stl") + "'";
    const CliResult r = strata_cli(dir, "mesh " + sphere + " -o a.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"first height: 0.000214, none asked: 20 layers at growth 1.2 reach 2 % of the walls' "
                                  "length 2 (--first-height H",
                                  "coverage: 20 layers asked, 0.04 thick", "checkMesh would say \"Mesh OK\""});
    const std::string report = slurp(dir.file("a.msh.report.json"));
    test::expect_contains(report, {"\"walls_length\": 2,", "\"options\": {}"});  // what was asked: nothing
    const std::string h = chosen_first_height(report);
    ASSERT_FALSE(h.empty()) << report;
    const CliResult asked = strata_cli(dir, "mesh " + sphere + " -o b.msh --layers 20 --first-height " + h + " -q");
    ASSERT_EQ(asked.code, 0) << asked.err;
    EXPECT_TRUE(slurp(dir.file("a.msh")) == slurp(dir.file("b.msh")));

    const std::string domain = "'" + example_data("hemisphere_cylinder_halfdomain.stp") +
                               "' --patch surface_1=farfield --patch surface_2=symmetry --patch surface_3=other";
    const CliResult cad = strata_cli(dir, "mesh " + domain + " --layers 10 -o c.msh");
    ASSERT_EQ(cad.code, 0) << cad.err;
    test::expect_contains(cad.out, {"size: the walls are meshed at 0.503, a twentieth of their own bounding box's "
                                    "diagonal, the other faces (the domain round them) up to 12.3",
                                    "none asked: 10 layers at growth 1.2 reach 2 % of the walls' length 10",
                                    "every layer on 100.0 %", "checkMesh would say \"Mesh OK\""});
    const std::string hc = chosen_first_height(slurp(dir.file("c.msh.report.json")));
    ASSERT_FALSE(hc.empty());
    const CliResult cad_asked = strata_cli(dir, "mesh " + domain + " --layers 10 -o d.msh -q --first-height " + hc);
    ASSERT_EQ(cad_asked.code, 0) << cad_asked.err;
    EXPECT_TRUE(slurp(dir.file("c.msh")) == slurp(dir.file("d.msh")));
    // A thickness given is reached instead, and a y+ is no automatic height.
    const CliResult thick = strata_cli(dir, "layers " + sphere + " -o t.msh --layers 5 --thickness 0.1");
    ASSERT_EQ(thick.code, 0) << thick.err;
    test::expect_contains(thick.out, {"5 layers at growth 1.2 reach the thickness 0.1 asked", "0.1 thick"});
    const CliResult yplus = strata_cli(dir, "layers " + sphere + " -o y.msh --yplus 1 --reynolds 1e6");
    ASSERT_EQ(yplus.code, 0) << yplus.err;
    EXPECT_EQ(yplus.out.find("none asked"), std::string::npos) << yplus.out;
    // No wall to choose it from: the layers' own error, not a missing first height; a.msh as it was.
    const std::string before = slurp(dir.file("a.msh"));
    const CliResult none = strata_cli(dir, "mesh " + sphere + " --patch Created_by_Gmsh=symmetry -o a.msh");
    EXPECT_NE(none.code, 0);
    test::expect_contains(none.err, {"no wall faces to extrude", "--patch NAME=wall"});
    EXPECT_EQ(none.err.find("first layer height"), std::string::npos) << none.err;
    EXPECT_TRUE(slurp(dir.file("a.msh")) == before);
}

TEST(Cli, FuseWrapsPartsThatTouchAlongALineOnly) {
    // examples/data/fins_touching_body.stl: four fins whose flat roots sit on a round body,
    // touching it along a line. Unfused they intersect; fused, no union bounds a volume, so the
    // walls are wrapped into one, and the summary says which it did.
    test::ScratchDir dir("cli_fuse_touching");
    const CliResult r = strata_cli(dir, "mesh --fuse '" + example_data("fins_touching_body.stl") +
                                            "' -o f.msh --layers 10 --first-height 5e-4 --growth 1.2");
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"fused: parts touch along a line or a point only", "the walls were wrapped",
                                  "wrapped: 2608 faces -> one watertight surface", "checkMesh would say \"Mesh OK\""});
    test::expect_contains(slurp(dir.file("f.msh.report.json")), {"\"touching_wrapped\": true"});
}

TEST(Cli, PatchesAreRenamedWithTheirKindsAndThoseGivenOneNameAreOne) {
    // --patch NAME=KIND:NEWNAME: the fused wing-fuselage's two largest faces as one patch
    // "fuselage", named so in the summary and in OpenFOAM's boundary file; a name OpenFOAM would
    // not take is refused.
    test::ScratchDir dir("cli_patch_rename");
    std::filesystem::create_directories(dir.file("case/constant"));
    const std::string step = "'" + example_data("wing_fuselage.step") + "'";
    const CliResult r = strata_cli(dir, "mesh " + step +
                                            " --fuse --patch surface_1=wall:fuselage --patch surface_2=wall:fuselage "
                                            "--layers 3 --first-height 1e-3 -o case/constant/polyMesh");
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"  patch 1 fuselage ", "13 patches"});
    const std::string boundary = slurp(dir.file("case/constant/polyMesh/boundary"));
    test::expect_contains(boundary, {"    fuselage\n", "inGroups        1(wall);"});
    EXPECT_EQ(boundary.find("    surface_1\n"), std::string::npos);
    EXPECT_EQ(boundary.find("    surface_2\n"), std::string::npos);
    const CliResult bad = strata_cli(dir, "surface " + step + " --patch 'surface_1=wall:wing (left)' -o s.msh");
    EXPECT_NE(bad.code, 0);
    test::expect_contains(bad.err, {"--patch", "'wing (left)'", "must start with a letter or _"});
}

TEST(Cli, ARevolvesProfileLeftBesideItsSolidIsSetAsideAndSaid) {
    // A STEP holding a cylinder and the rectangle it was revolved from: refused as open before
    // ("a hole or a crack"); the rectangle is set aside, the summary and the report say which.
    test::ScratchDir dir("cli_loose_profile");
    const CliResult r = strata_cli(dir, "mesh '" + test::test_data("cad_cylinder_and_profile.step") +
                                            "' -o c.msh --layers 5 --first-height 1e-3");
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"repaired: 1 faces of the CAD model that bound none of its solids",
                                  "set aside, not meshed (the first, surface 4, at (0.5, 0.65, 0))",
                                  "checkMesh would say \"Mesh OK\""});
    test::expect_contains(slurp(dir.file("c.msh.report.json")), {"\"ignored\": 1"});
}

TEST(Cli, AHalfModelWhoseShellHoldsItsNoseFaceTwiceIsMeshedWithTheCopySaid) {
    // A half model in its box whose shell holds the flat nose face twice, the copy remade on the
    // same edges (cad_half_model_nose_twice.py): refused before ("non-manifold edge ... shared by
    // 3 faces"); the copy is not meshed, and the summary and the report say which.
    test::ScratchDir dir("cli_nose_twice");
    std::string patches = " --patch surface_6=symmetry";
    for (const int s : {5, 7, 8, 9, 10}) patches += " --patch surface_" + std::to_string(s) + "=farfield";
    const CliResult r = strata_cli(dir, "mesh '" + test_data("cad_half_model_nose_twice_shell.brep") + "'" +
                                            patches + " -o h.msh --layers 5 --first-height 1e-3");
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"repaired: 1 faces the CAD model holds twice (bounded by the same edges as another "
                                  "face and lying on it, within ",
                                  "not meshed (the first, surface 11, a copy of surface 2, at (-0.5, ",
                                  "every layer on 100.0 %", "checkMesh would say \"Mesh OK\""});
    test::expect_contains(slurp(dir.file("h.msh.report.json")),
                          {"\"coincident\": 1", "\"coincident_surface\": 11", "\"coincident_with\": 2"});
}

TEST(Cli, AnStlWhoseFacesWereTessellatedApartHasItsCracksClosedAndSaid) {
    // A cylinder whose side and ends were meshed each with nodes of their own round the end
    // circles (tests/data/cylinder_cracks.py): refused before ("two boundary loops touch"); the
    // cracks are closed, said with the widest gap, and the cylinder gets every layer.
    test::ScratchDir dir("cli_cracks");
    const CliResult r = strata_cli(dir, "mesh '" + test_data("cylinder_cracks.stl") +
                                            "' -o c.msh --layers 5 --first-height 1e-3");
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"1 connected components (1 closed), 0 open boundary loops",
                                  "repaired: cracks closed where each side of an edge was meshed with nodes of its "
                                  "own, 80 faces split at the other side's nodes, gaps up to 0.00427757",
                                  "every layer on 100.0 %", "checkMesh would say \"Mesh OK\""});
    test::expect_contains(slurp(dir.file("c.msh.report.json")), {"\"split_faces\": 80"});
}

TEST(Cli, AnAirDomainWhoseOuterBoundaryIsLeftAWallIsRefusedNamingIt) {
    // The hemisphere-cylinder's air domain with only its symmetry plane mapped: the outer sphere
    // stays a wall round everything, and the region to fill is inside out. The error names the
    // patch and the kinds to give it (it was "fill_with_tets: the boundary encloses a volume of
    // -1.1e6", with nothing to act on).
    const std::string args = "mesh '" + example_data("hemisphere_cylinder_halfdomain.stp") +
                             "' --size 10 --layers 5 --first-height 0.02 --patch surface_2=symmetry -o h.msh";
    expect_clean_failure(args, "the wall patch 'surface_1' holds every other patch within its bounding box, as an air "
                               "domain's outer boundary does: if the input is the air round a body, give it --patch "
                               "surface_1=farfield", "inside_out");
}

TEST(Cli, StepBodyNamesAreSaidAndNameAllTheirPatches) {
    // A STEP whose two solids the CAD tool named (cad_named_bodies.py): each face is still a
    // patch of its own (surface_N), the summary says which body holds which, and --patch BODY=
    // sets a body's patches at once, here renamed into one patch each (OpenFOAM's boundary file).
    test::ScratchDir dir("cli_named_bodies");
    const std::string in = "mesh '" + test_data("cad_named_bodies.step") + "' --layers 3 --first-height 0.01";
    CliResult r = strata_cli(dir, in + " -o a.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"9 patches", "  bodies: 'Fuselage' (patches 1-6), 'Wing' (patches 7-9); --patch "
                                  "BODY=KIND[:NAME] sets all of a body's patches at once"});
    test::expect_contains(slurp(dir.file("a.msh.report.json")), {"\"body\": \"Wing\""});
    std::filesystem::create_directories(dir.path() / "case" / "constant");
    r = strata_cli(dir, in + " --patch Fuselage=wall:fuselage --patch Wing=wall:wing -o case/constant/polyMesh");
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"2 patches", "patch 1 fuselage", "patch 2 wing"});
    test::expect_contains(slurp(dir.file("case/constant/polyMesh/boundary")), {"fuselage", "wing"});
    expect_clean_failure(in + " --patch Tail=wall -o t.msh", "the bodies (each naming all its patches): 'Fuselage', 'Wing'",
                         "named_bodies");
}

TEST(Cli, LooseCadFacesAreSewnAndWiderGapsNamedWithTheirRemedy) {
    // A box of six faces that miss each other (tests/data/cad_box_loose_faces.py): by 1e-7 they
    // are sewn and meshed; by 3e-5, wider than sewing goes unasked, strata mesh refuses the open
    // surface on one line that gives the --sew-tolerance that sews it, and that one does.
    test::ScratchDir dir("cli_sewing");
    CliResult r = strata_cli(dir, "surface '" + test_data("cad_box_loose_faces_1e-7.brep") + "' -o s.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(r.out, {"sewn: 6 faces that bounded no solid", "free edges 24 -> 0, 1 solids made"});
    const std::string wide =
        "mesh '" + test_data("cad_box_loose_faces_3e-5.brep") + "' --layers 2 --first-height 0.01 ";
    expect_clean_failure(wide + "-o out.msh", "--sew-tolerance 6.7e-05 sews them", "sewing");
    r = strata_cli(dir, wide + "--sew-tolerance 6.7e-05 -o m.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("free edges 24 -> 0, 1 solids made"), std::string::npos) << r.out;
    // An IGES of trimmed faces is sewn too, and OpenCASCADE's IGES reader does not print its
    // statistics ("Total number of loaded entities") into the summary.
    r = strata_cli(dir, "surface '" + test_data("cad_nose_trimmed_faces.igs") + "' -o n.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out.rfind("surface: ", 0), 0u) << r.out;
    EXPECT_EQ(r.out.find("loaded entities"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("sewn: 5 faces that bounded no solid"), std::string::npos) << r.out;
    // Only for CAD; out of range refused.
    expect_clean_failure("surface '" + example_data("sphere.stl") + "' -o s.msh --sew-tolerance 1e-5",
                         "--merge-tolerance", "sewstl");
    expect_clean_failure("surface '" + test_data("cad_box_loose_faces_1e-7.brep") + "' -o s.msh --sew-tolerance 0.01",
                         "--sew-tolerance = 0.01: give a share", "sewrange");
}

TEST(Cli, HolesAreNamedWithTheFillHolesThatClosesThem) {
    // A cube whose top lost one triangle (tests/data/cli_cube_missing_face.stl): the hole lies
    // in the top's plane with the body on one side, but a face beside it lies in that plane, so
    // it is no half model (it was taken for one, and the "symmetry plane" then overlapped the
    // top); the error gives the --fill-holes that closes it, and that one does.
    const std::string cube = "mesh '" + test_data("cli_cube_missing_face.stl") + "' --layers 2 --first-height 0.01 ";
    expect_clean_failure(cube + "-o out.msh", "a face along them lies in it", "holeinplane");
    expect_clean_failure(cube + "-o out.msh", "--fill-holes 3 closes every open loop of up to 3 edges", "fillhint");
    test::ScratchDir dir("cli_fill_holes");
    CliResult r = strata_cli(dir, cube + "--fill-holes 3 -o m.msh");
    ASSERT_EQ(r.code, 0) << r.err;
    test::expect_contains(
        r.out, {"repaired: 1 holes closed with 1 triangles (--fill-holes; the largest, 3 edges", "1 closed"});
    expect_clean_failure(cube + "--fill-holes -1 -o out.msh", "--fill-holes = -1", "fillrange");
}

TEST(Cli, AGmshAbortIsOneLineAndExitOne) {
    // Gmsh 4.8 throws out of an OpenMP region on a face it cannot mesh, which ends its process
    // through std::terminate (tests/data/cli_gmsh_aborts.geo); it meshes in a child process, and
    // the run ends with one line naming the file, what was being done and Gmsh's message, exit
    // 1, no file.
    expect_clean_failure("surface '" + test_data("cli_gmsh_aborts.geo") + "' -o s.msh",
                         "Gmsh aborts (The 1D mesh seems not to be forming a closed loop) meshing the surfaces",
                         "abort");
}

TEST(Cli, MeshBadInputsFailCleanly) {
    // Open, but not along one plane: not a half model that could be closed.
    expect_clean_failure("mesh '" + test_data("cli_open_bent.stl") + "' -o out.cgr --layers 2 --first-height 1e-3",
                         "do not lie in one plane", "notahalfmodel");
    expect_clean_failure(
        "mesh '" + example_data("sphere.stl") + "' -o out.cgr --layers 5 --first-height 1e-3 --farfield cone", "cone",
        "farfield");
    expect_clean_failure(
        "mesh '" + example_data("sphere.stl") + "' -o out.cgr --layers 5 --first-height 1e-3 --farfield-size 1",
        "farfield-size", "ffsize");
    // Layers that do not fit in the generated farfield: the numbers and the size that would do.
    expect_clean_failure(
        "mesh '" + example_data("sphere.stl") + "' -o out.cgr --layers 10 --first-height 0.5 --farfield-size 1.1",
        "enlarge --farfield-size to", "layers_fit");
}

TEST(Cli, SameMeshAsTheLibraryGivenTheSameValues) {
    // Defaults and inference live in the Params structs: the program with the fewest options
    // and the library with the same values and default Params write the same bytes. (The
    // tetrahedron growth default used to be 0.3 in the program and 0 in TetFillParams.)
    test::ScratchDir dir("cli_same_as_library");
    CliResult r =
        strata_cli(dir, "mesh '" + example_data("sphere.stl") + "' -o cli.msh --layers 3 --first-height 2e-3");
    ASSERT_EQ(r.code, 0) << r.err;
    HybridParams p;
    p.layers.distribution.layers = 3;
    p.layers.distribution.first_height = 2e-3;
    const SurfaceMesh s = prepare_surface(example_data("sphere.stl"), {});
    write_volume(build_hybrid_mesh(s, p), dir.file("library.msh"));
    EXPECT_TRUE(slurp(dir.file("cli.msh")) == slurp(dir.file("library.msh")));
}

TEST(Cli, LibraryMessagesNameTheFlags) {
    // The library names parameters (DistributionParams::growth); the program shows its flags.
    const std::string in = "layers '" + example_data("sphere_pyhyp_quads.msh") + "' -o out.msh --layers 4";
    expect_clean_failure(in + " --first-height 1e-3 --growth 0.5", "--growth", "growth_flag");
    expect_clean_failure(in + " --first-height 1e-3 --distribution tanh --thickness 1e-3", "--first-height",
                         "tanh_flag");
}

/// True once process \p pid catches SIGINT (bit 2 of SigCgt in /proc/<pid>/status): the
/// program's handler is installed. Before that a SIGINT ends it by the default action, as it
/// would any program still loading its libraries.
bool catches(pid_t pid, int sig) {
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("SigCgt:", 0) == 0) return (std::stoull(line.substr(7), nullptr, 16) >> (sig - 1)) & 1u;
    return false;
}

/// What run_and_signal saw: the program's wait status and its stderr, or that it ended before
/// it caught the signal (or could not be started).
struct SignalledRun {
    bool ended_early = false;
    int status = 0;
    std::string err;
};

/// The strata program run with \p args in \p dir (stdout to /dev/null, stderr to a file read
/// and removed afterwards), sent \p sig \p delay_ms after it installs its handler for it.
SignalledRun run_and_signal(const test::ScratchDir& dir, const std::vector<std::string>& args, int sig, int delay_ms) {
    const std::string err = dir.file("stderr.txt");
    test::Argv argv(STRATA_CLI, args);
    SignalledRun r;
    const pid_t pid = fork();
    if (pid < 0) return {true, 0, "fork failed"};
    if (pid == 0) {
        if (chdir(dir.path().c_str()) != 0 || !std::freopen("/dev/null", "w", stdout) ||
            !std::freopen(err.c_str(), "w", stderr))
            _exit(127);
        execv(STRATA_CLI, argv.data());
        _exit(127);
    }
    for (int waited = 0; !catches(pid, sig) && waited < 30000; waited += 5) {
        if (waitpid(pid, &r.status, WNOHANG) == pid) {
            r.ended_early = true;
            break;
        }
        usleep(5000);
    }
    if (!r.ended_early) {
        usleep(static_cast<useconds_t>(delay_ms) * 1000);
        kill(pid, sig);
        waitpid(pid, &r.status, 0);
    }
    r.err = slurp(err);
    fs::remove(err);
    return r;
}

TEST(Cli, ACrashEndsWithOneLineNamingTheStage) {
    // Gmsh's surface mesher has crashed (SIGSEGV in MeshAdapt) on some CAD faces and sizes, and
    // it runs in this process. A SIGSEGV while Gmsh meshes a sphere finely (seconds of work)
    // stands for it: one line naming the signal, the stage and what to try, exit 1, nothing
    // written, instead of the shell's bare "Segmentation fault".
    test::ScratchDir dir("cli_crash");
    { std::ofstream(dir.file("ball.geo")) << "SetFactory(\"OpenCASCADE\");\nSphere(1) = {0, 0, 0, 1};\n"; }
    // Into Gmsh's meshing, which takes seconds at this size.
    const SignalledRun run = run_and_signal(
        dir, {"mesh", "ball.geo", "-o", "ball.msh", "--size", "0.002", "--layers", "5", "--first-height", "1e-3"},
        SIGSEGV, 800);
    ASSERT_FALSE(run.ended_early) << "the program ended before the signal: " << run.err;
    const int status = run.status;
    const std::string& message = run.err;
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1) << message;
    EXPECT_EQ(lines(message), 1u) << message;
    EXPECT_EQ(message.rfind("strata: error: the program crashed (SIGSEGV) in its surface stage on ball.geo (Gmsh "
                            "meshing",
                            0),
              0u)
        << message;
    test::expect_contains(message, {"--size", "nothing was written"});
    EXPECT_EQ(files_in(dir), std::vector<std::string>{"ball.geo"});
}

TEST(Cli, TimeoutStopsARunAndLeavesNoFile) {
    // A stage that polls stops at its next check (the layers, well within a second of a 0.05 s
    // limit); Gmsh meshing a sphere at a size of 1/1000 of its diameter cannot be asked to stop,
    // but it meshes in a child process, which is killed (before 2026-11-27 the watchdog ended
    // the program 5 s after the limit, "the running stage" could not stop). Either way: exit
    // 124, one message, no file.
    test::ScratchDir dir("cli_timeout");
    CliResult r = strata_cli(
        dir, "mesh '" + example_data("sphere.stl") + "' -o s.msh --layers 40 --first-height 1e-4 --timeout 0.05");
    EXPECT_EQ(r.code, 124) << r.err;
    EXPECT_EQ(r.err, "strata: error: stopped by --timeout 0.05 s; nothing was written\n");
    EXPECT_TRUE(files_in(dir).empty());
    { std::ofstream(dir.file("ball.geo")) << "SetFactory(\"OpenCASCADE\");\nSphere(1) = {0, 0, 0, 1};\n"; }
    r = strata_cli(dir, "mesh ball.geo -o ball.msh --size 0.002 --layers 5 --first-height 1e-3 --timeout 1");
    EXPECT_EQ(r.code, 124) << r.err;
    EXPECT_EQ(r.err, "strata: error: stopped by --timeout 1 s; nothing was written\n");
    EXPECT_EQ(files_in(dir), std::vector<std::string>{"ball.geo"});
    r = strata_cli(dir, "mesh ball.geo -o ball.msh --timeout -1");
    EXPECT_EQ(r.code, 2) << r.err;
}

TEST(Cli, CtrlCCancelsAndLeavesNoFile) {
    // One SIGINT, as a terminal sends on Ctrl-C, at several moments of a run of several seconds
    // (the half ONERA M6, 20 layers of hexahedra): wherever it lands, the running stage sees
    // it at its next check, the exit code is 130 and the directory stays empty, not even a
    // temporary file. (`timeout -s INT` is no substitute: it signals the child and then its
    // whole process group, two SIGINTs, and the second ends the program by design.)
    for (const int delay_ms : {0, 400, 1500}) {
        test::ScratchDir dir("cli_ctrl_c_" + std::to_string(delay_ms));
        const SignalledRun run =
            run_and_signal(dir,
                           {"mesh", example_data("onera_m6_pyhyp_quads.msh"), "-o", "m6.cgr", "--layers", "20",
                            "--first-height", "1e-5", "--growth", "1.15", "--farfield", "box"},
                           SIGINT, delay_ms);
        ASSERT_FALSE(run.ended_early) << "the program ended before it could be interrupted: " << run.err;
        const int status = run.status;
        const std::string& message = run.err;
        EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 130) << delay_ms << " ms: " << message;
        EXPECT_NE(message.find("cancelled"), std::string::npos) << delay_ms << " ms: " << message;
        EXPECT_TRUE(files_in(dir).empty()) << delay_ms << " ms";
    }
}

}  // namespace
}  // namespace strata
