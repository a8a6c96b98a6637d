#include <strata/core/error.h>
#include <strata/frontend/pipeline.h>
#include <strata/frontend/prepare_layers.h>
#include <strata/frontend/report.h>
#include <strata/io/formats.h>
#include <strata/io/write_report.h>
#include <strata/io/write_surface.h>
#include <strata/io/write_volume.h>

#include <chrono>
#include <utility>

namespace strata {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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
    const bool cad = request.surface ? static_cast<bool>(request.remesh) : any_cad;
    return prepare_for_layers(make, cad, request.prepare, request.mesh, &report);
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
    const std::string source = request.source.empty() ? input_name(request.inputs) : request.source;
    r.any_cad = !request.surface && any_cad_input(request.inputs);
    const auto t0 = std::chrono::steady_clock::now();
    r.surface = make_surface(request, source, r.any_cad, r.prepare, progress);
    r.seconds.surface = seconds_since(t0);
    if (request.job == Job::Layers) run_layers(request, source, r, progress);
    if (request.job == Job::Mesh) run_mesh(request, r, progress);
    r.report = run_report(request, r);
    return r;
}

std::vector<std::string> output_files(Job job, const std::string& output) {
    if (job == Job::Surface) return {output};
    std::vector<std::string> files = volume_output_files(output);
    files.push_back(report_path(output));
    return files;
}

void check_outputs(Job job, const std::string& output, double msh_version, const std::vector<std::string>& inputs,
                   const std::vector<std::string>& extra) {
    if (job == Job::Surface)
        check_surface_output(output, msh_version);
    else
        check_volume_output(output, msh_version);
    // No output replaces an input, and every output can be created (a run that takes minutes
    // should not end on a name that cannot be written); the first is the format's check's.
    std::vector<std::string> files = output_files(job, output);
    files.insert(files.end(), extra.begin(), extra.end());
    check_outputs_are_not_inputs(files, inputs);
    for (std::size_t i = 1; i < files.size(); ++i) check_output_path(files[i]);
}

void write_outputs(const Result& result, const std::string& output, double msh_version, Progress* progress,
                   OutputSet& outputs) {
    if (result.job == Job::Surface) {
        write_surface(result.surface, output, msh_version, progress, &outputs);
        return;
    }
    write_volume(result.volume(), output, msh_version, progress, &outputs);
    write_report(result.report, report_path(output), &outputs);
}

}  // namespace strata
