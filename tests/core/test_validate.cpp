#include "box_mesh.h"

#include <strata/core/cell_quality.h>
#include <strata/core/error.h>
#include <strata/core/validate.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace strata;
using strata::test::BoxMesh;
using strata::test::CubeSplit;

namespace {

/// Problems that contain \p text.
int count_problems(const ValidationReport& r, const std::string& text) {
    return static_cast<int>(std::count_if(r.problems.begin(), r.problems.end(),
                                          [&](const std::string& p) { return p.find(text) != std::string::npos; }));
}

std::string all_problems(const ValidationReport& r) {
    std::string s;
    for (const std::string& p : r.problems) s += "\n  " + p;
    return s;
}

/// One cell with its faces as boundary, each face given as a node set and oriented here
/// geometrically (away from the centroid), so the validator's face tables are checked
/// against geometry, not against a copy of themselves.
VolumeMesh single_cell(std::vector<Vec3> points, CellType type, const std::vector<std::vector<Index>>& faces) {
    VolumeMesh m;
    m.points = std::move(points);
    m.boundary.patches.push_back({"wall", PatchKind::Wall});
    Vec3 centre = Vec3::Zero();
    for (const Vec3& x : m.points) centre += x;
    centre /= static_cast<double>(m.points.size());
    for (const auto& f : faces) {
        Vec3 fc = Vec3::Zero();
        for (Index v : f) fc += m.points[v];
        fc /= static_cast<double>(f.size());
        const auto o = BoxMesh::oriented(m, f, fc - centre);
        m.boundary.add_face(o.data(), static_cast<Index>(o.size()), 0);
    }
    switch (type) {
        case CellType::Tet:
            m.tets.push_back({0, 1, 2, 3});
            break;
        case CellType::Pyramid:
            m.pyramids.push_back({0, 1, 2, 3, 4});
            break;
        case CellType::Prism:
            m.prisms.push_back({0, 1, 2, 3, 4, 5});
            break;
        case CellType::Hex:
            m.hexes.push_back({0, 1, 2, 3, 4, 5, 6, 7});
            break;
    }
    return m;
}

// Gmsh's reference elements.
VolumeMesh reference_tet() {
    return single_cell({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, CellType::Tet,
                       {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}});
}
VolumeMesh reference_pyramid() {
    return single_cell({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {0, 0, 1}}, CellType::Pyramid,
                       {{0, 1, 2, 3}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}});
}
VolumeMesh reference_prism() {
    return single_cell({{0, 0, -1}, {1, 0, -1}, {0, 1, -1}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, CellType::Prism,
                       {{0, 1, 2}, {3, 4, 5}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}});
}
VolumeMesh reference_hex() {
    return single_cell(
        {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}},
        CellType::Hex, {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}});
}

Index cell_faces(const VolumeMesh& m) {
    return static_cast<Index>(4 * m.tets.size() + 5 * m.pyramids.size() + 5 * m.prisms.size() + 6 * m.hexes.size());
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Reference elements: face tables point out of the cell, volumes are exact.

TEST(ReferenceCells, EveryFaceOfEveryTypeMatchesAnOutwardBoundaryFace) {
    for (const VolumeMesh& m : {reference_tet(), reference_pyramid(), reference_prism(), reference_hex()}) {
        const ValidationReport r = validate_mesh(m);
        EXPECT_TRUE(r.ok()) << all_problems(r);
        EXPECT_EQ(r.cells, 1);
        EXPECT_EQ(r.interior_faces, 0);
        EXPECT_EQ(r.boundary_faces, m.boundary.num_faces());
        EXPECT_GT(r.min_scaled_jacobian, 0.0);
    }
}

TEST(ReferenceCells, AnInwardBoundaryFaceIsReportedForEveryFaceOfEveryType) {
    for (const VolumeMesh& ref : {reference_tet(), reference_pyramid(), reference_prism(), reference_hex()}) {
        for (Index f = 0; f < ref.boundary.num_faces(); ++f) {
            VolumeMesh m = ref;
            std::reverse(m.boundary.face_nodes.begin() + m.boundary.face_offsets[f],
                         m.boundary.face_nodes.begin() + m.boundary.face_offsets[f + 1]);
            const ValidationReport r = validate_mesh(m);
            EXPECT_EQ(count_problems(r, "boundary face " + std::to_string(f) + " ("), 1) << all_problems(r);
            EXPECT_EQ(count_problems(r, "instead of out of the mesh"), 1) << all_problems(r);
        }
    }
}

TEST(CellVolume, ReferenceCellsHaveTheirExactVolume) {
    auto volume = [](const VolumeMesh& m, CellType t) {
        const Index* c = t == CellType::Tet       ? m.tets[0].data()
                         : t == CellType::Pyramid ? m.pyramids[0].data()
                         : t == CellType::Prism   ? m.prisms[0].data()
                                                  : m.hexes[0].data();
        return cell_volume(m.points, c, t);
    };
    EXPECT_NEAR(volume(reference_tet(), CellType::Tet), 1.0 / 6.0, 1e-15);
    EXPECT_NEAR(volume(reference_pyramid(), CellType::Pyramid), 4.0 / 3.0, 1e-15);
    EXPECT_NEAR(volume(reference_prism(), CellType::Prism), 1.0, 1e-15);
    EXPECT_NEAR(volume(reference_hex(), CellType::Hex), 8.0, 1e-15);
    // Inverted: negative.
    const VolumeMesh t = reference_tet();
    const std::array<Index, 4> flipped{0, 2, 1, 3};
    EXPECT_NEAR(cell_volume(t.points, flipped.data(), CellType::Tet), -1.0 / 6.0, 1e-15);
}

TEST(CellVolume, NonPlanarHexAgreesWithItsTetsWhenTheirDiagonalsMatch) {
    // A hex with a twisted top: its volume by the face formula (diagonal cross products) is
    // the volume the validator compares with the boundary; here it must equal its value on a
    // translated copy (no dependence on the origin).
    std::vector<Vec3> p{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1.3}, {1, 1, 0.8}, {0, 1, 1.1}};
    const std::array<Index, 8> h{0, 1, 2, 3, 4, 5, 6, 7};
    const double v = cell_volume(p, h.data(), CellType::Hex);
    EXPECT_GT(v, 0.9);
    EXPECT_LT(v, 1.2);
    for (Vec3& x : p) x += Vec3(1e6, -3e6, 2e6);
    EXPECT_NEAR(cell_volume(p, h.data(), CellType::Hex), v, 1e-8);
}

// ---------------------------------------------------------------------------------------
// The mixed 3 × 3 × 3 box.

TEST(ValidateMesh, MixedBoxIsValidWithExactVolume) {
    const VolumeMesh m = test::mixed_box().build();
    ASSERT_EQ(m.hexes.size(), 21u);
    ASSERT_EQ(m.prisms.size(), 4u);
    ASSERT_EQ(m.tets.size(), 10u);
    ASSERT_EQ(m.pyramids.size(), 16u);
    const ValidationReport r = validate_mesh(m);
    EXPECT_TRUE(r.ok()) << all_problems(r);
    EXPECT_EQ(r.cells, 51);
    EXPECT_NEAR(r.cell_volume, 27.0, 1e-12);
    EXPECT_NEAR(r.boundary_volume, 27.0, 1e-12);
    EXPECT_GT(r.min_scaled_jacobian, 0.0);
    EXPECT_LE(r.min_scaled_jacobian, 1.0);
    EXPECT_EQ(r.boundary_faces, m.boundary.num_faces());
    EXPECT_EQ(2 * r.interior_faces + r.boundary_faces, cell_faces(m));
    // 54 cube sides on the box, 4 of them (prism ends, Kuhn sides) two triangles.
    EXPECT_EQ(r.boundary_faces, 58);
    EXPECT_NO_THROW(require_valid_mesh(m, "mixed box"));
}

TEST(ValidateMesh, QualityPerCellTypeIsTheWorstOfEachType) {
    // The mixed box (unit hexahedra, Kuhn tetrahedra, pyramids, prisms): each type's minimum is the minimum of
    // its own cells, the overall one the smallest of them, each named by its worst cell.
    VolumeMesh m = test::mixed_box().build();
    const ValidationReport r = validate_mesh(m);
    for (const CellType t : kCellTypes) {
        double expected = 1.0;
        std::size_t worst = 0;
        for (std::size_t i = 0; i < m.num_cells(t); ++i) {
            const double j = min_scaled_jacobian(m.points, m.cell(t, i), t);
            if (j < expected) expected = j, worst = i;
        }
        const auto& q = r.by_type[static_cast<std::size_t>(t)];
        EXPECT_EQ(q.min_scaled_jacobian, expected) << to_string(t);
        EXPECT_EQ(q.worst_cell, describe_cell(m, t, static_cast<std::int64_t>(worst))) << to_string(t);
    }
    double overall = 1.0;
    for (const auto& q : r.by_type) overall = std::min(overall, q.min_scaled_jacobian);
    EXPECT_EQ(r.min_scaled_jacobian, overall);
    // Without hexahedra: that type reports 1 and no cell.
    m.hexes.clear();
    const ValidationReport no_hex = validate_mesh(m);
    EXPECT_EQ(no_hex.by_type[static_cast<std::size_t>(CellType::Hex)].min_scaled_jacobian, 1.0);
    EXPECT_TRUE(no_hex.by_type[static_cast<std::size_t>(CellType::Hex)].worst_cell.empty());
}

TEST(ValidateMesh, MixedBoxFarFromTheOriginAndSmallIsValid) {
    const VolumeMesh m = test::mixed_box(1e-3, Vec3(1e3, -2e3, 5e2)).build();
    const ValidationReport r = validate_mesh(m);
    EXPECT_TRUE(r.ok()) << all_problems(r);
    // The corners carry rounding of 1e3 + i·1e-3 (~1e-10 of a cell), the sums agree closer.
    EXPECT_NEAR(r.cell_volume, 27e-9, 27e-9 * 1e-8);
    EXPECT_NEAR(r.boundary_volume, r.cell_volume, 27e-9 * 1e-13);
}

TEST(ValidateMesh, PyramidCubeAmongHexesIsValid) {
    test::BoxMesh box(3, 3, 3);
    box.set(1, 1, 1, CubeSplit::Pyramids);
    const VolumeMesh m = box.build();
    const ValidationReport r = validate_mesh(m);
    EXPECT_TRUE(r.ok()) << all_problems(r);
    EXPECT_EQ(r.boundary_faces, 54);
    EXPECT_EQ(r.interior_faces, (cell_faces(m) - 54) / 2);
}

TEST(ValidateMesh, ReportIsTheSameForAnyThreadCount) {
    // 40³ hexahedra on 41³ nodes span two chunks of cells and five of nodes; problems in several
    // chunks (holes where cubes are missing, inverted cells) must come out in one order, with one
    // worst cell and the same sums, whatever the number of threads.
    VolumeMesh m = test::BoxMesh(40, 40, 40, 1.0 / 40).build();
    for (std::size_t c : {100u, 20000u, 40000u, 63000u})
        m.hexes.erase(m.hexes.begin() + static_cast<std::ptrdiff_t>(c));
    for (std::size_t c : {5u, 33000u, 62000u}) std::swap(m.hexes[c][0], m.hexes[c][1]);
    const ValidationReport one = validate_mesh(m, {.threads = 1});
    EXPECT_FALSE(one.ok());
    EXPECT_GE(one.problems.size(), 8u) << all_problems(one);
    for (int threads : {2, 3, 8}) {
        const ValidationReport r = validate_mesh(m, {.threads = threads});
        EXPECT_EQ(r.problems, one.problems) << threads << " threads";
        EXPECT_EQ(r.cell_volume, one.cell_volume) << threads << " threads";
        EXPECT_EQ(r.min_scaled_jacobian, one.min_scaled_jacobian) << threads << " threads";
        EXPECT_EQ(r.worst_cell, one.worst_cell) << threads << " threads";
        EXPECT_EQ(r.interior_faces, one.interior_faces) << threads << " threads";
    }
}

TEST(ValidateMesh, ANegativeThreadCountIsRefusedByName) {
    const VolumeMesh m = test::BoxMesh(2, 2, 2, 0.5).build();
    try {
        (void)validate_mesh(m, {.threads = -2});
        ADD_FAILURE() << "no exception";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), "ValidateParams::threads is -2: give 0 (all cores) or a positive count");
    }
}

TEST(ValidateMesh, RemovedInteriorCellLeavesAHoleAndAVolumeMismatch) {
    test::BoxMesh box(3, 3, 3);
    const VolumeMesh full = box.build();
    VolumeMesh m = full;
    // Cube (1, 1, 1) is hexahedron 13 (cubes in k, j, i order).
    ASSERT_EQ(m.hexes[13][0], 21);
    m.hexes.erase(m.hexes.begin() + 13);
    const ValidationReport r = validate_mesh(m);
    EXPECT_FALSE(r.ok());
    // Six faces around the missing cube: five listed, then the count.
    EXPECT_EQ(count_problems(r, "has no neighbouring cell and is no boundary face"), 5) << all_problems(r);
    EXPECT_EQ(count_problems(r, "... and 1 more unmatched cell faces"), 1) << all_problems(r);
    EXPECT_EQ(count_problems(r, "cells' volumes sum to 26 but the boundary encloses 27"), 1) << all_problems(r);
}

TEST(ValidateMesh, RemovedBoundaryCellLeavesStrayBoundaryFaces) {
    VolumeMesh m = test::BoxMesh(3, 3, 3).build();
    m.hexes.erase(m.hexes.begin());  // cube (0, 0, 0): three boundary faces lose their cell
    const ValidationReport r = validate_mesh(m);
    EXPECT_EQ(count_problems(r, "is no face of any cell"), 3) << all_problems(r);
    EXPECT_EQ(count_problems(r, "has no neighbouring cell"), 3) << all_problems(r);
    EXPECT_EQ(count_problems(r, "volumes sum to 26"), 1) << all_problems(r);
}

TEST(ValidateMesh, QuadAgainstTwoTrianglesIsNonConforming) {
    // Hexahedron next to a cube of six tetrahedra: the shared side is one quad on one side and
    // two triangles on the other. The boundary itself is right.
    test::BoxMesh box(2, 1, 1);
    box.set(1, 0, 0, CubeSplit::Kuhn);
    const VolumeMesh m = box.build();
    const ValidationReport r = validate_mesh(m);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(count_problems(r,
                             "quad face (1 4 10 7) of hexahedron 0 at (0.5, 0.5, 0.5) is not matched: its "
                             "neighbour has different faces (a quad never against two triangles)"),
              1)
        << all_problems(r);
    EXPECT_EQ(count_problems(r, "tetrahedron"), 1) << all_problems(r);
    // The quad and its triangles are explained once, not reported again as holes.
    EXPECT_EQ(count_problems(r, "has no neighbouring cell"), 0) << all_problems(r);
    EXPECT_EQ(count_problems(r, "boundary"), 0) << all_problems(r);  // the volume still matches
}

TEST(ValidateMesh, InvertedCellIsNamed) {
    VolumeMesh m = test::mixed_box().build();
    auto& h = m.hexes[7];
    std::swap(h[0], h[1]);
    const ValidationReport r = validate_mesh(m);
    ASSERT_FALSE(r.ok());
    EXPECT_LT(r.min_scaled_jacobian, 0.0);
    const auto it = std::find_if(r.problems.begin(), r.problems.end(), [](const std::string& p) {
        return p.find("min scaled Jacobian") != std::string::npos;
    });
    ASSERT_NE(it, r.problems.end()) << all_problems(r);
    EXPECT_EQ(it->rfind("hexahedron 7 at (", 0), 0u) << *it;
    EXPECT_EQ(count_problems(r, "min scaled Jacobian"), 1) << all_problems(r);
}

TEST(ValidateMesh, MirroredCellsAreAllReportedFiveThenACount) {
    VolumeMesh m = test::BoxMesh(3, 3, 3).build();
    for (auto& h : m.hexes) h = {h[4], h[5], h[6], h[7], h[0], h[1], h[2], h[3]};
    const ValidationReport r = validate_mesh(m);
    EXPECT_DOUBLE_EQ(r.min_scaled_jacobian, -1.0);
    EXPECT_EQ(count_problems(r, "min scaled Jacobian -1"), 5) << all_problems(r);
    EXPECT_EQ(count_problems(r, "... and 22 more inverted or degenerate cells"), 1) << all_problems(r);
    // Interior faces still pair up (both cells flipped); every boundary face is inward.
    EXPECT_EQ(count_problems(r, "same orientation"), 0) << all_problems(r);
    EXPECT_EQ(count_problems(r, "instead of out of the mesh"), 5) << all_problems(r);
    EXPECT_EQ(count_problems(r, "... and 49 more misoriented boundary faces"), 1) << all_problems(r);
    try {
        require_valid_mesh(m, "mirrored box");
        FAIL() << "no throw";
    } catch (const TopologyError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind("mirrored box: invalid mesh: ", 0), 0u) << what;
        // 27 cells, 54 boundary faces, the volume.
        EXPECT_NE(what.find(" 82 problems: hexahedron 0 at (0.5, 0.5, 0.5) has min scaled Jacobian -1"),
                  std::string::npos)
            << what;
        EXPECT_EQ(std::count(what.begin(), what.end(), ';'), 2) << what;
    }
}

TEST(ValidateMesh, WrongBoundaryOrientationIsReported) {
    VolumeMesh m = test::mixed_box().build();
    const Index f = 17;
    SurfaceMesh& b = m.boundary;
    std::reverse(b.face_nodes.begin() + b.face_offsets[f], b.face_nodes.begin() + b.face_offsets[f + 1]);
    const ValidationReport r = validate_mesh(m);
    EXPECT_EQ(count_problems(r, "boundary face 17 ("), 1) << all_problems(r);
    EXPECT_EQ(count_problems(r, "instead of out of the mesh; reverse its node order"), 1) << all_problems(r);
    EXPECT_EQ(count_problems(r, "the boundary encloses"), 1) << all_problems(r);
}

TEST(ValidateMesh, DuplicatedCellIsReported) {
    VolumeMesh m = test::mixed_box().build();
    // Cube (1, 1, 1): a hexahedron with six hexahedron or pyramid neighbours.
    const auto it = std::find_if(m.hexes.begin(), m.hexes.end(),
                                 [&](const auto& h) { return (m.points[h[0]] - Vec3(1, 1, 1)).norm() == 0.0; });
    ASSERT_NE(it, m.hexes.end());
    m.hexes.push_back(*it);
    const ValidationReport r = validate_mesh(m);
    EXPECT_EQ(count_problems(r, "is shared by 3 cells:"), 5) << all_problems(r);
    EXPECT_EQ(count_problems(r, "... and 1 more faces shared by three or more cells"), 1) << all_problems(r);
    EXPECT_EQ(count_problems(r, "volumes sum to 28"), 1) << all_problems(r);
}

TEST(ValidateMesh, DuplicatedBoundaryCellIsReported) {
    VolumeMesh m = test::BoxMesh(1, 1, 1).build();
    m.hexes.push_back(m.hexes[0]);
    const ValidationReport r = validate_mesh(m);
    EXPECT_EQ(count_problems(r, "is an interior face between hexahedron 0"), 5) << all_problems(r);
    EXPECT_EQ(count_problems(r, "... and 1 more boundary faces on interior faces"), 1) << all_problems(r);
}

TEST(ValidateMesh, OverlappingCellsAreReported) {
    // Two hexahedra on the same side of their shared face: the second is the first moved up
    // by one, but numbered as if it were below (mirrored) - same orientation at the face.
    VolumeMesh m = test::BoxMesh(1, 1, 2).build();
    auto& top = m.hexes[1];
    top = {top[4], top[5], top[6], top[7], top[0], top[1], top[2], top[3]};
    const ValidationReport r = validate_mesh(m);
    EXPECT_EQ(count_problems(r,
                             "hexahedron 0 at (0.5, 0.5, 0.5) and hexahedron 1 at (0.5, 0.5, 1.5) overlap or are "
                             "misoriented"),
              1)
        << all_problems(r);
}

TEST(ValidateMesh, VolumeToleranceIsRelative) {
    // A box whose cells are fine but whose boundary lacks a face: the volume differs by the
    // missing face's share, and a loose enough tolerance accepts the volume (not the hole).
    VolumeMesh m = test::BoxMesh(2, 2, 2).build();
    SurfaceMesh b;
    b.patches = m.boundary.patches;
    for (Index f = 1; f < m.boundary.num_faces(); ++f)
        b.add_face(m.boundary.face_begin(f), m.boundary.face_size(f), m.boundary.face_patch[f]);
    m.boundary = b;
    const ValidationReport tight = validate_mesh(m, {.volume_tolerance = 1e-9});
    EXPECT_EQ(count_problems(tight, "volumes sum to 8 but the boundary encloses"), 1) << all_problems(tight);
    EXPECT_EQ(count_problems(tight, "has no neighbouring cell"), 1) << all_problems(tight);
    const ValidationReport loose = validate_mesh(m, {.volume_tolerance = 0.5});
    EXPECT_EQ(count_problems(loose, "volumes sum to"), 0) << all_problems(loose);
    EXPECT_EQ(count_problems(loose, "has no neighbouring cell"), 1) << all_problems(loose);
}

TEST(ValidateMesh, BadIndicesAreReportedNotDereferenced) {
    VolumeMesh m = test::BoxMesh(1, 1, 1).build();
    m.hexes[0][3] = 1000;
    m.boundary.face_nodes[2] = -5;
    const ValidationReport r = validate_mesh(m);
    EXPECT_EQ(count_problems(r, "hexahedron 0 (0 1 3 1000 4 5 7 6) uses node 1000 but the mesh has 8 nodes"), 1)
        << all_problems(r);
    EXPECT_EQ(count_problems(r, "uses node -5"), 1) << all_problems(r);
    EXPECT_THROW(require_valid_mesh(m, "bad"), TopologyError);
}

TEST(ValidateMesh, EmptyMeshIsReported) {
    const ValidationReport r = validate_mesh(VolumeMesh{});
    EXPECT_EQ(count_problems(r, "no cells"), 1) << all_problems(r);
}

TEST(ValidateMesh, StructuredMeshSpanningManyChunksIsValid) {
    // 40³ hexahedra on 41³ nodes: the matcher works in chunks of 16384 nodes.
    const VolumeMesh m = test::BoxMesh(40, 40, 40, 1.0 / 40).build();
    const ValidationReport r = validate_mesh(m);
    EXPECT_TRUE(r.ok()) << all_problems(r);
    EXPECT_EQ(r.boundary_faces, 6 * 40 * 40);
    EXPECT_EQ(r.interior_faces, 3 * 39 * 40 * 40);
    EXPECT_NEAR(r.cell_volume, 1.0, 1e-12);
}

namespace strata {
namespace {

TEST(QualityBins, EdgesAreFourADecadeFromAMillionthToOne) {
    EXPECT_EQ(kQualityBins, 25);
    EXPECT_DOUBLE_EQ(quality_bin_edge(0), 1e-6);
    EXPECT_DOUBLE_EQ(quality_bin_edge(kQualityBins - 1), 1.0);
    EXPECT_NEAR(quality_bin_edge(4), 1e-5, 1e-20);
    EXPECT_EQ(quality_bin(0.0), 0);
    EXPECT_EQ(quality_bin(-0.5), 0);
    EXPECT_EQ(quality_bin(std::nan("")), 0);
    EXPECT_EQ(quality_bin(9.9e-7), 0);
    EXPECT_EQ(quality_bin(1e-6), 1);  // an edge starts the bin above it
    EXPECT_EQ(quality_bin(quality_bin_edge(12)), 13);
    EXPECT_EQ(quality_bin(std::nextafter(quality_bin_edge(12), 0.0)), 12);
    EXPECT_EQ(quality_bin(0.5), 23);  // [10^-0.5, 1)
    EXPECT_EQ(quality_bin(1.0), kQualityBins - 1);
    EXPECT_EQ(quality_bin(1.0 + 1e-15), kQualityBins - 1);
    for (int b = 1; b < kQualityBins; ++b) {  // each bin holds its lower edge and the middle of the bin
        EXPECT_EQ(quality_bin(quality_bin_edge(b - 1)), b) << b;
        EXPECT_EQ(quality_bin(std::sqrt(quality_bin_edge(b - 1) * quality_bin_edge(b))), b) << b;
    }
}

TEST(ValidateMesh, HistogramPerTypeCountsEveryCellInItsBin) {
    // The mixed box: every cell's own value in its own type's bin; the counts sum to the cells.
    const VolumeMesh m = test::mixed_box().build();
    const ValidationReport r = validate_mesh(m);
    for (const CellType t : kCellTypes) {
        std::array<Index, kQualityBins> expected{};
        for (std::size_t i = 0; i < m.num_cells(t); ++i)
            ++expected[static_cast<std::size_t>(quality_bin(min_scaled_jacobian(m.points, m.cell(t, i), t)))];
        const auto& h = r.by_type[static_cast<std::size_t>(t)].histogram;
        EXPECT_EQ(h, expected) << to_string(t);
        Index sum = 0;
        for (const Index c : h) sum += c;
        EXPECT_EQ(sum, static_cast<Index>(m.num_cells(t))) << to_string(t);
    }
    // Unit hexahedra are right-angled: all in the last bin.
    EXPECT_EQ(r.by_type[static_cast<std::size_t>(CellType::Hex)].histogram[kQualityBins - 1], 21);
    // The same for one thread and many.
    const ValidationReport one = validate_mesh(m, {.threads = 1});
    for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(one.by_type[k].histogram, r.by_type[k].histogram);
}

}  // namespace
}  // namespace strata
