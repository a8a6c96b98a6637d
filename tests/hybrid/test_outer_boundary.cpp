// Planes the layers end on: re-meshed around the layers' side faces, conforming, with the
// layers' corners on the planes' common edges; the inputs that cannot work are refused.

#include <strata/core/error.h>
#include <strata/geometry/topology.h>
#include <strata/hybrid/hybrid_mesh.h>
#include <strata/hybrid/outer_boundary.h>
#include <strata/surface/prepare.h>

#include <gtest/gtest.h>

#include "hybrid/reread_checks.h"
#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

namespace strata {
namespace {

HybridParams box_params() {
    HybridParams p;
    p.layers.distribution.layers = 8;
    p.layers.distribution.first_height = 0.005;
    p.layers.distribution.growth = 1.2;  // 0.082 in all
    return p;
}

Index patch_named(const SurfaceMesh& m, const std::string& name) {
    for (std::size_t i = 0; i < m.patches.size(); ++i)
        if (m.patches[i].name == name) return static_cast<Index>(i);
    ADD_FAILURE() << "no patch " << name;
    return kNone;
}

/// box_domain_geo(dir, height, size) prepared and meshed with box_params().
struct BoxRun {
    SurfaceMesh surface;
    HybridReport report;
    VolumeMesh mesh;
};
BoxRun mesh_box(const test::ScratchDir& dir, double height, double size) {
    BoxRun r;
    r.surface = prepare_surface(test::box_domain_geo(dir, height, size), {});
    r.mesh = build_hybrid_mesh(r.surface, box_params(), nullptr, &r.report);
    return r;
}

/// The mesh is valid and fills the box of \p volume: nothing lost, nothing overlapping.
void expect_whole_box(const HybridReport& rep, double volume) {
    ASSERT_TRUE(rep.validation.ok());
    EXPECT_NEAR(rep.validation.cell_volume, volume, 1e-9);
}

TEST(OuterBoundary, BoxSidesAreRemeshedAroundTheLayersAndTheMeshIsValid) {
    test::ScratchDir dir("outer_box");
    const auto [s, rep, m] = mesh_box(dir, 1.0, 0.1);
    ASSERT_NO_FATAL_FAILURE(expect_whole_box(rep, 1.0));
    EXPECT_GT(rep.validation.min_scaled_jacobian, 0.0);

    // The four sides were re-meshed, the lid was not.
    std::vector<Index> sides;
    for (const char* n : {"symmetry_x0", "symmetry_x1", "symmetry_y0", "symmetry_y1"})
        sides.push_back(patch_named(s, n));
    std::sort(sides.begin(), sides.end());
    EXPECT_EQ(rep.remeshed_patches, sides);

    // Every face of a side lies in its plane: the layers' side quads and the new triangles.
    const SurfaceMesh& b = m.boundary;
    Index side_quads = 0;
    for (Index f = 0; f < b.num_faces(); ++f) {
        const std::string& name = b.patches[static_cast<std::size_t>(b.face_patch[f])].name;
        if (name.rfind("symmetry_", 0) != 0) continue;
        const int axis = name[9] == 'x' ? 0 : 1;
        const double at = name[10] == '0' ? 0.0 : 1.0;
        for (const Index* v = b.face_begin(f); v != b.face_end(f); ++v)
            EXPECT_NEAR(m.points[*v][axis], at, 1e-12) << name;
        side_quads += b.face_size(f) == 4;
    }
    // One side quad per layer and per floor edge on the sides.
    const SurfaceMesh floor_top = [&] {
        SurfaceMesh t;
        t.points = s.points;
        for (Index f = 0; f < s.num_faces(); ++f)
            if (s.patches[static_cast<std::size_t>(s.face_patch[f])].kind == PatchKind::Wall)
                t.add_face(s.face_begin(f), s.face_size(f), 0);
        return t;
    }();
    const Csr loops = boundary_loops(floor_top);
    ASSERT_EQ(loops.rows(), 1);
    EXPECT_EQ(side_quads, 8 * loops.row_size(0));

    // The four corners of the floor march up the box's vertical edges.
    int corners = 0;
    for (Index i = 0; i < s.num_points(); ++i) {
        const Vec3& p = s.points[i];
        if (p.z() != 0.0 || (p.x() != 0.0 && p.x() != 1.0) || (p.y() != 0.0 && p.y() != 1.0)) continue;
        ++corners;
        // The column above the corner: mesh points with the corner's x and y up to the top.
        int above = 0;
        for (const Vec3& q : m.points)
            if (q.z() > 0.0 && q.z() < 0.0825 && std::abs(q.x() - p.x()) < 1e-12 && std::abs(q.y() - p.y()) < 1e-12)
                ++above;
        EXPECT_GE(above, 8) << "corner " << p.transpose();
    }
    EXPECT_EQ(corners, 4);

    test::expect_rereads_valid(m, dir, "box");
}

TEST(OuterBoundary, PatchEdgesAreCutAtTheTopOfTheLayersTheSameWayOnBothSides) {
    test::ScratchDir dir("outer_cut");
    const SurfaceMesh s = prepare_surface(test::box_domain_geo(dir, 1.0, 0.1), {});
    const LayerMesh lm = extrude_layers(s, box_params().layers);
    const OuterBoundary ob = outer_boundary(s, lm);
    // Closed together with the walls and the layers' side faces: every edge in exactly two faces.
    SurfaceMesh all = ob.mesh;
    std::vector<Index> id(static_cast<std::size_t>(lm.mesh.points.size()), kNone);
    // Map the layers' points into all: top nodes are the outer points with a top_node.
    for (std::size_t i = 0; i < ob.top_node.size(); ++i)
        if (ob.top_node[i] != kNone) id[static_cast<std::size_t>(lm.top_node(ob.top_node[i]))] = static_cast<Index>(i);
    auto node = [&](Index v) {
        Index& k = id[static_cast<std::size_t>(v)];
        if (k == kNone) {
            k = all.num_points();
            all.points.push_back(lm.mesh.points[v]);
        }
        return k;
    };
    const SurfaceMesh& lb = lm.mesh.boundary;
    for (Index f = 0; f < lb.num_faces(); ++f) {
        if (lb.face_patch[f] == lm.top_patch) continue;
        EXPECT_NE(lb.patches[static_cast<std::size_t>(lb.face_patch[f])].name, "layer_top");
        Index v[4];
        for (Index i = 0; i < lb.face_size(f); ++i) v[i] = node(lb.face_node(f, i));
        all.add_face(v, lb.face_size(f), 0);
    }
    const EdgeTable et = edge_table(all);
    for (Index e = 0; e < et.faces.rows(); ++e)
        ASSERT_EQ(et.faces.row_size(e), 2)
            << "edge at " << all.points[et.nodes[static_cast<std::size_t>(e)][0]].transpose();
    // The vertical edges were cut: no outer point below the top of the layers on them.
    for (const Vec3& p : ob.mesh.points)
        if ((p.x() == 0.0 || p.x() == 1.0) && (p.y() == 0.0 || p.y() == 1.0)) {
            EXPECT_GT(p.z(), 0.08);
        }
}

TEST(OuterBoundary, AFanEndingOnTheSymmetryPlaneIsMeshedRoundInThePlane) {
    // A wedge standing on the symmetry plane (y = 0), swept, its sharp edge (169 degrees) and
    // its base's two edges (95) running from the plane to a flat tip: the three edges' fans end
    // on the plane, each node there split into columns in the plane, and the plane is re-meshed
    // round the layers' sides through those columns' tops.
    test::ScratchDir dir("outer_fan");
    const std::string geo = dir.file("wedge.geo");
    std::ofstream(geo) << "SetFactory(\"OpenCASCADE\");\nBox(1) = {-2, 0, -2, 5, 3, 4};\n"
                       << "Point(101) = {0, 0, -0.1};\nPoint(102) = {0, 0, 0.1};\nPoint(103) = {1, 0, 0};\n"
                       << "Line(101) = {101, 103};\nLine(102) = {103, 102};\nLine(103) = {102, 101};\n"
                       << "Curve Loop(101) = {101, 102, 103};\nPlane Surface(101) = {101};\n"
                       << "e[] = Extrude {0.3, 1, 0} { Surface{101}; };\n"
                       << "BooleanDifference{ Volume{1}; Delete; }{ Volume{e[1]}; Delete; }\n"
                       << "sym[] = Surface In BoundingBox{-2.1, -1e-6, -2.1, 3.1, 1e-6, 2.1};\n"
                       << "wall[] = Surface In BoundingBox{-1e-3, -1e-3, -0.11, 1.301, 1.001, 0.11};\n"
                       << "all[] = Surface{:};\nPhysical Surface(\"wall\") = {wall[]};\n"
                       << "Physical Surface(\"symmetry\") = {sym[]};\nPhysical Surface(\"farfield\") = {all[]};\n"
                       << "Physical Surface(\"farfield\") -= {wall[], sym[]};\nMesh.MeshSizeMax = 0.5;\n";
    const SurfaceMesh s = prepare_surface(geo, {});
    HybridParams p;
    p.layers.distribution.layers = 6;
    p.layers.distribution.first_height = 0.005;  // 0.05 in all
    p.threads = 2;
    HybridReport rep;
    const VolumeMesh m = build_hybrid_mesh(s, p, nullptr, &rep);
    ASSERT_TRUE(rep.validation.ok());
    EXPECT_GT(rep.validation.min_scaled_jacobian, 0.05);
    EXPECT_NEAR(rep.validation.cell_volume, 60.0 - 0.1, 1e-9);  // the box less the wedge
    EXPECT_TRUE(rep.coverage.no_fan.empty());                   // no edge left without a fan
    EXPECT_EQ(rep.remeshed_patches, std::vector<Index>{patch_named(s, "symmetry")});
    // The three plane nodes' columns: the sharp edge's (at (1, 0, 0)) three, in the plane.
    int columns = 0;
    for (std::size_t i = 0; i < m.points.size(); ++i) {
        const Vec3 d = m.points[i] - Vec3(1.0, 0.0, 0.0);
        if (std::abs(d.y()) < 1e-12 && d.norm() > 0.04 && d.norm() < 0.06 && d.x() > -0.02) ++columns;
    }
    EXPECT_EQ(columns, 3);
    // Every face of the symmetry patch lies in its plane, the fans' end faces among them.
    const SurfaceMesh& b = m.boundary;
    Index on_plane = 0;
    for (Index f = 0; f < b.num_faces(); ++f) {
        const std::string& name = b.patches[static_cast<std::size_t>(b.face_patch[f])].name;
        EXPECT_NE(name, "layer_side");  // the fans' end faces are the plane's
        if (name != "symmetry") continue;
        ++on_plane;
        for (const Index* v = b.face_begin(f); v != b.face_end(f); ++v) EXPECT_NEAR(m.points[*v].y(), 0.0, 1e-12);
    }
    EXPECT_GT(on_plane, 0);
    test::expect_rereads_valid(m, dir, "wedge");
    // The same mesh on one thread.
    p.threads = 1;
    const VolumeMesh one = build_hybrid_mesh(s, p);
    EXPECT_EQ(one.points, m.points);
    test::expect_same_cells(one, m);
}

TEST(OuterBoundary, CurvedPatchMeetingTheWallsIsRefusedByName) {
    test::ScratchDir dir("outer_curved");
    const std::string geo = dir.file("cyl.geo");
    std::ofstream(geo) << "SetFactory(\"OpenCASCADE\");\nCylinder(1) = {0, 0, 0, 0, 0, 1, 0.5};\n"
                       << "Physical Surface(\"farfield_mantle\") = {1};\nPhysical Surface(\"farfield_lid\") = {2};\n"
                       << "Physical Surface(\"floor\") = {3};\nMesh.MeshSizeMax = 0.15;\n";
    const SurfaceMesh s = prepare_surface(geo, {});
    test::expect_error<InputError>([&] { build_hybrid_mesh(s, box_params()); }, {"'farfield_mantle'", "not planar"});
}

TEST(OuterBoundary, LayersTallerThanTheDomainStopBelowTheLidOrAreRefused) {
    test::ScratchDir dir("outer_thick");
    // 0.082 of layers in a box 0.05 high: with proximity (stop, the default) the columns end at
    // the last layer under 0.9 of the lid's distance, the first height kept; the mesh is whole.
    const auto [s, rep, m] = mesh_box(dir, 0.05, 0.02);
    ASSERT_NO_FATAL_FAILURE(expect_whole_box(rep, 0.05));
    EXPECT_EQ(rep.layers.stats.front().height, 0.005);
    Index by_proximity = 0;
    int fewest = 8;
    for (const PatchCoverage& c : rep.coverage.patches) {
        by_proximity += c.short_nodes(Shortfall::Proximity);
        fewest = std::min(fewest, c.min_layers);
    }
    EXPECT_GT(by_proximity, 0);
    EXPECT_LT(fewest, 8);
    for (const ShortNode& n : rep.coverage.short_nodes) EXPECT_LT(n.share * 0.082, 0.9 * 0.05 + 1e-12);
    // Without proximity limiting, the layers would cross the lid: refused before TetGen.
    HybridParams off = box_params();
    off.layers.proximity = ProximityMode::Off;
    try {
        build_hybrid_mesh(s, off);
        FAIL() << "layers beyond the lid must be refused";
    } catch (const TopologyError& e) {
        EXPECT_NE(std::string(e.what()).find("thinner layers"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace strata
