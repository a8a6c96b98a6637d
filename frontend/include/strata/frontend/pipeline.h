#pragma once
/// \file
/// The pipeline: the one place that calls the stages in order. The surface (read and meshed
/// from files, or given: a Gmsh model's), the walls prepared for the layers (prepare_for_layers),
/// the layers, the hybrid mesh, the validation. The strata program, the Python package (and
/// through it FreeCAD) and the Gmsh-API entry call run() and nothing else of the stages, so the
/// same files and options give the same mesh through every door, and a surface given (a Gmsh
/// model's) goes through the same stages as a file's.
///
///     strata::Options options;  // the CLI's flags and Python's keywords, as fields
///     options.surface.inputs = {"wing.step"};
///     options.layers.params.distribution.layers = 20;
///     options.layers.params.distribution.first_height = 1e-4;
///     const strata::Result result = strata::run(strata::make_request(strata::Job::Mesh, options));
///     strata::write_volume(result.volume(), "wing.cgr");

#include <strata/core/progress.h>
#include <strata/core/report_tree.h>
#include <strata/core/validate.h>
#include <strata/frontend/options.h>
#include <strata/hybrid/hybrid_mesh.h>
#include <strata/io/files.h>
#include <strata/io/formats.h>
#include <strata/io/openfoam_case.h>
#include <strata/module/layers.h>
#include <strata/surface/prepare.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace strata {

/// How far the pipeline goes.
enum class Job {
    Surface,  ///< the checked, oriented surface with patches
    Layers,   ///< the boundary layers alone on that surface, validated
    Mesh,     ///< the hybrid mesh: the walls prepared for the layers, layers, pyramids, tetrahedra, validated
};

/// What to mesh and how.
struct Request {
    Job job = Job::Mesh;
    /// CAD or surface-mesh files, read as one surface (prepare_surfaces); not read when \p surface is given.
    std::vector<std::string> inputs;
    /// A surface given as it is (a Gmsh model's, a caller's own reader's), before prepare_mesh:
    /// patch kinds, merging, checks and orientation are still done with \p prepare.
    std::optional<SurfaceMesh> surface;
    /// How the surface given is meshed again with the sizes asked at points below its own
    /// (CadParams::size_points, their growth): a Gmsh model's CAD. Given, the walls are prepared
    /// for the layers as a CAD file's are (prepare_for_layers); empty: the surface stays as given.
    std::function<SurfaceMesh(const std::vector<SizePoint>& points, double growth)> remesh;
    /// The input's name in messages ("a.stl + b.stl", "Gmsh model 'wing'"); empty: input_name(inputs).
    std::string source;
    PrepareParams prepare;
    /// The layers and the rest of the hybrid mesh; for Job::Layers only \p mesh.layers.
    HybridParams mesh;
    /// The options as the front-end was given them (make_request): the report's provenance.
    Options options;
};

/// The request the front-ends' \p options ask for \p job, with their checks (prepare_params,
/// layer_params, hybrid_params: InputError for a refused combination or value). The inputs'
/// name in messages is options.surface.input, or input_name of the inputs where it is empty.
Request make_request(Job job, const Options& options);

/// Seconds each stage took.
struct StageSeconds {
    double surface = 0.0;     ///< read, mesh and prepare the surface (with the walls' preparation)
    double layers = 0.0;      ///< the layers
    double pyramids = 0.0;    ///< Job::Mesh
    double tets = 0.0;        ///< Job::Mesh
    double validation = 0.0;  ///< the volume mesh's check
};

/// What run() made, and its reports.
/// The first height run() chose where none was asked (automatic_first_height).
struct FirstHeightChoice {
    bool automatic = false;
    double walls_length = 0.0;     ///< walls_length of the walls it was chosen on
    double thickness_share = 0.0;  ///< kAutomaticThicknessShare, or 0 when the thickness was given
    double height = 0.0;           ///< the first height chosen
};

/// The report's "automatic_first_height" of \p c: first_height, walls_length, thickness_share.
ReportNode first_height_report(const FirstHeightChoice& c);

struct Result {
    Job job = Job::Mesh;
    SurfaceMesh surface;    ///< the surface the layers grew from (Job::Surface: the result)
    PrepareReport prepare;  ///< how it was made
    bool any_cad = false;   ///< some input was a CAD file
    /// The options it ran with (Request::options): write_outputs reads how to write (OutputOptions).
    Options options;
    /// Job::Layers: the layers, their coverage and their check.
    LayerMesh layers;
    LayerReport coverage;
    ValidationReport validation;
    /// Job::Mesh: the hybrid mesh and its report (its coverage and check are the report's).
    VolumeMesh mesh;
    HybridReport hybrid;
    StageSeconds seconds;
    FirstHeightChoice first_height;  ///< where none was asked, the one chosen
    /// The run's report (report.h: surface_run_report, layers_run_report or mesh_run_report),
    /// which write_outputs writes as JSON, the CLI prints and Python returns as a dict.
    ReportNode report;

    /// The volume mesh: the layers' (Job::Layers) or the hybrid mesh (Job::Mesh).
    const VolumeMesh& volume() const { return job == Job::Layers ? layers.mesh : mesh; }
    /// Its coverage and check, whichever the job.
    const LayerReport& volume_coverage() const { return job == Job::Layers ? coverage : hybrid.coverage; }
    const ValidationReport& volume_validation() const { return job == Job::Layers ? validation : hybrid.validation; }
};

/// Run \p request's job: the surface (prepare_surfaces on the inputs, or prepare_mesh on the
/// surface given); for Job::Mesh the walls prepared for the layers (prepare_for_layers: CAD walls
/// meshed again finer for the layers' steps, fans and aspect ratio; an open surface's error then
/// says how sewing could close it, sewing_hint); for Job::Layers the layers with
/// require_valid_mesh; for Job::Mesh build_hybrid_mesh (validated). \p progress as for the stages.
/// Throws what the stages throw.
Result run(const Request& request, Progress* progress = nullptr);

/// The mesh's own path for `-o` \p output: \p output, or with OutputOptions::foam_case (for a
/// volume) the case's CASE/constant/polyMesh (foam_case_directory: \p output is CASE, or that
/// path already). The report and the plots' data go beside it (report_path, plot_data_path).
std::string mesh_output(Job job, const std::string& output, const OutputOptions& how = {});

/// Every file run() writes for \p output: the mesh (and Cobalt60's .bc) and, for a volume, its
/// report (report_path); with a case, its polyMesh and report only (check_outputs checks the rest).
std::vector<std::string> output_files(Job job, const std::string& output, const OutputOptions& how = {});

/// Before run(): \p output (its format, with \p msh; with \p how's foam_case the case,
/// check_foam_case_output) and every file output_files names can be written, and none is one of
/// \p inputs; \p extra outputs (the plots' data) too. A directory that is not a polyMesh is
/// refused without foam_case, which the message names.
void check_outputs(Job job, const std::string& output, MshFormat msh, const std::vector<std::string>& inputs,
                   const std::vector<std::string>& extra = {}, const OutputOptions& how = {});

/// The flow of the case OutputOptions::foam_case writes for \p options: the Reynolds number of
/// DistributionParams::reynolds where given (else FoamCaseParams' 1e6) on
/// DistributionParams::reference_length, U 1 along x; the layers' first height and the y+ it
/// gives at that Reynolds number (flat plate, first_height_from_yplus's estimate) for the comments.
FoamCaseParams foam_case_params(const Options& options);

/// What write_outputs wrote.
struct WrittenOutputs {
    std::vector<std::string> files;            ///< the mesh's files and its report, as a summary names them
    std::optional<FoamCaseWritten> foam_case;  ///< with OutputOptions::foam_case: the case's files
};

/// Write \p result to \p output: the surface (Job::Surface), or the volume mesh and its report
/// (result.report at report_path), into \p outputs (the caller commits them, with any of its own);
/// with result.options.output.foam_case, the case (write_foam_case, foam_case_params) and the
/// report beside its polyMesh.
WrittenOutputs write_outputs(const Result& result, const std::string& output, MshFormat msh, Progress* progress,
                             OutputSet& outputs);

}  // namespace strata
