// Fans at sharp convex edges and corners (module/src/fans.{h,cpp}, and through extrude_layers):
// a blade whose edge turns 170°, closed by end caps, with and without fans; the cells a fan's
// columns make on the wall; the same bytes for any thread count.

#include <strata/core/cell_quality.h>
#include <strata/core/error.h>
#include <strata/core/validate.h>
#include <strata/geometry/check.h>
#include <strata/geometry/topology.h>
#include <strata/module/layers.h>

#include <gtest/gtest.h>

#include "fans.h"
#include "same_bytes.h"
#include "test_support.h"

#include <cmath>
#include <limits>
#include <numbers>

namespace strata {
namespace {

LayerParams blade_layers(double fan_angle) {
    LayerParams p;
    p.distribution.layers = 5;
    p.distribution.first_height = 0.01;
    p.distribution.growth = 1.2;
    p.fan_angle_deg = fan_angle;
    return p;
}

/// The smallest scaled Jacobian of the layers' cells of \p type (prisms and hexahedra: Prism).
double layer_cell_quality(const LayerMesh& lm, CellType type = CellType::Prism) {
    const ValidationReport v = validate_mesh(lm.mesh);
    EXPECT_TRUE(v.ok()) << (v.problems.empty() ? std::string() : v.problems.front());
    const double q = v.by_type[static_cast<std::size_t>(type)].min_scaled_jacobian;
    return type == CellType::Prism ? std::min(q, v.by_type[static_cast<std::size_t>(CellType::Hex)].min_scaled_jacobian)
                                   : q;
}

/// The smallest sine of a corner angle of \p wall's faces: the best a prism on them can be.
double best_prism(const SurfaceMesh& wall) {
    return std::sin(needle_faces(wall, 0.0).sharpest_deg * std::numbers::pi / 180.0);
}

TEST(Fans, TheBladesEdgeAndTheLoopsClosingItGetFansAndItsCornersGetPolygons) {
    const SurfaceMesh wall = test::blade(8, 10.0);
    const FanWall fw = build_fans(wall, boundary_loops(wall), {}, 1.0, 120.0, {});
    // The sharp edge (8 edges), the base's two edges (16) and the caps' three (6).
    EXPECT_EQ(fw.fan_edges, 30);
    EXPECT_EQ(fw.fan_nodes, wall.num_points());
    EXPECT_EQ(fw.corners, 6);
    // The sharp edge's nodes: two sides 170° apart, two wedges of 85° (one column between).
    const Index edge_node = 3 * 4 + 2;
    std::vector<Vec3> dirs;
    for (Index i = 0; i < fw.mesh.num_points(); ++i)
        if (fw.base[static_cast<std::size_t>(i)] == edge_node)
            dirs.push_back(fw.direction[static_cast<std::size_t>(i)]);
    ASSERT_EQ(dirs.size(), 3u);
    for (const Vec3& d : dirs) EXPECT_NEAR(d.norm(), 1.0, 1e-12);
    // One column along +x (between), the others along the faces' normals (±z, tilted by 5°).
    int along_x = 0;
    for (const Vec3& d : dirs) along_x += d.x() > 0.99 ? 1 : 0;
    EXPECT_EQ(along_x, 1);
    // The wall is still one closed, consistently oriented surface, its fan faces of zero area.
    EXPECT_TRUE(boundary_loops(fw.mesh).rows() == 0);
    Index fan_faces = 0;
    for (const char f : fw.fan_face) fan_faces += f;
    EXPECT_EQ(fw.mesh.num_faces(), wall.num_faces() + fan_faces);
    // Two wedges per edge of the sharp edge (170°) and of the base (95°), one per cap edge (90°),
    // and at each corner its polygon of four columns (a quad, or two triangles).
    EXPECT_GE(fan_faces, 8 * 2 + 16 * 2 + 6 + 6);
    EXPECT_LE(fan_faces, 8 * 2 + 16 * 2 + 6 + 12);
    // Nothing to fan below the angle, or with the angle 0.
    EXPECT_TRUE(build_fans(wall, boundary_loops(wall), {}, 1.0, 175.0, {}).empty());
    EXPECT_TRUE(build_fans(wall, boundary_loops(wall), {}, 1.0, 0.0, {}).empty());
}

TEST(Fans, LiftTheQualityCapOfOneDirectionAtASharpEdge) {
    const SurfaceMesh wall = test::blade(8, 10.0);
    const LayerMesh with = extrude_layers(wall, blade_layers(120.0));
    EXPECT_EQ(with.fan_edges, 30);
    // With fans every column has every layer and every cell is near-orthogonal. With one
    // direction per node, the sharp edge's columns stop at the wall (--sharp-edge-stop) and the
    // base's and caps' cells are capped near cos(45°) on faces that are needles across the blade:
    // the columns keep only what the steps beside the sharp edge allow.
    for (Index i = 0; i < with.wall_nodes(); ++i) EXPECT_EQ(with.node_layers(i), 5) << i;
    // The wedges (hexahedra) are near-orthogonal; the prisms as good as their (needle) faces allow.
    EXPECT_GT(layer_cell_quality(with, CellType::Hex), 0.5);
    EXPECT_GT(layer_cell_quality(with), 0.8 * best_prism(wall));
    const LayerMesh none = extrude_layers(wall, blade_layers(0.0));
    int layers_with = 0, layers_none = 0;
    for (Index i = 0; i < wall.num_points(); ++i)
        layers_with += with.node_layers(i), layers_none += none.node_layers(i);
    for (Index j = 0; j <= 8; ++j) EXPECT_EQ(none.node_layers(3 * j + 2), 0) << j;
    EXPECT_LT(layers_none, layers_with * 3 / 4) << layers_none << " of " << layers_with;
    EXPECT_GT(layer_cell_quality(none), 0.0);
    // A blunter blade (40°) without fans grows, its sharp edge's cells poor or its columns short.
    const SurfaceMesh blunt = test::blade(8, 40.0);
    LayerParams single = blade_layers(0.0);
    single.sharp_edge_stop_deg = 0.0;  // one direction at the sharp edge (else it stops at the wall, below)
    const LayerMesh without = extrude_layers(blunt, single);
    EXPECT_EQ(without.fan_edges, 0);
    bool edge_short = false;
    for (Index j = 0; j <= 8; ++j) edge_short |= without.node_layers(3 * j + 2) < 5;
    EXPECT_TRUE(edge_short || layer_cell_quality(without) < 0.4 * best_prism(blunt));
    const LayerMesh fanned = extrude_layers(blunt, blade_layers(120.0));
    EXPECT_GT(layer_cell_quality(fanned, CellType::Hex), 0.5);
    EXPECT_GT(layer_cell_quality(fanned), 0.8 * best_prism(blunt));
    // The coverage report counts the wall's own faces and nodes, each node once (as its
    // shortest column).
    const LayerReport rep = layer_report(with);
    ASSERT_EQ(rep.patches.size(), 1u);
    EXPECT_EQ(rep.patches[0].faces, wall.num_faces());
    EXPECT_EQ(rep.patches[0].nodes, wall.num_points());
    EXPECT_EQ(rep.patches[0].all_layers, wall.num_points());
    EXPECT_TRUE(rep.short_nodes.empty());
    EXPECT_FALSE(with.mesh.hexes.empty());                               // the wedges above the wall
    EXPECT_FALSE(with.mesh.tets.empty() && with.mesh.pyramids.empty());  // the corners on the wall
    // The wall keeps its nodes: level 0 holds each once, the fans' columns start there.
    for (Index i = 0; i < with.wall_nodes(); ++i) EXPECT_LT(with.level_node(0, i), wall.num_points());
}

TEST(Fans, TheSameBytesForAnyThreadCount) {
    test::expect_same_bytes_for_any_thread_count(test::blade(8, 10.0), blade_layers(120.0));
}

TEST(Fans, NoFanWhereItsFirstCellsWouldBeUnusable) {
    // The sharp edge's middle node may not have a single layer (its limit is below the first
    // height): a fan there would have coincident columns on the front, so none is built there;
    // the two halves of the chain end beside it (terminals, whose columns stop at the wall) and
    // keep their fans, and the run says how many nodes lost theirs.
    const SurfaceMesh wall = test::blade(8, 40.0);  // grows without fans too
    LayerParams p = blade_layers(120.0);
    p.sharp_edge_stop_deg = 0.0;  // the edges whose fans go keep one direction, and grow
    LayerConstraints c;
    c.node_thickness_limit.assign(static_cast<std::size_t>(wall.num_points()), std::numeric_limits<double>::infinity());
    c.node_thickness_limit[3 * 4 + 2] = 0.005;
    const LayerMesh lm = extrude_layers(wall, p, c);
    EXPECT_FALSE(lm.fans_dropped.empty());
    EXPECT_TRUE(std::is_sorted(lm.fans_dropped.begin(), lm.fans_dropped.end()));
    EXPECT_EQ(std::adjacent_find(lm.fans_dropped.begin(), lm.fans_dropped.end()), lm.fans_dropped.end());
    EXPECT_NE(std::find(lm.fans_dropped.begin(), lm.fans_dropped.end(), 3 * 4 + 2), lm.fans_dropped.end());
    // The report says where: each such node once, at its place on the wall, by node id (with
    // those whose fan went for skewed cells; no chain is left unclosed: it ends beside the node).
    const LayerReport r = layer_report(lm);
    ASSERT_EQ(r.no_fan.size(), lm.fans_dropped.size() + lm.fans_skewed.size() + lm.fans_unclosed.size());
    EXPECT_EQ(r.no_fan_nodes(NoFan::Unusable), static_cast<Index>(lm.fans_dropped.size()));
    EXPECT_EQ(r.no_fan_nodes(NoFan::Skewed), static_cast<Index>(lm.fans_skewed.size()));
    EXPECT_EQ(r.no_fan_nodes(NoFan::Unclosed), static_cast<Index>(lm.fans_unclosed.size()));
    EXPECT_TRUE(lm.fans_unclosed.empty());
    EXPECT_EQ(lm.node_layers(3 * 3 + 2), 0) << "a terminal beside the dropped node";
    EXPECT_EQ(lm.node_layers(3 * 5 + 2), 0) << "a terminal beside the dropped node";
    for (std::size_t j = 0; j < r.no_fan.size(); ++j) {
        if (r.no_fan[j].reason == NoFan::Unclosed) {
            EXPECT_EQ(r.no_fan[j].node % 3, 2) << "a node of the sharp edge";
            EXPECT_EQ(r.no_fan[j].position, wall.points[static_cast<std::size_t>(r.no_fan[j].node)]);
            continue;
        }
        const std::vector<Index>& list = r.no_fan[j].reason == NoFan::Unusable ? lm.fans_dropped : lm.fans_skewed;
        EXPECT_NE(std::find(list.begin(), list.end(), r.no_fan[j].node), list.end());
        EXPECT_EQ(r.no_fan[j].position, wall.points[static_cast<std::size_t>(r.no_fan[j].node)]);
        if (j > 0) {
            EXPECT_LT(r.no_fan[j - 1].node, r.no_fan[j].node);
        }
    }
    EXPECT_LT(lm.fan_edges, 30);
    EXPECT_EQ(lm.node_layers(3 * 4 + 2), 0);
    const ValidationReport v = validate_mesh(lm.mesh);
    EXPECT_TRUE(v.ok()) << (v.problems.empty() ? std::string() : v.problems.front());
    EXPECT_TRUE(extrude_layers(wall, blade_layers(120.0)).fans_dropped.empty());
}

TEST(Fans, SharpEdgesWithoutAFanStopAtTheWall) {
    // A 40° blade without fans: its sharp edge turns 140°, its base's edges 110°. From
    // sharp_edge_stop_deg on, the nodes of such an edge stop at the wall (the faces between
    // the two sides' cells would be skewed), the others grow, and the report says why.
    const SurfaceMesh wall = test::blade(8, 40.0);
    LayerParams p = blade_layers(0.0);
    p.sharp_edge_stop_deg = 120.0;
    const LayerMesh lm = extrude_layers(wall, p);
    for (Index j = 0; j <= 8; ++j) {
        EXPECT_EQ(lm.node_layers(3 * j + 2), 0) << j;
        EXPECT_GT(lm.node_layers(3 * j), 0) << j;
        EXPECT_GT(lm.node_layers(3 * j + 1), 0) << j;
    }
    const ValidationReport v = validate_mesh(lm.mesh);
    EXPECT_TRUE(v.ok()) << (v.problems.empty() ? std::string() : v.problems.front());
    const LayerReport r = layer_report(lm);
    ASSERT_EQ(r.patches.size(), 1u);
    EXPECT_EQ(r.patches[0].short_nodes(Shortfall::SharpEdge), 9);
    Index sharp = 0;
    for (const ShortNode& s : r.short_nodes)
        if (s.reason == Shortfall::SharpEdge) {
            ++sharp;
            EXPECT_EQ(s.layers, 0);
            EXPECT_DOUBLE_EQ(s.position.x(), 1.0);  // on the sharp edge
        }
    EXPECT_EQ(sharp, 9);
    // Lower than the base's 110°: those stop too, and with them every node.
    p.sharp_edge_stop_deg = 100.0;
    EXPECT_THROW(extrude_layers(wall, p), TopologyError);
    // 0: one direction there. The cells on the edge's two sides would then share faces skewed
    // about 2 / sin(20°) = 5.8, above checkMesh's 4, so the columns stop at the wall all the
    // same, for quality (the faces measured, stop_columns) where the angle predicts it.
    p.sharp_edge_stop_deg = 0.0;
    const LayerMesh single = extrude_layers(wall, p);
    for (Index j = 0; j <= 8; ++j) EXPECT_EQ(single.node_layers(3 * j + 2), 0) << j;
    Index quality = 0;
    for (const ShortNode& s : layer_report(single).short_nodes) {
        EXPECT_NE(s.reason, Shortfall::SharpEdge);
        if (s.position.x() == 1.0) quality += s.reason == Shortfall::Quality ? 1 : 0;
    }
    EXPECT_EQ(quality, 9);
    // Out of range: an error naming the parameter.
    p.sharp_edge_stop_deg = 200.0;
    EXPECT_THROW(extrude_layers(wall, p), InputError);
}

/// A delta wing 1 long and 1.2 wide (apex at the origin, base at x = 1) with sharp leading
/// edges, each bevelled by about 7° on both sides (a 166° turn), \p n segments along each
/// leading edge, and a blunt base 0.02 thick: a convex solid, each triangle oriented away from
/// an inner point.
SurfaceMesh delta_wing(int n) {
    SurfaceMesh m;
    m.patches = {{"delta", PatchKind::Wall}};
    const double t = 0.01;
    const Vec3 apex(0, 0, 0), left(1, -0.6, 0), right(1, 0.6, 0);
    // Per level z = +t (upper) and -t (lower): the inset triangle's apex and base corners.
    auto inset = [&](double z, double y) {
        return std::array<Vec3, 3>{Vec3(0.16, 0, z), Vec3(1, -y, z), Vec3(1, y, z)};
    };
    auto add = [&](const Vec3& x) {
        m.points.push_back(x);
        return static_cast<Index>(m.points.size() - 1);
    };
    const Vec3 inner(0.6, 0, 0);
    auto tri = [&](Index a, Index b, Index c) {
        const Vec3 nrm = (m.points[b] - m.points[a]).cross(m.points[c] - m.points[a]);
        if (nrm.dot(m.points[a] - inner) > 0.0)
            m.add_face({a, b, c}, 0);
        else
            m.add_face({a, c, b}, 0);
    };
    std::vector<Index> le_left, le_right;  // apex first
    le_left.push_back(add(apex));
    le_right.push_back(le_left[0]);
    for (int k = 1; k <= n; ++k) {
        le_left.push_back(add(apex + (left - apex) * (static_cast<double>(k) / n)));
        le_right.push_back(add(apex + (right - apex) * (static_cast<double>(k) / n)));
    }
    for (const double z : {t, -t}) {
        const auto in = inset(z, 0.48);
        std::vector<Index> il, ir;  // the inset's sides, from its apex
        il.push_back(add(in[0]));
        ir.push_back(il[0]);
        for (int k = 1; k <= n; ++k) {
            il.push_back(add(in[0] + (in[1] - in[0]) * (static_cast<double>(k) / n)));
            ir.push_back(add(in[0] + (in[2] - in[0]) * (static_cast<double>(k) / n)));
        }
        for (int k = 0; k < n; ++k) {
            // Bevels: between the leading edge and the inset's side.
            for (const auto* side : {&le_left, &le_right}) {
                const auto& le = *side;
                const auto& is = side == &le_left ? il : ir;
                tri(le[k], le[k + 1], is[k + 1]);
                tri(le[k], is[k + 1], is[k]);
            }
            // The flat face between the inset's sides (a triangle at the apex).
            tri(il[k], il[k + 1], ir[k + 1]);
            if (k > 0) tri(il[k], ir[k + 1], ir[k]);
        }
        // The base: the leading edges' ends and the inset's corners.
        tri(le_left[n], il[n], ir[n]);
        tri(le_left[n], ir[n], le_right[n]);
    }
    return m;
}

TEST(Fans, ALeadingEdgeChainTurningAtTheApexIsSplitThereLikeACorner) {
    // A delta wing's two sharp leading edges meet at its apex at 62°. The chain through the
    // apex shared its columns between there: the wedges on both edges twisted by half the
    // 118° the chain turns, their faces skewed beyond checkMesh's 4, the apex's fan went, and
    // with it (a chain cannot end) the fans of both leading edges, whose columns then stopped
    // at the wall. The apex now gets each edge's columns and a polygon closing them.
    const SurfaceMesh wall = delta_wing(12);
    ASSERT_EQ(boundary_loops(wall).rows(), 0);
    const FanWall fw = build_fans(wall, boundary_loops(wall), {}, 1.0, 150.0, {});
    Index at_apex = 0;
    for (Index i = 0; i < fw.mesh.num_points(); ++i) at_apex += fw.base[static_cast<std::size_t>(i)] == 0 ? 1 : 0;
    EXPECT_EQ(at_apex, 4);  // its upper and lower sides, and one column between per leading edge
    LayerParams p;
    p.distribution.layers = 10;
    p.distribution.first_height = 1e-4;
    p.distribution.growth = 1.2;
    const LayerMesh lm = extrude_layers(wall, p);
    EXPECT_TRUE(lm.fans_skewed.empty());
    EXPECT_TRUE(lm.fans_dropped.empty());
    EXPECT_EQ(lm.fan_edges, fw.fan_edges);
    for (Index i = 0; i < lm.wall_nodes(); ++i)
        EXPECT_EQ(lm.node_layers(i), 10) << wall.points[static_cast<std::size_t>(i)];
    EXPECT_GT(layer_cell_quality(lm, CellType::Hex), 0.3);
    EXPECT_GT(layer_cell_quality(lm), 0.8 * best_prism(wall));
}

TEST(Fans, NoFanWhereTheNodesAreExcluded) {
    const SurfaceMesh wall = test::blade(8, 10.0);
    std::vector<char> excluded(static_cast<std::size_t>(wall.num_points()), 0);
    excluded[2] = 1;  // a corner of the sharp edge: its chain cannot close there, nor anything through it
    const FanWall fw = build_fans(wall, boundary_loops(wall), {}, 1.0, 120.0, excluded);
    for (Index i = 0; i < fw.mesh.num_points(); ++i) EXPECT_FALSE(fw.base[static_cast<std::size_t>(i)] == 2 && i != 2);
    EXPECT_LT(fw.fan_edges, 30);
}

TEST(Fans, SharpEdgesLeftWithoutAFanAreSaidWhy) {
    // A chain must close into a loop. Closed by both caps, the blade's sharp edge has its fan.
    const SurfaceMesh wall = test::blade(8, 10.0);
    EXPECT_TRUE(build_fans(wall, boundary_loops(wall), {}, 1.0, 120.0, {}).unfanned.empty());
    const std::vector<Index> edge{5, 8, 11, 14, 17, 20, 23, 26};  // the sharp edge's nodes j = 1..8
    // Open at y = 1 (its cap gone) in no plane that holds its nodes (an open edge of a wall,
    // not a half model's on its symmetry plane: AChainMayEndOnAPlaneNode...): no node on the
    // open boundary gets a fan, so the sharp edge's chain from the cap at y = 0 ends one node
    // before it (a terminal); the base's edges (95°, under the fan angle) may not end there, so
    // they have none; the sharp edge's node on the boundary is said to reach it.
    SurfaceMesh open = wall;
    open.face_offsets.pop_back();
    open.face_nodes.resize(static_cast<std::size_t>(open.face_offsets.back()));
    open.face_patch.pop_back();
    ASSERT_EQ(boundary_loops(open).rows(), 1);
    const FanWall half = build_fans(open, boundary_loops(open), {}, 1.0, 120.0, {});
    EXPECT_EQ(half.fan_edges, 3 + 7);  // the cap's loop, and the sharp edge but its last edge
    EXPECT_EQ(half.terminals, (std::vector<Index>{23}));
    ASSERT_EQ(half.unfanned.size(), 1u);
    EXPECT_EQ(half.unfanned[0].first, edge.back());
    EXPECT_EQ(half.unfanned[0].second, NoFan::Open);
    // Closed, but a node of the edge excluded (its fan dropped by the caller): the two halves of
    // the edge end beside it; the excluded node is its caller's to explain.
    std::vector<char> excluded(static_cast<std::size_t>(wall.num_points()), 0);
    excluded[14] = 1;
    const FanWall cut = build_fans(wall, boundary_loops(wall), {}, 1.0, 120.0, excluded);
    EXPECT_EQ(cut.fan_edges, 6 + 16 + 6);  // the caps, the base's two edges, the sharp edge but node 14's two
    EXPECT_EQ(cut.terminals, (std::vector<Index>{11, 17}));
    EXPECT_TRUE(cut.unfanned.empty());
    // Both ends of a lone edge terminals: nothing there splits, so it has no fan.
    excluded.assign(excluded.size(), 0);
    excluded[2] = excluded[11] = 1;  // the sharp edge's edge (5, 8) alone between them
    const FanWall lone = build_fans(wall, boundary_loops(wall), {}, 1.0, 120.0, excluded);
    for (Index i = wall.num_points(); i < lone.mesh.num_points(); ++i)
        EXPECT_TRUE(lone.base[static_cast<std::size_t>(i)] != 5 && lone.base[static_cast<std::size_t>(i)] != 8);
    EXPECT_TRUE(std::find(lone.terminals.begin(), lone.terminals.end(), 5) == lone.terminals.end());
}

TEST(Fans, AChainMayEndOnAPlaneNodeWhoseColumnsLieInThePlane) {
    // The blade open at y = 1 on a plane (a half model's wall on its symmetry plane), swept so
    // that its sharp edge meets the plane at 73 degrees. Its chain ends on the plane: the node
    // there splits into two sectors by its one fan edge, and its columns lie in the plane.
    SurfaceMesh open = test::blade(8, 10.0);
    open.face_offsets.pop_back();
    open.face_nodes.resize(static_cast<std::size_t>(open.face_offsets.back()));
    open.face_patch.pop_back();
    for (Vec3& p : open.points) p.x() += 0.3 * p.y();
    const Csr loops = boundary_loops(open);
    std::vector<Vec3> plane(open.points.size(), Vec3::Zero());
    for (const Index* v = loops.row_begin(0); v != loops.row_end(0); ++v)
        plane[static_cast<std::size_t>(*v)] = Vec3(0.0, 1.0, 0.0);
    const FanWall fw = build_fans(open, loops, plane, 1.0, 120.0, {});
    EXPECT_TRUE(fw.unfanned.empty());
    EXPECT_EQ(fw.fan_edges, 3 + 3 * 8);  // the cap's loop at y = 0, the sharp edge and the base's two
    EXPECT_EQ(fw.fan_nodes, 3 + 3 * 8);
    EXPECT_EQ(fw.plane_nodes, 3);  // the three edges' ends on the plane
    int on_plane = 0;
    for (Index i = 0; i < fw.mesh.num_points(); ++i)
        if (fw.base[static_cast<std::size_t>(i)] == 26) {
            ++on_plane;
            EXPECT_NEAR(fw.direction[static_cast<std::size_t>(i)].y(), 0.0, 1e-12);
        }
    EXPECT_EQ(on_plane, 3);  // 170 degrees: two wedges
    // The wall's open boundary now passes through them (the base's edges turn 95 degrees: two
    // wedges each too).
    const Csr after = boundary_loops(fw.mesh);
    ASSERT_EQ(after.rows(), 1);
    EXPECT_EQ(after.row_size(0), 3 + 3 * 2);
    // Along the edge the columns lean into the plane the nearer they are: an eighth from it
    // (node 23), the middle column's pull across the plane is a small part of the swept edge's.
    auto across = [](const FanWall& f, Index node) {
        double most = 0.0;
        for (Index i = 0; i < f.mesh.num_points(); ++i)
            if (f.base[static_cast<std::size_t>(i)] == node)
                most = std::max(most, std::abs(f.direction[static_cast<std::size_t>(i)].y()));
        return most;
    };
    const double unleaned = across(build_fans(open, loops, plane, 1e-9, 120.0, {}), 23);
    EXPECT_GT(unleaned, 0.2);
    EXPECT_LT(across(fw, 23), 0.25 * unleaned);
    // Without the plane the sharp edge's chain ends one node before the open boundary (a
    // terminal), and the base's (95°) have none.
    EXPECT_EQ(build_fans(open, loops, {}, 1.0, 120.0, {}).fan_edges, 3 + 7);
    // A node of the sharp edge excluded (its fan dropped by the caller): the edge's two halves
    // end beside it, one at a terminal, the other at the plane node.
    std::vector<char> excluded(open.points.size(), 0);
    excluded[14] = 1;
    const FanWall cut = build_fans(open, loops, plane, 1.0, 120.0, excluded);
    EXPECT_EQ(cut.fan_edges, 3 + 2 * 8 + 6);  // the cap, the base's edges, the sharp edge but node 14's two
    EXPECT_EQ(cut.terminals, (std::vector<Index>{11, 17}));
    EXPECT_TRUE(cut.unfanned.empty());
}

/// A cell of \p type whose ids are \p id, over the unit cube's corners (Gmsh's hexahedron order).
double quality(CellType type, const std::array<Index, 8>& id, const std::vector<Vec3>& p) {
    return min_scaled_jacobian(p, id.data(), type);
}

TEST(Fans, CollapsedCellsBecomeStandardCellsOfPositiveVolume) {
    // Corners: 0 at the origin (the wall node), 1..8 the tops of its columns.
    const std::vector<Vec3> p{Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1),
                              Vec3(0, 1, 1), Vec3(1, 0, 0), Vec3(1, 1, 0)};
    {  // a hexahedron whose bottom is one node: a pyramid with its apex below the top
        CellType t = CellType::Hex;
        std::array<Index, 8> id{0, 0, 0, 0, 1, 2, 3, 4};
        ASSERT_TRUE(collapse_cell(t, id));
        EXPECT_EQ(t, CellType::Pyramid);
        EXPECT_GT(quality(t, id, p), 0.0);
    }
    {  // bottom (0, 5, 5, 0): a wedge (prism) along x
        CellType t = CellType::Hex;
        std::array<Index, 8> id{0, 5, 5, 0, 1, 2, 3, 4};
        ASSERT_TRUE(collapse_cell(t, id));
        EXPECT_EQ(t, CellType::Prism);
        EXPECT_GT(quality(t, id, p), 0.0);
    }
    {  // bottom (0, 0, 6, 6)... the other pairing: a wedge along the other diagonal pair
        const std::vector<Vec3> q{Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 1),
                                  Vec3(1, 1, 1), Vec3(0, 1, 1), Vec3(0, 1, 0)};
        CellType t = CellType::Hex;
        std::array<Index, 8> id{0, 0, 5, 5, 1, 2, 3, 4};
        ASSERT_TRUE(collapse_cell(t, id));
        EXPECT_EQ(t, CellType::Prism);
        EXPECT_GT(quality(t, id, q), 0.0);
    }
    {  // a prism whose bottom is one node: a tetrahedron
        CellType t = CellType::Prism;
        std::array<Index, 8> id{0, 0, 0, 1, 2, 4, kNone, kNone};
        ASSERT_TRUE(collapse_cell(t, id));
        EXPECT_EQ(t, CellType::Tet);
        EXPECT_GT(quality(t, id, p), 0.0);
    }
    {  // a prism with one vertical edge collapsed: a pyramid on the opposite side
        const std::vector<Vec3> q{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 0, 1)};
        CellType t = CellType::Prism;
        std::array<Index, 8> id{0, 1, 2, 3, 4, 2, kNone, kNone};
        ASSERT_TRUE(collapse_cell(t, id));
        EXPECT_EQ(t, CellType::Pyramid);
        EXPECT_GT(quality(t, id, q), 0.0);
    }
    {  // nothing to collapse: unchanged
        CellType t = CellType::Tet;
        std::array<Index, 8> id{0, 1, 2, 4, kNone, kNone, kNone, kNone};
        ASSERT_TRUE(collapse_cell(t, id));
        EXPECT_EQ(t, CellType::Tet);
    }
    {  // two nodes of a triangle side collapsed (no standard cell)
        CellType t = CellType::Prism;
        std::array<Index, 8> id{0, 0, 5, 1, 2, 3, kNone, kNone};
        EXPECT_FALSE(collapse_cell(t, id));
    }
}

}  // namespace
}  // namespace strata
