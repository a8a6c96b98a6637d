#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/frontend/options.h>
#include <strata/frontend/prepare_layers.h>
#include <strata/geometry/intersections.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <optional>
#include <utility>

namespace strata {
namespace {

/// A surface and how it was made.
struct Made {
    SurfaceMesh mesh;
    PrepareReport report;
    PrepareParams params;
};

/// The first surface. Blossom's quads can fold where the surface nearly touches itself (the
/// winglet's junction under --fuse --quads, the plate's holes remeshed in quads), and no layer
/// can grow on a surface that intersects itself; Gmsh's simple recombination pairs fewer
/// triangles and may not fold there. Kept if it does not.
Made first_surface(const SurfaceSource& source, bool cad, const PrepareParams& params, int threads) {
    Made made{{}, {}, params};
    made.mesh = source(params, &made.report);
    const bool cad_blossom =
        !params.remesh && params.cad.elements != SurfaceElements::Triangles && !params.cad.simple_recombination && cad;
    const bool remesh_blossom = params.remesh && params.remeshing.quads && !params.remeshing.simple_recombination;
    if (!(cad_blossom || remesh_blossom) || !made.report.recombination.blossom_failure.empty()) return made;
    const std::vector<FacePair> folds = self_intersections(made.mesh, 1, threads);
    if (folds.empty()) return made;
    PrepareParams simple = params;
    simple.cad.simple_recombination = cad_blossom;
    simple.remeshing.simple_recombination = remesh_blossom;
    PrepareReport simple_report;
    try {
        SurfaceMesh again = source(simple, &simple_report);
        if (self_intersections(again, 1, threads).empty()) {
            simple_report.recombination.folded = true;
            simple_report.recombination.blossom_failure = describe_pair(made.mesh, folds[0]);
            return {std::move(again), std::move(simple_report), std::move(simple)};
        }
    } catch (const Error&) {  // Blossom's surface stays; build_hybrid_mesh names its fold
    }
    return made;
}

/// The sizes the layers' steps and fans ask on \p surface (step_plan), raised until the surface
/// stays within the faces budget; empty where none is asked or the budget cannot be met
/// (\p steps says which). \p share_before: the share of the thickness the plan keeps.
std::vector<SizePoint> step_points(const SurfaceMesh& surface, const PrepareParams& params, const HybridParams& mesh,
                                   StepSizeReport& steps, double& share_before) {
    std::vector<SizePoint> points;
    try {
        StepPlan plan = step_plan(surface, mesh, params.cad.step_quality, params.cad.max_aspect_ratio);
        points = std::move(plan.points);
        steps.points = static_cast<Index>(points.size());
        steps.fan_points = plan.fans.nodes;
        points.insert(points.end(), plan.fans.points.begin(), plan.fans.points.end());
        share_before = plan.thickness_share;
    } catch (const Error&) {  // the layers cannot be planned (an open surface): build_hybrid_mesh says why
        return {};
    }
    if (points.empty()) return {};

    // Within the faces budget, and at most kStepFacesGrowth times the faces the surface has:
    // the sizes raised (×1.25 at a time, up to 100-fold) until the estimate fits.
    const double budget = std::min(
        params.cad.wall_faces_budget > 0.0 ? params.cad.wall_faces_budget : std::numeric_limits<double>::infinity(),
        kStepFacesGrowth * static_cast<double>(surface.num_faces()));
    const double growth = params.cad.size_point_growth;
    for (int round = 0;; ++round) {
        const double estimate = faces_with_sizes(surface, PointSizes(points, growth));
        if (round == 0) steps.faces_estimate = estimate;
        if (estimate <= budget) break;
        if (steps.raised * 1.25 > 100.0) {
            steps.over_budget = true;
            return {};
        }
        steps.raised *= 1.25;
        for (SizePoint& q : points) q.size *= 1.25;
    }
    steps.smallest = points.front().size;
    for (const SizePoint& q : points) steps.smallest = std::min(steps.smallest, q.size);
    return points;
}

/// \p first made again with \p points as CadParams::size_points; nothing where Gmsh fails on
/// them, where the finer surface folds and the first did not, or where its plan keeps less of
/// the thickness (\p steps says which).
std::optional<Made> finer_surface(const SurfaceSource& source, const Made& first, std::vector<SizePoint> points,
                                  double share_before, const HybridParams& mesh, StepSizeReport& steps) {
    Made finer{{}, {}, first.params};
    const double scale = first.params.scale;
    for (SizePoint& q : points) {  // the CAD's unit: before PrepareParams::scale
        q.at /= scale;
        q.size /= scale;
    }
    finer.params.cad.size_points = std::move(points);
    try {
        finer.mesh = source(finer.params, &finer.report);
    } catch (const BackendError& e) {
        // The finer walls are an improvement, not the surface asked for: Gmsh failing on their
        // sizes (quads it cannot make there) leaves the first surface, which it could mesh.
        steps.failure = e.what();
        return std::nullopt;
    }
    // Nor a fold the first surface did not have (quads recombined across a narrow junction).
    if (const std::vector<FacePair> folds = self_intersections(finer.mesh, 1, mesh.threads);
        !folds.empty() && self_intersections(first.mesh, 1, mesh.threads).empty()) {
        steps.failure = "the finer surface intersects itself: " + describe_pair(finer.mesh, folds[0]);
        return std::nullopt;
    }
    finer.report.recombination = first.report.recombination;  // the choice made on the first surface
    // The finer walls must not cost layers: they resolve the gap better, and its limits, spread
    // along the walls, took 60.9 % of the thickness to 14.5 % on a slotted wing's main element.
    steps.thickness_before = share_before;
    try {
        steps.thickness_after = step_plan(finer.mesh, mesh, first.params.cad.step_quality).thickness_share;
    } catch (const Error&) {
        steps.thickness_after = 0.0;
    }
    if (steps.thickness_after < share_before - kStepThicknessLoss) {
        steps.kept = true;
        return std::nullopt;
    }
    steps.faces_after = finer.mesh.num_faces();
    return finer;
}

}  // namespace

SurfaceMesh prepare_for_layers(const SurfaceSource& source, bool cad, const PrepareParams& params,
                               const HybridParams& mesh, PrepareReport* report) {
    if (!(params.cad.step_quality >= 0.0 && params.cad.step_quality < 1.0))
        throw InputError("CadParams::step_quality = " + format_number(params.cad.step_quality) +
                         ": need a scaled Jacobian in [0, 1) for the cells closing the layers' steps (0: off)");
    Made first = first_surface(source, cad, params, mesh.threads);
    StepSizeReport steps;
    const auto t0 = std::chrono::steady_clock::now();
    const bool planned = (params.cad.step_quality > 0.0 || params.cad.max_aspect_ratio > 0.0) && cad;
    const auto done = [&](Made& made) {
        if (planned) steps.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (report) {
            *report = std::move(made.report);
            report->steps = steps;
        }
        return std::move(made.mesh);
    };
    if (!planned) return done(first);
    steps.quality = params.cad.step_quality;
    steps.faces_before = steps.faces_after = first.mesh.num_faces();
    double share_before = 1.0;
    std::vector<SizePoint> points = step_points(first.mesh, params, mesh, steps, share_before);
    if (points.empty()) return done(first);
    std::optional<Made> finer = finer_surface(source, first, std::move(points), share_before, mesh, steps);
    return finer ? done(*finer) : done(first);
}

}  // namespace strata
