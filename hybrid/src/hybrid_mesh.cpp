#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/geometry/topology.h>
#include <strata/hybrid/hybrid_mesh.h>
#include <strata/hybrid/outer_boundary.h>

#include <chrono>

namespace strata {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// One point inside each cavity that the layer top encloses (a closed component of it, i.e. a
/// body not cut by a plane): the centroid of the first-layer cell on the component's first
/// face. Components ending on a plane open onto the outside of the region and need none.
std::vector<Vec3> points_in_layers(const LayerMesh& lm) {
    Index nc = 0;
    const std::vector<Index> comp = face_components(lm.top, &nc);
    std::vector<char> open(static_cast<std::size_t>(nc), 0);
    const EdgeTable et = edge_table(lm.top);
    for (Index e = 0; e < static_cast<Index>(et.nodes.size()); ++e)
        if (et.faces.row_size(e) == 1)
            open[static_cast<std::size_t>(comp[static_cast<std::size_t>(*et.faces.row_begin(e))])] = 1;
    std::vector<Vec3> holes;
    std::vector<char> done(static_cast<std::size_t>(nc), 0);
    const Index nw = lm.wall_nodes;
    for (Index f = 0; f < lm.top.num_faces(); ++f) {
        const std::size_t c = static_cast<std::size_t>(comp[static_cast<std::size_t>(f)]);
        if (open[c] || done[c]) continue;
        done[c] = 1;
        Vec3 x = Vec3::Zero();
        for (const Index* v = lm.top.face_begin(f); v != lm.top.face_end(f); ++v)
            x += lm.mesh.points[*v] + lm.mesh.points[nw + *v];
        holes.push_back(x / (2.0 * static_cast<double>(lm.top.face_size(f))));
    }
    return holes;
}

}  // namespace

VolumeMesh build_hybrid_mesh(const SurfaceMesh& input, const HybridParams& params, Progress* progress,
                             HybridReport* report) {
    HybridReport rep;
    // The input is a fluid domain (walls inside farfield, symmetry, outflow patches) if it has
    // any non-wall face; walls alone get a generated farfield, and a half model (walls open
    // along one plane) a generated half farfield and symmetry plane.
    bool has_outer = false;
    for (Index f = 0; f < input.num_faces(); ++f)
        has_outer |= input.patches[static_cast<std::size_t>(input.face_patch[f])].kind != PatchKind::Wall;
    SurfaceMesh closed;
    if (boundary_loops(input).rows() > 0) {
        if (has_outer)
            throw InputError(
                "the fluid domain is open: its walls, symmetry, outflow and farfield patches must enclose it "
                "(a hole in the surface, or a patch missing from the input); close it, or run strata layers "
                "for the layers alone");
        closed = close_half_model(input, params.farfield);
        rep.closed_half_model = true;
        has_outer = true;
    }
    const SurfaceMesh& surface = rep.closed_half_model ? closed : input;
    auto t0 = std::chrono::steady_clock::now();
    const LayerMesh lm = extrude_layers(surface, params.layers, progress);
    rep.layer_stats = lm.stats;
    rep.unsmoothed_nodes = lm.unsmoothed_nodes;
    rep.seconds_layers = seconds_since(t0);

    t0 = std::chrono::steady_clock::now();
    const PyramidLayer pyr = build_pyramids(lm.top, params.pyramids);
    rep.seconds_pyramids = seconds_since(t0);
    strata::report(progress, "pyramids", 1.0);

    // Region to fill: between the pyramid-capped layer top and the farfield. TetGen wants
    // the region's boundary with normals pointing out of it: the layer top is reversed.
    t0 = std::chrono::steady_clock::now();
    SurfaceMesh region;
    region.patches = surface.patches;
    OuterBoundary outer;
    Index farfield_patch = kNone;
    if (has_outer) {
        outer = outer_boundary(surface, lm);
    } else {
        outer.mesh = make_farfield(surface.points, params.farfield);
        outer.top_node.assign(outer.mesh.points.size(), kNone);
        for (Index f = 0; f < outer.mesh.num_faces(); ++f)  // outward → into the fluid, as the input's
            std::swap(outer.mesh.face_nodes[static_cast<std::size_t>(outer.mesh.face_offsets[f]) + 1],
                      outer.mesh.face_nodes[static_cast<std::size_t>(outer.mesh.face_offsets[f]) + 2]);
        farfield_patch = static_cast<Index>(region.patches.size());
        region.patches.push_back({"farfield", PatchKind::Farfield});
    }
    rep.remeshed_patches = outer.remeshed;
    const Index top_patch = static_cast<Index>(region.patches.size());  // the last one
    region.patches.push_back({"layer_top", PatchKind::Other});
    region.points = pyr.surface.points;
    for (Index f = 0; f < pyr.surface.num_faces(); ++f) {
        const Index* v = pyr.surface.face_begin(f);
        region.add_face({v[0], v[2], v[1]}, top_patch);
    }
    // The outer boundary, reversed too (its normals point into the fluid). Its layer-top
    // points are the top nodes already in region (the pyramid surface's points start with
    // the top nodes, same ids).
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
        region.add_face({region_of[static_cast<std::size_t>(v[0])], region_of[static_cast<std::size_t>(v[2])],
                         region_of[static_cast<std::size_t>(v[1])]},
                        has_outer ? outer.mesh.face_patch[f] : farfield_patch);
    }
    TetFillParams tet_params = params.tets;
    tet_params.background_mesh = params.tets.background_mesh && outer.remeshed.empty();  // see TetFillParams
    const TetFill fill = fill_with_tets(region, points_in_layers(lm), tet_params);
    rep.seconds_tets = seconds_since(t0);
    strata::report(progress, "tetrahedra", 1.0);

    // Assembly: layer nodes, then apexes, then farfield and Steiner points.
    t0 = std::chrono::steady_clock::now();
    VolumeMesh mesh;
    mesh.points = lm.mesh.points;
    const Index top_base = static_cast<Index>(lm.layers) * lm.wall_nodes;  // top level of the layers
    const Index nt = lm.top.num_points();
    // fill.points: region.points (= pyramid surface points: top nodes, apexes; then outer) + Steiner.
    auto to_global = [&](Index i) -> Index {
        if (i < nt) return top_base + i;
        return static_cast<Index>(lm.mesh.points.size()) + (i - nt);
    };
    for (std::size_t i = static_cast<std::size_t>(nt); i < fill.points.size(); ++i)
        mesh.points.push_back(fill.points[i]);
    mesh.prisms = lm.mesh.prisms;
    mesh.hexes = lm.mesh.hexes;
    for (const auto& p : pyr.pyramids)
        mesh.pyramids.push_back({to_global(p[0]), to_global(p[1]), to_global(p[2]), to_global(p[3]), to_global(p[4])});
    for (const auto& t : fill.tets)
        mesh.tets.push_back({to_global(t[0]), to_global(t[1]), to_global(t[2]), to_global(t[3])});
    // Boundary: the walls and the side faces on planes (as the layers wrote them; their
    // patches are the input's, below layer_top's), then the outer faces of the fill.
    mesh.boundary.patches.assign(region.patches.begin(), region.patches.end() - 1);
    const SurfaceMesh& lb = lm.mesh.boundary;
    const Index input_patches = static_cast<Index>(surface.patches.size());
    for (Index f = 0; f < lb.num_faces(); ++f) {
        if (lb.face_patch[f] >= input_patches) continue;  // layer_top is interior now
        mesh.boundary.add_face(lb.face_begin(f), lb.face_size(f), lb.face_patch[f]);
    }
    for (Index f = 0; f < region.num_faces(); ++f) {
        if (region.face_patch[f] == top_patch) continue;
        mesh.boundary.add_face(
            {to_global(region.face_node(f, 0)), to_global(region.face_node(f, 1)), to_global(region.face_node(f, 2))},
            region.face_patch[f]);
    }
    rep.validation = require_valid_mesh(mesh, "hybrid mesh");
    rep.seconds_validate = seconds_since(t0);
    if (report) *report = std::move(rep);
    return mesh;
}

}  // namespace strata
