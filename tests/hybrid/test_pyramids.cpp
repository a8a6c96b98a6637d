// build_pyramids: apex placement, the capped surface's topology and orientation, volume
// closure (pyramids overlapping each other or the body would break it), shortening in concave
// corners and narrow gaps, the error for an impossible gap, triangles passing through.
//
// Overlap checks here are independent of the implementation: the divergence theorem on the
// closed capped surface, validate_mesh on the shell of pyramids, and a brute-force
// triangle–triangle crossing test with orientation predicates (no distances).

#include <strata/core/cell_quality.h>
#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/validate.h>
#include <strata/geometry/topology.h>
#include <strata/hybrid/pyramids.h>

#include "core/box_mesh.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <utility>

namespace strata {
namespace {

using test::closed_manifold;
using test::enclosed_volume;

using test::BoxMesh;

/// The boundary of a box of cubes as a surface (normals out of the solid: away from the
/// "layers", into the region still to mesh).
SurfaceMesh box_surface(const BoxMesh& box) {
    const VolumeMesh vm = box.build();
    SurfaceMesh s = vm.boundary;
    s.points = vm.points;
    return s;
}

/// Volume enclosed by a closed surface (divergence theorem; quads through their diagonals,
/// as validate.h does).
/// Every edge used once in each direction: closed, manifold, consistently oriented.
void expect_closed_oriented(const SurfaceMesh& s) {
    std::map<std::pair<Index, Index>, int> directed;
    for (Index f = 0; f < s.num_faces(); ++f)
        for (Index i = 0; i < s.face_size(f); ++i)
            ++directed[{s.face_node(f, i), s.face_node(f, (i + 1) % s.face_size(f))}];
    int bad = 0;
    for (const auto& [e, n] : directed) {
        const auto rev = directed.find({e.second, e.first});
        if (n != 1 || rev == directed.end() || rev->second != 1) ++bad;
    }
    EXPECT_EQ(bad, 0) << "edges not used exactly once in each direction";
}

double orient(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return (b - a).cross(c - a).dot(d - a);
}

/// Segment pq through the interior of triangle abc (strict orientation tests).
bool segment_crosses(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
    const double sp = orient(a, b, c, p), sq = orient(a, b, c, q);
    if (!((sp > 0 && sq < 0) || (sp < 0 && sq > 0))) return false;
    const double s1 = orient(p, q, a, b), s2 = orient(p, q, b, c), s3 = orient(p, q, c, a);
    return (s1 > 0 && s2 > 0 && s3 > 0) || (s1 < 0 && s2 < 0 && s3 < 0);
}

/// Pairs of triangles (the capped surface plus the quads as two triangles each) that cross
/// anywhere but at shared corners. Brute force: small meshes only.
int count_crossings(const SurfaceMesh& top, const PyramidLayer& layer) {
    std::vector<std::array<Index, 3>> tris;
    const auto& x = layer.surface.points;
    for (Index f = 0; f < layer.surface.num_faces(); ++f)
        tris.push_back({layer.surface.face_node(f, 0), layer.surface.face_node(f, 1), layer.surface.face_node(f, 2)});
    for (Index f = 0; f < top.num_faces(); ++f)
        if (top.face_size(f) == 4) {
            const Index* v = top.face_begin(f);
            tris.push_back({v[0], v[1], v[2]});
            tris.push_back({v[0], v[2], v[3]});
        }
    int crossings = 0;
    for (std::size_t i = 0; i < tris.size(); ++i)
        for (std::size_t j = i + 1; j < tris.size(); ++j) {
            const auto &s = tris[i], &t = tris[j];
            bool hit = false;
            for (int a = 0; a < 3 && !hit; ++a) {
                const Index p = s[a], q = s[(a + 1) % 3];
                if (p == t[0] || p == t[1] || p == t[2] || q == t[0] || q == t[1] || q == t[2]) continue;
                hit = segment_crosses(x[p], x[q], x[t[0]], x[t[1]], x[t[2]]);
            }
            for (int a = 0; a < 3 && !hit; ++a) {
                const Index p = t[a], q = t[(a + 1) % 3];
                if (p == s[0] || p == s[1] || p == s[2] || q == s[0] || q == s[1] || q == s[2]) continue;
                hit = segment_crosses(x[p], x[q], x[s[0]], x[s[1]], x[s[2]]);
            }
            crossings += hit;
        }
    return crossings;
}

double pyramid_volume(const PyramidLayer& l, std::size_t k) {
    return cell_volume(l.surface.points, l.pyramids[k].data(), CellType::Pyramid);
}

/// Apex height above the quad's centroid along its unit normal, and the quad's mean edge.
std::pair<double, double> height_and_size(const SurfaceMesh& top, const PyramidLayer& l, std::size_t k, Index f) {
    const Vec3 c = face_centroid(top, top.points, f), n = face_area_vector(top, f).normalized();
    double size = 0.0;
    for (Index i = 0; i < 4; ++i)
        size += 0.25 * (top.points[top.face_node(f, (i + 1) % 4)] - top.points[top.face_node(f, i)]).norm();
    return {(l.apexes[k] - c).dot(n), size};
}

/// Pyramids + the top quads reversed (inner) + the capped surface (outer): a closed shell.
VolumeMesh shell(const SurfaceMesh& top, const PyramidLayer& l) {
    VolumeMesh vm;
    vm.points = l.surface.points;
    vm.pyramids = l.pyramids;
    vm.boundary.patches = {{"inner", PatchKind::Wall}, {"outer", PatchKind::Other}};
    for (Index f = 0; f < top.num_faces(); ++f) {
        const Index* v = top.face_begin(f);
        vm.boundary.add_face({v[0], v[3], v[2], v[1]}, 0);
    }
    for (Index f = 0; f < l.surface.num_faces(); ++f) vm.boundary.add_face(l.surface.face_begin(f), 3, 1);
    return vm;
}

/// Two parallel n × n plates of unit quads facing each other across \p gap (z = 0 facing
/// +z, z = gap facing −z), the upper one shifted by \p shift in x and y.
SurfaceMesh facing_plates(int n, double gap, double shift = 0.0) {
    SurfaceMesh s = test::quad_grid(n, n);
    const Index nb = s.num_points();
    const SurfaceMesh up = test::quad_grid(n, n);
    for (const Vec3& p : up.points) s.points.push_back(p + Vec3(shift, shift, gap));
    for (Index f = 0; f < up.num_faces(); ++f) {
        const Index* v = up.face_begin(f);
        s.add_face({nb + v[0], nb + v[3], nb + v[2], nb + v[1]}, 0);
    }
    return s;
}

TEST(Pyramids, FlatGridApexAboveCentroidAtHalfEdge) {
    const SurfaceMesh top = test::quad_grid(4, 3, 2.0);
    const PyramidLayer l = build_pyramids(top, {});
    ASSERT_EQ(l.pyramids.size(), 12u);
    ASSERT_EQ(l.apexes.size(), 12u);
    EXPECT_EQ(l.surface.num_points(), top.num_points() + 12);
    EXPECT_EQ(l.surface.num_faces(), 48);
    EXPECT_EQ(l.surface.num_quads(), 0);
    for (std::size_t k = 0; k < 12; ++k) {
        const Index f = static_cast<Index>(k);
        const auto& p = l.pyramids[k];
        for (int i = 0; i < 4; ++i) EXPECT_EQ(p[i], top.face_node(f, i));
        EXPECT_EQ(p[4], top.num_points() + f);
        const Vec3 c = face_centroid(top, top.points, f);
        EXPECT_NEAR((l.apexes[k] - (c + Vec3(0, 0, 1.0))).norm(), 0.0, 1e-14);  // 0.5 × edge 2
        EXPECT_EQ(l.surface.points[p[4]], l.apexes[k]);
        EXPECT_GT(pyramid_min_scaled_jacobian(l.surface.points, p), 0.4);
        EXPECT_GT(cell_volume(l.surface.points, p.data(), CellType::Pyramid), 0.0);
    }
    // Side triangles point out of their pyramid and carry the quad's patch.
    for (Index f = 0; f < l.surface.num_faces(); ++f) {
        const std::size_t k = static_cast<std::size_t>(f / 4);
        const auto& p = l.pyramids[k];
        Vec3 mid = Vec3::Zero();
        for (Index v : p) mid += l.surface.points[v] / 5.0;
        const Vec3 a = face_area_vector(l.surface, f);
        EXPECT_GT(a.dot(face_centroid(l.surface, l.surface.points, f) - mid), 0.0) << "face " << f;
        EXPECT_EQ(l.surface.face_patch[f], 0);
    }
    EXPECT_EQ(count_crossings(top, l), 0);
}

TEST(Pyramids, WarpedQuadUsesMeanNormal) {
    SurfaceMesh top;
    top.patches.push_back({"wall", PatchKind::Wall});
    top.points = {{0, 0, 0.1}, {1, 0, -0.1}, {1, 1, 0.1}, {0, 1, -0.1}};
    top.add_face({0, 1, 2, 3}, 0);
    const PyramidLayer l = build_pyramids(top, {0.5, 0.1});
    const Vec3 n = face_area_vector(top, 0).normalized();
    const double size = std::sqrt(1.0 + 0.2 * 0.2);  // every edge
    EXPECT_NEAR((l.apexes[0] - (Vec3(0.5, 0.5, 0.0) + 0.5 * size * n)).norm(), 0.0, 1e-14);
    EXPECT_GT(pyramid_min_scaled_jacobian(l.surface.points, l.pyramids[0]), 0.0);
}

TEST(Pyramids, ClosedCubeGivesClosedShellWithVolumeClosure) {
    const int n = 4;
    const SurfaceMesh top = box_surface(BoxMesh(n, n, n, 1.0 / n));
    ASSERT_EQ(top.num_quads(), 6 * n * n);
    const PyramidLayer l = build_pyramids(top, {});
    ASSERT_EQ(l.pyramids.size(), static_cast<std::size_t>(6 * n * n));
    EXPECT_EQ(l.surface.num_faces(), 4 * 6 * n * n);
    expect_closed_oriented(l.surface);
    double sum = 0.0;
    for (std::size_t k = 0; k < l.pyramids.size(); ++k) {
        const double v = pyramid_volume(l, k);
        EXPECT_GT(v, 0.0);
        sum += v;
        // A convex body: nothing to shorten.
        const auto [h, size] = height_and_size(top, l, k, static_cast<Index>(k));
        EXPECT_NEAR(h, 0.5 * size, 1e-12);
    }
    EXPECT_NEAR(enclosed_volume(top), 1.0, 1e-12);
    EXPECT_NEAR(enclosed_volume(l.surface), 1.0 + sum, 1e-12);
    const ValidationReport r = validate_mesh(shell(top, l));
    EXPECT_TRUE(r.ok()) << (r.problems.empty() ? "" : r.problems.front());
    EXPECT_EQ(r.cells, 6 * n * n);
    EXPECT_GT(r.min_scaled_jacobian, 0.4);
    EXPECT_EQ(count_crossings(top, l), 0);
}

TEST(Pyramids, MixedTopTrianglesPassThrough) {
    // A box whose sides are partly triangulated (Kuhn cubes), plus a second patch.
    BoxMesh box(3, 2, 2, 0.5);
    box.set(0, 0, 0, test::CubeSplit::Kuhn);
    box.set(2, 1, 1, test::CubeSplit::Prisms);
    const SurfaceMesh top = box_surface(box);
    const Index nq = top.num_quads(), nt = top.num_triangles();
    ASSERT_GT(nq, 0);
    ASSERT_GT(nt, 0);
    const PyramidLayer l = build_pyramids(top, {});
    EXPECT_EQ(static_cast<Index>(l.pyramids.size()), nq);
    EXPECT_EQ(l.surface.num_faces(), 4 * nq + nt);
    EXPECT_EQ(l.surface.patches.size(), top.patches.size());
    expect_closed_oriented(l.surface);
    // Every triangle of the top, unchanged, on its patch; every side on its quad's patch.
    std::map<std::array<Index, 3>, Index> faces;
    for (Index f = 0; f < l.surface.num_faces(); ++f)
        faces[{l.surface.face_node(f, 0), l.surface.face_node(f, 1), l.surface.face_node(f, 2)}] =
            l.surface.face_patch[f];
    std::size_t k = 0;
    for (Index f = 0; f < top.num_faces(); ++f) {
        const Index* v = top.face_begin(f);
        if (top.face_size(f) == 3) {
            const auto it = faces.find({v[0], v[1], v[2]});
            ASSERT_NE(it, faces.end()) << "triangle " << f << " lost";
            EXPECT_EQ(it->second, top.face_patch[f]);
            continue;
        }
        const auto& p = l.pyramids[k];
        for (int i = 0; i < 4; ++i) EXPECT_EQ(p[i], v[i]);
        for (int i = 0; i < 4; ++i) {
            const auto it = faces.find({p[i], p[(i + 1) % 4], p[4]});
            ASSERT_NE(it, faces.end());
            EXPECT_EQ(it->second, top.face_patch[f]);
        }
        ++k;
    }
    double sum = 0.0;
    for (std::size_t j = 0; j < l.pyramids.size(); ++j) sum += pyramid_volume(l, j);
    EXPECT_NEAR(enclosed_volume(l.surface), enclosed_volume(top) + sum, 1e-12);
    EXPECT_EQ(count_crossings(top, l), 0);
}

/// An L-shaped solid (4 × 2 × 4 quarter cubes without the x, z ≥ 0.5 block): its re-entrant
/// edge along y at x = z = 0.5 is a 90° concave edge of the outer surface.
SurfaceMesh l_shape() {
    BoxMesh box(4, 2, 4, 0.25);
    for (int i = 2; i < 4; ++i)
        for (int j = 0; j < 2; ++j)
            for (int k = 2; k < 4; ++k) box.remove(i, j, k);
    return box_surface(box);
}

TEST(Pyramids, ConcaveEdgeShortensPyramidsNearTheCorner) {
    const SurfaceMesh top = l_shape();
    const PyramidLayer l = build_pyramids(top, {});
    expect_closed_oriented(l.surface);

    int shortened = 0;
    double sum = 0.0;
    for (std::size_t k = 0; k < l.pyramids.size(); ++k) {
        const Index f = static_cast<Index>(k);  // all faces are quads
        const auto [h, size] = height_and_size(top, l, k, f);
        const Vec3 c = face_centroid(top, top.points, f);
        const bool at_edge = std::abs(c.x() - 0.5) < 0.2 && std::abs(c.z() - 0.5) < 0.2 &&
                             (std::abs(c.x() - 0.5) < 1e-9 || std::abs(c.z() - 0.5) < 1e-9);
        if (at_edge) {
            EXPECT_LT(h, 0.5 * size * 0.99) << "quad " << f << " at " << c.transpose();
            ++shortened;
        }
        EXPECT_GE(h, 0.1 * size * (1 - 1e-12));
        sum += pyramid_volume(l, k);
        EXPECT_GT(pyramid_min_scaled_jacobian(l.surface.points, l.pyramids[k]), 0.0);
    }
    EXPECT_EQ(shortened, 4);  // two quads along the edge on each side of it
    // Overlapping pyramids would count twice in Σ volume but once in the enclosed volume.
    EXPECT_NEAR(enclosed_volume(top), 0.375, 1e-12);
    EXPECT_NEAR(enclosed_volume(l.surface), enclosed_volume(top) + sum, 1e-12);
    const ValidationReport r = validate_mesh(shell(top, l));
    EXPECT_TRUE(r.ok()) << (r.problems.empty() ? "" : r.problems.front());
    EXPECT_EQ(count_crossings(top, l), 0);
}

TEST(Pyramids, ConcaveEdgeWithTallPyramidsStaysDisjoint) {
    // Taller pyramids than the default reach across the corner unless shortened.
    const SurfaceMesh top = l_shape();
    const PyramidLayer l = build_pyramids(top, {1.5, 0.05});
    double sum = 0.0;
    for (std::size_t k = 0; k < l.pyramids.size(); ++k) sum += pyramid_volume(l, k);
    EXPECT_NEAR(enclosed_volume(l.surface), enclosed_volume(top) + sum, 1e-12);
    EXPECT_TRUE(validate_mesh(shell(top, l)).ok());
    EXPECT_EQ(count_crossings(top, l), 0);
}

/// The inside of a box of cubes: normals into the cavity, every edge and corner concave.
SurfaceMesh cavity(const BoxMesh& box, double zscale = 1.0) {
    SurfaceMesh s = box_surface(box);
    for (Vec3& p : s.points) p.z() *= zscale;
    for (Index f = 0; f < s.num_faces(); ++f)
        std::reverse(s.face_nodes.begin() + s.face_offsets[f], s.face_nodes.begin() + s.face_offsets[f + 1]);
    return s;
}

TEST(Pyramids, CavityCornersAndFacingWalls) {
    // A cube cavity (three concave edges at every corner) and a flat slab cavity whose floor
    // and ceiling face each other 0.6 quad sizes apart.
    for (const auto& [top, what] :
         {std::pair{cavity(BoxMesh(3, 3, 3)), "cube"}, std::pair{cavity(BoxMesh(4, 3, 1), 0.6), "slab"}}) {
        const PyramidLayer l = build_pyramids(top, {});
        expect_closed_oriented(l.surface);
        double sum = 0.0;
        for (std::size_t k = 0; k < l.pyramids.size(); ++k) {
            sum += pyramid_volume(l, k);
            EXPECT_GT(pyramid_min_scaled_jacobian(l.surface.points, l.pyramids[k]), 0.0);
        }
        EXPECT_LT(enclosed_volume(top), 0.0);  // normals point in
        EXPECT_NEAR(enclosed_volume(l.surface), enclosed_volume(top) + sum, 1e-12) << what;
        const ValidationReport r = validate_mesh(shell(top, l));
        EXPECT_TRUE(r.ok()) << what << ": " << (r.problems.empty() ? "" : r.problems.front());
        EXPECT_EQ(count_crossings(top, l), 0) << what;
    }
}

TEST(Pyramids, NarrowGapShortensBothSides) {
    for (const double shift : {0.0, 0.5, 0.3}) {
        const SurfaceMesh top = facing_plates(4, 0.6, shift);
        const PyramidLayer l = build_pyramids(top, {});
        ASSERT_EQ(l.pyramids.size(), 32u);
        double lowest_upper = 1e9, highest_lower = -1e9;
        for (std::size_t k = 0; k < 32; ++k) {
            const auto [h, size] = height_and_size(top, l, k, static_cast<Index>(k));
            EXPECT_LT(h, 0.3 * size) << "shift " << shift << " quad " << k;
            EXPECT_GE(h, 0.1 * size * (1 - 1e-12));
            if (k < 16)
                highest_lower = std::max(highest_lower, l.apexes[k].z());
            else
                lowest_upper = std::min(lowest_upper, l.apexes[k].z());
        }
        EXPECT_LT(highest_lower, lowest_upper);
        EXPECT_EQ(count_crossings(top, l), 0) << "shift " << shift;
    }
}

TEST(Pyramids, AQuadLeaningTowardsTheSymmetryPlaneRaisesItsApexAlongIt) {
    // A half box open on the plane y = 0 (a half model's layer top, its open boundary on the
    // symmetry plane), sheared so that its end y = 1 is 0.5 further in x: the side x = 1 + y/2
    // stands on the plane at 63° and leans towards it (its normal (2, -1, 0) / √5 points 27°
    // down to the plane). Along that normal its apex would come down towards the plane; it
    // rises parallel to it instead, and its side over the plane edge stands off the plane.
    SurfaceMesh top;
    top.patches = {{"top", PatchKind::Other}};
    for (const double y : {0.0, 1.0})
        for (const double z : {0.0, 1.0})
            for (const double x : {0.0, 1.0}) top.points.push_back(Vec3(x + 0.5 * y, y, z));
    auto at = [](int x, int y, int z) { return static_cast<Index>(4 * y + 2 * z + x); };
    top.add_face({at(1, 0, 0), at(1, 1, 0), at(1, 1, 1), at(1, 0, 1)}, 0);  // x = 1 + y/2
    top.add_face({at(0, 0, 0), at(0, 0, 1), at(0, 1, 1), at(0, 1, 0)}, 0);  // x = y/2
    top.add_face({at(0, 0, 0), at(0, 1, 0), at(1, 1, 0), at(1, 0, 0)}, 0);  // z = 0
    top.add_face({at(0, 0, 1), at(1, 0, 1), at(1, 1, 1), at(0, 1, 1)}, 0);  // z = 1
    top.add_face({at(0, 1, 0), at(0, 1, 1), at(1, 1, 1), at(1, 1, 0)}, 0);  // y = 1
    ASSERT_EQ(boundary_loops(top).rows(), 1);
    for (Index f = 0; f < top.num_faces(); ++f)  // out of the half box
        ASSERT_GT(face_area_vector(top, f).dot(face_centroid(top, top.points, f) - Vec3(0.75, 0.5, 0.5)), 0.0);
    const PyramidLayer l = build_pyramids(top, {});
    ASSERT_EQ(l.pyramids.size(), 5u);
    const Vec3& leaning = l.apexes[0];
    EXPECT_NEAR(leaning.y(), 0.5, 1e-12);  // the centroid's
    EXPECT_GT(leaning.x(), 1.25);
    // Its side over the edge on the plane stands off the plane by a tenth of the half-wedge
    // between the quad and its mirror image at least.
    const Vec3 q0 = top.points[at(1, 0, 0)];
    const Vec3 w = leaning - q0 - (leaning - q0).dot(Vec3::UnitZ()) * Vec3::UnitZ();
    const double off_plane = std::atan2(w.y(), w.x()) * 180.0 / std::numbers::pi;
    EXPECT_GT(off_plane, 0.1 * 63.4);
    // The side x = y/2 leans away from the plane: along its normal, as ever.
    const Vec3 n = Vec3(-2.0, 1.0, 0.0).normalized();
    const Vec3 c(0.25, 0.5, 0.5);
    EXPECT_LT((l.apexes[1] - c).cross(n).norm(), 1e-12);
}

TEST(Pyramids, GapTooNarrowForTwoButNotForOneShortensBoth) {
    // At 0.9 quad sizes, each apex alone clears the opposite plate (by 0.4 ≥ 0.5 × 0.5) but the
    // two pyramids would overlap: only the pair rules shorten them, both, to the next candidate.
    const SurfaceMesh top = facing_plates(3, 0.9);
    const PyramidLayer l = build_pyramids(top, {});
    for (std::size_t k = 0; k < l.pyramids.size(); ++k)
        EXPECT_NEAR(height_and_size(top, l, k, static_cast<Index>(k)).first, 0.25, 1e-12) << "quad " << k;
    EXPECT_EQ(count_crossings(top, l), 0);
}

/// The apex of the pyramid on the unit quad (0,0,0)-(1,1,0) next to one wall triangle
/// (\p tri, numbering the quad's corners 0-3 and \p extra 4 on), default parameters.
Vec3 apex_over_unit_quad(const std::vector<Vec3>& extra, std::initializer_list<Index> tri) {
    SurfaceMesh top;
    top.patches.push_back({"wall", PatchKind::Wall});
    top.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    top.points.insert(top.points.end(), extra.begin(), extra.end());
    top.add_face({0, 1, 2, 3}, 0);
    top.add_face(tri, 0);
    return build_pyramids(top, {}).apexes[0];
}

TEST(Pyramids, FoldAcrossConcaveEdgeShortens) {
    // A quad and a wall triangle across its edge at 90°: at 0.5 the side triangle would lie in
    // the bisector plane (apex 45° up, limit 0.9 × 45°); at 0.25 it is clear. The apex is still
    // 0.5 from the wall, so the clearance rules alone would accept 0.5.
    EXPECT_NEAR((apex_over_unit_quad({{0.5, 0, 1}}, {1, 0, 4}) - Vec3(0.5, 0.5, 0.25)).norm(), 0.0, 1e-15);
}

TEST(Pyramids, ApexKeepsClearOfAFaceAbove) {
    // A triangle 0.6 above the quad, facing down: at 0.5 the apex would be 0.1 from it (less
    // than half the height, though nothing crosses); at 0.25 it is 0.35 away.
    EXPECT_NEAR(
        (apex_over_unit_quad({{-2, -2, 0.6}, {0.5, 3, 0.6}, {3, -2, 0.6}}, {4, 5, 6}) - Vec3(0.5, 0.5, 0.25)).norm(),
        0.0, 1e-15);
}

TEST(Pyramids, SideCrossingAFaceShortens) {
    // A large vertical triangle at x = 0.9 reaching down to z = 0.05 over the quad cuts the
    // pyramid's side while staying 0.4 from its apex: shortened until the side passes under it
    // (height 0.25 touches it at z = 0.05, 0.125 clears it).
    EXPECT_NEAR(
        (apex_over_unit_quad({{0.9, -1, 0.05}, {0.9, 2, 0.05}, {0.9, 0.5, 3}}, {4, 5, 6}) - Vec3(0.5, 0.5, 0.125))
            .norm(),
        0.0, 1e-15);
}

TEST(Pyramids, ImpossibleGapThrowsNamingTheQuad) {
    const SurfaceMesh top = facing_plates(3, 0.01);
    test::expect_error<TopologyError>(
        [&] {
            build_pyramids(top, {0.5, 0.1});
        },
        {"quad ", "centroid (", "fewer layers"});
}

TEST(Pyramids, EveryQuadThatCannotBeCappedIsNamedAtOnce) {
    // Two dart-shaped quads (a reflex corner: no apex above inverts none of the pyramid's
    // corners) far apart, and a good one: the error carries both darts' nodes, four each, so
    // build_hybrid_mesh mends both in one round instead of marching the layers once per quad.
    SurfaceMesh top;
    top.patches.push_back({"top", PatchKind::Wall});
    for (const double x : {0.0, 10.0}) {
        const auto b = static_cast<Index>(top.points.size());
        top.points.insert(top.points.end(), {{x, 0, 0}, {x + 1, 0, 0}, {x + 1, 1, 0}, {x + 0.7, 0.3, 0}});
        top.add_face({b, b + 1, b + 2, b + 3}, 0);
    }
    top.points.insert(top.points.end(), {{5, 0, 0}, {6, 0, 0}, {6, 1, 0}, {5, 1, 0}});
    top.add_face({8, 9, 10, 11}, 0);
    try {
        build_pyramids(top, {0.5, 0.02});
        FAIL() << "expected LocalTopologyError";
    } catch (const LocalTopologyError& e) {
        EXPECT_EQ(e.nodes(), (std::vector<Index>{0, 1, 2, 3, 4, 5, 6, 7}));
        const std::string what = e.what();
        test::expect_contains(what, {"quad 0 ", "and 1 other quads of the layer top cannot be capped either"});
    }
}

TEST(Pyramids, BadParametersAreInputErrors) {
    const SurfaceMesh top = test::quad_grid(2, 2);
    EXPECT_THROW(build_pyramids(top, {0.0, 0.1}), InputError);
    EXPECT_THROW(build_pyramids(top, {0.5, 0.0}), InputError);
    EXPECT_THROW(build_pyramids(top, {0.5, 0.6}), InputError);
}

TEST(Pyramids, TrianglesOnlyTopIsCopied) {
    SurfaceMesh top;
    top.patches.push_back({"wall", PatchKind::Wall});
    top.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    top.add_face({0, 1, 2}, 0);
    const PyramidLayer l = build_pyramids(top, {});
    EXPECT_TRUE(l.pyramids.empty());
    EXPECT_EQ(l.surface.points, top.points);
    EXPECT_EQ(l.surface.face_nodes, top.face_nodes);
    EXPECT_EQ(l.surface.face_patch, top.face_patch);
}

TEST(Pyramids, HeightsDoNotDependOnTheFaceOrder) {
    // Conflicts between pyramids are settled in rounds on the heights at the start of the round,
    // so the quads' order in the input must not change any apex: the same quads listed backwards
    // (and each rotated by one corner) give bit-identical apexes.
    const SurfaceMesh top = facing_plates(6, 0.7, 0.25);
    SurfaceMesh permuted;
    permuted.points = top.points;
    permuted.patches = top.patches;
    for (Index f = top.num_faces() - 1; f >= 0; --f) {
        std::vector<Index> v(top.face_begin(f), top.face_end(f));
        std::rotate(v.begin(), v.begin() + 1, v.end());
        permuted.add_face(v.data(), static_cast<Index>(v.size()), top.face_patch[f]);
    }
    auto apex_of_quad = [](const PyramidLayer& l) {
        std::map<std::array<Index, 4>, Vec3, std::less<>> out;
        for (std::size_t k = 0; k < l.pyramids.size(); ++k) {
            std::array<Index, 4> key{l.pyramids[k][0], l.pyramids[k][1], l.pyramids[k][2], l.pyramids[k][3]};
            std::sort(key.begin(), key.end());
            out.emplace(key, l.apexes[k]);
        }
        return out;
    };
    const auto a = apex_of_quad(build_pyramids(top, {})), b = apex_of_quad(build_pyramids(permuted, {}));
    ASSERT_EQ(a.size(), b.size());
    ASSERT_GT(a.size(), 0u);
    int shortened = 0;  // the plates interact: some pyramids are below the full 0.5 x edge
    for (const auto& [quad, apex] : a) {
        ASSERT_TRUE(b.count(quad));
        EXPECT_EQ(apex, b.at(quad));
        Vec3 c = Vec3::Zero();
        for (Index v : quad) c += top.points[v] / 4.0;
        shortened += (apex - c).norm() < 0.5 - 1e-9;
    }
    EXPECT_GT(shortened, 0);
}

}  // namespace
}  // namespace strata
