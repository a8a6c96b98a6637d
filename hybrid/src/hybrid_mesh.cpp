#include <strata/error.h>
#include <strata/geometry/face_geometry.h>
#include <strata/geometry/topology.h>
#include <strata/hybrid/hybrid_mesh.h>

#include <chrono>

namespace strata {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// A point inside the cavity that the layer top encloses: the centroid of the first cell of
/// the first layer (inside the layers, hence inside the cavity, whatever the body's shape).
Vec3 point_in_layers(const LayerMesh& lm) {
    Vec3 c = Vec3::Zero();
    if (!lm.mesh.prisms.empty()) {
        for (Index v : lm.mesh.prisms.front()) c += lm.mesh.points[v];
        return c / 6.0;
    }
    for (Index v : lm.mesh.hexes.front()) c += lm.mesh.points[v];
    return c / 8.0;
}

}  // namespace

VolumeMesh build_hybrid_mesh(const SurfaceMesh& surface, const HybridParams& params, Progress* progress,
                             HybridReport* report) {
    HybridReport rep;
    // The closed outer boundary: the input's farfield faces, or a generated one.
    SurfaceMesh outer;
    outer.patches = surface.patches;
    bool has_farfield = false, has_symmetry = false;
    for (Index f = 0; f < surface.num_faces(); ++f) {
        const PatchKind k = surface.patches[static_cast<std::size_t>(surface.face_patch[f])].kind;
        has_farfield |= k == PatchKind::Farfield;
        has_symmetry |= k == PatchKind::Symmetry || k == PatchKind::Other;
    }
    if (has_symmetry)
        throw InputError("symmetry and other non-wall, non-farfield patches (half models, outflow planes) are not "
                         "supported by the hybrid stage yet: mesh the full body, or run strata layers for the layers alone");

    if (boundary_loops(surface).rows() > 0)
        throw InputError("the surface is open (e.g. a half model cut at its symmetry plane) and the hybrid stage needs a "
                         "closed body or a closed fluid domain: mesh the full body, or run strata layers for the layers alone");
    auto t0 = std::chrono::steady_clock::now();
    const LayerMesh lm = extrude_layers(surface, params.layers, progress);
    rep.layer_stats = lm.stats;
    rep.unsmoothed_nodes = lm.unsmoothed_nodes;
    if (boundary_loops(lm.top).rows() > 0)
        throw InputError("the walls end on another patch (a symmetry plane or a farfield side), so the layers' sides lie "
                         "on it; re-meshing that plane around the layers is not supported yet: mark the whole closed "
                         "boundary as walls, or run strata layers for the layers alone");
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
    const Index top_patch = static_cast<Index>(region.patches.size());
    region.patches.push_back({"layer_top", PatchKind::Other});
    region.points = pyr.surface.points;
    for (Index f = 0; f < pyr.surface.num_faces(); ++f) {
        const Index* v = pyr.surface.face_begin(f);
        region.add_face({v[0], v[2], v[1]}, top_patch);
    }
    const Index outer_base = region.num_points();
    if (has_farfield) {
        // The input's own farfield faces (already oriented into the fluid: reverse them so
        // their normals point out of the region).
        std::vector<Index> map(static_cast<std::size_t>(surface.num_points()), kNone);
        for (Index f = 0; f < surface.num_faces(); ++f) {
            if (surface.patches[static_cast<std::size_t>(surface.face_patch[f])].kind != PatchKind::Farfield) continue;
            Index v[4];
            const Index n = surface.face_size(f);
            for (Index i = 0; i < n; ++i) {
                Index& m = map[static_cast<std::size_t>(surface.face_node(f, i))];
                if (m == kNone) {
                    m = region.num_points();
                    region.points.push_back(surface.points[surface.face_node(f, i)]);
                }
                v[n - 1 - i] = m;
            }
            if (n == 4) {  // TetGen's boundary is triangles
                region.add_face({v[0], v[1], v[2]}, surface.face_patch[f]);
                region.add_face({v[0], v[2], v[3]}, surface.face_patch[f]);
            } else {
                region.add_face(v, 3, surface.face_patch[f]);
            }
        }
    } else {
        const SurfaceMesh ff = make_farfield(surface.points, params.farfield);
        const Index patch = static_cast<Index>(region.patches.size());
        region.patches.push_back({"farfield", PatchKind::Farfield});
        region.points.insert(region.points.end(), ff.points.begin(), ff.points.end());
        for (Index f = 0; f < ff.num_faces(); ++f)
            region.add_face({outer_base + ff.face_node(f, 0), outer_base + ff.face_node(f, 1), outer_base + ff.face_node(f, 2)},
                            patch);
    }
    const TetFill fill = fill_with_tets(region, {point_in_layers(lm)}, params.tets);
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
    for (std::size_t i = static_cast<std::size_t>(nt); i < fill.points.size(); ++i) mesh.points.push_back(fill.points[i]);
    mesh.prisms = lm.mesh.prisms;
    mesh.hexes = lm.mesh.hexes;
    for (const auto& p : pyr.pyramids)
        mesh.pyramids.push_back({to_global(p[0]), to_global(p[1]), to_global(p[2]), to_global(p[3]), to_global(p[4])});
    for (const auto& t : fill.tets) mesh.tets.push_back({to_global(t[0]), to_global(t[1]), to_global(t[2]), to_global(t[3])});
    // Boundary: the walls (as the layers wrote them) and the outer faces of the fill.
    mesh.boundary.patches = surface.patches;
    const SurfaceMesh& lb = lm.mesh.boundary;
    for (Index f = 0; f < lb.num_faces(); ++f) {
        const PatchKind k = lb.patches[static_cast<std::size_t>(lb.face_patch[f])].kind;
        if (k != PatchKind::Wall) continue;  // layer_top is interior now
        mesh.boundary.add_face(lb.face_begin(f), lb.face_size(f), lb.face_patch[f]);
    }
    // Region patches beyond the input's (a generated farfield) are appended once.
    std::vector<Index> patch_of(region.patches.size(), kNone);
    for (Index f = 0; f < region.num_faces(); ++f) {
        const Index rp = region.face_patch[f];
        if (rp == top_patch) continue;
        Index& patch = patch_of[static_cast<std::size_t>(rp)];
        if (patch == kNone) {
            if (rp < static_cast<Index>(surface.patches.size())) {
                patch = rp;
            } else {
                patch = static_cast<Index>(mesh.boundary.patches.size());
                mesh.boundary.patches.push_back(region.patches[static_cast<std::size_t>(rp)]);
            }
        }
        mesh.boundary.add_face({to_global(region.face_node(f, 0)), to_global(region.face_node(f, 1)),
                                to_global(region.face_node(f, 2))},
                               patch);
    }
    rep.validation = require_valid_mesh(mesh, "hybrid mesh");
    rep.seconds_validate = seconds_since(t0);
    if (report) *report = std::move(rep);
    return mesh;
}

}  // namespace strata
