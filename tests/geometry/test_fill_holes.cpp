// Holes closed by triangles (geometry/fill_holes.h): the sphere of examples/data with faces
// taken out is closed again, as it was oriented, in the patch round each hole; loops larger
// than asked stay open.

#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/geometry/fill_holes.h>
#include <strata/geometry/topology.h>
#include <strata/surface/prepare.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <cmath>
#include <map>
#include <numbers>
#include <set>

namespace strata {
namespace {

/// The merged, oriented unit sphere of examples/data (606 triangles, radius 1), two patches:
/// the faces above z = 0.5 in "cap", the others in "sphere".
SurfaceMesh sphere() {
    SurfaceMesh m = prepare_surface(test::example_data("sphere.stl"), {});
    m.patches = {{"sphere", PatchKind::Wall}, {"cap", PatchKind::Wall}};
    for (Index f = 0; f < m.num_faces(); ++f) m.face_patch[f] = face_centroid(m, m.points, f).z() > 0.5 ? 1 : 0;
    return m;
}

/// \p m without the faces \p drop.
SurfaceMesh without(const SurfaceMesh& m, const std::set<Index>& drop) {
    std::vector<char> gone(static_cast<std::size_t>(m.num_faces()), 0);
    for (const Index f : drop) gone[static_cast<std::size_t>(f)] = 1;
    return remove_faces(m, gone);
}

/// Every directed edge used once and its reverse once: closed and consistently oriented.
bool oriented_closed(const SurfaceMesh& m) {
    std::map<std::pair<Index, Index>, int> uses;
    for (Index f = 0; f < m.num_faces(); ++f)
        for (Index i = 0, n = m.face_size(f); i < n; ++i) ++uses[{m.face_node(f, i), m.face_node(f, (i + 1) % n)}];
    for (const auto& [e, n] : uses)
        if (n != 1 || !uses.count({e.second, e.first})) return false;
    return true;
}

/// The faces round node \p v.
std::set<Index> faces_at(const SurfaceMesh& m, Index v) {
    std::set<Index> out;
    for (Index f = 0; f < m.num_faces(); ++f)
        for (Index i = 0; i < m.face_size(f); ++i)
            if (m.face_node(f, i) == v) out.insert(f);
    return out;
}

TEST(FillHoles, MissingFacesAreClosedAsTheSurfaceWasOrientedInThePatchRoundThem) {
    const SurfaceMesh full = sphere();
    // One face missing low on the sphere, and every face round a node of the cap (a hole of as
    // many edges as the node had neighbours).
    Index capped = kNone;
    for (Index v = 0; v < full.num_points() && capped == kNone; ++v)
        if (full.points[static_cast<std::size_t>(v)].z() > 0.8) capped = v;
    ASSERT_NE(capped, kNone);
    std::set<Index> drop = faces_at(full, capped);
    const auto ring = static_cast<Index>(drop.size());
    Index low = kNone;
    for (Index f = 0; f < full.num_faces() && low == kNone; ++f)
        if (face_centroid(full, full.points, f).z() < -0.5) low = f;
    drop.insert(low);
    const SurfaceMesh holed = without(full, drop);
    ASSERT_EQ(boundary_loops(holed).rows(), 2);

    HoleReport r;
    const SurfaceMesh m = fill_holes(holed, ring, &r);
    EXPECT_EQ(r.holes, 2);
    EXPECT_EQ(r.triangles, 1 + (ring - 2));
    EXPECT_EQ(r.largest, ring);
    EXPECT_LT((r.where - full.points[static_cast<std::size_t>(capped)]).norm(), 0.2);
    EXPECT_EQ(r.left, 0);
    EXPECT_TRUE(oriented_closed(m));
    EXPECT_NEAR(test::enclosed_volume(m), test::enclosed_volume(full), 0.01 * test::enclosed_volume(full));
    // The new faces: the low one in "sphere", the cap's in "cap".
    for (Index f = holed.num_faces(); f < m.num_faces(); ++f)
        EXPECT_EQ(m.face_patch[f], face_centroid(m, m.points, f).z() > 0.5 ? 1 : 0) << f;
    EXPECT_EQ(m.num_points(), holed.num_points());  // no node added
}

TEST(FillHolesLimits, LoopsLargerThanAskedStayOpen) {
    const SurfaceMesh full = sphere();
    // A hole of 3 edges, and the faces above z = 0.9 taken away (a large loop).
    std::set<Index> drop;
    bool low = false;
    for (Index f = 0; f < full.num_faces(); ++f) {
        const double z = face_centroid(full, full.points, f).z();
        if (z > 0.9 || (z < -0.5 && !low)) drop.insert(f);
        low = low || z < -0.5;
    }
    const SurfaceMesh holed = without(full, drop);
    const Csr loops = boundary_loops(holed);
    ASSERT_EQ(loops.rows(), 2) << drop.size() << " faces dropped of " << full.num_faces();
    const Index big = std::max(loops.row_size(0), loops.row_size(1));
    ASSERT_GT(big, 3);
    HoleReport r;
    const SurfaceMesh m = fill_holes(holed, 3, &r);
    EXPECT_EQ(r.holes, 1);
    EXPECT_EQ(r.left, 1);
    EXPECT_EQ(r.largest_left, big);
    EXPECT_EQ(boundary_loops(m).rows(), 1);
    // Nothing asked: nothing changes.
    EXPECT_EQ(fill_holes(holed, 0).num_faces(), holed.num_faces());
    EXPECT_TRUE(test::closed_manifold(fill_holes(holed, big)));
}

/// A tube of radius 0.5 along x from 0 to 3, open at both ends: \p around nodes per ring, 20
/// rings, triangles in patch "vessel", oriented outward.
SurfaceMesh open_tube(int around) {
    SurfaceMesh m;
    m.patches.push_back({"vessel", PatchKind::Wall});
    const int rings = 20;
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < around; ++j) {
            const double t = 2.0 * std::numbers::pi * j / around;
            m.points.emplace_back(3.0 * i / (rings - 1), 0.5 * std::cos(t), 0.5 * std::sin(t));
        }
    const auto at = [&](int i, int j) { return static_cast<Index>(i * around + (j % around)); };
    for (int i = 0; i + 1 < rings; ++i)
        for (int j = 0; j < around; ++j) {
            m.add_face({at(i, j), at(i, j + 1), at(i + 1, j + 1)}, 0);
            m.add_face({at(i, j), at(i + 1, j + 1), at(i + 1, j)}, 0);
        }
    return m;
}

TEST(CapHoles, EachOpeningGetsAPlanarCapOfItsOwnWithNodesInside) {
    const SurfaceMesh tube = open_tube(32);
    HoleReport r;
    const SurfaceMesh m = cap_holes(tube, 64, &r);
    EXPECT_TRUE(r.caps);
    EXPECT_EQ(r.holes, 2);
    EXPECT_EQ(r.largest, 32);
    EXPECT_TRUE(oriented_closed(m));
    ASSERT_EQ(m.patches.size(), 3u);
    EXPECT_EQ(m.patches[1].name, "cap_1");
    EXPECT_EQ(m.patches[2].name, "cap_2");
    EXPECT_EQ(m.patches[1].kind, PatchKind::Other);
    EXPECT_EQ(m.patches[2].kind, PatchKind::Other);
    // Nodes inside each cap (a fan of 30 triangles from the rim would be needles), every one in
    // its cut's plane, and the caps' faces facing out of the tube.
    EXPECT_GT(m.num_points(), tube.num_points() + 20);
    std::set<Index> cap_nodes;
    for (Index f = 0; f < m.num_faces(); ++f) {
        if (m.face_patch[f] == 0) continue;
        const double x = m.face_patch[f] == 1 ? 0.0 : 3.0;
        const Vec3 c = face_centroid(m, m.points, f);
        EXPECT_NEAR(c.x(), x, 1e-12);
        EXPECT_GT(face_area_vector(m, f).x() * (x == 0.0 ? -1.0 : 1.0), 0.0) << "face " << f;
        for (Index i = 0; i < 3; ++i) cap_nodes.insert(m.face_node(f, i));
    }
    EXPECT_GT(cap_nodes.size(), 64u + 20u);
    // The tube's own faces unchanged; the same bytes twice.
    for (Index f = 0; f < tube.num_faces(); ++f) EXPECT_EQ(m.face_patch[f], 0);
    const SurfaceMesh again = cap_holes(tube, 64);
    EXPECT_EQ(again.points, m.points);
    EXPECT_EQ(again.face_nodes, m.face_nodes);
    // Loops larger than asked stay open and take no patch.
    HoleReport none;
    const SurfaceMesh open = cap_holes(tube, 16, &none);
    EXPECT_EQ(none.left, 2);
    EXPECT_EQ(open.patches.size(), 1u);
}

}  // namespace
}  // namespace strata
