#pragma once
// Shared by the layer module's tests: the layers are the same, bit for bit, for any thread count.

#include <strata/core/surface_mesh.h>
#include <strata/module/layers.h>

#include <gtest/gtest.h>

namespace strata::test {

/// The same layers, bit for bit: points, cells, and every column's layers.
inline void expect_same_layers(const LayerMesh& a, const LayerMesh& b, const char* what = "") {
    EXPECT_EQ(a.mesh.points, b.mesh.points) << what;
    EXPECT_EQ(a.mesh.hexes, b.mesh.hexes) << what;
    EXPECT_EQ(a.mesh.prisms, b.mesh.prisms) << what;
    EXPECT_EQ(a.mesh.pyramids, b.mesh.pyramids) << what;
    EXPECT_EQ(a.mesh.tets, b.mesh.tets) << what;
    ASSERT_EQ(a.wall_nodes(), b.wall_nodes()) << what;
    for (Index i = 0; i < a.wall_nodes(); ++i) EXPECT_EQ(a.node_layers(i), b.node_layers(i)) << what << ", node " << i;
}

/// extrude_layers of \p wall with \p p (and \p c) on 1 and on 2 threads: the same points and cells.
inline void expect_same_bytes_for_any_thread_count(const SurfaceMesh& wall, LayerParams p,
                                                   const LayerConstraints& c = {}) {
    p.threads = 1;
    const LayerMesh one = extrude_layers(wall, p, c);
    p.threads = 2;
    const LayerMesh two = extrude_layers(wall, p, c);
    expect_same_layers(one, two, "1 and 2 threads");
}

}  // namespace strata::test
