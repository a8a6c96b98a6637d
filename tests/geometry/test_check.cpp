#include <gtest/gtest.h>

#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/geometry/check.h>
#include <strata/geometry/primitives.h>
#include <strata/geometry/topology.h>

#include "test_support.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace strata {
namespace {

using test::quad_grid;

// ---------------------------------------------------------------- helpers

/// Runs \p f, expects exception E, returns its message.
template <class E, class F>
std::string message_of(F&& f) {
    return test::error_message<E>(std::forward<F>(f));
}

bool contains(const std::string& s, const std::string& part) {
    return s.find(part) != std::string::npos;
}

/// Append an icosphere (20·4^levels triangles) of \p radius around \p centre on \p patch,
/// every face oriented outward (checked here from geometry, so the builder cannot silently be
/// inward).
void add_icosphere(SurfaceMesh& m, int levels, double radius, const Vec3& centre, Index patch) {
    const SurfaceMesh s = icosphere(centre, radius, levels, {"sphere", PatchKind::Wall});
    const Index base = m.num_points();
    m.points.insert(m.points.end(), s.points.begin(), s.points.end());
    for (Index f = 0; f < s.num_faces(); ++f) {
        const Vec3 a = s.points[s.face_node(f, 0)], b = s.points[s.face_node(f, 1)], c = s.points[s.face_node(f, 2)];
        ASSERT_GT((b - a).cross(c - a).dot(a - centre), 0.0) << "icosphere face " << f << " points inward";
        m.add_face({base + s.face_node(f, 0), base + s.face_node(f, 1), base + s.face_node(f, 2)}, patch);
    }
}

SurfaceMesh sphere(int levels = 2, double radius = 1.0, const Vec3& centre = Vec3::Zero(),
                   PatchKind kind = PatchKind::Wall) {
    SurfaceMesh m;
    m.patches.push_back({kind == PatchKind::Farfield ? "farfield" : "wall", kind});
    add_icosphere(m, levels, radius, centre, 0);
    return m;
}

/// Reverse face f completely (a,b,c → c,b,a): a different node order from orient's own flip.
void reverse_face(SurfaceMesh& m, Index f) {
    std::reverse(m.face_nodes.begin() + m.face_offsets[f], m.face_nodes.begin() + m.face_offsets[f + 1]);
}

/// Signed "outwardness" of face f relative to centre: > 0 when its normal points away.
double outwardness(const SurfaceMesh& m, Index f, const Vec3& centre) {
    return face_area_vector(m, f).dot(face_centroid(m, m.points, f) - centre);
}

/// Same node set, same first node: orient only reorders the tail of a face.
void expect_same_faces_up_to_orientation(const SurfaceMesh& a, const SurfaceMesh& b) {
    ASSERT_EQ(a.num_faces(), b.num_faces());
    EXPECT_EQ(a.face_offsets, b.face_offsets);
    EXPECT_EQ(a.points, b.points);
    EXPECT_EQ(a.face_patch, b.face_patch);
    for (Index f = 0; f < a.num_faces(); ++f) {
        std::vector<Index> x(a.face_begin(f), a.face_end(f)), y(b.face_begin(f), b.face_end(f));
        EXPECT_EQ(x[0], y[0]) << "face " << f;
        std::sort(x.begin(), x.end());
        std::sort(y.begin(), y.end());
        EXPECT_EQ(x, y) << "face " << f;
    }
}

// ---------------------------------------------------------------- check_surface

TEST(NeedleFaces, CountsFacesWithACornerBelowTheBoundAndNamesTheSharpest) {
    SurfaceMesh m;
    m.patches = {{"body", PatchKind::Wall}, {"plane", PatchKind::Symmetry}};
    m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0),  Vec3(0, 1, 0),      // right isoceles: 45° corners
                Vec3(2, 0, 0), Vec3(12, 0, 0), Vec3(12, 0.5, 0),   // a needle: atan(0.05) = 2.86°
                Vec3(0, 0, 5), Vec3(10, 0, 5), Vec3(10, 0.1, 5)};  // sharper (0.57°), on the plane
    m.add_face({0, 1, 2}, 0);
    m.add_face({3, 4, 5}, 0);
    m.add_face({6, 7, 8}, 1);
    const NeedleReport all = needle_faces(m, 5.0);
    EXPECT_EQ(all.faces, 3);
    EXPECT_EQ(all.needles, 2);
    EXPECT_EQ(all.worst_face, 2);
    EXPECT_NEAR(all.sharpest_deg, std::atan(0.01) * 180.0 / std::numbers::pi, 1e-9);
    EXPECT_EQ(all.where, m.points[6]);
    const NeedleReport walls = needle_faces(m, 5.0, {PatchKind::Wall});
    EXPECT_EQ(walls.faces, 2);
    EXPECT_EQ(walls.needles, 1);
    EXPECT_EQ(walls.worst_face, 1);
    EXPECT_NEAR(walls.sharpest_deg, std::atan(0.05) * 180.0 / std::numbers::pi, 1e-9);
    EXPECT_EQ(walls.where, m.points[3]);
    EXPECT_EQ(needle_faces(m, 2.0, {PatchKind::Wall}).needles, 0);
}

TEST(CheckSurface, ValidMeshesPass) {
    EXPECT_NO_THROW(check_surface(quad_grid(4, 3), "grid"));
    EXPECT_NO_THROW(check_surface(sphere(), "sphere"));
    // The area threshold is relative: a millimetre-sized model is not degenerate.
    EXPECT_NO_THROW(check_surface(quad_grid(10, 10, 1e-7), "tiny"));
    EXPECT_NO_THROW(check_surface(sphere(1, 1e-4, Vec3(1e3, 0, 0)), "far"));
}

TEST(CheckSurface, EmptyMeshIsAnInputError) {
    const std::string msg = message_of<InputError>([] { check_surface(SurfaceMesh{}, "wing.stl"); });
    EXPECT_EQ(msg.rfind("wing.stl: no faces", 0), 0u) << msg;
}

TEST(CheckSurface, NonFiniteCoordinateNamesTheNode) {
    SurfaceMesh m = quad_grid(2, 2);
    m.points[4].y() = std::numeric_limits<double>::quiet_NaN();
    std::string msg = message_of<TopologyError>([&] { check_surface(m, "body.msh"); });
    EXPECT_EQ(msg.rfind("body.msh: ", 0), 0u) << msg;
    EXPECT_TRUE(contains(msg, "node 4 ")) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos);

    m.points[4].y() = 1.0;
    m.points[7].z() = std::numeric_limits<double>::infinity();
    msg = message_of<TopologyError>([&] { check_surface(m, "body.msh"); });
    EXPECT_TRUE(contains(msg, "node 7 ")) << msg;
}

TEST(CheckSurface, SpanFrom1e100IsATopologyErrorGivingTheBox) {
    // Areas (squares) and the volumes orientation needs (cubes) overflow a double near 1e102.
    test::expect_error<TopologyError>(
        [] { check_surface(quad_grid(1, 1, 1e100), "huge.stl"); },
        {"huge.stl: the nodes span from (0, 0, 0) to (1e+100, 1e+100, 0)", "diagonal of 1.41e+100", "wrong unit"});
    EXPECT_NO_THROW(check_surface(quad_grid(1, 1, 1e99), "large.stl"));
}

TEST(CheckSurface, OutOfRangeNodeId) {
    SurfaceMesh m = quad_grid(1, 1);
    m.add_face({0, 2, 99}, 0);
    const std::string msg = message_of<InputError>([&] { check_surface(m, "in.stl"); });
    EXPECT_TRUE(contains(msg, "face 1 ")) << msg;
    EXPECT_TRUE(contains(msg, "node 99")) << msg;
}

/// A unit quad plus a triangle (\p face) on a second patch \p patch over the extra \p points:
/// the TopologyError check_surface gives for it, read as "in.msh".
std::string message_for_extra_face(const std::string& patch, const std::vector<Vec3>& points,
                                   std::initializer_list<Index> face) {
    SurfaceMesh m = quad_grid(1, 1);
    m.patches.push_back({patch, PatchKind::Wall});
    m.points.insert(m.points.end(), points.begin(), points.end());
    m.add_face(face, 1);
    return message_of<TopologyError>([&] { check_surface(m, "in.msh"); });
}

TEST(CheckSurface, RepeatedNodeNamesTheFaceAndPatch) {
    const std::string msg = message_for_extra_face("fin", {Vec3(2, 0, 0)}, {1, 4, 4});
    EXPECT_EQ(msg.rfind("in.msh: face 1 ", 0), 0u) << msg;
    EXPECT_TRUE(contains(msg, "'fin'")) << msg;
    EXPECT_TRUE(contains(msg, "node 4 twice")) << msg;
}

TEST(CheckSurface, ZeroAreaFaceNamesTheFacePatchAndCentroid) {
    const std::string msg = message_for_extra_face("flap", {Vec3(2, 0, 0), Vec3(3, 0, 0)}, {1, 4, 5});  // collinear
    EXPECT_TRUE(contains(msg, "face 1 ")) << msg;
    EXPECT_TRUE(contains(msg, "'flap'")) << msg;
    EXPECT_TRUE(contains(msg, "(2, 0, 0)")) << msg;  // centroid
    EXPECT_TRUE(contains(msg, "zero area")) << msg;

    // Near zero relative to the model: a sliver of area ~1e-15 in a unit model.
    SurfaceMesh s = quad_grid(1, 1);
    s.points.emplace_back(0.5, 1e-15, 0.0);
    s.add_face({0, 1, 4}, 0);
    EXPECT_TRUE(contains(message_of<TopologyError>([&] { check_surface(s, "s"); }), "face 1 "));
}

TEST(CheckSurface, NonManifoldEdgeNamesBothNodesAndTheFaces) {
    SurfaceMesh m;
    m.patches.push_back({"wall", PatchKind::Wall});
    m.points = {Vec3(1, 0, 0.5), Vec3(-1, 0, 0.5), Vec3(0, 1, 0.5), Vec3(0, -1, 0.5),
                Vec3(0, 0, 0),   Vec3(5, 5, 5),    Vec3(6, 5, 5),   Vec3(0, 0, 1)};
    m.add_face({4, 7, 0}, 0);
    m.add_face({7, 4, 1}, 0);
    m.add_face({4, 7, 2}, 0);  // third face on edge 4–7
    m.add_face({3, 5, 6}, 0);
    const std::string msg = message_of<TopologyError>([&] { check_surface(m, "fins.stl"); });
    EXPECT_EQ(msg.rfind("fins.stl: ", 0), 0u) << msg;
    EXPECT_TRUE(contains(msg, "node 4 (0, 0, 0)")) << msg;
    EXPECT_TRUE(contains(msg, "node 7 (0, 0, 1)")) << msg;
    EXPECT_TRUE(contains(msg, "3 faces: 0 ")) << msg;
    EXPECT_TRUE(contains(msg, ", 1 ") && contains(msg, ", 2 ")) << msg;
    EXPECT_TRUE(contains(msg, "merge the duplicate faces")) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos);
}

TEST(CheckSurface, SameDirectionEdgeIsLeftToOrient) {
    SurfaceMesh m = quad_grid(2, 1);
    reverse_face(m, 1);
    EXPECT_NO_THROW(check_surface(m, "grid"));
}

// ---------------------------------------------------------------- orient_surface

TEST(OrientSurface, SphereWithThirtyPercentFlippedFacesIsRepairedOutward) {
    const SurfaceMesh good = sphere();
    ASSERT_EQ(good.num_faces(), 320);
    for (unsigned seed : {1u, 2u, 3u}) {
        SurfaceMesh m = good;
        std::vector<Index> order(320);
        for (Index f = 0; f < 320; ++f) order[f] = f;
        std::mt19937 rng(seed);
        std::shuffle(order.begin(), order.end(), rng);
        order.resize(96);                                                                        // 30 %
        if (seed == 1 && std::find(order.begin(), order.end(), 0) == order.end()) order[0] = 0;  // BFS root flipped
        for (Index f : order) reverse_face(m, f);

        OrientReport rep;
        const SurfaceMesh o = orient_surface(m, &rep);
        EXPECT_EQ(rep.flipped_faces, 96);
        EXPECT_EQ(rep.components, 1);
        EXPECT_EQ(rep.closed_components, 1);
        for (Index f = 0; f < o.num_faces(); ++f) EXPECT_GT(outwardness(o, f, Vec3::Zero()), 0.0) << "face " << f;
        expect_same_faces_up_to_orientation(m, o);
        EXPECT_NO_THROW(node_rings(o));
    }
}

TEST(OrientSurface, InwardSphereBecomesOutward) {
    SurfaceMesh m = sphere();
    for (Index f = 0; f < m.num_faces(); ++f) reverse_face(m, f);
    OrientReport rep;
    const SurfaceMesh o = orient_surface(m, &rep);
    EXPECT_EQ(rep.flipped_faces, m.num_faces());
    for (Index f = 0; f < o.num_faces(); ++f) EXPECT_GT(outwardness(o, f, Vec3::Zero()), 0.0);

    // Already outward: untouched. Far from the origin: still outward (volume measured locally).
    const SurfaceMesh far = sphere(2, 1e-3, Vec3(1e5, -2e5, 3e5));
    EXPECT_EQ(orient_surface(far, &rep).face_nodes, far.face_nodes);
    EXPECT_EQ(rep.flipped_faces, 0);
}

TEST(OrientSurface, QuadCubeFlipKeepsTheFirstNode) {
    // Unit cube of inward quads; orient reverses each as a,b,c,d → a,d,c,b.
    SurfaceMesh m = test::cube_corners();
    m.add_face({0, 1, 3, 2}, 0);
    m.add_face({4, 6, 7, 5}, 0);
    m.add_face({0, 4, 5, 1}, 0);
    m.add_face({2, 3, 7, 6}, 0);
    m.add_face({0, 2, 6, 4}, 0);
    m.add_face({1, 5, 7, 3}, 0);
    OrientReport rep;
    const SurfaceMesh o = orient_surface(m, &rep);
    EXPECT_EQ(rep.flipped_faces, 6);
    EXPECT_EQ((std::vector<Index>(o.face_begin(0), o.face_end(0))), (std::vector<Index>{0, 2, 3, 1}));
    for (Index f = 0; f < 6; ++f) EXPECT_GT(outwardness(o, f, Vec3(0.5, 0.5, 0.5)), 0.0);
}

TEST(OrientSurface, SphereInsideSphereOuterPointsInwardInnerOutward) {
    for (bool inner_first : {true, false}) {
        SurfaceMesh m;
        m.patches.push_back({"body", PatchKind::Wall});
        m.patches.push_back({"box", PatchKind::Wall});  // not named farfield: containment decides
        const Vec3 ci(0.7, -0.4, 0.3);
        if (inner_first) add_icosphere(m, 2, 1.0, ci, 0);
        add_icosphere(m, 2, 5.0, Vec3::Zero(), 1);
        if (!inner_first) add_icosphere(m, 2, 1.0, ci, 0);
        // Scramble some faces of both so neither starts consistent.
        for (Index f = 0; f < m.num_faces(); f += 3) reverse_face(m, f);

        OrientReport rep;
        const SurfaceMesh o = orient_surface(m, &rep);
        EXPECT_EQ(rep.components, 2);
        EXPECT_EQ(rep.closed_components, 2);
        for (Index f = 0; f < o.num_faces(); ++f) {
            if (o.face_patch[f] == 0)
                EXPECT_GT(outwardness(o, f, ci), 0.0) << "inner face " << f;
            else
                EXPECT_LT(outwardness(o, f, Vec3::Zero()), 0.0) << "outer face " << f;
        }
    }
}

TEST(OrientSurface, SideBySideBodiesBothPointOutward) {
    SurfaceMesh m;
    m.patches.push_back({"wall", PatchKind::Wall});
    add_icosphere(m, 1, 1.0, Vec3(-2, 0, 0), 0);
    add_icosphere(m, 1, 1.0, Vec3(2, 0, 0), 0);
    for (Index f = 0; f < m.num_faces(); ++f) reverse_face(m, f);
    OrientReport rep;
    const SurfaceMesh o = orient_surface(m, &rep);
    EXPECT_EQ(rep.components, 2);
    for (Index f = 0; f < o.num_faces(); ++f) {
        const Vec3 c = face_centroid(o, o.points, f).x() < 0 ? Vec3(-2, 0, 0) : Vec3(2, 0, 0);
        EXPECT_GT(outwardness(o, f, c), 0.0);
    }
}

TEST(OrientSurface, FarfieldSphereAlonePointsInward) {
    const SurfaceMesh m = sphere(2, 10.0, Vec3::Zero(), PatchKind::Farfield);
    OrientReport rep;
    const SurfaceMesh o = orient_surface(m, &rep);
    EXPECT_EQ(rep.flipped_faces, m.num_faces());
    for (Index f = 0; f < o.num_faces(); ++f) EXPECT_LT(outwardness(o, f, Vec3::Zero()), 0.0);
}

TEST(OrientSurface, InternalFlowPointsTheOutermostWallsInward) {
    // A duct or a tunnel: the fluid is inside the walls. Alone, the closed wall points inward;
    // with bodies inside, they point outward into the fluid, the outermost wall inward, whatever
    // the order of the components and however their faces start.
    const SurfaceMesh alone = sphere(2, 3.0);
    OrientReport rep;
    const SurfaceMesh in = orient_surface(alone, &rep, true);
    EXPECT_EQ(rep.flipped_faces, alone.num_faces());
    for (Index f = 0; f < in.num_faces(); ++f) EXPECT_LT(outwardness(in, f, Vec3::Zero()), 0.0) << f;
    for (bool inner_first : {true, false}) {
        SurfaceMesh m;
        m.patches.push_back({"body", PatchKind::Wall});
        m.patches.push_back({"tunnel", PatchKind::Wall});
        const Vec3 a(1.5, 0.5, 0.0), b(-1.5, -0.5, 0.5);
        if (inner_first) {
            add_icosphere(m, 1, 0.6, a, 0);
            add_icosphere(m, 1, 0.6, b, 0);
        }
        add_icosphere(m, 2, 5.0, Vec3::Zero(), 1);
        if (!inner_first) {
            add_icosphere(m, 1, 0.6, a, 0);
            add_icosphere(m, 1, 0.6, b, 0);
        }
        for (Index f = 0; f < m.num_faces(); f += 3) reverse_face(m, f);
        const SurfaceMesh o = orient_surface(m, &rep, true);
        EXPECT_EQ(rep.closed_components, 3);
        for (Index f = 0; f < o.num_faces(); ++f) {
            const Vec3 x = face_centroid(o, o.points, f);
            if (o.face_patch[f] == 0)
                EXPECT_GT(outwardness(o, f, (x - a).norm() < (x - b).norm() ? a : b), 0.0) << "body face " << f;
            else
                EXPECT_LT(outwardness(o, f, Vec3::Zero()), 0.0) << "tunnel face " << f;
        }
        // Without internal flow the same bodies side by side in nothing would point outward;
        // here the tunnel holds them, so it points inward either way.
        const SurfaceMesh ext = orient_surface(m, &rep);
        for (Index f = 0; f < ext.num_faces(); ++f) {
            if (ext.face_patch[f] == 1) {
                EXPECT_LT(outwardness(ext, f, Vec3::Zero()), 0.0) << f;
            }
        }
    }
}

TEST(OrientSurface, InternalFlowNeedsAClosedSurface) {
    SurfaceMesh open = sphere();
    open.face_offsets.pop_back();  // drop the last face: a hole
    open.face_nodes.resize(static_cast<std::size_t>(open.face_offsets.back()));
    open.face_patch.pop_back();
    const std::string msg = message_of<InputError>([&] { orient_surface(open, nullptr, true); });
    test::expect_contains(msg, {"internal flow", "no part of the surface is closed"});
    EXPECT_NO_THROW(orient_surface(open));
}

TEST(OrientSurface, MoebiusStripIsNotOrientable) {
    const SurfaceMesh m = test::moebius_strip();
    ASSERT_NO_THROW(check_surface(m, "strip"));
    const std::string msg = message_of<TopologyError>([&] { orient_surface(m); });
    EXPECT_TRUE(contains(msg, "not orientable")) << msg;
    EXPECT_TRUE(contains(msg, "component 0")) << msg;
    EXPECT_TRUE(contains(msg, "edge between node ")) << msg;
}

TEST(OrientSurface, OpenGridKeepsTheMajorityOrientation) {
    const SurfaceMesh grid = quad_grid(4, 4);
    for (Index bad : {Index{0}, Index{9}, Index{15}}) {
        SurfaceMesh m = grid;
        reverse_face(m, bad);
        OrientReport rep;
        const SurfaceMesh o = orient_surface(m, &rep);
        EXPECT_EQ(rep.flipped_faces, 1) << "flipped face " << bad;
        EXPECT_EQ(rep.components, 1);
        EXPECT_EQ(rep.closed_components, 0);
        for (Index f = 0; f < o.num_faces(); ++f) EXPECT_GT(face_area_vector(o, f).z(), 0.0);
    }
    // A consistent -z grid stays -z.
    SurfaceMesh down = grid;
    for (Index f = 0; f < down.num_faces(); ++f) reverse_face(down, f);
    OrientReport rep;
    EXPECT_EQ(orient_surface(down, &rep).face_nodes, down.face_nodes);
    EXPECT_EQ(rep.flipped_faces, 0);
}

TEST(OrientSurface, AHalfModelPointsOutOfTheBodyItsCutCloses) {
    // The inward unit cube of quads without its face y = 0: a half model open on its symmetry
    // plane, as a CAD tool exports the fluid's boundary (into the body). Its cut is closed by the
    // plane, so it is a body, and it is turned outward, off the file's consistent orientation.
    SurfaceMesh m = test::cube_corners(Vec3(5.0, 0.0, -3.0));
    m.add_face({0, 1, 3, 2}, 0);
    m.add_face({4, 6, 7, 5}, 0);
    m.add_face({2, 3, 7, 6}, 0);  // y = 1
    m.add_face({0, 2, 6, 4}, 0);
    m.add_face({1, 5, 7, 3}, 0);
    OrientReport rep;
    const SurfaceMesh o = orient_surface(m, &rep);
    EXPECT_EQ(rep.flipped_faces, 5);
    EXPECT_EQ(rep.closed_components, 0);
    for (Index f = 0; f < 5; ++f) EXPECT_GT(outwardness(o, f, Vec3(5.5, 0.5, -2.5)), 0.0) << "face " << f;
    // Outward already: untouched. With its cut not in one plane (a corner of the rim moved off
    // it), no body is closed by a plane: the file's orientation stays.
    EXPECT_EQ(orient_surface(o, &rep).face_nodes, o.face_nodes);
    EXPECT_EQ(rep.flipped_faces, 0);
    SurfaceMesh bent = m;
    bent.points[0].y() = -0.3;
    EXPECT_EQ(orient_surface(bent, &rep).face_nodes, bent.face_nodes);
    EXPECT_EQ(rep.flipped_faces, 0);
}

}  // namespace
}  // namespace strata
