// Edges far shorter than the mesh around them, collapsed (geometry/short_edges.h): a sphere
// with one node moved next to its neighbour (the short side of two needle faces, as a CAD
// model's small edge leaves them) loses that edge and its two needles; the node on a patch seam
// stays where it is; a uniformly fine mesh, symmetry planes and a patch's last faces are left.

#include <strata/geometry/check.h>
#include <strata/geometry/primitives.h>
#include <strata/geometry/short_edges.h>
#include <strata/geometry/topology.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <algorithm>

namespace strata {
namespace {

using test::closed_manifold;
using test::enclosed_volume;

SurfaceMesh sphere() {
    return icosphere(Vec3::Zero(), 1.0, 3, {"wall", PatchKind::Wall});
}

/// Node \p a's neighbours (sorted).
std::vector<Index> neighbours(const SurfaceMesh& m, Index a) {
    std::vector<Index> out;
    for (Index f = 0; f < m.num_faces(); ++f)
        for (Index i = 0; i < 3; ++i)
            if (m.face_node(f, i) == a)
                for (Index j = 1; j < 3; ++j) out.push_back(m.face_node(f, (i + j) % 3));
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

/// The faces with both \p a and \p b.
std::vector<Index> faces_on(const SurfaceMesh& m, Index a, Index b) {
    std::vector<Index> out;
    for (Index f = 0; f < m.num_faces(); ++f) {
        const Index* v = m.face_begin(f);
        if (std::find(v, v + 3, a) != v + 3 && std::find(v, v + 3, b) != v + 3) out.push_back(f);
    }
    return out;
}

/// True if \p p is (to rounding) one of \p m's points.
bool has_point(const SurfaceMesh& m, const Vec3& p) {
    return std::any_of(m.points.begin(), m.points.end(), [&](const Vec3& q) { return (q - p).norm() < 1e-14; });
}

/// \p m with node \p a moved to 1e-3 of the way from its neighbour \p b: edge (a, b) 1e-3 of its
/// old length, its two faces needles.
SurfaceMesh with_short_edge(SurfaceMesh m, Index a, Index b) {
    m.points[a] = m.points[b] + 1e-3 * (m.points[a] - m.points[b]);
    return m;
}

TEST(ShortEdges, ATinyEdgeAndItsTwoNeedlesGoTheOtherNodesStay) {
    const SurfaceMesh clean = sphere();
    const Index a = 40, b = neighbours(clean, a).front();
    const SurfaceMesh m = with_short_edge(clean, a, b);
    ASSERT_EQ(faces_on(m, a, b).size(), 2u);
    EXPECT_EQ(needle_faces(m, kNeedleCornerDeg).needles, 2);

    ShortEdgeReport rep;
    const SurfaceMesh out = collapse_short_edges(m, 0.05, &rep);
    EXPECT_EQ(rep.collapsed, 1);
    EXPECT_EQ(rep.left, 0);
    EXPECT_NEAR(rep.longest, (m.points[a] - m.points[b]).norm(), 1e-15);
    EXPECT_LT(rep.largest_share, 2e-3);
    EXPECT_EQ(out.num_faces(), m.num_faces() - 2);
    EXPECT_EQ(out.num_points(), m.num_points() - 1);
    EXPECT_TRUE(closed_manifold(out));
    EXPECT_NO_THROW(check_surface(out, "collapsed"));
    EXPECT_EQ(needle_faces(out, kNeedleCornerDeg).needles, 0);
    // Outward still, the same volume to the size of the moved node's faces, every point one of
    // the input's (the node that moved is gone, none was made).
    EXPECT_NEAR(enclosed_volume(out), enclosed_volume(m), 1e-3 * enclosed_volume(m));
    for (const Vec3& p : out.points) EXPECT_TRUE(has_point(m, p));
    // The higher id of the two (a tie: both in one smooth patch) is the one that moved.
    EXPECT_EQ(rep.where, m.points[std::max(a, b)]);

    // Off: the mesh as it was.
    ShortEdgeReport none;
    const SurfaceMesh same = collapse_short_edges(m, 0.0, &none);
    EXPECT_EQ(none.collapsed, 0);
    EXPECT_EQ(same.face_nodes, m.face_nodes);
}

TEST(ShortEdges, TheNodeOnAPatchSeamStays) {
    // Two patches, the faces above and below z = 0; the short edge joins a node of the seam
    // (faces of both patches round it) and one inside the top patch. Whichever id is higher, the
    // inner node moves onto the seam node, so the seam keeps its line.
    SurfaceMesh clean = sphere();
    clean.patches.push_back({"bottom", PatchKind::Wall});
    for (Index f = 0; f < clean.num_faces(); ++f) {
        double z = 0.0;
        for (Index i = 0; i < 3; ++i) z += clean.points[clean.face_node(f, i)].z();
        if (z < 0.0) clean.face_patch[f] = 1;
    }
    auto on_seam = [&](Index v) {
        bool top = false, bottom = false;
        for (Index f = 0; f < clean.num_faces(); ++f)
            for (Index i = 0; i < 3; ++i)
                if (clean.face_node(f, i) == v) (clean.face_patch[f] == 0 ? top : bottom) = true;
        return top && bottom;
    };
    int tested = 0;
    for (Index s = 0; s < clean.num_points() && tested < 2; ++s) {
        if (!on_seam(s)) continue;
        for (const Index i : neighbours(clean, s)) {
            bool inner = !on_seam(i);
            for (const Index j : neighbours(clean, i)) inner &= !on_seam(j) || j == s;
            if (!inner) continue;
            // One case with the inner node's id above the seam node's, one below.
            if ((tested == 0) != (i > s)) continue;
            const SurfaceMesh m = with_short_edge(clean, i, s);
            ShortEdgeReport rep;
            const SurfaceMesh out = collapse_short_edges(m, 0.05, &rep);
            EXPECT_EQ(rep.collapsed, 1) << "seam node " << s << ", inner node " << i;
            EXPECT_EQ(rep.where, m.points[i]);
            EXPECT_TRUE(has_point(out, m.points[s]));
            EXPECT_FALSE(has_point(out, m.points[i]));
            EXPECT_TRUE(closed_manifold(out));
            ++tested;
            break;
        }
    }
    EXPECT_EQ(tested, 2);
}

TEST(ShortEdges, AUniformlyFineMeshIsLeftAlone) {
    // Every edge is about as long as its neighbours: none is an outlier, even at the largest
    // share allowed.
    const SurfaceMesh fine = icosphere(Vec3::Zero(), 1e-3, 4, {"wall", PatchKind::Wall});
    ShortEdgeReport rep;
    const SurfaceMesh out = collapse_short_edges(fine, 0.5, &rep);
    EXPECT_EQ(rep.collapsed, 0);
    EXPECT_EQ(rep.left, 0);
    EXPECT_EQ(out.face_nodes, fine.face_nodes);
    EXPECT_EQ(out.points, fine.points);
}

TEST(ShortEdges, SymmetryPlanesAndAPatchsLastFacesAreLeftAndCounted) {
    const SurfaceMesh clean = sphere();
    const Index a = 40, b = neighbours(clean, a).front();
    const std::vector<Index> two = faces_on(clean, a, b);
    for (const PatchKind kind : {PatchKind::Symmetry, PatchKind::Wall}) {
        // The two faces on the edge are a patch of their own: a symmetry plane (its nodes must
        // stay in it), or a wall patch that would lose every face.
        SurfaceMesh m = with_short_edge(clean, a, b);
        m.patches.push_back({"small", kind});
        for (const Index f : two) m.face_patch[f] = 1;
        ShortEdgeReport rep;
        const SurfaceMesh out = collapse_short_edges(m, 0.05, &rep);
        EXPECT_EQ(rep.collapsed, 0) << to_string(kind);
        EXPECT_EQ(rep.left, 1) << to_string(kind);
        EXPECT_LT(rep.left_share, 2e-3);
        EXPECT_LT((rep.left_where - 0.5 * (m.points[a] + m.points[b])).norm(), 1e-12);
        EXPECT_EQ(out.face_nodes, m.face_nodes);
    }
}

TEST(ShortEdges, NothingOnAnOpenBoundaryMoves) {
    // A sphere cut open: the faces round the short edge's nodes lose one face each, so both
    // nodes lie on the hole's rim.
    const SurfaceMesh clean = sphere();
    const Index a = 40, b = neighbours(clean, a).front();
    SurfaceMesh m = with_short_edge(clean, a, b);
    Index at_a = kNone, at_b = kNone;  // a face at a without b, one at b without a
    for (Index f = 0; f < m.num_faces(); ++f) {
        const Index* v = m.face_begin(f);
        const bool has_a = std::find(v, v + 3, a) != v + 3, has_b = std::find(v, v + 3, b) != v + 3;
        if (has_a && !has_b && at_a == kNone) at_a = f;
        if (has_b && !has_a && at_b == kNone) at_b = f;
    }
    std::vector<char> drop(static_cast<std::size_t>(m.num_faces()), 0);
    drop[static_cast<std::size_t>(at_a)] = drop[static_cast<std::size_t>(at_b)] = 1;
    const SurfaceMesh open = remove_faces(m, drop);
    ASSERT_FALSE(closed_manifold(open));
    ShortEdgeReport rep;
    const SurfaceMesh out = collapse_short_edges(open, 0.05, &rep);
    EXPECT_EQ(rep.collapsed, 0);
    EXPECT_EQ(out.face_nodes, open.face_nodes);
}

}  // namespace
}  // namespace strata
