// The pipeline (frontend/pipeline.h): the same input and options give the same bytes through
// every door (the strata program, the Python package, run() in C++), on a CAD case whose walls
// prepare_for_layers meshes again; and a surface given (the Gmsh-API door's) goes through the
// same stages as the file it came from.

#include <strata/core/error.h>
#include <strata/frontend/pipeline.h>
#include <strata/io/formats.h>
#include <strata/io/read_surface.h>
#include <strata/io/write_report.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "test_support.h"

using namespace strata;

namespace {

/// Issue 9's two spheres 0.0118 apart, 12 layers from 1e-3: the layers step at the gap, so
/// prepare_for_layers meshes the walls there again finer (CadParams::step_quality).
const std::string kArgs = " --size 0.1 --layers 12 --first-height 1e-3 --growth 1.2";

Options two_spheres() {
    Options o;
    o.surface.inputs = {test::example_data("two_spheres_narrow_gap.geo")};
    o.surface.input = input_name(o.surface.inputs);
    o.surface.prepare.cad.size = 0.1;
    o.layers.params.distribution.layers = 12;
    o.layers.params.distribution.first_height = 1e-3;
    o.layers.params.distribution.growth = 1.2;
    return o;
}

/// \p json without its "times" node and with every other "seconds" at 0 (the seconds a stage
/// took differ from run to run).
std::string without_times(std::string json) {
    json = std::regex_replace(json, std::regex("\"seconds\": [-+.0-9eE]+"), "\"seconds\": 0");
    const std::size_t start = json.find("\"times\": {");
    if (start == std::string::npos) return json;
    int depth = 0;
    for (std::size_t i = json.find('{', start); i < json.size(); ++i) {
        depth += json[i] == '{' ? 1 : json[i] == '}' ? -1 : 0;
        if (depth == 0) return json.substr(0, start) + json.substr(i + 1);
    }
    return json;
}

/// The mesh, its Cobalt60 patch map (which names the grid file: each door writes mesh.cgr in a
/// directory of its own) and its report without its times, as bytes.
std::vector<std::string> outputs_of(const std::string& cgr) {
    std::vector<std::string> bytes;
    for (const std::string& f : output_files(Job::Mesh, cgr)) bytes.push_back(without_times(test::slurp(f)));
    return bytes;
}

}  // namespace

TEST(Pipeline, EveryDoorGivesTheSameBytesWhereTheWallsAreMeshedAgain) {
    const test::ScratchDir dir("pipeline_doors");
    for (const char* door : {"cpp", "cli", "py"}) std::filesystem::create_directories(dir.path() / door);
    const Result r = run(make_request(Job::Mesh, two_spheres()));
    // The case is one prepare_for_layers changes: its finer walls kept.
    const StepSizeReport& steps = r.prepare.steps;
    ASSERT_GT(steps.points, 0);
    EXPECT_FALSE(steps.kept || steps.over_budget || !steps.failure.empty());
    EXPECT_GT(steps.faces_after, 2 * steps.faces_before);
    EXPECT_EQ(r.surface.num_faces(), steps.faces_after);
    EXPECT_GT(r.mesh.num_cells(CellType::Pyramid), 0);
    {
        OutputSet outputs;
        write_outputs(r, dir.file("cpp/mesh.cgr"), 4.1, nullptr, outputs);
        outputs.commit();
    }
    const std::vector<std::string> cpp = outputs_of(dir.file("cpp/mesh.cgr"));
    ASSERT_EQ(cpp.size(), 3u);  // .cgr, .bc, .report.json
    for (const std::string& b : cpp) EXPECT_FALSE(b.empty());

    const test::CliResult cli = test::run_program(
        dir, STRATA_CLI, "mesh '" + test::example_data("two_spheres_narrow_gap.geo") + "' -o cli/mesh.cgr -q" + kArgs);
    ASSERT_EQ(cli.code, 0) << cli.err;
    EXPECT_TRUE(outputs_of(dir.file("cli/mesh.cgr")) == cpp) << "the CLI's mesh differs from run()'s";

    if (std::string(STRATA_TEST_PYTHON).empty()) GTEST_SKIP() << "no Python package in this build";
    const std::string script = "import strata; strata.mesh(\"" + test::example_data("two_spheres_narrow_gap.geo") +
                               "\", output=\"py/mesh.cgr\", size=0.1, layers=12, first_height=1e-3, growth=1.2)";
    const test::CliResult py = test::run_program(
        dir, "env",
        std::string("PYTHONPATH='") + STRATA_TEST_PYTHON_PATH + "' '" + STRATA_TEST_PYTHON + "' -c '" + script + "'");
    ASSERT_EQ(py.code, 0) << py.err;
    EXPECT_TRUE(outputs_of(dir.file("py/mesh.cgr")) == cpp) << "Python's mesh differs from run()'s";
}

TEST(Pipeline, ASurfaceGivenGoesThroughTheStagesOfItsFile) {
    // The sphere's STL read by the caller (as the Gmsh-API door reads its model) gives the mesh
    // the file gives: the same preparation, layers and tetrahedra.
    Options o;
    o.surface.inputs = {test::example_data("sphere.stl")};
    o.layers.params.distribution.layers = 4;
    o.layers.params.distribution.first_height = 1e-3;
    const Request from_file = make_request(Job::Mesh, o);
    Request given = from_file;
    given.inputs.clear();
    given.surface = read_stl(o.surface.inputs[0]);
    given.source = "a caller's sphere";
    const Result a = run(from_file);
    const Result b = run(given);
    EXPECT_FALSE(b.any_cad);
    EXPECT_EQ(a.surface.points, b.surface.points);
    EXPECT_EQ(a.mesh.points, b.mesh.points);
    EXPECT_EQ(a.mesh.tets, b.mesh.tets);
    EXPECT_EQ(a.mesh.prisms, b.mesh.prisms);
    EXPECT_EQ(a.hybrid.validation.min_scaled_jacobian, b.hybrid.validation.min_scaled_jacobian);
}

TEST(Pipeline, LayersAreCheckedAndASurfaceJobStopsAtTheSurface) {
    Options o;
    o.surface.inputs = {test::example_data("sphere.stl")};
    o.layers.params.distribution.layers = 3;
    o.layers.params.distribution.first_height = 1e-3;
    const Request request = make_request(Job::Layers, o);
    EXPECT_EQ(request.source, o.surface.inputs[0]);  // the inputs' name where the options give none
    const Result layers = run(request);
    EXPECT_EQ(layers.volume().num_cells(CellType::Prism), 3 * static_cast<std::size_t>(layers.surface.num_faces()));
    EXPECT_EQ(layers.volume().num_cells(CellType::Tet), 0u);
    EXPECT_TRUE(layers.volume_validation().ok());
    EXPECT_EQ(layers.volume_coverage().layers, 3);
    const Result surface = run(make_request(Job::Surface, o));
    EXPECT_EQ(surface.surface.face_nodes, layers.surface.face_nodes);
    EXPECT_EQ(surface.volume().num_cells(), 0);
}

TEST(Pipeline, NoInputIsAnInputError) {
    Request r;
    r.job = Job::Surface;
    EXPECT_THROW(run(r), InputError);
}

TEST(Pipeline, AFoamCasesOutputsAndFlow) {
    // -o CASE with foam_case: the mesh is CASE/constant/polyMesh, its report beside it; the flow
    // from the layer options (Re from DistributionParams::reynolds where given, y+ of the first height).
    OutputOptions foam;
    foam.foam_case = true;
    EXPECT_EQ(mesh_output(Job::Mesh, "run/case", foam), "run/case/constant/polyMesh");
    EXPECT_EQ(mesh_output(Job::Layers, "run/case/constant/polyMesh", foam), "run/case/constant/polyMesh");
    EXPECT_EQ(mesh_output(Job::Mesh, "run/case", {}), "run/case");
    EXPECT_EQ(output_files(Job::Mesh, "case", foam),
              (std::vector<std::string>{"case/constant/polyMesh", "case/constant/polyMesh.report.json"}));
    Options o;
    o.layers.params.distribution.first_height = 1e-3;
    FoamCaseParams p = foam_case_params(o);
    EXPECT_EQ(p.reynolds, 1e6);
    EXPECT_EQ(p.reference_length, 1.0);
    EXPECT_EQ(p.first_height, 1e-3);
    EXPECT_NEAR(p.yplus, 1e-3 * 1e6 * std::sqrt(0.5 * 0.026 * std::pow(1e6, -1.0 / 7.0)), 1e-9);
    o.layers.params.distribution.reynolds = 2e5;
    o.layers.params.distribution.reference_length = 0.5;
    p = foam_case_params(o);
    EXPECT_EQ(p.reynolds, 2e5);
    EXPECT_EQ(p.reference_length, 0.5);
    EXPECT_DOUBLE_EQ(foam_viscosity(p), 0.5 / 2e5);

    // Checked before the work: a directory without the flag is refused saying what to add; with
    // it, a case in a directory that does not exist, naming it.
    test::ScratchDir dir("pipeline_foam_case");
    const std::vector<std::string> inputs = {test::example_data("sphere.stl")};
    test::expect_error<InputError>([&] { check_outputs(Job::Mesh, dir.path().string(), {}, inputs); },
                                   {"it is a directory", "OutputOptions::foam_case = true"});
    EXPECT_NO_THROW(check_outputs(Job::Mesh, dir.file("case"), {}, inputs, {}, foam));
    test::expect_error<InputError>([&] { check_outputs(Job::Mesh, dir.file("no/case"), {}, inputs, {}, foam); },
                                   {"cannot write the OpenFOAM case", "does not exist"});
    EXPECT_TRUE(test::dir_entries(dir.path()).empty());  // checking writes nothing
}
