// The paper's first example (section 5.1): the notional Apollo surface has the paper's
// topology (1580 quads, 20 triangles around a 20-valent nose, one open end in the nozzle exit
// plane), points out of the body, and its 30 layers are valid with the exit nodes held in the
// exit plane.

#include "apollo/apollo_surface.h"

#include <strata/core/cell_quality.h>
#include <strata/core/validate.h>
#include <strata/geometry/check.h>
#include <strata/geometry/topology.h>
#include <strata/module/layers.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>

namespace strata {
namespace {

TEST(Apollo, FaceCountsAndTwentyValentNose) {
    const SurfaceMesh m = apollo_surface();
    EXPECT_EQ(m.num_quads(), 1580);
    EXPECT_EQ(m.num_triangles(), 20);
    EXPECT_EQ(m.num_points(), 1 + 80 * 20);
    EXPECT_NO_THROW(check_surface(m, "apollo"));
    ASSERT_EQ(m.patches.size(), 1u);
    EXPECT_EQ(m.patches[0].name, "apollo");
    EXPECT_EQ(m.patches[0].kind, PatchKind::Wall);

    // Exactly one node has 20 faces around it, and every triangle is one of them.
    const Csr vf = vertex_faces(m);
    Index nose = kNone;
    for (Index i = 0; i < m.num_points(); ++i) {
        if (vf.row_size(i) != 20) {
            EXPECT_LE(vf.row_size(i), 4) << "node " << i;
            continue;
        }
        EXPECT_EQ(nose, kNone) << "a second 20-valent node: " << i;
        nose = i;
    }
    ASSERT_NE(nose, kNone);
    for (const Index* f = vf.row_begin(nose); f != vf.row_end(nose); ++f) EXPECT_EQ(m.face_size(*f), 3);
    // The nose is the apex on the axis, the most forward point.
    EXPECT_EQ(m.points[nose].y(), 0.0);
    EXPECT_EQ(m.points[nose].z(), 0.0);
    for (const Vec3& p : m.points) EXPECT_GE(p.x(), m.points[nose].x());
}

TEST(Apollo, ClosedExceptTheNozzleExitLoop) {
    const SurfaceMesh m = apollo_surface();
    const EdgeTable edges = edge_table(m);
    Index boundary = 0;
    for (Index e = 0; e < edges.faces.rows(); ++e) {
        ASSERT_GE(edges.faces.row_size(e), 1);
        ASSERT_LE(edges.faces.row_size(e), 2);
        boundary += edges.faces.row_size(e) == 1 ? 1 : 0;
    }
    EXPECT_EQ(boundary, 20);

    const Csr loops = boundary_loops(m);
    ASSERT_EQ(loops.rows(), 1);
    ASSERT_EQ(loops.row_size(0), 20);
    // The loop is the aft end: every node exactly in the plane x = x_exit, the largest x.
    double x_max = -1e300;
    for (const Vec3& p : m.points) x_max = std::max(x_max, p.x());
    for (const Index i : loops.values) EXPECT_EQ(m.points[i].x(), x_max) << "exit node " << i;
}

TEST(Apollo, OrientedOutOfTheBody) {
    const SurfaceMesh m = apollo_surface();
    // Consistent: each directed edge is used once, so neighbours traverse shared edges oppositely.
    std::map<std::pair<Index, Index>, int> directed;
    for (Index f = 0; f < m.num_faces(); ++f)
        for (Index i = 0; i < m.face_size(f); ++i)
            ++directed[{m.face_node(f, i), m.face_node(f, (i + 1) % m.face_size(f))}];
    for (const auto& [edge, count] : directed) EXPECT_EQ(count, 1) << edge.first << "-" << edge.second;

    // Outward: the volume enclosed with the exit disk, ∮ x n_x dA (the disk's normal is +x),
    // is positive and about that of the notional stack (~74 m³).
    double volume = 0.0;
    auto add_triangle = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
        volume += (a.x() + b.x() + c.x()) / 3.0 * 0.5 * (b - a).cross(c - a).x();
    };
    for (Index f = 0; f < m.num_faces(); ++f) {
        const Index* v = m.face_begin(f);
        add_triangle(m.points[v[0]], m.points[v[1]], m.points[v[2]]);
        if (m.face_size(f) == 4) add_triangle(m.points[v[0]], m.points[v[2]], m.points[v[3]]);
    }
    const Csr loops = boundary_loops(m);
    ASSERT_EQ(loops.rows(), 1);
    double disk = 0.0;  // |area| of the exit polygon in the y-z plane
    for (Index i = 0; i < loops.row_size(0); ++i) {
        const Vec3& p = m.points[loops.values[static_cast<std::size_t>(i)]];
        const Vec3& q = m.points[loops.values[static_cast<std::size_t>((i + 1) % loops.row_size(0))]];
        disk += 0.5 * (p.y() * q.z() - q.y() * p.z());
    }
    volume += m.points[loops.values[0]].x() * std::abs(disk);
    std::printf("apollo: enclosed volume %.3f m^3\n", volume);
    EXPECT_GT(volume, 60.0);
    EXPECT_LT(volume, 90.0);

    // And locally: on the service module (r = 1.95 m) the faces point away from the axis.
    for (Index f = 0; f < m.num_faces(); ++f) {
        const Index* v = m.face_begin(f);
        if (m.face_size(f) != 4) continue;
        Vec3 c = Vec3::Zero();
        bool cylinder = true;
        for (int i = 0; i < 4; ++i) {
            c += m.points[v[i]] / 4.0;
            cylinder = cylinder && std::abs(std::hypot(m.points[v[i]].y(), m.points[v[i]].z()) - 1.95) < 1e-9;
        }
        if (!cylinder) continue;
        const Vec3 n = (m.points[v[2]] - m.points[v[0]]).cross(m.points[v[3]] - m.points[v[1]]);
        EXPECT_GT(n.dot(Vec3(0.0, c.y(), c.z())), 0.0) << "face " << f;
    }
}

TEST(Apollo, LayersValidAndExitNodesStayInTheirPlane) {
    const SurfaceMesh wall = apollo_surface();
    const LayerParams params = apollo_layer_params();
    const LayerMesh lm = extrude_layers(wall, params);
    ASSERT_EQ(lm.layers(), 30);
    for (const ShortNode& n : layer_report(lm).short_nodes)
        std::printf("short: node %d at (%g %g %g) %d layers, %s\n", static_cast<int>(n.node), n.position.x(),
                    n.position.y(), n.position.z(), n.layers, std::string(to_string(n.reason)).c_str());
    EXPECT_EQ(lm.mesh.hexes.size(), 30u * 1580u);
    EXPECT_EQ(lm.mesh.prisms.size(), 30u * 20u);
    EXPECT_EQ(lm.unsmoothed_nodes, 0);

    ValidationReport report;
    ASSERT_NO_THROW(report = require_valid_mesh(lm.mesh, "apollo layers"));
    double hex_min = 1.0;
    for (const auto& c : lm.mesh.hexes) hex_min = std::min(hex_min, hex_min_scaled_jacobian(lm.mesh.points, c));
    std::printf("apollo layers: min scaled Jacobian %.4f (hexahedra %.4f)\n", report.min_scaled_jacobian, hex_min);
    // Measured 0.3077: the nose prisms, whose 18° apex corner bounds them by sin 18° = 0.309.
    EXPECT_GT(report.min_scaled_jacobian, 0.28);
    // Measured 0.563: the first cells in the 70° concave base/nozzle corner.
    EXPECT_GT(hex_min, 0.5);
    for (const LayerStats& s : lm.stats) EXPECT_GT(s.min_scaled_jacobian, 0.28);

    const Csr loops = boundary_loops(wall);
    ASSERT_EQ(loops.rows(), 1);
    const double x_exit = wall.points[loops.values[0]].x();
    double deviation = 0.0;
    for (int k = 0; k <= lm.layers(); ++k)
        for (const Index i : loops.values) {
            const double x = lm.mesh.points[static_cast<std::size_t>(lm.level_node(k, i))].x();
            EXPECT_NEAR(x, x_exit, 1e-12) << "level " << k << ", exit node " << i;
            deviation = std::max(deviation, std::abs(x - x_exit));
        }
    std::printf("apollo layers: exit nodes max |x - x_exit| %.3g m\n", deviation);
    // They did march: the outermost exit nodes lie 0.3 m (the total thickness) out, about.
    for (const Index i : loops.values) {
        const Vec3& top = lm.mesh.points[static_cast<std::size_t>(lm.top_node(i))];
        const double r0 = std::hypot(wall.points[i].y(), wall.points[i].z());
        EXPECT_NEAR(std::hypot(top.y(), top.z()) - r0, 0.3, 0.03) << "exit node " << i;
    }
}

}  // namespace
}  // namespace strata
