#pragma once
// Shared by the layer module's tests: the layers are the same, bit for bit, for any thread count.

#include <strata/core/surface_mesh.h>
#include <strata/module/layers.h>

#include <gtest/gtest.h>

namespace strata::test {

/// extrude_layers of \p wall with \p p (and \p c) on 1 and on 2 threads: the same points and cells.
inline void expect_same_bytes_for_any_thread_count(const SurfaceMesh& wall, LayerParams p,
                                                   const LayerConstraints& c = {}) {
    p.threads = 1;
    const LayerMesh one = extrude_layers(wall, p, c);
    p.threads = 2;
    const LayerMesh two = extrude_layers(wall, p, c);
    EXPECT_EQ(one.mesh.points, two.mesh.points);
    EXPECT_EQ(one.mesh.hexes, two.mesh.hexes);
    EXPECT_EQ(one.mesh.prisms, two.mesh.prisms);
    EXPECT_EQ(one.mesh.pyramids, two.mesh.pyramids);
    EXPECT_EQ(one.mesh.tets, two.mesh.tets);
}

}  // namespace strata::test
