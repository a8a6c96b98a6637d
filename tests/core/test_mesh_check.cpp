// The one array check: every problem named, indexability, the error kind require_sound throws.

#include <strata/core/error.h>
#include <strata/core/mesh_check.h>

#include <gtest/gtest.h>

#include "core/box_mesh.h"
#include "test_support.h"

#include <cmath>
#include <string>

namespace strata {
namespace {

bool mentions(const MeshProblems& p, const std::string& text) {
    for (const std::string& l : p.lines)
        if (l.find(text) != std::string::npos) return true;
    return false;
}

TEST(CheckFaceArrays, SoundMeshesPass) {
    EXPECT_TRUE(check_surface_arrays(test::quad_grid(3, 2)).ok());
    EXPECT_TRUE(check_volume_arrays(test::BoxMesh(2, 2, 2).build()).ok());
}

TEST(CheckFaceArrays, NamesEachProblem) {
    SurfaceMesh m = test::quad_grid(2, 2);
    m.add_face({0, 1, 99}, 0);  // node out of range
    m.add_face({0, 1, 2}, 7);   // patch out of range
    m.points[3].x() = NAN;      // non-finite
    const MeshProblems p = check_surface_arrays(m);
    EXPECT_EQ(p.count, 3u);
    EXPECT_FALSE(p.indexable);
    EXPECT_TRUE(mentions(p, "face 4 (0 1 99) uses node 99, but the mesh has 9 nodes"));
    EXPECT_TRUE(mentions(p, "face 5 is on patch 7, but there are 1 patches"));
    EXPECT_TRUE(mentions(p, "node 3 has a non-finite coordinate"));
    EXPECT_FALSE(p.first_non_finite);
    EXPECT_THROW(require_sound(p, "x: "), InputError);

    SurfaceMesh q = test::quad_grid(1, 1);
    EXPECT_FALSE(check_surface_arrays(q, {.triangles_only = true}).ok());  // TetGen takes triangles only
    q.points[0].z() = INFINITY;
    const MeshProblems nf = check_surface_arrays(q);
    EXPECT_TRUE(nf.first_non_finite);
    EXPECT_TRUE(nf.indexable);
    EXPECT_THROW(require_sound(nf, "x: "), TopologyError);
    EXPECT_TRUE(check_surface_arrays(q, {.coordinates = false}).ok());

    EXPECT_TRUE(mentions(check_surface_arrays(SurfaceMesh{}), "no faces"));
    EXPECT_TRUE(check_surface_arrays(SurfaceMesh{}, {.require_faces = false}).ok());
}

TEST(CheckFaceArrays, DecreasingOffsetsAreMalformed) {
    // Start 0 and end at the node count, but a face in the middle runs past the end (a fuzzer's
    // find: the check read face_nodes beyond its size).
    SurfaceMesh m = test::quad_grid(3, 1);  // offsets 0 4 8 12
    m.face_offsets[1] = 10;
    m.face_offsets[2] = 6;
    const MeshProblems p = check_surface_arrays(m);
    EXPECT_FALSE(p.indexable);
    EXPECT_TRUE(mentions(p, "face offsets are malformed (they must start at 0, never decrease")) << p.lines[0];
    EXPECT_THROW(require_sound(p, "x: "), InputError);
}

TEST(CheckVolumeArrays, NamesCellsAndBoundaryFacesAndKeepsFiveLines) {
    VolumeMesh m = test::BoxMesh(3, 1, 1).build();
    for (std::size_t c = 0; c < 3; ++c) m.hexes[c][0] = 500;
    m.boundary.face_nodes[0] = -1;
    m.boundary.face_nodes[4] = -2;
    m.boundary.face_nodes[8] = -3;
    const MeshProblems p = check_volume_arrays(m);
    EXPECT_EQ(p.count, 6u);
    EXPECT_EQ(p.lines.size(), MeshProblems::kMaxLines);
    EXPECT_FALSE(p.indexable);
    EXPECT_TRUE(mentions(p, "hexahedron 0 (500 1 5 4 8 9 13 12) uses node 500 but the mesh has 16 nodes"));
    EXPECT_TRUE(mentions(p, "boundary face 0"));
    EXPECT_TRUE(mentions(check_volume_arrays(VolumeMesh{}), "no cells"));
    try {
        require_sound(p, "cannot write 'm.msh': ");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("(and 5 more problems)"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace strata
