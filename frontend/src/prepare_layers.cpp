#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/frontend/options.h>
#include <strata/frontend/prepare_layers.h>
#include <strata/geometry/intersections.h>

#include <algorithm>
#include <chrono>
#include <limits>

namespace strata {

SurfaceMesh prepare_for_layers(const std::vector<std::string>& inputs, const PrepareParams& params,
                               const HybridParams& mesh, PrepareReport* report, Progress* progress) {
    if (!(params.cad.step_quality >= 0.0 && params.cad.step_quality < 1.0))
        throw InputError("CadParams::step_quality = " + format_number(params.cad.step_quality) +
                         ": need a scaled Jacobian in [0, 1) for the cells closing the layers' steps (0: off)");
    PrepareReport first_report;
    SurfaceMesh surface = prepare_surfaces(inputs, params, &first_report, progress);
    // Blossom's quads can fold where the surface nearly touches itself (the winglet's junction
    // under --fuse --quads, the plate's holes remeshed in quads), and no layer can grow on a
    // surface that intersects itself; Gmsh's simple recombination pairs fewer triangles and may
    // not fold there. Kept if it does not.
    PrepareParams chosen = params;
    const bool cad_blossom = !params.remesh && params.cad.elements != SurfaceElements::Triangles &&
                             !params.cad.simple_recombination && any_cad_input(inputs);
    const bool remesh_blossom = params.remesh && params.remeshing.quads && !params.remeshing.simple_recombination;
    if ((cad_blossom || remesh_blossom) && first_report.recombination.blossom_failure.empty()) {
        const std::vector<FacePair> folds = self_intersections(surface, 1, mesh.threads);
        if (!folds.empty()) {
            PrepareParams simple = params;
            simple.cad.simple_recombination = cad_blossom;
            simple.remeshing.simple_recombination = remesh_blossom;
            PrepareReport simple_report;
            try {
                SurfaceMesh again = prepare_surfaces(inputs, simple, &simple_report, progress);
                if (self_intersections(again, 1, mesh.threads).empty()) {
                    simple_report.recombination.folded = true;
                    simple_report.recombination.blossom_failure = describe_pair(surface, folds[0]);
                    surface = std::move(again);
                    first_report = std::move(simple_report);
                    chosen = std::move(simple);
                }
            } catch (const Error&) {  // Blossom's surface stays; build_hybrid_mesh names its fold
            }
        }
    }
    StepSizeReport steps;
    const auto t0 = std::chrono::steady_clock::now();
    const bool planned = (params.cad.step_quality > 0.0 || params.cad.max_aspect_ratio > 0.0) && any_cad_input(inputs);
    const auto done = [&](SurfaceMesh result, const PrepareReport& r) {
        if (planned) steps.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (report) {
            *report = r;
            report->steps = steps;
        }
        return result;
    };
    if (!planned) return done(std::move(surface), first_report);
    steps.quality = params.cad.step_quality;
    steps.faces_before = steps.faces_after = surface.num_faces();

    std::vector<SizePoint> points;
    double share_before = 1.0;
    try {
        StepPlan plan = step_plan(surface, mesh, params.cad.step_quality, params.cad.max_aspect_ratio);
        points = std::move(plan.points);
        steps.points = static_cast<Index>(points.size());
        steps.fan_points = plan.fans.nodes;
        points.insert(points.end(), plan.fans.points.begin(), plan.fans.points.end());
        share_before = plan.thickness_share;
    } catch (const Error&) {  // the layers cannot be planned (an open surface): build_hybrid_mesh says why
        return done(std::move(surface), first_report);
    }
    if (points.empty()) return done(std::move(surface), first_report);

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
            return done(std::move(surface), first_report);
        }
        steps.raised *= 1.25;
        for (SizePoint& q : points) q.size *= 1.25;
    }
    steps.smallest = points.front().size;
    for (const SizePoint& q : points) steps.smallest = std::min(steps.smallest, q.size);

    PrepareParams again = chosen;
    again.cad.size_points = points;
    for (SizePoint& q : again.cad.size_points) {  // the CAD's unit: before PrepareParams::scale
        q.at /= params.scale;
        q.size /= params.scale;
    }
    PrepareReport second_report;
    SurfaceMesh finer;
    try {
        finer = prepare_surfaces(inputs, again, &second_report, progress);
    } catch (const BackendError& e) {
        // The finer walls are an improvement, not the surface asked for: Gmsh failing on their
        // sizes (quads it cannot make there) leaves the first surface, which it could mesh.
        steps.failure = e.what();
        return done(std::move(surface), first_report);
    }
    // Nor a fold the first surface did not have (quads recombined across a narrow junction).
    if (const std::vector<FacePair> folds = self_intersections(finer, 1, mesh.threads);
        !folds.empty() && self_intersections(surface, 1, mesh.threads).empty()) {
        steps.failure = "the finer surface intersects itself: " + describe_pair(finer, folds[0]);
        return done(std::move(surface), first_report);
    }
    second_report.recombination = first_report.recombination;  // the choice made on the first surface
    // The finer walls must not cost layers: they resolve the gap better, and its limits, spread
    // along the walls, took 60.9 % of the thickness to 14.5 % on a slotted wing's main element.
    steps.thickness_before = share_before;
    try {
        steps.thickness_after = step_plan(finer, mesh, params.cad.step_quality).thickness_share;
    } catch (const Error&) {
        steps.thickness_after = 0.0;
    }
    if (steps.thickness_after < share_before - kStepThicknessLoss) {
        steps.kept = true;
        return done(std::move(surface), first_report);
    }
    steps.faces_after = finer.num_faces();
    return done(std::move(finer), second_report);
}

}  // namespace strata
