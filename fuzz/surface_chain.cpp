// The geometry stage's input code on whatever mesh a fuzz target made: every piece alone, then
// prepare_mesh as a whole, with a few oracles on what it returns (surface_chain.h).

#include <strata/core/error.h>
#include <strata/geometry/check.h>
#include <strata/geometry/topology.h>
#include <strata/surface/prepare.h>

#include "fuzz_support.h"
#include "surface_chain.h"

#include <string>

namespace strata::fuzz {
namespace {

/// Run \p f; a strata::Error is an expected outcome (false), anything else escapes.
template <class F>
bool survives(F&& f) {
    try {
        f();
        return true;
    } catch (const Error&) {
        return false;
    }
}

/// The derived connectivity of \p mesh (each piece refuses bad ids itself) and its sizes.
void connectivity(const SurfaceMesh& mesh) {
    survives([&] {
        const Csr vf = vertex_faces(mesh);
        require(vf.rows() == mesh.num_points(), "vertex_faces has a row per node");
    });
    survives([&] {
        const EdgeTable edges = edge_table(mesh);
        require(edges.faces.rows() == static_cast<Index>(edges.nodes.size()), "edge_table has faces per edge");
    });
    survives([&] { boundary_loops(mesh); });
    survives([&] {
        Index count = 0;
        const std::vector<Index> comp = face_components(mesh, &count);
        require(comp.size() == static_cast<std::size_t>(mesh.num_faces()), "face_components has one per face");
    });
    survives([&] {
        const NodeRings rings = node_rings(mesh);
        require(rings.neighbours.rows() == mesh.num_points(), "node_rings has a ring per node");
        require(rings.faces.size() == rings.neighbours.values.size(), "node_rings' faces align with neighbours");
    });
}

}  // namespace

int run_surface_chain(const SurfaceMesh& mesh, const PrepareParams& params, const std::string& source) {
    // The pieces alone on the mesh as given. orient_surface and needle_faces require a mesh
    // that check_surface passed (their documented precondition).
    connectivity(mesh);
    if (survives([&] { check_surface(mesh, source); })) {
        survives([&] {
            const SurfaceMesh oriented = orient_surface(mesh, nullptr, params.internal_flow);
            require(oriented.num_faces() == mesh.num_faces(), "orient_surface keeps every face");
            node_rings(oriented);
        });
        needle_faces(mesh, kNeedleCornerDeg);
    }

    // The whole chain.
    SurfaceMesh prepared;
    PrepareReport report;
    if (!survives([&] { prepared = prepare_mesh(mesh, params, source, &report); })) return 0;
    // What prepare_mesh returns has passed check_surface; orienting must not have changed that.
    require(survives([&] { check_surface(prepared, source + " (prepared)"); }),
            "the prepared surface passes check_surface");
    require(report.merged_nodes >= 0 && report.collapsed_faces >= 0, "the report's counts are not negative");
    needle_faces(prepared, kNeedleCornerDeg, {PatchKind::Wall});
    connectivity(prepared);
    return survives([&] { node_rings(prepared); }) ? 2 : 1;
}

}  // namespace strata::fuzz
