#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/geometry/check.h>
#include <strata/geometry/intersections.h>
#include <strata/geometry/topology.h>
#include <strata/geometry/touching.h>
#include <strata/io/files.h>
#include <strata/io/input_file.h>
#include <strata/io/read_surface.h>
#include <strata/surface/cad.h>
#include <strata/surface/prepare.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <set>

namespace strata {
namespace {

/// \p stage's result, its topology and input errors named after \p source: the stages after
/// check_surface (filling holes, orienting, fusing, collapsing short edges) name faces, nodes
/// and edges, not the file they came from.
template <class F>
auto naming(const std::string& source, F&& stage) -> decltype(stage()) {
    const auto named = [&](const std::exception& e) {
        const std::string what = e.what();
        return what.compare(0, source.size(), source) == 0 ? what : source + ": " + what;
    };
    try {
        return stage();
    } catch (const TopologyError& e) {
        throw TopologyError(named(e));
    } catch (const InputError& e) {
        throw InputError(named(e));
    }
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

/// The reader for \p path's extension: CAD through Gmsh (mesh_cad), STL and MSH through io/.
SurfaceMesh read_any(const std::string& path, const PrepareParams& params, const CadParams& cad, CadUnits* units,
                     WallSizeReport* walls, SewReport* sew, RecombinationReport* recombination,
                     const Progress* progress) {
    check_input_source(path);  // not check_input_file: opening a pipe here would lose what it holds
    if (is_cad_file(path)) {
        CadParams with_kinds = cad;
        with_kinds.wall_patch_kinds = params.patch_kinds;
        WallSizeReport one;
        SewReport sewn;
        RecombinationReport recombined;
        SurfaceMesh mesh = mesh_cad(path, with_kinds, units, &one, &sewn, &recombined, progress);
        // Several inputs: the first file whose recombination fell back says so.
        if (recombination && recombination->blossom_failure.empty()) *recombination = recombined;
        if (sew) sew->written_twice += sewn.written_twice;
        if (sew && sewn.coincident > 0) {  // several inputs: summed, the first located
            if (sew->coincident == 0)
                sew->coincident_surface = sewn.coincident_surface, sew->coincident_with = sewn.coincident_with,
                sew->coincident_at = sewn.coincident_at;
            sew->coincident += sewn.coincident;
            sew->coincident_distance = std::max(sew->coincident_distance, sewn.coincident_distance);
        }
        if (sew && sewn.ignored > 0) {  // several inputs: summed, the first located
            if (sew->ignored == 0) sew->ignored_surface = sewn.ignored_surface, sew->ignored_at = sewn.ignored_at;
            sew->ignored += sewn.ignored;
        }
        if (sew && sewn.faces > 0) {
            // Several inputs: summed, the widest gap and the largest tolerance kept.
            sew->faces += sewn.faces;
            sew->free_before += sewn.free_before;
            sew->free_after += sewn.free_after;
            sew->solids += sewn.solids;
            sew->cracks += sewn.cracks;
            sew->tolerance = std::max(sew->tolerance, sewn.tolerance);
            sew->first_tolerance = std::max(sew->first_tolerance, sewn.first_tolerance);
            sew->gap_before = std::max(sew->gap_before, sewn.gap_before);
            sew->suggested_tolerance = std::max(sew->suggested_tolerance, sewn.suggested_tolerance);
            if (sewn.widest_gap > sew->widest_gap) sew->widest_gap = sewn.widest_gap, sew->gap_at = sewn.gap_at;
            sew->renumbered = sew->renumbered || sewn.renumbered;
            sew->rejected = sew->rejected || sewn.rejected;
            sew->moved = std::max(sew->moved, sewn.moved);
        }
        if (walls) {
            // Several inputs: the worst of them, the caps' surfaces and faces summed.
            walls->max_aspect_ratio = one.max_aspect_ratio;
            walls->worst_before = std::max(walls->worst_before, one.worst_before);
            walls->worst_after = std::max(walls->worst_after, one.worst_after);
            walls->cap = std::max(walls->cap, one.cap);
            walls->surfaces += one.surfaces;
            walls->curves += one.curves;
            walls->faces_estimate += one.faces_estimate;
            walls->over_budget = walls->over_budget || one.over_budget;
            if (one.thin_size > 0.0 && (walls->thin_size == 0.0 || one.thin_size < walls->thin_size))
                walls->thin_size = one.thin_size, walls->default_size = one.default_size;
            if (one.walls_default_size > 0.0 && (walls->walls_default_size == 0.0 ||
                                                  one.walls_default_size < walls->walls_default_size)) {
                walls->walls_default_size = one.walls_default_size;
                walls->default_size = one.default_size;
            }
            walls->narrow_ratio = one.narrow_ratio;
            if (one.narrow_faces > 0 && (walls->narrow_faces == 0 || one.narrowest < walls->narrowest))
                walls->narrowest = one.narrowest, walls->narrowest_surface = one.narrowest_surface;
            if (one.narrow_faces > 0)
                walls->narrow_size =
                    walls->narrow_faces == 0 ? one.narrow_size : std::min(walls->narrow_size, one.narrow_size);
            walls->narrow_faces += one.narrow_faces;
            walls->narrow_faces_estimate += one.narrow_faces_estimate;
            walls->narrow_over_budget = walls->narrow_over_budget || one.narrow_over_budget;
        }
        return mesh;
    }
    const std::string ext = lower_extension(path);
    if (ext == ".stl") return read_stl(path);
    if (ext == ".msh") return read_msh(path);
    throw InputError("'" + path + "': unknown file type '" + ext +
                     "'; Strata reads CAD (.step .stp .iges .igs .brep .brp .geo) and surface "
                     "meshes (.stl .msh)");
}

}  // namespace

namespace {

/// The patches of \p mesh, "a, b, c", for messages.
std::string patch_list(const SurfaceMesh& mesh) {
    std::string list, bodies;
    std::set<std::string> seen;
    for (const Patch& p : mesh.patches) {
        list += (list.empty() ? "" : ", ") + p.name;
        if (!p.body.empty() && seen.insert(p.body).second) bodies += (bodies.empty() ? "" : "', '") + p.body;
    }
    return bodies.empty() ? list : list + "; the bodies (each naming all its patches): '" + bodies + "'";
}

/// The patches \p name names: the one of that name, else of the word the readers make of it (an
/// STL solid "Wing Body (left)" is the patch Wing_Body_left), else every patch of the CAD body
/// of that name (Patch::body, either form); none.
std::vector<Index> named_patches(const SurfaceMesh& mesh, const std::string& name) {
    if (name.empty()) return {};
    const std::string word = patch_word(name, 0);
    for (const std::string& n : {name, word})
        if (const Index i = find_patch(mesh, n); i != kNone) return {i};
    std::vector<Index> of_body;
    for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
        const std::string& body = mesh.patches[i].body;
        if (!body.empty() && (body == name || patch_word(body, 0) == word)) of_body.push_back(static_cast<Index>(i));
    }
    return of_body;
}

/// A patch name OpenFOAM and CGNS both take as it is.
bool solver_name(const std::string& name) {
    if (name.empty() || name.size() > 32 || !(std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_'))
        return false;
    return std::all_of(name.begin(), name.end(),
                       [](unsigned char c) { return std::isalnum(c) || c == '_' || c == '-'; });
}

}  // namespace

PatchKind patch_kind_of(const std::string& name, const std::vector<std::pair<std::string, PatchKind>>& kinds) {
    for (auto it = kinds.rbegin(); it != kinds.rend(); ++it)
        if (it->first == name) return it->second;
    const std::string n = lower(name);
    if (n.find("symmetry") != std::string::npos) return PatchKind::Symmetry;
    if (n.find("farfield") != std::string::npos) return PatchKind::Farfield;
    return PatchKind::Wall;
}

void assign_patch_kinds(SurfaceMesh& mesh, const std::vector<std::pair<std::string, PatchKind>>& kinds,
                        const std::string& source) {
    for (Patch& p : mesh.patches) p.kind = patch_kind_of(p.name, {});
    for (const auto& [name, kind] : kinds) {
        const std::vector<Index> named = named_patches(mesh, name);
        if (named.empty()) {
            throw InputError(source + ": PrepareParams::patch_kinds " + name + "=" + std::string(to_string(kind)) +
                             ": no patch named '" + name + "'; the patches are: " + patch_list(mesh));
        }
        for (const Index i : named) mesh.patches[static_cast<std::size_t>(i)].kind = kind;
    }
}

void rename_patches(SurfaceMesh& mesh, const std::vector<std::pair<std::string, std::string>>& names,
                    const std::string& source) {
    if (names.empty()) return;
    for (const auto& [from, to] : names) {
        const std::vector<Index> named = named_patches(mesh, from);
        if (named.empty())
            throw InputError(source + ": PrepareParams::patch_names " + from + " -> " + to + ": no patch named '" +
                             from + "'; the patches are: " + patch_list(mesh));
        if (!solver_name(to))
            throw InputError(source + ": PrepareParams::patch_names " + from + " -> '" + to +
                             "': a patch name must start with a letter or _ and hold only letters, digits, _ and -, "
                             "at most 32 (OpenFOAM and CGNS take it as it is)");
        for (const Index i : named) mesh.patches[static_cast<std::size_t>(i)].name = to;
    }
    // Patches that now carry a name given by a rename become the first patch of that name.
    std::set<std::string> given;
    for (const auto& n : names) given.insert(n.second);
    std::vector<Index> into(mesh.patches.size());
    std::vector<Patch> kept;
    for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
        const Patch& p = mesh.patches[i];
        auto same = std::find_if(kept.begin(), kept.end(), [&](const Patch& k) { return k.name == p.name; });
        if (!given.count(p.name) || same == kept.end()) {
            into[i] = static_cast<Index>(kept.size());
            kept.push_back(p);
            continue;
        }
        if (same->kind != p.kind)
            throw InputError(source + ": PrepareParams::patch_names gives patches of kinds " +
                             std::string(to_string(same->kind)) + " and " + std::string(to_string(p.kind)) +
                             " one name, '" + p.name + "'; give them one kind or two names");
        into[i] = static_cast<Index>(same - kept.begin());
    }
    for (Index& p : mesh.face_patch) p = into[static_cast<std::size_t>(p)];
    mesh.patches = std::move(kept);
}

namespace {

/// InputError naming \p source unless \p params' numbers are in their ranges.
void check_prepare_params(const PrepareParams& params, const std::string& source) {
    if (!(params.scale > 0.0) || !std::isfinite(params.scale))
        throw InputError(source + ": PrepareParams::scale = " + format_number(params.scale) +
                         ": need a positive, finite factor");
    if (!(params.collapse_ratio >= 0.0 && params.collapse_ratio <= 0.5))
        throw InputError(source + ": PrepareParams::collapse_ratio = " + format_number(params.collapse_ratio) +
                         ": need a share of the local edge length in [0, 0.5] (0: no edge collapsed)");
    if (!(params.fill_holes >= 0 && params.fill_holes <= 10000))
        throw InputError(source + ": PrepareParams::fill_holes = " + std::to_string(params.fill_holes) +
                         ": need a number of edges in [0, 10000] (0: no hole filled)");
    if (params.caps && params.fill_holes == 0)
        throw InputError(source + ": PrepareParams::caps closes the loops PrepareParams::fill_holes closes, and that "
                                  "is 0: give the most edges an opening has (PrepareParams::fill_holes 1000)");
    if (!(params.merge_tolerance >= 0.0 && params.merge_tolerance <= 1e-3))
        throw InputError(source + ": PrepareParams::merge_tolerance = " + format_number(params.merge_tolerance) +
                         ": need a share of the model's size in [0, 0.001] (nodes closer than it are one; a larger "
                         "one would merge the nodes of real features)");
}

/// PrepareParams::patch_kinds and patch_names split: those naming a cap the surface has not got
/// yet (PrepareParams::caps; cap_1, cap_2, ...) and the others.
struct CapOptions {
    std::vector<std::pair<std::string, PatchKind>> cap_kinds, other_kinds;
    std::vector<std::pair<std::string, std::string>> cap_names, other_names;
};

CapOptions cap_options(const SurfaceMesh& raw, const PrepareParams& params) {
    const auto is_cap = [&](const std::string& name) {
        return params.caps && name.rfind("cap_", 0) == 0 && find_patch(raw, name) == kNone;
    };
    CapOptions o;
    for (const auto& k : params.patch_kinds) (is_cap(k.first) ? o.cap_kinds : o.other_kinds).push_back(k);
    for (const auto& n : params.patch_names) (is_cap(n.first) ? o.cap_names : o.other_names).push_back(n);
    return o;
}

/// The kinds and names \p o gives the caps, applied to \p capped; InputError naming a cap it
/// has not got.
void name_caps(SurfaceMesh& capped, const CapOptions& o, const std::string& source) {
    for (const auto& [name, kind] : o.cap_kinds) {
        const Index i = find_patch(capped, name);
        if (i == kNone)
            throw InputError(source + ": PrepareParams::patch_kinds " + name + "=" + std::string(to_string(kind)) +
                             ": no cap named '" + name + "' (PrepareParams::caps closed " +
                             std::to_string(std::count_if(capped.patches.begin(), capped.patches.end(),
                                                          [](const Patch& p) { return p.name.rfind("cap_", 0) == 0; })) +
                             " loops); the patches are: " + patch_list(capped));
        capped.patches[static_cast<std::size_t>(i)].kind = kind;
    }
    rename_patches(capped, o.cap_names, source);
}

/// How far off the edge beside them (a share of its length) nodes of a crack may lie: a curved
/// edge's sagitta over its chord is about an eighth of the angle the chord spans, 0.1 at 45°.
constexpr double kCrackShare = 0.1;

/// \p raw with coincident nodes merged, faces with a repeated node and copies of faces removed,
/// T-junctions split, cracks closed where that closes the surface, and sheets hanging off it
/// removed where that leaves it manifold; \p rep counts each.
SurfaceMesh clean_faces(const SurfaceMesh& raw, const PrepareParams& params, const std::string& source,
                        PrepareReport& rep) {
    SurfaceMesh merged = naming(source, [&] { return merge_coincident_nodes(raw, params.merge_tolerance); });
    rep.merged_nodes = raw.num_points() - merged.num_points();
    merged = remove_collapsed_faces(merged, &rep.collapsed_faces);
    // One edge table for both (the surface is the same unless a copy went).
    const EdgeTable edges = edge_table(merged);
    merged = remove_duplicate_faces(merged, edges, &rep.duplicate_faces);
    merged = rep.duplicate_faces > 0 ? split_t_junctions(merged, &rep.t_junctions)
                                     : split_t_junctions(merged, edges, &rep.t_junctions);
    const EdgeTable now = rep.duplicate_faces > 0 || rep.t_junctions > 0 ? edge_table(merged) : edges;
    bool open = false;
    for (Index e = 0; e < now.faces.rows() && !open; ++e) open = now.faces.row_size(e) == 1;
    if (open) merged = stitch_cracks(merged, kCrackShare, &rep.cracks);
    return remove_hanging_sheets(merged, &rep.hanging);
}

/// Bodies touching along a common face: the walls between them are not the union's, so removed
/// from \p mesh. The number removed.
Index remove_touching_faces(SurfaceMesh& mesh) {
    const std::vector<Index> back_to_back = touching_faces(mesh);
    if (back_to_back.empty()) return 0;
    std::vector<char> drop(static_cast<std::size_t>(mesh.num_faces()), 0);
    for (const Index f : back_to_back) drop[static_cast<std::size_t>(f)] = 1;
    mesh = remove_faces(mesh, drop);
    return static_cast<Index>(back_to_back.size());
}

/// What check_merged_surface adds to an error where the surface cannot be mended in place.
constexpr const char* kWrapHint =
    " (where the surface cannot be repaired, PrepareParams::wrap replaces it by a watertight surface wrapped "
    "round it)";

/// check_surface; without fusing, its TopologyError says where bodies touch back to back; any
/// other names the wrap.
void check_merged_surface(const SurfaceMesh& merged, const PrepareParams& params, const std::string& source) {
    try {
        check_surface(merged, source);
    } catch (const TopologyError& e) {
        const std::vector<Index> back_to_back = params.fuse ? std::vector<Index>{} : touching_faces(merged);
        if (back_to_back.empty()) throw TopologyError(std::string(e.what()) + (params.wrap ? "" : kWrapHint));
        throw TopologyError(std::string(e.what()) + ". Bodies touch there: " + std::to_string(back_to_back.size()) +
                            " faces lie back to back on another body's (the first, " +
                            describe_face(merged, back_to_back.front()) +
                            "); fusing the bodies into one (CadParams::fuse) removes them");
    }
}

/// TopologyError naming \p source where openings of the oriented surface touch at a node (each
/// must be a loop of its own for the mesh stage to close or fill it), with the wrap's hint.
void check_openings(const SurfaceMesh& oriented, const PrepareParams& params, const std::string& source) {
    try {
        naming(source, [&] { return boundary_loops(oriented); });
    } catch (const TopologyError& e) {
        throw TopologyError(std::string(e.what()) + (params.wrap ? "" : kWrapHint));
    }
}

/// \p raw replaced by its alpha wrap (PrepareParams::wrap), its figures in \p rep; InputError
/// naming the first patch that is not a wall's (a wrap would close a symmetry plane's cut or
/// turn a farfield into a body).
SurfaceMesh wrap_soup(const SurfaceMesh& raw, const PrepareParams& params, const std::string& source,
                      PrepareReport& rep) {
    for (const Patch& p : raw.patches)
        if (p.kind != PatchKind::Wall)
            throw InputError(source + ": PrepareParams::wrap wraps the walls as one closed body, but patch '" +
                             p.name + "' is " + std::string(to_string(p.kind)) +
                             " (a wrap would close over it); wrap the body alone, or make the patch a wall "
                             "(PrepareParams::patch_kinds " +
                             p.name + "=wall)");
    SurfaceMesh wrapped = naming(source, [&] { return wrap_surface(raw, params.wrapping, &rep.wrap); });
    rep.wrapped = true;
    return wrapped;
}

/// \p oriented, whose parts touch along a line or a point only (\p why: fuse_components'
/// TouchingPartsError), wrapped into one (wrap_soup), checked and oriented; TopologyError where
/// a patch is not a wall's, which a wrap would close over.
SurfaceMesh wrap_touching(const SurfaceMesh& oriented, const PrepareParams& params, const std::string& source,
                          const std::string& why, PrepareReport& rep) {
    if (std::any_of(oriented.patches.begin(), oriented.patches.end(),
                    [](const Patch& p) { return p.kind != PatchKind::Wall; }))
        throw TopologyError(source + ": " + why +
                            "; PrepareParams::wrap would join them, but it wraps walls only");
    rep.touching_wrapped = true;
    const SurfaceMesh wrapped = wrap_soup(oriented, params, source, rep);
    check_surface(wrapped, source + " (wrapped)");
    return naming(source, [&] { return orient_surface(wrapped, &rep.orient, params.internal_flow); });
}

/// \p oriented with its overlapping bodies replaced by their union (fuse_components), then
/// merged, cleaned, checked and oriented again; \p rep counts what that did.
SurfaceMesh fuse_bodies(SurfaceMesh oriented, const PrepareParams& params, const std::string& source,
                        PrepareReport& rep) {
    FuseReport fuse;
    bool touching = false;
    std::string why;
    SurfaceMesh fused = naming(source, [&] {
        try {
            return fuse_components(oriented, &fuse);
        } catch (const TouchingPartsError& e) {
            touching = true, why = e.what();
            return SurfaceMesh{};
        }
    });
    if (touching) return wrap_touching(oriented, params, source, why, rep);
    rep.fused_components = fuse.fused;
    if (fuse.fused == 0) return oriented;
    // The union's faces with the untouched components: checked and oriented again.
    fused = naming(source, [&] { return merge_coincident_nodes(fused, params.merge_tolerance); });
    // The union's cuts can pass within the merge tolerance of a node (a cone's faceted
    // side across a sphere's vertex): merged, the sliver faces between repeat a node.
    Index reduced = 0;
    fused = remove_collapsed_faces(fused, &reduced);
    rep.collapsed_faces += reduced;
    // And where two bodies' facets nearly coincide, flat slivers (a cap, its apex on its
    // longest edge): flipped away.
    Index flipped = 0;
    fused = flip_flat_triangles(fused, 1e-6, &flipped);
    rep.fused_slivers = flipped;
    try {
        check_surface(fused, source + " (fused)", params.remesh);
    } catch (const TopologyError& e) {
        // The union's cuts where two bodies' facets nearly coincide (a cylinder and a cone
        // tessellated apart, meeting at one circle) can leave faces far smaller than
        // the mesh: remeshing rebuilds the surface over them.
        if (params.remesh) throw;
        throw TopologyError(std::string(e.what()) +
                            " (the union of the bodies left it where their facets nearly coincide: PrepareParams::remesh "
                            "rebuilds the united surface)");
    }
    return naming(source, [&] { return orient_surface(fused, &rep.orient, params.internal_flow); });
}

/// \p oriented remeshed (remesh_surface), merged, checked and oriented again.
SurfaceMesh remesh_oriented(const SurfaceMesh& oriented, const PrepareParams& params, const std::string& source,
                            PrepareReport& rep) {
    SurfaceMesh remeshed = remesh_surface(oriented, params.remeshing, source, &rep.remesh);
    remeshed = naming(source, [&] { return merge_coincident_nodes(remeshed, params.merge_tolerance); });
    check_surface(remeshed, source + " (remeshed)");
    OrientReport again;
    SurfaceMesh out = naming(source, [&] { return orient_surface(remeshed, &again, params.internal_flow); });
    rep.orient.flipped_faces += again.flipped_faces;
    return out;
}

/// The fields of \p rep that prepare_mesh fills, copied to \p report.
void copy_prepare_report(const PrepareReport& rep, const PrepareParams& params, PrepareReport& report) {
    report.short_edges = rep.short_edges;
    report.remeshed = params.remesh;
    report.wrapped = rep.wrapped;
    report.touching_wrapped = rep.touching_wrapped;
    report.wrap = rep.wrap;
    report.remesh = rep.remesh;
    report.recombination = rep.remesh.recombination;
    report.scale = params.scale;
    report.fused_components = rep.fused_components;
    report.fused_slivers = rep.fused_slivers;
    report.touching_faces = rep.touching_faces;
    report.internal_flow = params.internal_flow;
    report.merged_nodes = rep.merged_nodes;
    report.collapsed_faces = rep.collapsed_faces;
    report.duplicate_faces = rep.duplicate_faces;
    report.t_junctions = rep.t_junctions;
    report.cracks = rep.cracks;
    report.hanging = rep.hanging;
    report.holes = rep.holes;
    report.orient = rep.orient;
}

/// What reading the inputs reported, copied to \p report (the recombination only where
/// prepare_mesh's remeshing left none).
void copy_read_reports(const CadUnits& units, const WallSizeReport& walls, const SewReport& sew,
                       const RecombinationReport& recombination, PrepareReport& report) {
    report.units = units;
    report.walls = walls;
    report.sew = sew;
    if (report.recombination.blossom_failure.empty()) report.recombination = recombination;
}

}  // namespace

SurfaceMesh prepare_mesh(SurfaceMesh raw, const PrepareParams& params, const std::string& source, PrepareReport* report,
                         Progress* progress) {
    strata::report(progress, "surface", 0.6);
    check_prepare_params(params, source);
    if (params.scale != 1.0)
        for (Vec3& x : raw.points) x *= params.scale;
    // With caps, the mappings naming caps (cap_1, ...) apply once the caps exist.
    const CapOptions later = cap_options(raw, params);
    assign_patch_kinds(raw, later.other_kinds, source);
    rename_patches(raw, later.other_names, source);
    // Check the raw mesh for NaN and emptiness before merging (merging NaN points is meaningless).
    if (raw.num_faces() == 0) throw InputError(source + ": no faces; it holds no surface mesh");
    PrepareReport rep;
    if (params.wrap) raw = wrap_soup(raw, params, source, rep);
    SurfaceMesh merged = clean_faces(raw, params, source, rep);
    raw = SurfaceMesh{};  // the input copy is no longer needed
    strata::report(progress, "surface", 0.7);
    if (params.fuse) rep.touching_faces = remove_touching_faces(merged);
    check_merged_surface(merged, params, source);
    if (params.fill_holes > 0)
        merged = naming(source, [&] {
            return params.caps ? cap_holes(merged, params.fill_holes, &rep.holes)
                               : fill_holes(merged, params.fill_holes, &rep.holes);
        });
    if (params.caps) name_caps(merged, later, source);
    strata::report(progress, "surface", 0.8);
    SurfaceMesh oriented = naming(source, [&] { return orient_surface(merged, &rep.orient, params.internal_flow); });
    check_openings(oriented, params, source);
    if (params.fuse) oriented = fuse_bodies(std::move(oriented), params, source, rep);
    // Not before remeshing, which rebuilds the surface from the input's own edges: given the
    // collapsed glider STL, Gmsh's surfaces kept 148 needles instead of 4.
    if (params.collapse_ratio > 0.0 && !params.remesh) {
        SurfaceMesh shorter =
            naming(source, [&] { return collapse_short_edges(oriented, params.collapse_ratio, &rep.short_edges); });
        if (rep.short_edges.collapsed > 0) {
            check_surface(shorter, source + " (short edges collapsed)");
            oriented = std::move(shorter);
        }
    }
    if (params.remesh) {
        strata::report(progress, "surface", 0.9);
        oriented = remesh_oriented(oriented, params, source, rep);
    }
    if (report) copy_prepare_report(rep, params, *report);
    strata::report(progress, "surface", 1.0);
    return oriented;
}

SurfaceMesh prepare_surfaces(const std::vector<std::string>& paths, const PrepareParams& params, PrepareReport* report,
                             Progress* progress) {
    if (paths.empty()) throw InputError("no input file given; name one or more CAD or surface-mesh files");
    if (paths.size() == 1) return prepare_surface(paths[0], params, report, progress);
    strata::report(progress, "surface", 0.0);
    CadParams cad = params.cad;
    CadUnits units;
    WallSizeReport walls;
    SewReport sew;
    RecombinationReport recombination;
    SurfaceMesh all;
    std::string source;
    for (const std::string& path : paths) {
        CadUnits read_in;
        // Only STEP and IGES declare a unit; the others keep what was asked (an error if any).
        const std::string ext = lower_extension(path);
        const bool has_unit = ext == ".step" || ext == ".stp" || ext == ".iges" || ext == ".igs";
        CadParams this_cad = cad;
        if (!has_unit) this_cad.units = params.cad.units;
        const SurfaceMesh one = read_any(path, params, this_cad, &read_in, &walls, &sew, &recombination, progress);
        // The first CAD file with a unit sets it for the others (unless one was asked).
        if (!read_in.unit.empty() && units.unit.empty()) {
            units = read_in;
            if (cad.units.empty()) cad.units = read_in.unit;
        }
        const auto offset = static_cast<Index>(all.points.size());
        all.points.insert(all.points.end(), one.points.begin(), one.points.end());
        std::vector<Index> patch_of(one.patches.size());
        for (std::size_t p = 0; p < one.patches.size(); ++p) {
            Patch patch = one.patches[p];
            // A name an earlier file has: the file's after it, as one word ("part (b.stl)" is
            // part_b.stl, which --patch takes in either form).
            if (find_patch(all, patch.name) != kNone)
                patch.name = patch_word(patch.name + " (" + path.substr(path.find_last_of('/') + 1) + ")", p);
            patch_of[p] = static_cast<Index>(all.patches.size());
            all.patches.push_back(patch);
        }
        for (Index f = 0; f < one.num_faces(); ++f) {
            std::array<Index, 4> v{};
            for (Index i = 0; i < one.face_size(f); ++i) v[static_cast<std::size_t>(i)] = offset + one.face_node(f, i);
            all.add_face(v.data(), one.face_size(f), patch_of[static_cast<std::size_t>(one.face_patch[f])]);
        }
        source += (source.empty() ? "" : " + ") + path;
    }
    SurfaceMesh out = prepare_mesh(std::move(all), params, source, report, progress);
    if (report) copy_read_reports(units, walls, sew, recombination, *report);
    return out;
}

SurfaceMesh prepare_surface(const std::string& path, const PrepareParams& params, PrepareReport* report,
                            Progress* progress) {
    strata::report(progress, "surface", 0.0);
    CadUnits units;
    WallSizeReport walls;
    SewReport sew;
    RecombinationReport recombination;
    SurfaceMesh raw = read_any(path, params, params.cad, &units, &walls, &sew, &recombination, progress);
    SurfaceMesh out;
    try {
        out = prepare_mesh(std::move(raw), params, path, report, progress);
    } catch (const TopologyError& e) {
        // A surface model (faces, sewn here) of several bodies that share edges or faces (an
        // assembly written as IGES faces): sewing cannot tell the bodies apart.
        if (sew.faces == 0) throw;
        throw TopologyError(std::string(e.what()) + " (this CAD file is a surface model: its " +
                            std::to_string(sew.faces) +
                            " faces bound no solid and were sewn here, and where several bodies touch or share "
                            "an edge, sewing cannot tell them apart: export the bodies as solids, STEP or BREP, "
                            "and give CadParams::fuse)");
    }
    if (report) copy_read_reports(units, walls, sew, recombination, *report);
    return out;
}

}  // namespace strata
