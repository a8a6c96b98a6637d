// Local layer stopping and the ragged LayerMesh (module/src/columns.{h,cpp}, through
// extrude_layers): a column limited to fewer layers on a flat plate of triangles and of quads,
// the cells closing its steps, the level-major numbering, how far a limit reaches, and the
// same bytes for any thread count.

#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/validate.h>
#include <strata/module/layers.h>

#include <gtest/gtest.h>

#include "columns.h"
#include "same_bytes.h"
#include "test_support.h"

#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace strata {
namespace {

/// The 10 × 10 quad plate, or each quad split into two triangles.
SurfaceMesh plate(bool triangles) {
    SurfaceMesh q = test::quad_grid(10, 10, 0.1);
    if (!triangles) return q;
    return test::split_into_triangles(q, false);
}

/// 8 layers of 0.01 (0.08 in all), front limits spread at 0.25.
LayerParams eight_layers() {
    LayerParams p;
    p.distribution.layers = 8;
    p.distribution.first_height = 0.01;
    p.distribution.growth = 1.0;
    p.proximity = ProximityMode::Stop;
    p.proximity_limits.front_slope = 0.25;  // spread to the rings round it (the default, 1, spares them)
    return p;
}

/// The centre node (5, 5) of \p wall limited to 0.025 (two of eight_layers).
LayerConstraints limited_centre(const SurfaceMesh& wall) {
    LayerConstraints c;
    c.node_thickness_limit.assign(wall.points.size(), std::numeric_limits<double>::infinity());
    c.node_thickness_limit[5 * 11 + 5] = 0.025;
    return c;
}

/// \p x turned by \p deg about the vertical axis through \p centre.
Vec3 turned(const Vec3& x, const Vec3& centre, double deg) {
    const double a = deg * std::numbers::pi / 180.0;
    const Vec3 d = x - centre;
    return centre + Vec3(std::cos(a) * d.x() - std::sin(a) * d.y(), std::sin(a) * d.x() + std::cos(a) * d.y(), d.z());
}

TEST(Columns, ReachOfANodeHeldInAPlaneCountsTheFacesMirrorImages) {
    // Half of a thin wedge cut along its mid-plane y = 0: one face from the sharp edge (the
    // x axis) up to y = 0.1 over x = 1, normal tilted 84.3° from the plane's. Free, node 0
    // could march along that normal (reach 1); held in y = 0 its direction lies in the plane,
    // within 84.3° of the face and of its mirror image: cos 84.3° = 0.0995, counted as kMinReach.
    SurfaceMesh m;
    m.patches.push_back({"fin", PatchKind::Wall});
    m.points = {Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(-1, 0.1, 0)};
    m.add_face({0, 1, 2}, 0);
    const Vec3 n = face_area_vector(m, 0).normalized();
    ASSERT_NEAR(std::abs(n.y()), std::cos(std::atan(0.1)), 1e-12);
    EXPECT_DOUBLE_EQ(wall_reach(m)[0], 1.0);
    const std::vector<Vec3> plane(3, Vec3(0, 1, 0));
    EXPECT_DOUBLE_EQ(wall_reach(m, plane)[0], kMinReach);
    // A blunter wedge (y up to 2 over x = 1): the direction in the plane is within 26.6° of
    // both, cos = 0.894.
    m.points[2] = Vec3(-1, 2, 0);
    EXPECT_NEAR(wall_reach(m, plane)[0], std::sin(std::atan(2.0)), 1e-9);
    // Held on a line, that line is the direction: along the edge (z) it is 90° off the face.
    const std::vector<Vec3> line(3, Vec3(0, 0, 1));
    EXPECT_DOUBLE_EQ(wall_reach(m, {}, line)[0], kMinReach);
    const std::vector<Vec3> along_x(3, Vec3(-1, 0, 0));
    EXPECT_NEAR(wall_reach(m, {}, along_x)[0], -face_area_vector(m, 0).normalized().x(), 1e-12);
}

TEST(Columns, TwistIsTheTopsTurnAboutTheCellsAxis) {
    const std::array<Vec3, 4> quad{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
    const Vec3 up(0, 0, 0.1), centre(0.5, 0.5, 0.1);
    std::array<Vec3, 4> top;
    for (int t : {-35, 0, 20}) {
        for (std::size_t c = 0; c < 4; ++c) top[c] = turned(quad[c] + up, centre, t);
        EXPECT_NEAR(cell_twist_deg(quad, top, 4), std::abs(t), 1e-9) << t;
    }
    // Moved aside or stretched: no twist. Sheared: the edges across the shear turn, the others
    // not, so a shear of 0.3 counts as a few degrees (under atan 0.3 = 16.7).
    for (std::size_t c = 0; c < 4; ++c) top[c] = quad[c] + up + Vec3(0.05, -0.02, 0.0);
    EXPECT_NEAR(cell_twist_deg(quad, top, 4), 0.0, 1e-9);
    for (std::size_t c = 0; c < 4; ++c) top[c] = 1.5 * quad[c] + up;
    EXPECT_NEAR(cell_twist_deg(quad, top, 4), 0.0, 1e-9);
    for (std::size_t c = 0; c < 4; ++c) top[c] = quad[c] + up + Vec3(0.3 * quad[c].y(), 0.0, 0.0);
    EXPECT_GT(cell_twist_deg(quad, top, 4), 1.0);
    EXPECT_LT(cell_twist_deg(quad, top, 4), 16.7);
    // A triangle turned 40 degrees about its centroid, seen along a tilted axis.
    const std::array<Vec3, 4> tri{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3::Zero()};
    const Vec3 g(1.0 / 3.0, 1.0 / 3.0, 0.1);
    for (std::size_t c = 0; c < 3; ++c) top[c] = turned(tri[c] + Vec3(0, 0, 0.1), g, 40);
    EXPECT_NEAR(cell_twist_deg(tri, top, 3), 40.0, 1e-9);
    // The stopping test's shortcut agrees with the measure, turned, sheared and tilted alike.
    const double bound = 30.0, tan_bound = std::tan(bound * std::numbers::pi / 180.0);
    for (int t = -80; t <= 80; t += 7)
        for (double shear : {0.0, 0.4, -0.9})
            for (double tilt : {0.0, 0.3}) {
                for (std::size_t c = 0; c < 4; ++c)
                    top[c] = turned(quad[c] + up + Vec3(shear * quad[c].y() + tilt, 0.0, 0.0), centre, t);
                EXPECT_EQ(twists_more_than(quad, top, 4, bound, tan_bound), cell_twist_deg(quad, top, 4) > bound)
                    << t << " " << shear << " " << tilt;
            }
}

TEST(Columns, ATwistedCellStopsItsColumns) {
    // One quad whose next level is turned 40 degrees about its axis: a cell of fair scaled
    // Jacobian for a rigid turn of a square, but twisted: its columns stop with that reason. At
    // 20 degrees (under the 30 asked) they go on.
    const SurfaceMesh wall = test::quad_grid(1, 1, 1.0);
    for (const double deg : {20.0, 40.0}) {
        std::vector<Vec3> points = wall.points;
        Columns col(wall, 3, points);
        std::vector<Vec3> next(wall.points.size());
        Vec3 centre = Vec3::Zero();
        for (const Vec3& x : wall.points) centre += x / 4.0;
        for (std::size_t i = 0; i < next.size(); ++i)
            next[i] = turned(wall.points[i] + Vec3(0, 0, 0.2), centre + Vec3(0, 0, 0.2), deg);
        StopRules rules;
        rules.min_quality = 0.05;
        rules.max_twist_deg = 30.0;
        const Index stopped = stop_columns(col, rules, 0, next);
        if (deg < 30.0) {
            EXPECT_EQ(stopped, 0);
        } else {
            EXPECT_EQ(stopped, 4);
            for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(col.reason[i], Shortfall::Twist) << i;
        }
    }
}

TEST(Columns, TwoCellsStackedAcrossAnAcuteConcaveEdgeStopTheEdgesColumns) {
    // Two wall triangles folded about their shared edge AB so that the fluid lies in the wedge
    // between them, each column along its face's normal and the edge's along their bisector:
    // at 15 degrees the first two cells lie stacked rather than side by side, and the face
    // between them is skewed far beyond checkMesh's 4. A and B stop (the cells then close the
    // step onto the edge and share no face); C and D go on. Opened to 120 degrees, nothing
    // stops. Quality alone (a bar of 0.01) would let every cell through.
    for (const double deg : {15.0, 120.0}) {
        const double t = deg * std::numbers::pi / 180.0;
        SurfaceMesh wall;
        wall.patches.push_back({"wall", PatchKind::Wall});
        wall.points = {Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(1, 0.5, 0), Vec3(std::cos(t), 0.5, std::sin(t))};
        wall.add_face({0, 2, 1}, 0);  // normal +z, into the wedge
        wall.add_face({0, 1, 3}, 0);  // normal (sin t, 0, -cos t), into the wedge
        const Vec3 n1(0, 0, 1), n2(std::sin(t), 0, -std::cos(t));
        const Vec3 bisector = (n1 + n2).normalized();
        const double h = 0.01;
        std::vector<Vec3> points = wall.points;
        Columns col(wall, 3, points);
        const std::vector<Vec3> next{wall.points[0] + h * bisector, wall.points[1] + h * bisector,
                                     wall.points[2] + h * n1, wall.points[3] + h * n2};
        StopRules rules;
        rules.min_quality = 0.01;
        const Index stopped = stop_columns(col, rules, 0, next);
        if (deg > 90.0) {
            EXPECT_EQ(stopped, 0);
            continue;
        }
        EXPECT_EQ(stopped, 2);
        EXPECT_EQ(col.reason[0], Shortfall::Quality);
        EXPECT_EQ(col.reason[1], Shortfall::Quality);
        EXPECT_EQ(col.levels[0], 0);
        EXPECT_EQ(col.levels[1], 0);
        EXPECT_EQ(col.levels[2], 1);
        EXPECT_EQ(col.levels[3], 1);
    }
}

TEST(Columns, TheBarIsRelativeToTheFaceAndRaisedToHalfTheBoundWhereTheFaceAllowsIt) {
    // A fair face (best 0.6): 0.2 of it; one whose best is 0.4 (under 0.5): raised to 0.1; a
    // poor face (best 0.1, under min_quality: a needle): 0.2 of it.
    EXPECT_DOUBLE_EQ(cell_bar(0.2, 0.6), 0.2 * 0.6);
    EXPECT_DOUBLE_EQ(cell_bar(0.2, 0.4), 0.1);
    EXPECT_DOUBLE_EQ(cell_bar(0.2, 0.2), 0.1);
    EXPECT_DOUBLE_EQ(cell_bar(0.2, 0.1), 0.2 * 0.1);
    EXPECT_DOUBLE_EQ(cell_bar(0.0, 0.5), 0.0);
}

/// One parallelogram quad with corner angle \p deg (its best cell: sin deg) and its next level
/// moved by (\p shear, 0, \p height): a hexahedron whose corners are all sin(deg) cos(tilt).
/// Returns whether its columns stopped (for quality), after checking the cell's quality is
/// \p q_min to \p q_max.
bool sheared_cell_stops(double deg, double shear, double height, double q_min, double q_max) {
    SurfaceMesh wall = test::quad_grid(1, 1, 1.0);
    const double a = deg * std::numbers::pi / 180.0;
    for (Vec3& x : wall.points) x = Vec3(x.x() + x.y() * std::cos(a), x.y() * std::sin(a), 0.0);
    std::vector<Vec3> points = wall.points;
    Columns col(wall, 3, points);
    EXPECT_NEAR(face_corner_quality(col, 0), std::sin(a), 1e-12);
    std::vector<Vec3> next(wall.points.size());
    for (std::size_t i = 0; i < next.size(); ++i) next[i] = wall.points[i] + Vec3(shear, 0.0, height);
    const double q = column_cell_jacobian(col, 0, next);
    EXPECT_GT(q, q_min);
    EXPECT_LT(q, q_max);
    StopRules rules;  // min_quality 0.2
    const Index stopped = stop_columns(col, rules, 0, next);
    if (stopped > 0) {
        for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(col.reason[i], Shortfall::Quality) << i;
    }
    return stopped > 0;
}

TEST(Columns, ACellOnAFairFaceStopsBelowHalfTheBoundAndOnAPoorFaceAtAFifthOfItsBest) {
    // Best 0.41 (24 degrees): a cell of 0.09 is above 0.2 of the best (0.081), which let the
    // notched box's corner prisms fall to 0.091; below 0.1 it now stops. One of 0.3 goes on.
    const double fair = std::sin(24.0 * std::numbers::pi / 180.0);
    const double tilt = std::sqrt(std::pow(fair / 0.09, 2) - 1.0);
    EXPECT_TRUE(sheared_cell_stops(24.0, 0.5 * tilt, 0.5, 0.085, 0.095));
    EXPECT_TRUE(sheared_cell_stops(24.0, 0.01 * tilt, 0.01, 0.085, 0.095));
    EXPECT_FALSE(sheared_cell_stops(24.0, 0.5, 0.5, 0.25, 0.35));
    // Best 0.14 (8 degrees, a poor face): a cell at 0.35 of it goes on, one at 0.15 stops.
    const double poor = std::sin(8.0 * std::numbers::pi / 180.0);
    EXPECT_FALSE(sheared_cell_stops(8.0, 0.5 * std::sqrt(std::pow(1.0 / 0.35, 2) - 1.0), 0.5, 0.3 * poor, 0.4 * poor));
    EXPECT_TRUE(sheared_cell_stops(8.0, 0.5 * std::sqrt(std::pow(1.0 / 0.15, 2) - 1.0), 0.5, 0.1 * poor, 0.2 * poor));
}

TEST(Columns, FullColumnsKeepTheUniformNumbering) {
    const SurfaceMesh wall = plate(true);
    const LayerMesh lm = extrude_layers(wall, eight_layers());
    const Index nw = lm.wall_nodes();
    for (Index i = 0; i < nw; ++i) {
        EXPECT_EQ(lm.node_layers(i), 8);
        for (int k = 0; k <= 8; ++k) EXPECT_EQ(lm.level_node(k, i), k * nw + i);
    }
    EXPECT_EQ(lm.mesh.prisms.size(), 8u * static_cast<std::size_t>(wall.num_faces()));
    EXPECT_TRUE(lm.mesh.pyramids.empty());
    EXPECT_TRUE(lm.mesh.tets.empty());
}

TEST(Columns, AStoppedColumnOnTrianglesIsClosedByPyramidsAndItsNeighboursFollowTheEnvelope) {
    const SurfaceMesh wall = plate(true);
    const LayerMesh lm = extrude_layers(wall, eight_layers(), limited_centre(wall));
    const ValidationReport v = validate_mesh(lm.mesh);
    ASSERT_TRUE(v.ok()) << v.problems.front();
    const Index centre = 5 * 11 + 5;
    EXPECT_EQ(lm.node_layers(centre), 2);                                           // 0.02 ≤ 0.025 < 0.03
    EXPECT_EQ(lm.stop_reason[static_cast<std::size_t>(centre)], Shortfall::Front);  // an extra (front) limit
    // A front limit lowers its own column and, through the thickness envelope (0.25 per unit of
    // wall distance), those near it: the ring at 0.1 may have 0.05 (4 or 5 layers of 0.01, as
    // the sum rounds), the next ring 0.075, then every layer. Not one layer less per edge, as
    // proximity limits are: on a coarse wall that took every column down with it.
    const Index ring = lm.node_layers(centre + 1);
    EXPECT_GE(ring, 4);
    EXPECT_LE(ring, 5);
    EXPECT_GE(lm.node_layers(centre + 2), 7);
    EXPECT_EQ(lm.node_layers(centre + 4), 8);
    EXPECT_EQ(lm.stop_reason[static_cast<std::size_t>(centre + 1)], Shortfall::Front);
    // Numbering: level-major, a column above its top is its top, level_of inverts it.
    const Index nw = lm.wall_nodes();
    Index expected = nw;
    for (int k = 1; k <= 8; ++k)
        for (Index i = 0; i < nw; ++i) {
            const Index id = lm.level_node(k, i);
            if (k <= lm.node_layers(i)) {
                EXPECT_EQ(id, expected++) << k << " " << i;
            } else {
                EXPECT_EQ(id, lm.top_node(i));
            }
            EXPECT_EQ(lm.level_of(id), std::min(k, lm.node_layers(i)));
        }
    EXPECT_EQ(static_cast<std::size_t>(expected), lm.mesh.points.size());
    // The steps: pyramids whose apex is a stopped column's top; every face has cells; the top
    // is the wall's faces at the columns' tops.
    EXPECT_GT(lm.mesh.pyramids.size(), 0u);
    std::vector<char> is_top(lm.mesh.points.size(), 0);
    for (Index i = 0; i < nw; ++i) is_top[static_cast<std::size_t>(lm.top_node(i))] = 1;
    for (const auto& pyr : lm.mesh.pyramids) EXPECT_TRUE(is_top[static_cast<std::size_t>(pyr[4])]);
    for (const int n : lm.face_layers) EXPECT_GE(n, 2);
    ASSERT_EQ(lm.top.num_faces(), wall.num_faces());
    for (Index i = 0; i < nw; ++i)
        EXPECT_EQ(lm.top.points[static_cast<std::size_t>(i)], lm.mesh.points[static_cast<std::size_t>(lm.top_node(i))]);
    // The step cells' worst is reported per layer, and it is above zero.
    Index steps = 0;
    for (const LayerStats& s : lm.stats) {
        steps += s.transition_cells;
        if (s.transition_cells > 0) {
            EXPECT_GT(s.min_transition_jacobian, 0.0);
        }
    }
    EXPECT_EQ(steps, static_cast<Index>(lm.mesh.pyramids.size() + lm.mesh.tets.size()));
    // The report: the centre short for the front limit, its ring for the same reason (lowered by it).
    const LayerReport r = layer_report(lm);
    ASSERT_EQ(r.patches.size(), 1u);
    EXPECT_EQ(r.patches[0].min_layers, 2);
    EXPECT_LT(r.patches[0].all_layers, r.patches[0].nodes);
    EXPECT_GT(r.patches[0].short_nodes(Shortfall::Front), 0);
}

TEST(Columns, AFrontLimitKeepsTheFirstHeightAndEveryLayerItsTallestLayersCapped) {
    // Eight layers from 0.01 at growth 1.2 (0.165 in all) with the centre bounded to 0.1, as a
    // front round bounds a column whose top met the front: the column keeps its eight layers, its
    // first height and its growth up to a cap (0.01, 0.012, then six of about 0.0129), and is as
    // thick as the six layers that fit the bound (0.0993); bounded below eight layers of 0.01
    // (0.08), it loses layers instead.
    const SurfaceMesh wall = plate(true);
    LayerParams p = eight_layers();
    p.distribution.growth = 1.2;
    LayerConstraints c = limited_centre(wall);
    const Index centre = 5 * 11 + 5;
    c.node_thickness_limit[static_cast<std::size_t>(centre)] = 0.1;
    const LayerMesh lm = extrude_layers(wall, p, c);
    const ValidationReport v = validate_mesh(lm.mesh);
    ASSERT_TRUE(v.ok()) << v.problems.front();
    ASSERT_EQ(lm.node_layers(centre), 8);
    auto height = [&](Index i, int k) {
        return (lm.mesh.points[lm.level_node(k + 1, i)] - lm.mesh.points[lm.level_node(k, i)]).norm();
    };
    EXPECT_NEAR(height(centre, 0), 0.01, 1e-4);
    double length = 0.0;
    for (int k = 0; k < 8; ++k) {
        length += height(centre, k);
        if (k > 0) {
            EXPECT_GE(height(centre, k), height(centre, k - 1) * (1.0 - 1e-3)) << k;
        }
    }
    double six = 0.0;
    for (int k = 0; k < 6; ++k) six += 0.01 * std::pow(1.2, k);
    EXPECT_NEAR(length, six, 0.003);
    EXPECT_NEAR(height(centre, 1), 0.012, 2e-4);
    EXPECT_NEAR(height(centre, 7), height(centre, 2), 2e-4);  // capped
    EXPECT_NEAR(lm.height_scale[static_cast<std::size_t>(centre)], six / 0.165, 0.003);
    // The report: every node has every layer, the centre and its ring short of thickness for the front.
    const LayerReport r = layer_report(lm);
    EXPECT_EQ(r.patches[0].all_layers, r.patches[0].nodes);
    EXPECT_GT(r.patches[0].short_nodes(Shortfall::Front), 0);
    EXPECT_LT(r.patches[0].full_nodes, r.patches[0].nodes);

    c.node_thickness_limit[static_cast<std::size_t>(centre)] = 0.05;
    const LayerMesh fewer = extrude_layers(wall, p, c);
    EXPECT_EQ(fewer.node_layers(centre), 3);  // 0.01 + 0.012 + 0.0144, and a fourth of 0.01728 would pass 0.05
    EXPECT_EQ(fewer.stop_reason[static_cast<std::size_t>(centre)], Shortfall::Front);
}

TEST(Columns, MarchesSharingTheirSmoothingGiveTheSameLayersAsFreshOnes) {
    // build_hybrid_mesh's rounds share one SmoothedLevels (LayerConstraints::smoothed): a round
    // whose bounds differ from the round before reuses the levels it smooths alike and smooths
    // the others again; other settings (another key) smooth every level again. Either way the
    // same bytes as a march with a store of its own.
    const SurfaceMesh wall = plate(true);
    LayerParams p = eight_layers();
    p.distribution.growth = 1.2;
    LayerConstraints shared = limited_centre(wall);
    shared.smoothed = make_smoothed_levels();
    const Index centre = 5 * 11 + 5;
    auto alone = [&](const LayerParams& params) {
        LayerConstraints own = shared;
        own.smoothed = nullptr;  // extrude_layers makes its own
        return extrude_layers(wall, params, own);
    };
    test::expect_same_layers(extrude_layers(wall, p, shared), alone(p), "the first march");
    shared.node_thickness_limit[static_cast<std::size_t>(centre)] = 0.1;  // a front round's bound
    test::expect_same_layers(extrude_layers(wall, p, shared), alone(p), "a round after it");
    test::expect_same_layers(extrude_layers(wall, p, shared), alone(p), "the same round again");
    LayerParams other = p;
    other.tolerance = 1e-4;
    test::expect_same_layers(extrude_layers(wall, other, shared), alone(other), "other settings");
    shared.node_thickness_limit[static_cast<std::size_t>(centre)] = 0.05;
    test::expect_same_layers(extrude_layers(wall, p, shared), alone(p), "back to the first settings");
}

TEST(Columns, AColumnBoundWhereItStoppedKeepsEveryLayerCappedAndItsReason) {
    // A stop bound as extrude_layers sets it where a column stopped (the six layers it reached,
    // 0.255 of eight from 0.02 at growth 1.3, 0.477 in all): the centre keeps all eight, ends
    // there and is short for the reason it stopped; the ring round it, 0.1 away, follows the
    // bound's envelope (0.255 + 2 × 0.1 < 0.477), short for its neighbour.
    const SurfaceMesh wall = plate(true);
    LayerParams p = eight_layers();
    p.distribution.first_height = 0.02;
    p.distribution.growth = 1.3;
    LayerConstraints c;
    const Index centre = 5 * 11 + 5;
    c.node_stop_limit.assign(wall.points.size(), std::numeric_limits<double>::infinity());
    c.node_stop_reason.assign(wall.points.size(), Shortfall::None);
    double six = 0.0;
    for (int k = 0; k < 6; ++k) six += 0.02 * std::pow(1.3, k);
    c.node_stop_limit[static_cast<std::size_t>(centre)] = six;
    c.node_stop_reason[static_cast<std::size_t>(centre)] = Shortfall::Quality;
    const LayerMesh lm = extrude_layers(wall, p, c);
    ASSERT_EQ(lm.node_layers(centre), 8);
    const double length = (lm.mesh.points[lm.top_node(centre)] - lm.mesh.points[lm.level_node(0, centre)]).norm();
    EXPECT_NEAR(length, six, 1e-3);
    const LayerReport r = layer_report(lm);
    EXPECT_EQ(r.patches[0].all_layers, r.patches[0].nodes);
    EXPECT_EQ(r.patches[0].short_nodes(Shortfall::Quality), 1);
    EXPECT_GT(r.patches[0].short_nodes(Shortfall::Neighbours), 0);
    c.node_stop_reason.pop_back();
    test::expect_error<InputError>([&] { (void)extrude_layers(wall, p, c); }, {"node_stop_reason"});
}

TEST(Columns, ColumnsThatStopOnABumpAreMarchedAgainWithEveryLayer) {
    // The plate's centre raised 0.1 into a bump, eight layers from 0.01 at growth 1.3, and
    // columns allowed to turn 4 degrees a layer: those round the bump, spreading as they rise,
    // stop for turning some layers up. Marched again with each bounded where it stopped, every
    // column has all eight layers (a column short for turning with every layer is one capped),
    // the bump's short of thickness for their turning or their neighbours.
    SurfaceMesh wall = plate(true);
    const Index centre = 5 * 11 + 5;
    wall.points[static_cast<std::size_t>(centre)].z() = 0.1;
    LayerParams p = eight_layers();
    p.distribution.first_height = 0.01;
    p.distribution.growth = 1.3;
    p.max_turn_deg = 4.0;
    const LayerMesh lm = extrude_layers(wall, p);
    const ValidationReport v = validate_mesh(lm.mesh);
    ASSERT_TRUE(v.ok()) << v.problems.front();
    const LayerReport r = layer_report(lm);
    EXPECT_EQ(r.patches[0].all_layers, r.patches[0].nodes);
    EXPECT_GT(r.patches[0].short_nodes(Shortfall::Turning), 0);
    EXPECT_LT(r.patches[0].min_share, 0.9);
}

TEST(Columns, AStepMayDropFiveTimesItsWallDistanceBeforeItsNeighboursStop) {
    // Layers of 0.1 on the plate of spacing 0.1, the centre limited to one: the step round it
    // drops a wall spacing per layer. Its cells are judged against what a right step of that
    // drop allows, so the ring round the centre keeps growing until the drop passes five times
    // its wall distance; the next ring, judged against the first ring's top, keeps every layer.
    const SurfaceMesh wall = plate(true);
    LayerParams p = eight_layers();
    p.distribution.first_height = 0.1;
    p.distribution.layers = 10;
    p.proximity_limits.front_slope = 1e3;  // the limit stays at the centre
    LayerConstraints c = limited_centre(wall);
    c.node_thickness_limit[5 * 11 + 5] = 0.15;
    const LayerMesh lm = extrude_layers(wall, p, c);
    const ValidationReport v = validate_mesh(lm.mesh);
    ASSERT_TRUE(v.ok()) << v.problems.front();
    const Index centre = 5 * 11 + 5;
    EXPECT_EQ(lm.node_layers(centre), 1);
    for (const Index ring : {centre - 1, centre + 1, centre - 11, centre + 11}) {
        EXPECT_GE(lm.node_layers(ring), 6) << ring;  // a drop of 0.5 at 0.1: five times
        EXPECT_LT(lm.node_layers(ring), 10) << ring;
        EXPECT_EQ(lm.stop_reason[static_cast<std::size_t>(ring)], Shortfall::Neighbours) << ring;
    }
    for (const Index far : {centre - 3, centre + 3, centre - 33, centre + 33}) EXPECT_EQ(lm.node_layers(far), 10) << far;
    // Five layers drop at most four spacings: nothing but the centre stops.
    p.distribution.layers = 5;
    const LayerMesh five = extrude_layers(wall, p, c);
    for (Index i = 0; i < five.wall_nodes(); ++i) {
        if (i != centre) {
            EXPECT_EQ(five.node_layers(i), 5) << i;
        }
    }
}

TEST(Columns, AColumnStopsBeforeALayerTallerThanTheFrontIsWideWhereAsked) {
    // Quads of 0.1, layers 0.03, 0.048, 0.0768, 0.1229, ...: with LayerParams::isotropy 1 every
    // column stops before the fourth, taller than the front's spacing; without, none stops.
    const SurfaceMesh wall = plate(false);
    LayerParams p = eight_layers();
    p.distribution.first_height = 0.03;
    p.distribution.growth = 1.6;
    p.distribution.layers = 6;
    p.isotropy = 1.0;
    const LayerMesh lm = extrude_layers(wall, p);
    for (Index i = 0; i < lm.wall_nodes(); ++i) {
        EXPECT_EQ(lm.node_layers(i), 3) << i;
        EXPECT_EQ(lm.stop_reason[static_cast<std::size_t>(i)], Shortfall::Isotropic) << i;
    }
    EXPECT_EQ(layer_report(lm).patches[0].short_nodes(Shortfall::Isotropic), lm.wall_nodes());
    p.isotropy = 0.0;
    const LayerMesh all = extrude_layers(wall, p);
    for (Index i = 0; i < all.wall_nodes(); ++i) EXPECT_EQ(all.node_layers(i), 6) << i;
    // A first layer taller than the front is wide is kept.
    p.isotropy = 0.2;
    const LayerMesh first = extrude_layers(wall, p);
    for (Index i = 0; i < first.wall_nodes(); ++i) EXPECT_EQ(first.node_layers(i), 1) << i;
    p.isotropy = -1.0;
    EXPECT_THROW(extrude_layers(wall, p), InputError);
}

TEST(Columns, AFrontLimitSpreadsAtTheFrontSlopeAndAProximityLimitAtItsOwn) {
    // The centre limited to 0.025 (an extra limit, as a front round sets): at front_slope 1
    // its ring at 0.1 may have 0.125, more than the 0.08 asked, so only the centre is lowered;
    // at 0.25 the ring may have 0.05 (4 or 5 layers). The proximity slope plays no part.
    const SurfaceMesh wall = plate(true);
    const Index centre = 5 * 11 + 5;
    LayerParams p = eight_layers();
    p.proximity_limits.front_slope = 1.0;
    p.proximity_limits.slope = 0.05;
    LayerMesh lm = extrude_layers(wall, p, limited_centre(wall));
    EXPECT_EQ(lm.node_layers(centre), 2);
    for (const Index ring : {centre + 1, centre - 1, centre + 11, centre - 11}) EXPECT_EQ(lm.node_layers(ring), 8);
    Index lowered = 0;
    for (Index i = 0; i < lm.wall_nodes(); ++i) lowered += lm.node_layers(i) < 8 ? 1 : 0;
    EXPECT_EQ(lowered, 1);
    p.proximity_limits.front_slope = 0.25;
    lm = extrude_layers(wall, p, limited_centre(wall));
    EXPECT_GE(lm.node_layers(centre + 1), 4);
    EXPECT_LE(lm.node_layers(centre + 1), 5);
    EXPECT_GE(lm.node_layers(centre + 2), 7);
}

TEST(Columns, EachFrontLimitSpreadsAtItsOwnNodesSlope) {
    // Two nodes limited to 0.025 as a front round sets, four spacings apart: the one given a
    // slope of 0.25 (a column lowered again) lowers its ring to 4 or 5 layers, the one at the
    // settings' 1 lowers only itself.
    const SurfaceMesh wall = plate(true);
    const Index a = 5 * 11 + 3, b = 5 * 11 + 7;
    LayerParams p = eight_layers();
    p.proximity_limits.front_slope = 1.0;
    LayerConstraints c = limited_centre(wall);
    c.node_thickness_limit[5 * 11 + 5] = std::numeric_limits<double>::infinity();
    c.node_thickness_limit[a] = c.node_thickness_limit[b] = 0.025;
    c.node_front_slope.assign(wall.points.size(), 1.0);
    c.node_front_slope[a] = 0.25;
    const LayerMesh lm = extrude_layers(wall, p, c);
    EXPECT_EQ(lm.node_layers(a), 2);
    EXPECT_EQ(lm.node_layers(b), 2);
    for (const Index ring : {a - 1, a - 11, a + 11}) {
        EXPECT_GE(lm.node_layers(ring), 4) << ring;
        EXPECT_LE(lm.node_layers(ring), 5) << ring;
    }
    for (const Index ring : {b + 1, b - 11, b + 11}) EXPECT_EQ(lm.node_layers(ring), 8) << ring;
    c.node_front_slope[a] = 0.0;
    EXPECT_THROW(extrude_layers(wall, p, c), InputError);
    c.node_front_slope.pop_back();
    EXPECT_THROW(extrude_layers(wall, p, c), InputError);
}

TEST(Columns, AStoppedColumnOnQuadsSplitsItsQuadsAndKeepsHexahedraElsewhere) {
    const SurfaceMesh wall = plate(false);
    const LayerMesh lm = extrude_layers(wall, eight_layers(), limited_centre(wall));
    const ValidationReport v = validate_mesh(lm.mesh);
    ASSERT_TRUE(v.ok()) << v.problems.front();
    EXPECT_GT(lm.mesh.hexes.size(), 0u);
    EXPECT_GT(lm.mesh.prisms.size(), 0u);  // the split quads' columns
    EXPECT_GT(lm.top.num_faces(), wall.num_faces());
    EXPECT_GT(lm.top.num_triangles(), 0);
    // The boundary's wall is the plate's area, split or not.
    double area = 0.0;
    for (Index f = 0; f < lm.mesh.boundary.num_faces(); ++f)
        if (lm.mesh.boundary.patches[static_cast<std::size_t>(lm.mesh.boundary.face_patch[f])].kind == PatchKind::Wall)
            area += face_area_vector(lm.mesh.boundary, lm.mesh.points, f).norm();
    EXPECT_NEAR(area, 1.0, 1e-12);
}

TEST(Columns, ColumnsRoundAThinRodKeepEveryLayerWhereTheFrontStretchesItsFaces) {
    // Layers to eleven times the rod's radius: the front's faces, square on the wall, come out
    // about six times as long round the rod as along it (twelve with plain extrusion), their
    // corners' sines far under a fifth of what the wall faces allow. That is the geometry's:
    // every column keeps every layer (judged against the wall's bar alone, they stopped), and
    // every cell is valid.
    const double r = 0.01;
    const SurfaceMesh wall = test::thin_torus(0.25, r, 12, 300);  // 0.0052 round, 0.0052 along
    LayerParams p;
    p.distribution.layers = 12;
    p.distribution.growth = 1.2;
    p.distribution.first_height = 11.0 * r * 0.2 / (std::pow(1.2, 12) - 1.0);
    p.proximity = ProximityMode::Off;
    const LayerMesh lm = extrude_layers(wall, p);
    const ValidationReport v = validate_mesh(lm.mesh);
    ASSERT_TRUE(v.ok()) << v.problems.front();
    for (Index i = 0; i < lm.wall_nodes(); ++i) ASSERT_EQ(lm.node_layers(i), 12) << i;
    // The top faces are as stretched as said: round the rod against along it.
    auto top = [&](Index i) { return lm.mesh.points[static_cast<std::size_t>(lm.top_node(i))]; };
    const double round = (top(1) - top(0)).norm(), along = (top(12) - top(0)).norm();
    EXPECT_GT(round / along, 5.0);
}

TEST(Columns, SameBytesForAnyThreadCount) {
    const SurfaceMesh wall = plate(false);
    test::expect_same_bytes_for_any_thread_count(wall, eight_layers(), limited_centre(wall));
}

}  // namespace
}  // namespace strata
