#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/solver_checks.h>
#include <strata/frontend/pipeline.h>
#include <strata/frontend/prepare_layers.h>
#include <strata/geometry/point_sizes.h>
#include <strata/frontend/report.h>
#include <strata/io/formats.h>
#include <strata/io/openfoam_case.h>
#include <strata/io/write_report.h>
#include <strata/io/write_surface.h>
#include <strata/io/write_volume.h>
#include <strata/module/distribution.h>
#include <strata/module/step_sizes.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <limits>
#include <utility>

namespace strata {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Whether \p request's walls are meshed by Strata (CAD input, or a surface with --remesh), so
/// that they can be meshed again finer.
bool remeshable(const Request& request, bool any_cad) {
    return request.surface ? static_cast<bool>(request.remesh) : any_cad;
}

/// The surface of \p request: made from its inputs or its surface (prepare_surfaces,
/// prepare_mesh), for a hybrid mesh with the walls prepared for the layers.
SurfaceMesh make_surface(const Request& request, const std::string& source, bool any_cad, PrepareReport& report,
                         Progress* progress) {
    const SurfaceSource make = [&](const PrepareParams& params, PrepareReport* made) {
        if (!request.surface) return prepare_surfaces(request.inputs, params, made, progress);
        if (params.cad.size_points.empty() || !request.remesh)
            return prepare_mesh(*request.surface, params, source, made, progress);
        return prepare_mesh(request.remesh(params.cad.size_points, params.cad.size_point_growth), params, source, made,
                            progress);
    };
    if (request.job != Job::Mesh) return make(request.prepare, &report);
    return prepare_for_layers(make, remeshable(request, any_cad), request.prepare, request.mesh, &report);
}

/// \p request with the first height chosen from the walls of \p surface where none was asked
/// (automatic_first_height): for the layers, the walls' sizing (size_walls_for_layers, where
/// Strata meshes them) and the options the report and an OpenFOAM case read. Said in
/// \p r.report's "automatic_first_height" (run_report). A surface without walls is refused as the
/// layers refuse it (require_wall_faces); walls of no extent keep it unset.
Request with_first_height(const Request& request, const SurfaceMesh& surface, Result& r) {
    require_wall_faces(surface);
    const double length = walls_length(surface);
    if (!(length > 0.0)) return request;
    Request sized = request;
    const DistributionParams& d = request.mesh.layers.distribution;
    const double h = automatic_first_height(d, length);
    sized.mesh.layers.distribution.first_height = h;
    sized.options.layers.params.distribution.first_height = h;
    if (remeshable(request, r.any_cad)) size_walls_for_layers(sized.prepare, sized.mesh.layers, h);
    r.first_height = {true, length, d.thickness > 0.0 ? 0.0 : kAutomaticThicknessShare, h};
    return sized;
}

/// The surface of \p request, and \p request with its first height chosen where none was asked
/// (with_first_height): from the walls as they come, which walls Strata meshes (CAD, --remesh)
/// are then meshed again sized for it.
SurfaceMesh make_sized_surface(const Request& request, const std::string& source, Result& r, Request& sized,
                               Progress* progress) {
    sized = request;
    const bool automatic =
        request.job != Job::Surface && automatic_first_height(request.mesh.layers.distribution);
    if (automatic && remeshable(request, r.any_cad)) {
        Request plain = request;
        plain.job = Job::Surface;
        PrepareReport first;
        sized = with_first_height(request, make_surface(plain, source, r.any_cad, first, progress), r);
    }
    SurfaceMesh surface = make_surface(sized, source, r.any_cad, r.prepare, progress);
    if (automatic && !remeshable(request, r.any_cad)) sized = with_first_height(request, surface, r);
    return surface;
}

/// The layers alone on \p r.surface, checked.
void run_layers(const Request& request, const std::string& source, Result& r, Progress* progress) {
    auto t0 = std::chrono::steady_clock::now();
    r.layers = extrude_layers(r.surface, request.mesh.layers, progress);
    r.seconds.layers = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    r.validation =
        require_valid_mesh(r.layers.mesh, source, {.threads = request.mesh.layers.threads, .progress = progress});
    r.seconds.validation = seconds_since(t0);
    r.coverage = layer_report(r.layers);
}

/// The hybrid mesh on \p r.surface; an open surface's error says how sewing could close it.
void run_mesh(const Request& request, Result& r, Progress* progress) {
    try {
        r.mesh = build_hybrid_mesh(r.surface, request.mesh, progress, &r.hybrid);
    } catch (const InputError& e) {
        const std::string hint = sewing_hint(r.prepare.sew);
        if (hint.empty()) throw;
        throw InputError(e.what() + hint);
    }
    r.seconds.layers = r.hybrid.seconds_layers;
    r.seconds.pyramids = r.hybrid.seconds_pyramids;
    r.seconds.tets = r.hybrid.seconds_tets;
    r.seconds.validation = r.hybrid.seconds_validate;
}

/// The sizes that bring \p cells (above checkMesh's aspect ratio) to kStepSizeShare of \p
/// limit: at each one's centre, its longest edge scaled by the limit over its figure (the flat
/// cells at the wall are as flat as their wall edge is long over the layer's height).
std::vector<SizePoint> aspect_sizes(const std::vector<HighAspectCell>& cells, double limit) {
    std::vector<SizePoint> points;
    for (const HighAspectCell& c : cells)
        points.push_back({c.centre, kStepSizeShare * c.longest_edge * limit / c.aspect_ratio});
    return points;
}

/// Where the hybrid mesh of \p r has cells checkMesh fails for their aspect ratio and Strata
/// meshes its walls: those walls meshed again finer round them (aspect_sizes) and the mesh made
/// again, once, kept if it has fewer such cells. They are the cells closing a step down to the
/// wall beside full columns (a front round's stop, a fan's end at a junction), about as flat as
/// their wall edge over the first height, twice a prism's: the wall sizing before the layers
/// (CadParams::max_aspect_ratio) cannot forecast where the front stops columns.
void remesh_for_aspect(const Request& request, const std::string& source, Result& r, Progress* progress) {
    const SolverChecks& checks = r.hybrid.validation.solver;
    const double limit = request.prepare.cad.max_aspect_ratio;
    if (checks.high_aspect.empty() || !(limit > 0.0) || !remeshable(request, r.any_cad)) return;
    const auto t0 = std::chrono::steady_clock::now();
    AspectRemeshReport a;
    a.cells = checks.high_aspect_cells, a.worst = checks.max_aspect_ratio, a.worst_cell = checks.worst_aspect;
    a.faces_before = r.surface.num_faces();
    std::vector<SizePoint> points = aspect_sizes(checks.high_aspect, limit);
    a.smallest = std::numeric_limits<double>::infinity();
    for (const SizePoint& q : points) a.smallest = std::min(a.smallest, q.size);
    // Within the faces budget and kStepFacesGrowth times the surface's faces, as the steps' sizes.
    const CadParams& cad = request.prepare.cad;
    const double budget =
        std::min(cad.wall_faces_budget > 0.0 ? cad.wall_faces_budget : std::numeric_limits<double>::infinity(),
                 kStepFacesGrowth * static_cast<double>(a.faces_before));
    a.faces_estimate = faces_with_sizes(r.surface, PointSizes(points, cad.size_point_growth));
    if (a.faces_estimate > budget) {
        a.over_budget = true;
        r.prepare.aspect_remesh = a;
        return;
    }
    Request again = request;
    for (SizePoint& q : points) q.at /= r.prepare.scale, q.size /= r.prepare.scale;  // the CAD's unit
    std::vector<SizePoint>& asked = again.prepare.cad.size_points;
    asked.insert(asked.end(), points.begin(), points.end());
    Result second;
    second.any_cad = r.any_cad;
    try {
        second.surface = make_surface(again, source, r.any_cad, second.prepare, progress);
        second.seconds.surface = r.seconds.surface + seconds_since(t0);  // both surfaces
        run_mesh(again, second, progress);
    } catch (const Error& e) {  // the first mesh is valid: it stays, and the summary says why
        a.failure = e.what();
        a.seconds = seconds_since(t0);
        r.prepare.aspect_remesh = a;
        return;
    }
    const SolverChecks& after = second.hybrid.validation.solver;
    a.faces_after = second.surface.num_faces();
    a.cells_after = after.high_aspect_cells, a.worst_after = after.max_aspect_ratio;
    a.seconds = seconds_since(t0);
    if (after.high_aspect_cells < checks.high_aspect_cells) {
        r.surface = std::move(second.surface), r.prepare = std::move(second.prepare);
        r.mesh = std::move(second.mesh), r.hybrid = std::move(second.hybrid), r.seconds = second.seconds;
    }
    r.prepare.aspect_remesh = a;
}

/// The report of \p r, built once from its stages' results.
ReportNode run_report(const Request& request, const Result& r) {
    const StageSeconds& t = r.seconds;
    switch (request.job) {
        case Job::Surface:
            return surface_run_report(r.surface, r.prepare, request.options, {{"surface", t.surface}});
        case Job::Layers:
            return layers_run_report(r.layers, r.coverage, r.validation, &r.surface, &r.prepare, request.options,
                                     {{"surface", t.surface}, {"layers", t.layers}, {"validation", t.validation}});
        case Job::Mesh:
            break;
    }
    return mesh_run_report(&r.mesh, r.hybrid, &r.surface, &r.prepare, request.options, {{"surface", t.surface}});
}

}  // namespace

ReportNode first_height_report(const FirstHeightChoice& c) {
    ReportNode n;
    n.set("first_height", c.height).set("walls_length", c.walls_length).set("thickness_share", c.thickness_share);
    return n;
}

Request make_request(Job job, const Options& options) {
    Request r;
    r.job = job;
    SurfaceOptions surface = options.surface;
    if (surface.input.empty()) surface.input = input_name(surface.inputs);
    r.inputs = surface.inputs;
    r.source = surface.input;
    if (job == Job::Layers) r.mesh.layers = layer_params(options.layers);
    if (job == Job::Mesh) r.mesh = hybrid_params(options.layers, options.mesh);
    r.prepare = prepare_params(surface, job == Job::Surface ? nullptr : &r.mesh.layers);
    r.options = options;
    return r;
}

Result run(const Request& request, Progress* progress) {
    Result r;
    r.job = request.job;
    r.options = request.options;
    const std::string source = request.source.empty() ? input_name(request.inputs) : request.source;
    r.any_cad = !request.surface && any_cad_input(request.inputs);
    const auto t0 = std::chrono::steady_clock::now();
    Request sized;
    r.surface = make_sized_surface(request, source, r, sized, progress);
    r.seconds.surface = seconds_since(t0);
    if (sized.job == Job::Layers) run_layers(sized, source, r, progress);
    if (sized.job == Job::Mesh) {
        run_mesh(sized, r, progress);
        remesh_for_aspect(sized, source, r, progress);
    }
    r.options = sized.options;
    r.report = run_report(sized, r);
    if (r.first_height.automatic) {
        r.report.set("automatic_first_height", first_height_report(r.first_height));
        r.report.set("provenance", provenance_report(request.options));  // what was asked
    }
    return r;
}

std::string mesh_output(Job job, const std::string& output, const OutputOptions& how) {
    if (!how.foam_case || job == Job::Surface) return output;
    return foam_polymesh_path(foam_case_directory(output));
}

std::vector<std::string> output_files(Job job, const std::string& output, const OutputOptions& how) {
    if (job == Job::Surface) return {output};
    const std::string mesh = mesh_output(job, output, how);
    std::vector<std::string> files = how.foam_case ? std::vector<std::string>{mesh} : volume_output_files(mesh);
    files.push_back(report_path(mesh));
    return files;
}

void check_outputs(Job job, const std::string& output, MshFormat msh, const std::vector<std::string>& inputs,
                   const std::vector<std::string>& extra, const OutputOptions& how) {
    const bool foam = how.foam_case && job != Job::Surface;
    std::error_code ec;
    if (job != Job::Surface && !foam && !is_polymesh_path(output) && std::filesystem::is_directory(output, ec))
        throw InputError("cannot write '" + output +
                         "': it is a directory; for an OpenFOAM case there add OutputOptions::foam_case = true, "
                         "else name a mesh file");
    // No output replaces an input, and every output can be created (a run that takes minutes
    // should not end on a name that cannot be written); the first is the format's check's.
    std::vector<std::string> files = output_files(job, output, how);
    files.insert(files.end(), extra.begin(), extra.end());
    std::vector<std::string> in_case;  // a case's polyMesh, 0/ and files, which its own check checks
    if (foam)
        in_case = check_foam_case_output(foam_case_directory(output));
    else if (job == Job::Surface)
        check_surface_output(output, msh);
    else
        check_volume_output(output, msh);
    std::vector<std::string> all = files;
    all.insert(all.end(), in_case.begin(), in_case.end());
    check_outputs_are_not_inputs(all, inputs);
    for (std::size_t i = 1; i < files.size(); ++i) {
        // In a case directory still to be made (the case, its constant/): its check made one.
        const std::filesystem::path parent = std::filesystem::path(files[i]).parent_path();
        const bool made_later = foam && !std::filesystem::is_directory(parent, ec);
        // A .vtm's blocks' directory: check_volume_output checked it as a directory.
        const bool blocks = !foam && is_vtm_path(output) && files[i] == vtm_block_directory(output);
        if (!made_later && !blocks) check_output_path(files[i]);
    }
}

FoamCaseParams foam_case_params(const Options& options) {
    FoamCaseParams p;
    const DistributionParams& d = options.layers.params.distribution;
    if (d.reynolds > 0.0) p.reynolds = d.reynolds;
    p.reference_length = d.reference_length;
    try {
        p.first_height = resolve(d).first_height;
        p.yplus = p.first_height / first_height_from_yplus(1.0, p.reynolds, p.reference_length);
    } catch (const InputError&) {
        p.first_height = p.yplus = 0.0;  // not said: the layers' own check names the problem
    }
    return p;
}

WrittenOutputs write_outputs(const Result& result, const std::string& output, MshFormat msh, Progress* progress,
                             OutputSet& outputs) {
    WrittenOutputs w;
    const OutputOptions& how = result.options.output;
    w.files = output_files(result.job, output, how);
    if (result.job == Job::Surface) {
        write_surface(result.surface, output, msh, progress, &outputs);
        return w;
    }
    if (how.foam_case)
        w.foam_case = write_foam_case(result.volume(), foam_case_directory(output), foam_case_params(result.options),
                                      progress, &outputs);
    else
        write_volume(result.volume(), output, msh, progress, &outputs);
    write_report(result.report, report_path(mesh_output(result.job, output, how)), &outputs);
    return w;
}

}  // namespace strata
