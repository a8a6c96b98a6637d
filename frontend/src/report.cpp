// The report tree of a run: report.h.

#include <strata/core/cell_quality.h>
#include <strata/core/solver_checks.h>
#include <strata/frontend/report.h>
#include <strata/geometry/check.h>
#include <strata/geometry/intersections.h>
#include <strata/core/union_find.h>
#include <strata/geometry/topology.h>
#include <strata/module/distribution.h>

#include <algorithm>
#include <array>

#include <type_traits>
#include <variant>

#ifndef STRATA_VERSION
#define STRATA_VERSION "unknown"
#endif
#ifndef STRATA_GIT_COMMIT
#define STRATA_GIT_COMMIT "unknown"
#endif

namespace strata {
namespace {

ReportValue point(const Vec3& p) {
    return ReportValue::list_of(std::vector<double>{p.x(), p.y(), p.z()});
}

/// An option's value in the report: a number, a flag, a text or a list of them.
template <class T>
ReportValue option_value(const T& v) {
    if constexpr (std::is_same_v<T, std::vector<int>> || std::is_same_v<T, std::vector<std::string>>)
        return ReportValue::list_of(v);
    else
        return ReportValue(v);
}

ReportNode walls_report(const WallSizeReport& w) {
    ReportNode n;
    n.set("max_aspect_ratio", w.max_aspect_ratio).set("worst_before", w.worst_before).set("worst_after", w.worst_after);
    n.set("size", w.cap).set("surfaces", w.surfaces).set("curves", w.curves).set("faces_estimate", w.faces_estimate);
    n.set("over_budget", w.over_budget).set("thin_size", w.thin_size).set("default_size", w.default_size);
    n.set("walls_default_size", w.walls_default_size);
    ReportNode narrow;
    narrow.set("ratio", w.narrow_ratio).set("faces", w.narrow_faces).set("narrowest", w.narrowest);
    narrow.set("narrowest_surface", w.narrowest_surface).set("size", w.narrow_size);
    narrow.set("faces_estimate", w.narrow_faces_estimate).set("over_budget", w.narrow_over_budget);
    n.set("narrow", std::move(narrow));
    return n;
}

ReportNode sewing_report(const SewReport& s) {
    ReportNode n;
    n.set("faces", s.faces).set("written_twice", s.written_twice).set("tolerance", s.tolerance);
    n.set("free_edges_before", s.free_before).set("free_edges_after", s.free_after).set("solids", s.solids);
    n.set("cracks", s.cracks).set("widest_gap", s.widest_gap).set("gap_at", point(s.gap_at));
    n.set("suggested_tolerance", s.suggested_tolerance).set("renumbered", s.renumbered).set("moved", s.moved);
    n.set("rejected", s.rejected).set("gap_before", s.gap_before).set("first_tolerance", s.first_tolerance);
    n.set("ignored", s.ignored).set("ignored_surface", s.ignored_surface).set("ignored_at", point(s.ignored_at));
    n.set("coincident", s.coincident).set("coincident_surface", s.coincident_surface);
    n.set("coincident_with", s.coincident_with).set("coincident_at", point(s.coincident_at));
    n.set("coincident_distance", s.coincident_distance);
    return n;
}

ReportNode aspect_remesh_report(const AspectRemeshReport& a) {
    ReportNode n;
    n.set("cells", a.cells).set("worst", a.worst).set("worst_cell", a.worst_cell).set("smallest", a.smallest);
    n.set("faces_before", a.faces_before).set("faces_after", a.faces_after).set("cells_after", a.cells_after);
    n.set("worst_after", a.worst_after).set("faces_estimate", a.faces_estimate).set("over_budget", a.over_budget);
    n.set("failure", a.failure).set("seconds", a.seconds);
    return n;
}

ReportNode steps_report(const StepSizeReport& st) {
    ReportNode n;
    n.set("quality", st.quality).set("points", st.points).set("fan_points", st.fan_points);
    n.set("smallest", st.smallest).set("faces_before", st.faces_before).set("faces_after", st.faces_after);
    n.set("faces_estimate", st.faces_estimate).set("raised", st.raised).set("over_budget", st.over_budget);
    n.set("failure", st.failure).set("thickness_before", st.thickness_before);
    n.set("thickness_after", st.thickness_after).set("kept", st.kept).set("seconds", st.seconds);
    return n;
}

ReportNode remesh_report(const RemeshReport& r) {
    ReportNode n;
    n.set("faces_before", r.faces_before).set("faces_after", r.faces_after).set("surfaces", r.surfaces);
    n.set("size", r.size).set("size_halved", r.size_halved).set("asked_feature_angle_deg", r.asked_feature_angle_deg);
    n.set("feature_angle_deg", r.feature_angle_deg).set("split_edges", r.split_edges);
    n.set("needles_before", r.needles_before).set("needles_after", r.needles_after);
    n.set("sharpest_before_deg", r.sharpest_before_deg).set("sharpest_after_deg", r.sharpest_after_deg);
    return n;
}

ReportNode wrap_report(const WrapReport& r) {
    ReportNode n;
    n.set("alpha", r.alpha).set("offset", r.offset).set("input_faces", r.input_faces).set("faces", r.faces);
    n.set("wrap_to_input", r.wrap_to_input).set("wrap_to_input_at", point(r.wrap_to_input_at));
    n.set("input_to_wrap", r.input_to_wrap).set("input_to_wrap_at", point(r.input_to_wrap_at));
    n.set("hausdorff", r.hausdorff()).set("seconds", r.seconds);
    return n;
}

/// The wall's needle faces (a corner under kNeedleCornerDeg), which cap the layer cells on them.
ReportNode needles_report(const SurfaceMesh& mesh) {
    const NeedleReport n = needle_faces(mesh, kNeedleCornerDeg, {PatchKind::Wall});
    ReportNode r;
    r.set("faces", n.needles).set("wall_faces", n.faces).set("corner_deg", kNeedleCornerDeg);
    r.set("sharpest_deg", n.sharpest_deg);
    if (n.needles == 0) return r;
    r.set("worst_face", describe_face(mesh, n.worst_face));
    const Index f = n.worst_face;
    if (mesh.face_size(f) == 3) {  // its longest edge over its shortest height
        const Vec3 &a = mesh.points[static_cast<std::size_t>(mesh.face_node(f, 0))],
                   &b = mesh.points[static_cast<std::size_t>(mesh.face_node(f, 1))],
                   &c = mesh.points[static_cast<std::size_t>(mesh.face_node(f, 2))];
        const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
        const double twice_area = (b - a).cross(c - a).norm();
        if (twice_area > 0.0) r.set("worst_aspect_ratio", longest * longest / twice_area);
    }
    return r;
}

/// A kept surface's wall faces against a first layer of height \p h: how many would make its
/// cells' aspect ratio exceed \p max_aspect_ratio, and the worst.
ReportNode wall_aspect_report(const SurfaceMesh& mesh, double h, double max_aspect_ratio) {
    double worst = 0.0;
    Index worst_face = kNone, over = 0, walls = 0;
    for (Index f = 0; f < mesh.num_faces(); ++f) {
        if (mesh.patches[static_cast<std::size_t>(mesh.face_patch[static_cast<std::size_t>(f)])].kind !=
            PatchKind::Wall)
            continue;
        std::array<Vec3, 4> corners;
        const int n = mesh.face_size(f);
        for (int k = 0; k < n; ++k)
            corners[static_cast<std::size_t>(k)] = mesh.points[static_cast<std::size_t>(mesh.face_node(f, k))];
        const double ar = right_prism_aspect_ratio(corners.data(), n, h);
        ++walls;
        if (!(ar > max_aspect_ratio)) continue;
        ++over;
        if (ar > worst) worst = ar, worst_face = f;
    }
    ReportNode r;
    r.set("first_height", h).set("max_aspect_ratio", max_aspect_ratio).set("walls", walls).set("over", over);
    r.set("worst", worst);
    if (over > 0) r.set("worst_face", describe_face(mesh, worst_face));
    return r;
}

/// The coverage head: what was asked.
void set_asked(ReportNode& n, const LayerReport& r) {
    n.set("layers", r.layers).set("first_height", r.first_height).set("thickness", r.thickness);
}

ReportValue layer_stats(const std::vector<LayerStats>& stats) {
    ReportValue::List rows;
    for (std::size_t k = 0; k < stats.size(); ++k) {
        const LayerStats& s = stats[k];
        ReportNode n;
        n.set("layer", k + 1).set("height", s.height).set("min_scaled_jacobian", s.min_scaled_jacobian);
        n.set("mean_scaled_jacobian", s.mean_scaled_jacobian).set("max_orthogonality_deg", s.max_orthogonality_deg);
        n.set("columns", s.columns).set("stopped_nodes", s.stopped_nodes).set("held_nodes", s.held_nodes);
        n.set("mean_orthogonality_deg", s.mean_orthogonality_deg).set("sweeps", s.sweeps);
        n.set("transition_cells", s.transition_cells).set("min_transition_jacobian", s.min_transition_jacobian);
        rows.emplace_back(std::move(n));
    }
    return rows;
}

/// The figures of \p c (a wall patch's, or the whole wall's) into \p p.
void set_patch_coverage(ReportNode& p, const PatchCoverage& c) {
    ReportNode short_by;
    for (std::size_t k = 1; k < kShortfalls; ++k)  // every reason but None, by name
        short_by.set(std::string(to_string(static_cast<Shortfall>(k))), c.short_by[k]);
    p.set("faces", c.faces).set("nodes", c.nodes).set("full_nodes", c.full_nodes).set("all_layers", c.all_layers);
    p.set("unbound_nodes", c.unbound_nodes).set("unbound_all_layers", c.unbound_all_layers);
    p.set("mean_share", c.mean_share).set("unbound_mean_share", c.unbound_mean_share).set("min_share", c.min_share);
    p.set("mean_layers", c.mean_layers).set("min_layers", c.min_layers).set("short", std::move(short_by));
}

/// "coverage": the whole wall's figures, its shares, and its short nodes split into those short
/// for their own reason and those short only because of a neighbour.
ReportNode wall_coverage(const PatchCoverage& c) {
    ReportNode w;
    set_patch_coverage(w, c);
    w.set("all_layers_share", c.all_layers_share()).set("unbound_all_layers_share", c.unbound_all_layers_share());
    w.set("own_reason_nodes", c.own_reason_nodes()).set("neighbour_nodes", c.short_nodes(Shortfall::Neighbours));
    return w;
}

/// "coverage", "patches", "short_nodes" and "no_fan_nodes" of \p r.
void set_coverage(ReportNode& n, const LayerReport& r) {
    ReportValue::List patches, short_nodes, no_fan;
    for (const PatchCoverage& c : r.patches) {
        ReportNode p;
        p.set("name", c.name);
        set_patch_coverage(p, c);
        patches.emplace_back(std::move(p));
    }
    for (const ShortNode& s : r.short_nodes) {
        ReportNode p;
        p.set("node", s.node).set("position", point(s.position)).set("share", s.share).set("layers", s.layers);
        p.set("reason", std::string(to_string(s.reason)));
        short_nodes.emplace_back(std::move(p));
    }
    for (const NoFanNode& s : r.no_fan) {
        ReportNode p;
        p.set("node", s.node).set("position", point(s.position)).set("reason", std::string(to_string(s.reason)));
        no_fan.emplace_back(std::move(p));
    }
    n.set("coverage", wall_coverage(r.wall));
    n.set("patches", std::move(patches)).set("short_nodes", std::move(short_nodes));
    n.set("no_fan_nodes", std::move(no_fan));
}

void set_counts(ReportNode& n, const LayerCounts& c) {
    n.set("unsmoothed_nodes", c.unsmoothed_nodes).set("thinned_nodes", c.thinned_nodes);
    n.set("min_thickness_share", c.min_thickness_share).set("fan_edges", c.fan_edges).set("fan_nodes", c.fan_nodes);
    n.set("fan_corners", c.fan_corners).set("fan_plane_nodes", c.fan_plane_nodes);
}

/// The mesh's figures (quality_report's keys) at the root of \p n.
void set_quality(ReportNode& n, const ValidationReport& v, const VolumeMesh* mesh) {
    ReportNode q = quality_report(v, mesh);
    for (const ReportNode::Entry& e : q.entries()) n.set(e.key, e.value);
}

ReportNode tet_improve_report(const TetImproveReport& ti) {
    ReportNode n;
    n.set("below", ti.below).set("flips", ti.flips).set("edge_removals", ti.edge_removals);
    n.set("moved_nodes", ti.moved_nodes).set("inserted_nodes", ti.inserted_nodes);
    n.set("below_before", ti.below_before).set("below_after", ti.below_after).set("min_before", ti.min_before);
    n.set("min_after", ti.min_after).set("skew_changes", ti.skew_changes).set("skewed_before", ti.skewed_before);
    n.set("skewed_after", ti.skewed_after).set("seconds", ti.seconds).set("budget_reached", ti.budget_reached);
    return n;
}

/// "surface" (when given: with its walls against the first layer of \p options if the surface
/// was kept as it is), "times" and "provenance".
void set_run(ReportNode& n, const SurfaceMesh* surface, const PrepareReport* prepared, const Options& options,
             const StageTimes& times) {
    if (surface && prepared) {
        const bool cad = any_cad_input(options.surface.inputs);
        ReportNode s = surface_report(*surface, *prepared, cad);
        const double max_aspect_ratio = options.surface.prepare.cad.max_aspect_ratio;
        if (!cad && !prepared->remeshed && max_aspect_ratio > 0.0) {
            const double h = resolve(layer_params(options.layers).distribution).first_height;
            if (h > 0.0) s.set("wall_aspect", wall_aspect_report(*surface, h, max_aspect_ratio));
        }
        n.set("surface", std::move(s));
    }
    ReportNode t;
    for (const auto& [stage, seconds] : times) t.set(stage, seconds);
    n.set("times", std::move(t)).set("provenance", provenance_report(options));
}

}  // namespace

std::string strata_version() {
    return STRATA_VERSION;
}
std::string strata_commit() {
    return STRATA_GIT_COMMIT;
}

ReportNode provenance_report(const Options& options) {
    Options given = options, defaults;
    ReportNode opts;
    for (const OptionSpec& spec : option_table()) {
        std::visit(
            [&](auto field) {
                const auto& value = field(given);
                if (value == field(defaults)) return;
                const std::string key = !spec.keyword.empty() ? spec.keyword : spec.flag.substr(2);
                opts.set(key, option_value(value));
            },
            spec.field);
    }
    ReportNode n;
    n.set("strata_version", strata_version()).set("git_commit", strata_commit());
    n.set("inputs", ReportValue::list_of(options.surface.inputs)).set("options", std::move(opts));
    return n;
}

namespace {

/// The open boundary loops of \p s, counted as the groups of free edges joined at nodes
/// (boundary_loops refuses loops that touch at a node, which a surface can have that the mesh
/// stage goes on to refuse with its own error).
Index open_loop_count(const SurfaceMesh& s) {
    const EdgeTable et = edge_table(s);
    UnionFind joined(static_cast<std::size_t>(s.num_points()));
    std::vector<char> on_free(static_cast<std::size_t>(s.num_points()), 0);
    for (std::size_t e = 0; e < et.nodes.size(); ++e)
        if (et.faces.row_size(static_cast<Index>(e)) == 1) {
            joined.unite(et.nodes[e][0], et.nodes[e][1]);
            on_free[static_cast<std::size_t>(et.nodes[e][0])] = on_free[static_cast<std::size_t>(et.nodes[e][1])] = 1;
        }
    Index loops = 0;
    for (Index v = 0; v < s.num_points(); ++v) loops += on_free[static_cast<std::size_t>(v)] && joined.find(v) == v;
    return loops;
}

}  // namespace

ReportNode surface_report(const SurfaceMesh& s, const PrepareReport& r, bool cad_input) {
    ReportNode n;
    n.set("nodes", s.num_points()).set("triangles", s.num_triangles()).set("quads", s.num_quads());
    n.set("patches", s.patches.size());
    std::vector<Index> faces(s.patches.size(), 0);
    for (const Index p : s.face_patch) ++faces[static_cast<std::size_t>(p)];
    ReportValue::List table;
    for (std::size_t i = 0; i < s.patches.size(); ++i) {
        ReportNode p;
        p.set("name", s.patches[i].name).set("kind", std::string(to_string(s.patches[i].kind))).set("faces", faces[i]);
        if (!s.patches[i].body.empty()) p.set("body", s.patches[i].body);
        table.emplace_back(std::move(p));
    }
    n.set("patch_table", std::move(table)).set("cad_input", cad_input);
    n.set("open_loops", open_loop_count(s));
    n.set("merged_nodes", r.merged_nodes).set("collapsed_faces", r.collapsed_faces);
    n.set("duplicate_faces", r.duplicate_faces).set("t_junctions", r.t_junctions);
    ReportNode cracks;
    cracks.set("split_faces", r.cracks.split).set("widest_gap", r.cracks.widest).set("at", point(r.cracks.at));
    n.set("cracks", std::move(cracks));
    ReportNode hanging;
    hanging.set("sheets", r.hanging.sheets).set("faces", r.hanging.faces).set("at", point(r.hanging.at));
    n.set("hanging_sheets", std::move(hanging));
    n.set("flipped_faces", r.orient.flipped_faces).set("components", r.orient.components);
    n.set("closed_components", r.orient.closed_components).set("fused_components", r.fused_components);
    n.set("fused_slivers", r.fused_slivers).set("touching_faces", r.touching_faces).set("remeshed", r.remeshed);
    n.set("internal_flow", r.internal_flow).set("units", r.units.unit).set("declared_units", r.units.declared);
    n.set("scale", r.scale).set("blossom_failure", r.recombination.blossom_failure);
    n.set("blossom_folded", r.recombination.folded);
    n.set("walls", walls_report(r.remeshed ? r.remesh.walls : r.walls));
    ReportNode holes;
    holes.set("filled", r.holes.holes).set("triangles", r.holes.triangles).set("largest", r.holes.largest);
    holes.set("where", point(r.holes.where)).set("left", r.holes.left).set("largest_left", r.holes.largest_left);
    holes.set("max_edges", r.holes.max_edges).set("caps", r.holes.caps);
    n.set("holes", std::move(holes)).set("sewn", sewing_report(r.sew)).set("steps", steps_report(r.steps));
    n.set("aspect_remesh", aspect_remesh_report(r.aspect_remesh));
    const ShortEdgeReport& e = r.short_edges;
    ReportNode edges;
    edges.set("collapsed", e.collapsed).set("longest", e.longest).set("largest_share", e.largest_share);
    edges.set("where", point(e.where)).set("left", e.left);
    n.set("short_edges", std::move(edges));
    n.set("wrapped", r.wrapped).set("touching_wrapped", r.touching_wrapped);
    if (r.wrapped) n.set("wrap", wrap_report(r.wrap));
    if (r.remeshed) n.set("remesh", remesh_report(r.remesh));
    n.set("needles", needles_report(s));
    return n;
}

ReportNode quality_report(const ValidationReport& v, const VolumeMesh* mesh) {
    ReportNode cells, min_sj, worst, histograms, foam;
    min_sj.set("all", v.min_scaled_jacobian);
    worst.set("all", v.worst_cell);
    for (const CellType t : kCellTypes) {
        const auto& q = v.by_type[static_cast<std::size_t>(t)];
        Index count = 0;
        for (const Index c : q.histogram) count += c;
        const std::string name(to_string(t));
        cells.set(name, count);
        if (count == 0) continue;
        min_sj.set(name, q.min_scaled_jacobian);
        worst.set(name, q.worst_cell);
        histograms.set(name, ReportValue::list_of(q.histogram));
    }
    std::vector<double> edges{0.0};
    for (int b = 0; b < kQualityBins; ++b) edges.push_back(quality_bin_edge(b));
    const SolverChecks& f = v.solver;
    foam.set("max_non_orthogonality_deg", f.max_non_orthogonality_deg);
    foam.set("mean_non_orthogonality_deg", f.mean_non_orthogonality_deg);
    foam.set("severely_non_orthogonal_faces", f.severely_non_orthogonal);
    foam.set("non_orthogonality_errors", f.non_orthogonality_errors);
    foam.set("worst_non_orthogonal", f.worst_non_orthogonal).set("max_skewness", f.max_skewness);
    foam.set("skew_faces", f.skew_faces).set("worst_skew", f.worst_skew).set("max_aspect_ratio", f.max_aspect_ratio);
    foam.set("high_aspect_cells", f.high_aspect_cells).set("worst_aspect", f.worst_aspect);
    foam.set("worst_aspect_type", std::string(to_string(f.worst_aspect_type)));
    foam.set("negative_pyramids", f.negative_pyramids).set("unused_points", f.unused_points).set("check_mesh_ok", f.ok());
    foam.set("failures", ReportValue::list_of(f.failures()));
    ReportNode q;
    q.set("min_scaled_jacobian", std::move(min_sj)).set("bin_edges", ReportValue::list_of(edges));
    q.set("histograms", std::move(histograms)).set("openfoam", std::move(foam)).set("worst_cell", std::move(worst));
    q.set("cell_volume", v.cell_volume).set("boundary_volume", v.boundary_volume);
    ReportNode n;
    if (mesh) n.set("nodes", mesh->points.size());
    n.set("cells", std::move(cells)).set("quality", std::move(q));
    return n;
}

ReportNode surface_run_report(const SurfaceMesh& surface, const PrepareReport& report, const Options& options,
                              const StageTimes& times) {
    ReportNode n = surface_report(surface, report, any_cad_input(options.surface.inputs));
    set_run(n, nullptr, nullptr, options, times);
    return n;
}

ReportNode layers_run_report(const LayerMesh& lm, const LayerReport& coverage, const ValidationReport& validation,
                             const SurfaceMesh* surface, const PrepareReport* prepared, const Options& options,
                             const StageTimes& times) {
    ReportNode n;
    set_asked(n, coverage);
    set_quality(n, validation, &lm.mesh);
    n.set("layer_stats", layer_stats(lm.stats));
    set_coverage(n, coverage);
    set_counts(n, lm);
    set_run(n, surface, prepared, options, times);
    return n;
}

ReportNode mesh_run_report(const VolumeMesh* mesh, const HybridReport& hr, const SurfaceMesh* surface,
                           const PrepareReport* prepared, const Options& options, const StageTimes& times) {
    ReportNode n;
    set_asked(n, hr.coverage);
    set_quality(n, hr.validation, mesh);
    n.set("layer_stats", layer_stats(hr.layers.stats));
    set_coverage(n, hr.coverage);
    set_counts(n, hr.layers);
    n.set("internal_flow", hr.internal_flow).set("closed_half_model", hr.closed_half_model);
    n.set("front_rounds", hr.front_rounds).set("front_lowered_nodes", hr.front_lowered_nodes);
    n.set("tet_retries", hr.tet_retries).set("split_quads", hr.split_quads).set("skew_capped", hr.skew_capped);
    const auto patch_name = [&](Index p) {
        return mesh ? mesh->boundary.patches[static_cast<std::size_t>(p)].name : std::to_string(p);
    };
    ReportNode planes;  // patch name -> the planes it was re-meshed as
    for (const auto& [p, count] : hr.planes_of_patches) planes.set(patch_name(p), count);
    ReportValue::List remeshed;
    for (const Index p : hr.remeshed_patches) remeshed.emplace_back(patch_name(p));
    n.set("planes_of_patches", std::move(planes)).set("remeshed_patches", std::move(remeshed));
    n.set("tets_fallback", hr.tets_fallback);
    n.set("tet_improve", tet_improve_report(hr.tet_improve));
    StageTimes all = times;
    for (const auto& [stage, seconds] : StageTimes{{"layers", hr.seconds_layers},
                                                   {"pyramids", hr.seconds_pyramids},
                                                   {"tetrahedra", hr.seconds_tets},
                                                   {"validation", hr.seconds_validate}})
        all.emplace_back(stage, seconds);
    set_run(n, surface, prepared, options, all);
    return n;
}

void set_time(ReportNode& report, const std::string& stage, double seconds) {
    const ReportValue* t = report.find("times");
    ReportNode times = t ? t->node() : ReportNode();
    times.set(stage, seconds);
    report.set("times", std::move(times));
}

}  // namespace strata
