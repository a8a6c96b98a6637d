// The whole pipeline after the surface (hybrid_mesh.h): close the domain if needed, the layers,
// the pyramids, the tetrahedra, then one mesh assembled from the stages' own numberings through
// explicit node maps, validated.

#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/format.h>
#include <strata/core/parallel.h>
#include <strata/geometry/intersections.h>
#include <strata/geometry/topology.h>
#include <strata/hybrid/hybrid_mesh.h>
#include <strata/hybrid/outer_boundary.h>
#include <strata/module/step_sizes.h>

#include "tet_fill_parts.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <type_traits>
#include <variant>

namespace strata {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// One point inside each cavity that the layer top encloses (a closed component of it, i.e. a
/// body not cut by a plane): the centroid of the first-layer cell on the component's first face
/// whose columns all have a layer; where none has (no column of the body grew), a point just
/// behind its first face, inside the body. Components ending on a plane open onto the outside
/// of the region and need none.
std::vector<Vec3> points_in_layers(const LayerMesh& lm) {
    Index nc = 0;
    const std::vector<Index> comp = face_components(lm.top, &nc);
    std::vector<char> open(static_cast<std::size_t>(nc), 0);
    const EdgeTable et = edge_table(lm.top);
    for (Index e = 0; e < static_cast<Index>(et.nodes.size()); ++e)
        if (et.faces.row_size(e) == 1)
            open[static_cast<std::size_t>(comp[static_cast<std::size_t>(*et.faces.row_begin(e))])] = 1;
    std::vector<Vec3> hole(static_cast<std::size_t>(nc), Vec3::Zero());
    std::vector<char> found(static_cast<std::size_t>(nc), 0);  // 0 none, 1 behind a face, 2 in a cell
    for (Index f = 0; f < lm.top.num_faces(); ++f) {
        const std::size_t c = static_cast<std::size_t>(comp[static_cast<std::size_t>(f)]);
        if (open[c] || found[c] == 2) continue;
        bool full = true;
        for (const Index* v = lm.top.face_begin(f); v != lm.top.face_end(f); ++v) full &= lm.node_layers(*v) >= 1;
        if (full) {
            Vec3 x = Vec3::Zero();
            for (const Index* v = lm.top.face_begin(f); v != lm.top.face_end(f); ++v)
                x += lm.mesh.points[lm.level_node(0, *v)] + lm.mesh.points[lm.level_node(1, *v)];
            hole[c] = x / (2.0 * static_cast<double>(lm.top.face_size(f))), found[c] = 2;
        } else if (!found[c]) {  // behind the wall face (its normal points into the flow)
            // Level 0 is the wall, node i being wall node i: the top's faces on mesh.points are the wall's.
            const Vec3 a = face_area_vector(lm.top, lm.mesh.points, f);
            if (a.norm() > 0.0)
                hole[c] = face_centroid(lm.top, lm.mesh.points, f) - 1e-3 * std::sqrt(a.norm()) * a.normalized(),
                found[c] = 1;
        }
    }
    std::vector<Vec3> holes;
    for (std::size_t c = 0; c < hole.size(); ++c)
        if (found[c]) holes.push_back(hole[c]);
    return holes;
}

/// The domain the layers grow in: \p input itself if it is closed (walls inside farfield,
/// symmetry or outflow patches, walls alone around a body, or walls alone around the fluid:
/// internal flow), a half model (walls alone, open along one plane) closed by a generated half
/// farfield and symmetry plane. \p has_outer: the input closes the fluid itself (no farfield
/// to generate); \p internal: it does so with walls alone.
SurfaceMesh closed_domain(const SurfaceMesh& input, const FarfieldParams& farfield, bool& has_outer,
                          bool& closed_half_model, bool& internal) {
    has_outer = internal = false;
    for (Index f = 0; f < input.num_faces(); ++f)
        has_outer |= input.patches[static_cast<std::size_t>(input.face_patch[f])].kind != PatchKind::Wall;
    closed_half_model = false;
    if (boundary_loops(input).rows() == 0) {
        // Walls alone pointing inward on the whole: the fluid is inside them (orient_surface's
        // internal flow), so there is no farfield to add.
        if (!has_outer && signed_volume(input) < 0.0) has_outer = internal = true;
        return input;
    }
    if (has_outer)
        throw InputError(
            "the fluid domain is open: its walls, symmetry, outflow and farfield patches must enclose it "
            "(a hole in the surface, or a patch missing from the input); close it, or run strata layers "
            "for the layers alone");
    has_outer = closed_half_model = true;
    return close_half_model(input, farfield);
}

/// The region the tetrahedra fill, with normals pointing out of it as TetGen wants: the
/// pyramid-capped layer top (patch top_patch) and the outer boundary, both reversed. Its points:
/// the pyramid surface's (the layer-top nodes, same ids, then the apexes), then the outer
/// boundary's own; outer points on the layer top are the top nodes already there.
SurfaceMesh region_to_fill(const std::vector<Patch>& patches, const PyramidLayer& pyr, const OuterBoundary& outer,
                           Index farfield_patch, Index& top_patch) {
    SurfaceMesh region;
    region.patches = patches;
    if (farfield_patch != kNone) region.patches.push_back({"farfield", PatchKind::Farfield});
    top_patch = static_cast<Index>(region.patches.size());
    region.patches.push_back({"layer_top", PatchKind::Other});
    region.points = pyr.surface.points;
    for (Index f = 0; f < pyr.surface.num_faces(); ++f)
        region.add_face(pyr.surface.face_begin(f), pyr.surface.face_size(f), top_patch);
    std::vector<Index> region_of(outer.mesh.points.size());
    for (std::size_t i = 0; i < outer.mesh.points.size(); ++i) {
        if (outer.top_node[i] != kNone) {
            region_of[i] = outer.top_node[i];
            continue;
        }
        region_of[i] = region.num_points();
        region.points.push_back(outer.mesh.points[i]);
    }
    for (Index f = 0; f < outer.mesh.num_faces(); ++f) {
        const Index* v = outer.mesh.face_begin(f);
        region.add_face({region_of[static_cast<std::size_t>(v[0])], region_of[static_cast<std::size_t>(v[1])],
                         region_of[static_cast<std::size_t>(v[2])]},
                        farfield_patch != kNone ? farfield_patch : outer.mesh.face_patch[f]);
    }
    flip_faces(region);  // the layer top and the outer boundary point into the fluid: out of the region
    return region;
}

/// Before any layer: the layers asked (\p asked thick) must fit between the body and the
/// farfield build_hybrid_mesh generates around it, with the share proximity leaves any other
/// patch (0.9); else an InputError with the numbers and the farfield size that would do. The
/// farfield is convex about the body's bounding-box centre: its clearance is the least distance
/// from that centre to a face's plane, less the farthest body point's distance from it.
void check_layers_fit_farfield(const SurfaceMesh& surface, const FarfieldParams& farfield, double asked, double share) {
    const SurfaceMesh far = make_farfield(surface.points, farfield);
    const BoundingBox bb = bounding_box(surface.points);
    const Vec3 c = 0.5 * (bb.min + bb.max);
    double inscribed = std::numeric_limits<double>::infinity(), farthest = 0.0;
    for (Index f = 0; f < far.num_faces(); ++f) {
        const Vec3 n = face_area_vector(far, f);
        if (n.norm() > 0.0)
            inscribed = std::min(inscribed, std::abs((face_centroid(far, far.points, f) - c).dot(n.normalized())));
    }
    for (const Vec3& p : surface.points) farthest = std::max(farthest, (p - c).norm());
    const double clearance = inscribed - farthest;
    if (asked <= share * clearance) return;
    // The inscribed radius grows with the size; the body does not.
    const double needed = farfield.size * (asked / share + farthest) / inscribed;
    throw InputError("the layers asked are " + format_number(asked, 4) + " thick, but the generated farfield (" +
                     std::string(to_string(farfield.shape)) + ", FarfieldParams::size " +
                     format_number(farfield.size, 4) + ": that many times the body's diagonal across) leaves " +
                     format_number(std::max(clearance, 0.0), 4) +
                     " between the body and it, of which layers may take " + format_number(share * 100.0, 3) +
                     " %: enlarge FarfieldParams::size to " + format_number(std::ceil(needed * 10.0) / 10.0, 4) +
                     " or more, or ask for thinner layers (fewer, a smaller first height or growth)");
}

/// The outer boundary of the fluid domain: the input's non-wall patches, re-meshed where the
/// layers end on them, or a generated farfield (pointing into the fluid, as an input's would).
OuterBoundary outer_part(const SurfaceMesh& surface, const LayerMesh& lm, bool has_outer,
                         const FarfieldParams& farfield, double growth) {
    if (has_outer) return outer_boundary(surface, lm, growth);
    OuterBoundary outer;
    outer.mesh = make_farfield(surface.points, farfield);
    flip_faces(outer.mesh);  // outward → into the fluid
    outer.top_node.assign(outer.mesh.points.size(), kNone);
    return outer;
}

/// One mesh from the stages' numberings: the layers' nodes and cells as they are; the
/// pyramids' and tetrahedra's nodes (the fill's points: the region's, then Steiner points)
/// mapped so that layer-top nodes are the layers' top nodes and the rest follow the layers'
/// nodes in order; the boundary: the layers' (walls, sides on planes) but not their top, then
/// the region's outer faces.
/// Most planes a non-wall patch the layers end on is split into (split_into_planes): a wind
/// tunnel's five faces; a curved patch, faceted, would give a piece per few faces.
constexpr std::size_t kMostPlanes = 16;

/// The non-wall patches of \p surface that the walls meet (a node of a wall face on them) and
/// that are not planar but made of at most kMostPlanes planes (faces connected across an edge
/// whose nodes lie in one plane, to 1e-6 of the patch's size): each plane after the first
/// becomes a patch of its own, appended with the same kind (the hybrid stage re-meshes only
/// planar patches round the layers' sides). Returns, per appended patch, the patch it came from.
std::vector<Index> split_into_planes(SurfaceMesh& surface) {
    const auto np = static_cast<Index>(surface.patches.size());
    std::vector<char> wall_node(surface.points.size(), 0), meets(surface.patches.size(), 0);
    auto wall = [&](Index f) {
        return surface.patches[static_cast<std::size_t>(surface.face_patch[f])].kind == PatchKind::Wall;
    };
    for (Index f = 0; f < surface.num_faces(); ++f)
        if (wall(f))
            for (const Index* v = surface.face_begin(f); v != surface.face_end(f); ++v)
                wall_node[static_cast<std::size_t>(*v)] = 1;
    for (Index f = 0; f < surface.num_faces(); ++f)
        if (!wall(f))
            for (const Index* v = surface.face_begin(f); v != surface.face_end(f); ++v)
                if (wall_node[static_cast<std::size_t>(*v)]) meets[static_cast<std::size_t>(surface.face_patch[f])] = 1;
    std::vector<Index> from;
    const EdgeTable et = edge_table(surface);
    for (Index p = 0; p < np; ++p) {
        if (!meets[static_cast<std::size_t>(p)]) continue;
        const PatchPlane whole = patch_plane(surface, p);
        if (whole.planar()) continue;
        const double tol = 1e-6 * whole.size;
        // Grow each plane from its lowest unassigned face across edges to faces whose nodes lie
        // in the seed face's plane.
        std::vector<Index> piece(static_cast<std::size_t>(surface.num_faces()), kNone);
        std::vector<std::vector<Index>> pieces;
        for (Index seed = 0; seed < surface.num_faces() && pieces.size() <= kMostPlanes; ++seed) {
            if (surface.face_patch[seed] != p || piece[static_cast<std::size_t>(seed)] != kNone) continue;
            const Vec3 n = face_area_vector(surface, seed).normalized();
            const Vec3 o = surface.points[surface.face_node(seed, 0)];
            const auto id = static_cast<Index>(pieces.size());
            pieces.push_back({seed});
            piece[static_cast<std::size_t>(seed)] = id;
            for (std::size_t q = 0; q < pieces.back().size(); ++q) {
                const Index f = pieces.back()[q];
                const Index k = surface.face_size(f);
                for (Index c = 0; c < k; ++c) {
                    const Index e = find_edge(et, surface.face_node(f, c), surface.face_node(f, (c + 1) % k));
                    for (const Index* g = et.faces.row_begin(e); g != et.faces.row_end(e); ++g) {
                        if (surface.face_patch[*g] != p || piece[static_cast<std::size_t>(*g)] != kNone) continue;
                        bool flat = true;
                        for (const Index* v = surface.face_begin(*g); v != surface.face_end(*g); ++v)
                            flat &= std::abs((surface.points[*v] - o).dot(n)) <= tol;
                        if (!flat) continue;
                        piece[static_cast<std::size_t>(*g)] = id;
                        pieces.back().push_back(*g);
                    }
                }
            }
        }
        if (pieces.size() < 2 || pieces.size() > kMostPlanes) continue;  // curved: the error names it
        for (std::size_t k = 1; k < pieces.size(); ++k) {
            Patch extra = surface.patches[static_cast<std::size_t>(p)];
            extra.name += " (plane " + std::to_string(k + 1) + ")";
            surface.patches.push_back(extra);
            for (const Index f : pieces[k]) surface.face_patch[f] = static_cast<Index>(surface.patches.size() - 1);
            from.push_back(p);
        }
    }
    return from;
}

/// The planes split_into_planes made one patch again in \p mesh's boundary: the \p from.size()
/// patches from \p first on go back to the patch they came from, the ones after them move down.
void merge_planes(VolumeMesh& mesh, Index first, const std::vector<Index>& from, std::vector<Index>& remeshed) {
    if (from.empty()) return;
    const auto n = static_cast<Index>(from.size());
    auto to = [&](Index p) {
        return p < first ? p : p < first + n ? from[static_cast<std::size_t>(p - first)] : p - n;
    };
    for (Index& p : mesh.boundary.face_patch) p = to(p);
    mesh.boundary.patches.erase(mesh.boundary.patches.begin() + first, mesh.boundary.patches.begin() + first + n);
    for (Index& p : remeshed) p = to(p);
    std::sort(remeshed.begin(), remeshed.end());
    remeshed.erase(std::unique(remeshed.begin(), remeshed.end()), remeshed.end());
}

VolumeMesh assemble(const LayerMesh& lm, const PyramidLayer& pyr, const SurfaceMesh& region, Index top_patch,
                    const TetFill& fill, const std::vector<Patch>& patches) {
    VolumeMesh mesh;
    mesh.points = lm.mesh.points;
    const Index nt = lm.top.num_points();
    const Index first_new = static_cast<Index>(lm.mesh.points.size());
    auto node = [&](Index i) { return i < nt ? lm.top_node(i) : first_new + (i - nt); };
    mesh.points.insert(mesh.points.end(), fill.points.begin() + nt, fill.points.end());
    // The layers' own cells first (where columns stop unevenly they hold pyramids and
    // tetrahedra closing the steps), then the stages'.
    mesh.tets = lm.mesh.tets;
    mesh.pyramids = lm.mesh.pyramids;
    mesh.prisms = lm.mesh.prisms;
    mesh.hexes = lm.mesh.hexes;
    append_cells(mesh.pyramids, pyr.pyramids, node);
    append_cells(mesh.tets, fill.tets, node);
    // The layers' cells keep their layer, the pyramids and tetrahedra added have none (0).
    const std::vector<std::int32_t> layers = layer_of_cells(lm);
    const std::size_t lm_tets = lm.mesh.tets.size(), lm_pyramids = lm.mesh.pyramids.size();
    mesh.cell_layers.assign(layers.begin(), layers.begin() + static_cast<std::ptrdiff_t>(lm_tets));
    mesh.cell_layers.resize(mesh.tets.size(), 0);
    mesh.cell_layers.insert(mesh.cell_layers.end(), layers.begin() + static_cast<std::ptrdiff_t>(lm_tets),
                            layers.begin() + static_cast<std::ptrdiff_t>(lm_tets + lm_pyramids));
    mesh.cell_layers.resize(mesh.tets.size() + mesh.pyramids.size(), 0);
    mesh.cell_layers.insert(mesh.cell_layers.end(), layers.begin() + static_cast<std::ptrdiff_t>(lm_tets + lm_pyramids),
                            layers.end());

    mesh.boundary.patches = patches;
    const SurfaceMesh& lb = lm.mesh.boundary;
    for (Index f = 0; f < lb.num_faces(); ++f) {
        if (lb.face_patch[f] == lm.top_patch) continue;  // interior now
        if (lb.face_patch[f] >= static_cast<Index>(patches.size()))
            throw TopologyError("assembling the hybrid mesh: the layers end on an open edge with no patch beside it");
        mesh.boundary.add_face(lb.face_begin(f), lb.face_size(f), lb.face_patch[f]);
    }
    // Wall faces where no column grew: the front there is the wall itself (reversed: out of the fluid).
    for (Index f = 0; f < lm.top.num_faces(); ++f) {
        if (lm.face_layers[static_cast<std::size_t>(f)] > 0) continue;
        Index v[4];
        const Index n = lm.top.face_size(f);
        v[0] = lm.top_node(lm.top.face_node(f, 0));
        for (Index i = 1; i < n; ++i) v[i] = lm.top_node(lm.top.face_node(f, n - i));
        mesh.boundary.add_face(v, n, lm.top.face_patch[f]);
    }
    for (Index f = 0; f < region.num_faces(); ++f) {
        if (region.face_patch[f] == top_patch) continue;
        mesh.boundary.add_face(
            {node(region.face_node(f, 0)), node(region.face_node(f, 1)), node(region.face_node(f, 2))},
            region.face_patch[f]);
    }
    return mesh;
}

/// Rounds of lowering colliding columns before giving up (lower_marked_columns).
constexpr int kFrontRounds = 8;

/// The error when the boundary TetGen is to fill against still crosses itself after every
/// round: found here, with exact predicates, where it is and why, rather than by TetGen (which
/// stops without a place).
std::string front_intersects_message(const SurfaceMesh& region, const std::vector<FacePair>& pairs) {
    std::string where;
    for (std::size_t i = 0; i < std::min<std::size_t>(pairs.size(), 3); ++i)
        where += (i ? "; " : "") + describe_pair(region, pairs[i]);
    return "the boundary of the region to fill with tetrahedra (the layer top and the outer boundary) "
           "intersects itself in " +
           std::to_string(pairs.size()) + " pairs of faces after lowering the layers there " +
           std::to_string(kFrontRounds) + " times: " + where +
           (pairs.size() > 3 ? "; and " + std::to_string(pairs.size() - 3) + " more" : "") +
           ". The layers collide there (a gap narrower than the layers on both sides) or reach the "
           "outer boundary: fewer or thinner layers (DistributionParams::layers, "
           "DistributionParams::first_height, DistributionParams::growth), or a larger farfield";
}

/// A stage's local failure, in place of its result: what to change before the layers are marched
/// again (build_hybrid_mesh applies it to the LayerConstraints and the surface), and why.
struct Repair {
    enum class Stage { Layers, Pyramids, Front, Tets };
    Repair(Stage stage, std::string failure) : from(stage), why(std::move(failure)) {}
    Stage from;
    std::string why;  ///< the failure: the error if no round is left to mend it
    /// Per input node, a bound on its layers' thickness (the lowest holds): one per column lowered.
    std::vector<std::pair<Index, double>> bounds;
    std::vector<Index> no_fan;               ///< input nodes to march without a fan
    std::vector<std::vector<Index>> splits;  ///< wall quads (their input nodes, ascending) to split in two
};

/// A stage's result, or the repair it asks for.
template <class T>
using Outcome = std::variant<T, Repair>;

/// A LocalTopologyError as a value: where a stage could not go on (nodes of the surface it was
/// given) and how far the layers got there.
struct LocalFailure {
    std::string why;
    std::vector<Index> nodes;
    double reached = 0.0;
};

/// \p stage's result, or its LocalTopologyError as a value. extrude_layers, build_pyramids and
/// fill_with_tets throw it from deep inside (a fold with stopping off, a quad no apex caps, a face
/// TetGen cannot recover); this is the one place the pipeline turns it into an outcome.
template <class F>
std::variant<std::invoke_result_t<F>, LocalFailure> local_failure_as_value(F&& stage) {
    try {
        return stage();
    } catch (const LocalTopologyError& e) {
        return LocalFailure{e.what(), e.nodes(), e.reached()};
    }
}

/// The quad face of \p mesh over the four nodes \p nodes (any order), or kNone.
Index find_quad(const SurfaceMesh& mesh, std::vector<Index> nodes) {
    if (nodes.size() != 4) return kNone;
    std::sort(nodes.begin(), nodes.end());
    for (Index f = 0; f < mesh.num_faces(); ++f) {
        if (mesh.face_size(f) != 4) continue;
        std::array<Index, 4> sorted{};
        std::copy(mesh.face_begin(f), mesh.face_end(f), sorted.begin());
        std::sort(sorted.begin(), sorted.end());
        if (std::equal(sorted.begin(), sorted.end(), nodes.begin())) return f;
    }
    return kNone;
}

/// Quad \p quad of \p mesh replaced in place by two triangles split along its shorter diagonal,
/// each keeping the quad's orientation and patch.
void split_quad(SurfaceMesh& mesh, Index quad) {
    SurfaceMesh out;
    out.points = mesh.points;
    out.patches = mesh.patches;
    for (Index f = 0; f < mesh.num_faces(); ++f) {
        const Index p = mesh.face_patch[static_cast<std::size_t>(f)];
        if (f != quad) {
            out.add_face(mesh.face_begin(f), mesh.face_size(f), p);
            continue;
        }
        const Index* q = mesh.face_begin(f);
        const int d = quad_shorter_diagonal(mesh, f);
        out.add_face({q[d], q[d + 1], q[d + 2]}, p);
        out.add_face({q[d], q[d + 2], q[(d + 3) % 4]}, p);
    }
    mesh = std::move(out);
}

/// Mark the wall columns under layer-top face \p f of \p region: region node ids below the
/// wall's node count are wall nodes; the next ones pyramid apexes (their quad's nodes count);
/// outer points are left alone.
void mark_columns(const SurfaceMesh& region, Index f, Index nw, const PyramidLayer& pyr, std::vector<char>& marked) {
    for (const Index* v = region.face_begin(f); v != region.face_end(f); ++v) {
        if (*v < nw) {
            marked[static_cast<std::size_t>(*v)] = 1;
        } else if (*v < nw + static_cast<Index>(pyr.pyramids.size())) {
            for (int c = 0; c < 4; ++c)
                marked[static_cast<std::size_t>(pyr.pyramids[static_cast<std::size_t>(*v - nw)][c])] = 1;
        }
    }
}

/// The length wall node \p w's column reached.
double column_length(const LayerMesh& lm, Index w) {
    return (lm.mesh.points[lm.top_node(w)] - lm.mesh.points[lm.level_node(0, w)]).norm();
}

/// The \p marked columns bounded in \p repair: to the layers below their top layer the first
/// time (the heights asked, times the share of them the column was asked: height_scale, below
/// 1 where it is scaled or capped), to half that the times after, so
/// that a collision takes off what closing it needs where one layer does and goes deeper only
/// where the front meets itself again (ALGORITHM.md, "Proximity"). \p reach: the thickness of
/// the first k layers asked, k = 0, ..., layers; \p limit: per input node, its bound so far
/// (infinite: none). Returns how many of them had grown at all (the others' bound becomes 0,
/// which changes nothing).
Index lower_marked_columns(const std::vector<char>& marked, const LayerMesh& lm, const std::vector<double>& reach,
                           const std::vector<double>& limit, Repair& repair) {
    Index grew = 0;
    for (Index w = 0; w < lm.wall_nodes(); ++w) {
        if (!marked[static_cast<std::size_t>(w)]) continue;
        const Index v = lm.input_node[static_cast<std::size_t>(w)];
        const auto n = static_cast<std::size_t>(lm.node_layers(w));
        const double scale = lm.height_scale.empty() ? 1.0 : lm.height_scale[static_cast<std::size_t>(w)];
        const bool first = !std::isfinite(limit[static_cast<std::size_t>(v)]);
        repair.bounds.emplace_back(v, first && n > 0 ? scale * reach[n - 1] : 0.5 * scale * reach[n]);
        if (n > 0) ++grew;
    }
    return grew;
}

/// The layers on \p surface; or, where a cell folds (local stopping off), the columns of its
/// nodes bounded to 0.7 of what the layers below it reached (half the thickness \p asked if not known).
Outcome<LayerMesh> march_layers(const SurfaceMesh& surface, const LayerParams& params,
                                const LayerConstraints& constraints, double asked, Progress* progress) {
    auto out = local_failure_as_value([&] { return extrude_layers(surface, params, constraints, progress); });
    const auto* fold = std::get_if<LocalFailure>(&out);
    if (!fold) return std::get<LayerMesh>(std::move(out));
    Repair repair(Repair::Stage::Layers, fold->why);
    const double to = fold->reached > 0.0 ? 0.7 * fold->reached : 0.5 * asked;
    for (const Index n : fold->nodes) repair.bounds.emplace_back(n, to);
    return repair;
}

/// The repair of the layer-top quads that took no pyramid (four wall nodes each in \p failed,
/// pyramids.h), all in one round. \p uncappable: the quads that failed in the rounds before.
Repair pyramid_repair(const LocalFailure& failed, const LayerMesh& lm, const SurfaceMesh& surface,
                      std::set<std::vector<Index>>& uncappable) {
    Repair repair(Repair::Stage::Pyramids, failed.why);
    for (std::size_t at = 0; at + 4 <= failed.nodes.size(); at += 4) {
        const auto quad_begin = failed.nodes.begin() + static_cast<std::ptrdiff_t>(at);
        const std::vector<Index> quad(quad_begin, quad_begin + 4);
        // A face of a fan (its columns twist from one end to the other where the wall is
        // small against the layers): no fan on its nodes.
        bool fan = false;
        for (const Index w : quad) fan |= !lm.fan_column.empty() && lm.fan_column[static_cast<std::size_t>(w)];
        if (fan) {
            for (const Index w : quad) repair.no_fan.push_back(lm.input_node[static_cast<std::size_t>(w)]);
            continue;
        }
        // A wall quad with no layer on it (its columns stopped at the wall), or whose
        // columns were lowered for it before, that no apex can cap (a quad bent round a
        // small hole): split into two triangles, whose columns need no pyramid.
        std::vector<Index> wall_nodes;
        bool on_wall = true;
        for (const Index w : quad) {
            on_wall &= lm.top_node(w) == lm.level_node(0, w);
            wall_nodes.push_back(lm.input_node[static_cast<std::size_t>(w)]);
        }
        std::sort(wall_nodes.begin(), wall_nodes.end());
        const bool again = !uncappable.insert(wall_nodes).second;
        const bool split_already =
            std::find(repair.splits.begin(), repair.splits.end(), wall_nodes) != repair.splits.end();
        if ((on_wall || again) && !split_already && find_quad(surface, wall_nodes) != kNone) {
            repair.splits.push_back(std::move(wall_nodes));
            continue;
        }
        for (const Index w : quad)
            repair.bounds.emplace_back(lm.input_node[static_cast<std::size_t>(w)], 0.5 * column_length(lm, w));
    }
    return repair;
}

/// The pyramids on \p lm's top, or the repair of the quads none can cap (pyramid_repair).
Outcome<PyramidLayer> cap_with_pyramids(const LayerMesh& lm, const SurfaceMesh& surface, const PyramidParams& params,
                                        std::set<std::vector<Index>>& uncappable, Progress* progress) {
    auto out = local_failure_as_value([&] { return build_pyramids(lm.top, params, progress); });
    if (const auto* failed = std::get_if<LocalFailure>(&out)) return pyramid_repair(*failed, lm, surface, uncappable);
    return std::get<PyramidLayer>(std::move(out));
}

/// Nothing if the boundary TetGen is to fill against does not cross itself; else the columns
/// under the layer-top faces of the crossing pairs lowered (lower_marked_columns).
std::optional<Repair> front_repair(const SurfaceMesh& region, Index top_patch, const LayerMesh& lm,
                                   const PyramidLayer& pyr, const std::vector<double>& reach,
                                   const std::vector<double>& limit, int threads) {
    const std::vector<FacePair> pairs = self_intersections(region, 0, threads);
    if (pairs.empty()) return std::nullopt;
    Repair repair(Repair::Stage::Front, front_intersects_message(region, pairs));
    std::vector<char> marked(static_cast<std::size_t>(lm.wall_nodes()), 0);
    for (const FacePair& p : pairs)
        for (const Index f : {p.a, p.b})
            if (region.face_patch[f] == top_patch) mark_columns(region, f, lm.wall_nodes(), pyr, marked);
    lower_marked_columns(marked, lm, reach, limit, repair);
    return repair;
}

/// InputError where \p region encloses no volume (its faces point into what it bounds): the
/// input's walls hold the domain from outside, as an air domain's outer boundary does. The
/// wall patch of \p surface whose bounding box holds every other patch's is named, with the
/// kinds that say what it is.
void check_not_inside_out(const SurfaceMesh& region, const SurfaceMesh& surface) {
    const double volume = tet_fill::enclosed_volume(region);
    if (volume > 0.0) return;
    std::vector<std::array<Vec3, 2>> box(surface.patches.size(),
                                         {Vec3::Constant(std::numeric_limits<double>::infinity()),
                                          Vec3::Constant(-std::numeric_limits<double>::infinity())});
    for (Index f = 0; f < surface.num_faces(); ++f)
        for (const Index* v = surface.face_begin(f); v != surface.face_end(f); ++v) {
            auto& b = box[static_cast<std::size_t>(surface.face_patch[f])];
            b[0] = b[0].cwiseMin(surface.points[static_cast<std::size_t>(*v)]);
            b[1] = b[1].cwiseMax(surface.points[static_cast<std::size_t>(*v)]);
        }
    std::string outer;
    for (std::size_t p = 0; p < box.size() && outer.empty(); ++p) {
        if (surface.patches[p].kind != PatchKind::Wall) continue;
        const double tol = 1e-9 * (box[p][1] - box[p][0]).norm();
        bool holds = true;
        for (std::size_t q = 0; q < box.size() && holds; ++q)
            holds = q == p || !(box[q][0].x() <= box[q][1].x()) ||
                    ((box[q][0].array() >= box[p][0].array() - tol).all() &&
                     (box[q][1].array() <= box[p][1].array() + tol).all());
        if (holds && box.size() > 1) outer = surface.patches[p].name;
    }
    std::string msg = "the region to fill between the layers and the farfield is inside out (its boundary encloses a "
                      "volume of " + format_number(volume, 6) + "): the walls hold the domain from outside";
    if (!outer.empty())
        msg += "; the wall patch '" + outer + "' holds every other patch within its bounding box, as an air "
               "domain's outer boundary does: if the input is the air round a body, give it "
               "PrepareParams::patch_kinds " + outer + "=farfield (and the planes the domain is cut by symmetry or "
               "other); if the flow is inside it, PrepareParams::internal_flow";
    else
        msg += ": give the input's outer boundary the kind farfield (PrepareParams::patch_kinds NAME=farfield), or "
               "PrepareParams::internal_flow for a flow inside the walls";
    throw InputError(msg);
}

/// fill_with_tets by the mesher \p params asks; where HXT fails (a configuration its Delaunay
/// or boundary recovery cannot handle), TetGen fills the region instead and \p fallback says why.
TetFill fill_falling_back(const SurfaceMesh& region, const std::vector<Vec3>& holes, const TetFillParams& params,
                          Progress* progress, std::string& fallback) {
    if (params.mesher != TetMesher::Hxt) return fill_with_tets(region, holes, params, progress);
    try {
        return fill_with_tets(region, holes, params, progress);
    } catch (const BackendError& e) {
        fallback = e.what();
    }
    TetFillParams tetgen = params;
    tetgen.mesher = TetMesher::TetGen;
    return fill_with_tets(region, holes, tetgen, progress);
}

/// The tetrahedra filling \p region. Where TetGen stops on one of its internal checks recovering
/// a face of the layer top (a configuration of the front it cannot handle, though no face crosses
/// another), the columns under every layer-top face touching that face's nodes lowered, so that
/// the front there changes shape; an error where none of them grew (a face of the outer boundary
/// or of walls with no layers: nothing there can change).
Outcome<TetFill> fill_region(const SurfaceMesh& region, Index top_patch, const LayerMesh& lm, const PyramidLayer& pyr,
                             const std::vector<double>& reach, const std::vector<double>& limit,
                             const TetFillParams& params, Progress* progress, std::string& fallback) {
    auto out = local_failure_as_value(
        [&] { return fill_falling_back(region, points_in_layers(lm), params, progress, fallback); });
    const auto* stuck = std::get_if<LocalFailure>(&out);
    if (!stuck) return std::get<TetFill>(std::move(out));
    std::vector<char> marked(static_cast<std::size_t>(lm.wall_nodes()), 0);
    for (Index f = 0; f < region.num_faces(); ++f) {
        if (region.face_patch[f] != top_patch) continue;
        bool touches = false;
        for (const Index* v = region.face_begin(f); v != region.face_end(f) && !touches; ++v)
            touches = std::find(stuck->nodes.begin(), stuck->nodes.end(), *v) != stuck->nodes.end();
        if (touches) mark_columns(region, f, lm.wall_nodes(), pyr, marked);
    }
    Repair repair(Repair::Stage::Tets, stuck->why);
    if (lower_marked_columns(marked, lm, reach, limit, repair) == 0)
        throw LocalTopologyError(stuck->why, stuck->nodes, stuck->reached);
    return repair;
}

/// What build_hybrid_mesh's rounds carry from one to the next.
struct Rounds {
    SurfaceMesh surface;                      ///< the domain the layers grow on, its wall quads split so far
    bool has_outer = false;                   ///< the input closes the fluid itself (closed_domain)
    Index farfield_patch = kNone;             ///< the generated farfield's patch of the region, if any
    double asked = 0.0;                       ///< the thickness asked: the sum of the layer heights
    std::vector<double> reach;                ///< the thickness of the first k layers asked, k = 0, ..., layers
    LayerParams layers;                       ///< the settings
    LayerConstraints constraints;             ///< the thickness bounds, their slopes and the nodes without a fan
    std::vector<double> limit_before;         ///< the thickness bounds of the round before
    std::vector<int> repeats;                 ///< per input node, the rounds that lowered it again
    std::vector<Index> uncapped;              ///< input nodes whose fan's face on the layer top took no pyramid
    std::set<Index> unusable, skewed;         ///< input nodes whose fan extrude_layers dropped (LayerMesh)
    std::set<std::vector<Index>> uncappable;  ///< the input nodes of quads that took no pyramid

    /// The front rounds' bounds spread along the wall from each column lowered at front_slope
    /// (ProximityParams, \p given), halved for a column from the second round on that lowers it
    /// again, and from round kFrontRounds / 2 on at the proximity limits' slope for the columns
    /// that round lowers (never above what was asked): a lowering stays local unless the front
    /// keeps meeting itself there, and only there does it spread wider (ALGORITHM.md, "Proximity").
    void spread(int round, const ProximityParams& given) {
        const std::vector<double>& limit = constraints.node_thickness_limit;
        std::vector<double>& slope = constraints.node_front_slope;
        if (slope.size() != limit.size()) slope.assign(limit.size(), given.front_slope);
        repeats.resize(limit.size(), 0);
        const double lowest = std::min(given.front_slope, given.slope);  // extrude_layers refuses 0
        for (std::size_t i = 0; i < limit.size(); ++i) {
            if (!(limit[i] < limit_before[i])) continue;
            if (std::isfinite(limit_before[i]) && ++repeats[i] > 1) slope[i] *= 0.5;
            if (round >= kFrontRounds / 2) slope[i] = 0.0;
            slope[i] = std::max(slope[i], lowest);
        }
        limit_before = limit;
    }

    /// The fans \p lm dropped stay dropped in the rounds after: the same march without trying them again.
    void keep_dropped_fans(const LayerMesh& lm) {
        for (const auto& [dropped, into] :
             {std::pair{&lm.fans_dropped, &unusable}, std::pair{&lm.fans_skewed, &skewed}})
            for (const Index v : *dropped) {
                constraints.bar_fan(v, surface.points.size());
                into->insert(v);
            }
    }

    /// The columns \p lm capped where they stopped stay capped in the rounds after, which make
    /// no further marches for such stops: a round after a repair marches once, not once plus
    /// the stop marches (extrude_layers) again from no cap.
    void keep_stop_bounds(const LayerMesh& lm) {
        constraints.node_stop_limit = lm.stop_limit, constraints.node_stop_reason = lm.stop_limit_reason;
        constraints.stop_marches = lm.stop_marches;
    }

    /// \p repair carried out for the next round, and counted in \p rep.
    void apply(const Repair& repair, HybridReport& rep) {
        for (const auto& [node, bound] : repair.bounds) {
            double& l = constraints.node_thickness_limit[static_cast<std::size_t>(node)];
            l = std::min(l, bound);
        }
        for (const Index v : repair.no_fan)
            if (constraints.bar_fan(v, surface.points.size())) uncapped.push_back(v);
        for (const std::vector<Index>& quad : repair.splits) split_quad(surface, find_quad(surface, quad));
        rep.front_lowered_nodes += static_cast<Index>(repair.bounds.size());
        rep.split_quads += static_cast<int>(repair.splits.size());
        rep.tet_retries += repair.from == Repair::Stage::Tets ? 1 : 0;
    }
};

/// What one round's stages made, the mesh is assembled from.
struct Stages {
    LayerMesh lm;
    PyramidLayer pyr;
    OuterBoundary outer;
    SurfaceMesh region;  ///< what the tetrahedra fill (region_to_fill)
    Index top_patch = kNone;
    TetFill fill;
};

/// One round: the layers, the pyramids, the front's check and the tetrahedra, or the first
/// stage's repair.
Outcome<Stages> attempt(const HybridParams& params, Rounds& rounds, HybridReport& rep, Progress* progress) {
    using clock = std::chrono::steady_clock;
    Stages s;
    auto t0 = clock::now();
    Outcome<LayerMesh> layers = march_layers(rounds.surface, rounds.layers, rounds.constraints, rounds.asked, progress);
    rep.seconds_layers += seconds_since(t0);
    if (auto* repair = std::get_if<Repair>(&layers)) return std::move(*repair);
    s.lm = std::get<LayerMesh>(std::move(layers));
    rounds.keep_dropped_fans(s.lm);
    rounds.keep_stop_bounds(s.lm);
    t0 = clock::now();
    Outcome<PyramidLayer> pyr = cap_with_pyramids(s.lm, rounds.surface, params.pyramids, rounds.uncappable, progress);
    rep.seconds_pyramids += seconds_since(t0);
    if (auto* repair = std::get_if<Repair>(&pyr)) return std::move(*repair);
    s.pyr = std::get<PyramidLayer>(std::move(pyr));
    t0 = clock::now();
    s.outer = outer_part(rounds.surface, s.lm, rounds.has_outer, params.farfield, params.tets.growth);
    s.region = region_to_fill(rounds.surface.patches, s.pyr, s.outer, rounds.farfield_patch, s.top_patch);
    check_not_inside_out(s.region, rounds.surface);
    const std::vector<double>& limit = rounds.constraints.node_thickness_limit;
    std::optional<Repair> crossing = front_repair(s.region, s.top_patch, s.lm, s.pyr, rounds.reach, limit, params.threads);
    rep.seconds_tets += seconds_since(t0);
    if (crossing) return std::move(*crossing);
    t0 = clock::now();
    strata::report(progress, "tetrahedra", 0.0);
    TetFillParams tet_params = params.tets;
    tet_params.background_mesh = params.tets.background_mesh && s.outer.remeshed.empty();  // see TetFillParams
    tet_params.threads = params.threads;
    // TetGen's phases up to 0.9 of the stage, the improvement's passes after.
    ProgressRange filling(progress, 0.0, 0.9), improving(progress, 0.9, 1.0);
    Outcome<TetFill> fill = fill_region(s.region, s.top_patch, s.lm, s.pyr, rounds.reach, limit, tet_params,
                                        progress ? &filling : nullptr, rep.tets_fallback);
    if (auto* repair = std::get_if<Repair>(&fill)) {
        rep.seconds_tets += seconds_since(t0);
        return std::move(*repair);
    }
    s.fill = std::get<TetFill>(std::move(fill));
    TetImproveParams improve = params.improve;
    improve.threads = params.threads;
    rep.tet_improve = improve_tets(s.fill, s.region.num_points(), improve, progress ? &improving : nullptr);
    rep.seconds_tets += seconds_since(t0);
    strata::report(progress, "tetrahedra", 1.0);
    return s;
}

/// The rounds' starting point on \p surface (closed_domain's): the settings of \p params, no
/// bound on any node's thickness; an InputError if the layers asked cannot fit the farfield
/// generated around the body.
Rounds first_round(SurfaceMesh surface, bool has_outer, const HybridParams& params) {
    Rounds rounds;
    rounds.has_outer = has_outer;
    rounds.farfield_patch = has_outer ? kNone : static_cast<Index>(surface.patches.size());
    rounds.layers = params.layers;
    rounds.layers.threads = params.threads;
    rounds.constraints.node_thickness_limit.assign(surface.points.size(), std::numeric_limits<double>::infinity());
    rounds.constraints.smoothed = make_smoothed_levels();  // the rounds smooth a level once where they march it alike
    rounds.limit_before = rounds.constraints.node_thickness_limit;
    const std::vector<double> heights = layer_heights(params.layers.distribution);
    rounds.reach.push_back(0.0);
    for (int k = 0; k < params.layers.distribution.layers; ++k)
        rounds.reach.push_back(rounds.reach.back() + heights[static_cast<std::size_t>(k)]);
    rounds.asked = rounds.reach.back();
    if (!has_outer)
        check_layers_fit_farfield(surface, params.farfield, rounds.asked, params.layers.proximity_limits.other_patch);
    rounds.surface = std::move(surface);
    return rounds;
}

/// The stages marched round after round, each round's repair applied before the next, until
/// every stage goes through; after kFrontRounds rounds, the last failure is the error.
Stages march_with_repairs(const HybridParams& params, Rounds& rounds, HybridReport& rep, Progress* progress) {
    for (int round = 0;; ++round) {
        rounds.spread(round, params.layers.proximity_limits);
        Outcome<Stages> outcome = attempt(params, rounds, rep, progress);
        const Repair* repair = std::get_if<Repair>(&outcome);
        if (!repair) return std::get<Stages>(std::move(outcome));
        if (round == kFrontRounds) throw TopologyError(repair->why);
        rounds.apply(*repair, rep);
        rep.front_rounds = round + 1;
    }
}

/// The mesh of \p stages (layers, pyramids, tetrahedra, the planes merged back into the input's
/// \p input_patches by \p plane_of), validated, with its coverage and counts in \p rep.
VolumeMesh assembled(Stages& stages, Rounds& rounds, Index input_patches, const std::vector<Index>& plane_of,
                     const HybridParams& params, HybridReport& rep, Progress* progress) {
    LayerMesh& lm = stages.lm;
    rep.layers = static_cast<const LayerCounts&>(lm);
    lm.fans_dropped.assign(rounds.unusable.begin(), rounds.unusable.end());
    lm.fans_skewed.assign(rounds.skewed.begin(), rounds.skewed.end());
    rep.coverage = layer_report(lm);
    std::sort(rounds.uncapped.begin(), rounds.uncapped.end());
    for (const Index v : rounds.uncapped)
        rep.coverage.no_fan.push_back({v, rounds.surface.points[static_cast<std::size_t>(v)], NoFan::Uncapped});
    std::sort(rep.coverage.no_fan.begin(), rep.coverage.no_fan.end(),
              [](const NoFanNode& a, const NoFanNode& b) { return a.node < b.node; });
    rep.remeshed_patches = stages.outer.remeshed;

    auto t0 = std::chrono::steady_clock::now();
    const std::vector<Patch> patches(stages.region.patches.begin(), stages.region.patches.begin() + stages.top_patch);
    VolumeMesh mesh = assemble(lm, stages.pyr, stages.region, stages.top_patch, stages.fill, patches);
    merge_planes(mesh, input_patches, plane_of, rep.remeshed_patches);
    rep.validation = require_valid_mesh(mesh, "hybrid mesh", {.threads = params.threads, .progress = progress});
    rep.seconds_validate = seconds_since(t0);
    return mesh;
}

}  // namespace

VolumeMesh build_hybrid_mesh(const SurfaceMesh& input, const HybridParams& params, Progress* progress,
                             HybridReport* report) {
    HybridReport rep;
    check_threads(params.threads, "HybridParams::threads");
    check_tet_improve_params(params.improve);  // before the work it would otherwise end
    bool has_outer = false;
    SurfaceMesh surface = closed_domain(input, params.farfield, has_outer, rep.closed_half_model, rep.internal_flow);
    const auto input_patches = static_cast<Index>(surface.patches.size());
    const std::vector<Index> plane_of = has_outer ? split_into_planes(surface) : std::vector<Index>{};
    for (const Index p : plane_of) {
        if (rep.planes_of_patches.empty() || rep.planes_of_patches.back().first != p)
            rep.planes_of_patches.emplace_back(p, 1);
        ++rep.planes_of_patches.back().second;
    }
    if (const std::vector<FacePair> crossing = self_intersections(surface, 1, params.threads); !crossing.empty())
        throw InputError("the surface intersects itself: " + describe_pair(surface, crossing[0]) +
                         "; overlapping bodies must be fused into one (CadParams::fuse), and a surface mesh that "
                         "folds where two of its faces nearly touch (quads recombined across a narrow junction, a "
                         "coarse size there) meshed again finer, without quads, or repaired, before layers can grow "
                         "on it");

    // Layers, pyramids and the front TetGen fills against, marched again after each stage's
    // repair (a thickness bound, no fan, a split quad) until all go through.
    Rounds rounds = first_round(std::move(surface), has_outer, params);
    VolumeMesh mesh;
    for (int pass = 0;; ++pass) {
        Stages stages = march_with_repairs(params, rounds, rep, progress);
        mesh = assembled(stages, rounds, input_patches, plane_of, params, rep, progress);
        // Faces between layer cells checkMesh would fail as skewed: their columns capped below
        // them (cap_skewed_columns) and the mesh made again, once.
        if (pass > 0 || rep.validation.solver.skew_faces == 0 ||
            !cap_skewed_columns(stages.lm, rounds.layers, rounds.surface.points.size(), rounds.constraints,
                                params.threads))
            break;
        rep.skew_capped = true;
    }
    if (report) *report = std::move(rep);
    return mesh;
}

StepPlan step_plan(const SurfaceMesh& input, const HybridParams& params, double quality, double max_aspect_ratio) {
    check_threads(params.threads, "HybridParams::threads");
    bool has_outer = false, half = false, internal = false;
    SurfaceMesh surface = closed_domain(input, params.farfield, has_outer, half, internal);
    if (has_outer) split_into_planes(surface);  // as build_hybrid_mesh marches them
    LayerParams layer_params = params.layers;
    layer_params.threads = params.threads;
    const ProximityPlan plan = proximity_plan(surface, layer_params);
    const std::vector<double> heights = layer_heights(params.layers.distribution);
    StepPlan out;
    if (quality > 0.0) out.points = step_sizes(surface, plan, heights, quality);
    if (!heights.empty()) out.fans = fan_wedge_sizes(surface, plan, heights.front(), max_aspect_ratio);
    // Thickness per level, and each wall face's area shared among its nodes.
    std::vector<double> reached(heights.size() + 1, 0.0);
    for (std::size_t k = 0; k < heights.size(); ++k) reached[k + 1] = reached[k] + heights[k];
    const double asked = reached.back();
    double area = 0.0, covered = 0.0;
    for (Index f = 0; f < surface.num_faces(); ++f) {
        if (surface.patches[static_cast<std::size_t>(surface.face_patch[f])].kind != PatchKind::Wall) continue;
        const double share = face_area_vector(surface, f).norm() / static_cast<double>(surface.face_size(f));
        for (const Index* v = surface.face_begin(f); v != surface.face_end(f); ++v) {
            const int k = std::clamp(plan.levels[static_cast<std::size_t>(*v)], 0, static_cast<int>(heights.size()));
            area += share;
            covered += share * reached[static_cast<std::size_t>(k)];
        }
    }
    if (area > 0.0 && asked > 0.0) out.thickness_share = covered / (area * asked);
    return out;
}

}  // namespace strata
