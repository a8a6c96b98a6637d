// The face matcher: slots, the faces across, the problems it names, and a result independent of
// the thread count. The boxes come from box_mesh.h, oriented geometrically there.

#include <strata/core/cell_faces.h>
#include <strata/core/face_match.h>

#include <gtest/gtest.h>

#include "core/box_mesh.h"

#include <algorithm>
#include <string>
#include <vector>

namespace strata {
namespace {

using test::BoxMesh;
using test::CubeSplit;

std::vector<FaceIssue> issues(const FaceMatch& m) {
    std::vector<FaceIssue> out;
    for (const FaceMatch::Problem& p : m.problems) out.push_back(p.issue);
    return out;
}

TEST(FaceSlots, NumberFacesCellByCellInCellNumberingOrder) {
    BoxMesh box(2, 1, 1);
    box.set(1, 0, 0, CubeSplit::Prisms);  // two prisms after the hexahedron of cube 0
    const VolumeMesh m = box.build();
    const FaceSlots slots(m);
    ASSERT_EQ(slots.count(), 2u * 5u + 6u);  // prisms before hexahedra (CellNumbering)
    EXPECT_EQ(slots.start(CellType::Prism), 0u);
    EXPECT_EQ(slots.start(CellType::Hex), 10u);
    const FaceSlots::Slot s = slots.locate(12);
    EXPECT_EQ(s.type, CellType::Hex);
    EXPECT_EQ(s.index, 0);
    EXPECT_EQ(s.face, 2);
    EXPECT_EQ(slots.cell(12), 2);  // the hexahedron is global cell 2
    Index v[4];
    ASSERT_EQ(slots.nodes(12, v), 4);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(v[k], m.hexes[0][static_cast<std::size_t>(kHexFaces.node[2][k])]);
}

TEST(MatchFaces, TwoCubesShareOneFaceAndTheRestIsBoundary) {
    const VolumeMesh m = BoxMesh(2, 1, 1).build();
    const FaceMatch match = match_faces(m);
    EXPECT_TRUE(match.ok());
    EXPECT_EQ(match.interior, 1);
    EXPECT_EQ(match.boundary, 10);
    int interior_slots = 0;
    for (std::uint64_t s = 0; s < match.slots.count(); ++s) {
        const std::int64_t a = match.across[s];
        ASSERT_NE(a, FaceMatch::kUnmatched);
        if (a >= 0) {
            ++interior_slots;
            EXPECT_EQ(match.across[static_cast<std::uint64_t>(a)], static_cast<std::int64_t>(s));
            EXPECT_NE(match.slots.cell(s), match.slots.cell(static_cast<std::uint64_t>(a)));
        } else {
            // The boundary face across has this slot's nodes, in the same orientation.
            const auto f = static_cast<Index>(-1 - a);
            Index v[4];
            const int n = match.slots.nodes(s, v);
            ASSERT_EQ(m.boundary.face_size(f), n);
            EXPECT_EQ(relative_orientation(v, m.boundary.face_begin(f), n), 1);
        }
    }
    EXPECT_EQ(interior_slots, 2);
}

TEST(MatchFaces, NamesEachKindOfProblem) {
    // A third cube on the shared face of two.
    VolumeMesh three = BoxMesh(2, 1, 1).build();
    for (int k = 0; k < 4; ++k) three.points.emplace_back(5.0 + k, 5.0, 5.0);
    three.hexes.push_back({1, 12, 13, 4, 7, 14, 15, 10});
    const FaceMatch m3 = match_faces(three);
    ASSERT_FALSE(m3.ok());
    EXPECT_EQ(m3.problems.front().issue, FaceIssue::SharedByThreeOrMoreCells);
    EXPECT_NE(describe(m3, m3.problems.front()).find("(1 4 10 7) is shared by 3 cells"), std::string::npos);

    // A hexahedron against a cube of six tetrahedra: the quad is explained by its two triangles.
    BoxMesh kuhn(2, 1, 1);
    kuhn.set(1, 0, 0, CubeSplit::Kuhn);
    const FaceMatch mq = match_faces(kuhn.build());
    EXPECT_EQ(issues(mq), std::vector<FaceIssue>{FaceIssue::QuadAgainstTriangles});
    ASSERT_EQ(mq.problems.front().faces.size(), 3u);  // the quad, then the two triangles
    EXPECT_TRUE(mq.is_slot(mq.problems.front().faces[0]));

    // A missing boundary face: a hole; an extra one: stray; one listed twice: duplicated.
    VolumeMesh hole = BoxMesh(1, 1, 1).build();
    hole.boundary.face_offsets.pop_back();
    hole.boundary.face_nodes.resize(static_cast<std::size_t>(hole.boundary.face_offsets.back()));
    hole.boundary.face_patch.pop_back();
    EXPECT_EQ(issues(match_faces(hole)), std::vector<FaceIssue>{FaceIssue::Hole});
    VolumeMesh stray = BoxMesh(1, 1, 1).build();
    stray.boundary.add_face({0, 5, 6}, 1);
    EXPECT_EQ(issues(match_faces(stray)), std::vector<FaceIssue>{FaceIssue::StrayBoundary});
    VolumeMesh twice = BoxMesh(1, 1, 1).build();
    twice.boundary.add_face(twice.boundary.face_begin(0), 4, 2);
    EXPECT_EQ(issues(match_faces(twice)), std::vector<FaceIssue>{FaceIssue::BoundaryDuplicated});

    // A boundary face turned inward.
    VolumeMesh inward = BoxMesh(1, 1, 1).build();
    std::reverse(inward.boundary.face_nodes.begin(), inward.boundary.face_nodes.begin() + 4);
    const FaceMatch mi = match_faces(inward);
    EXPECT_EQ(issues(mi), std::vector<FaceIssue>{FaceIssue::BoundaryMisoriented});
    EXPECT_NE(describe(mi, mi.problems.front()).find("instead of out of the mesh"), std::string::npos);
}

TEST(MatchFaces, SameResultForAnyThreadCount) {
    // 41³ nodes: five chunks of nodes. Holes in several of them.
    VolumeMesh m = BoxMesh(40, 40, 40, 1.0 / 40).build();
    for (std::size_t c : {64u, 21000u, 47000u}) m.hexes.erase(m.hexes.begin() + static_cast<std::ptrdiff_t>(c));
    const FaceMatch one = match_faces(m, 1);
    ASSERT_EQ(one.problems.size(), 18u);  // six faces round each missing cube
    for (int threads : {2, 5}) {
        const FaceMatch r = match_faces(m, threads);
        EXPECT_EQ(r.across, one.across) << threads;
        EXPECT_EQ(r.interior, one.interior) << threads;
        ASSERT_EQ(r.problems.size(), one.problems.size()) << threads;
        for (std::size_t i = 0; i < r.problems.size(); ++i) EXPECT_EQ(r.problems[i].faces, one.problems[i].faces);
    }
}

}  // namespace
}  // namespace strata
