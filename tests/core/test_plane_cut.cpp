// The cells cut by an axis-aligned plane (core/plane_cut.h): the polygons tile the section.

#include <strata/core/error.h>
#include <strata/core/plane_cut.h>
#include "box_mesh.h"

#include <gtest/gtest.h>

#include "test_support.h"

#include <cmath>

namespace strata {
namespace {

/// Σ of the polygons' areas (shoelace), each polygon's sign checked to be one orientation.
double total_area(const PlaneCut& cut) {
    double total = 0.0;
    for (Index p = 0; p < cut.num_polygons(); ++p) {
        double a = 0.0;
        const Index b = cut.offsets[static_cast<std::size_t>(p)], e = cut.offsets[static_cast<std::size_t>(p) + 1];
        EXPECT_GE(e - b, 3);
        for (Index k = b; k < e; ++k) {
            const auto& x = cut.points[static_cast<std::size_t>(k)];
            const auto& y = cut.points[static_cast<std::size_t>(k + 1 == e ? b : k + 1)];
            a += x[0] * y[1] - y[0] * x[1];
        }
        EXPECT_GT(a, 0.0) << "polygon " << p << " is not counter-clockwise";
        total += 0.5 * a;
    }
    return total;
}

TEST(PlaneCut, SectionsOfTheMixedBoxTileItsCrossSection) {
    // Every cell type, every junction: the polygons cover the 3 × 3 section exactly, for a
    // plane across each axis, between nodes and through a cube's diagonal nodes alike.
    const VolumeMesh m = test::mixed_box().build();
    for (int axis = 0; axis < 3; ++axis)
        for (const double value : {0.5, 1.25, 1.5, 2.7}) {
            const PlaneCut cut = cut_cells(m, axis, value, {-1, 4, -1, 4});
            EXPECT_NEAR(total_area(cut), 9.0, 1e-12) << "axis " << axis << " at " << value;
            EXPECT_EQ(cut.offsets.size(), cut.types.size() + 1);
        }
    const PlaneCut z = cut_cells(m, 2, 1.5, {-1, 4, -1, 4});
    EXPECT_EQ(z.u, 0);
    EXPECT_EQ(z.v, 1);
    bool types[4] = {};
    for (const CellType t : z.types) types[static_cast<int>(t)] = true;
    EXPECT_TRUE(types[0] && types[1] && types[3]) << "z = 1.5 crosses tets, pyramids and hexahedra";
}

TEST(PlaneCut, TheWindowKeepsCellsWhollyInside) {
    const VolumeMesh m = test::mixed_box().build();
    // Cells wholly in the window only: the column over x in [0, 1] (area 3), the cube over [0, 1]².
    EXPECT_NEAR(total_area(cut_cells(m, 1, 0.5, {0, 1, 0, 3})), 3.0, 1e-12);
    EXPECT_NEAR(total_area(cut_cells(m, 2, 2.5, {0, 1, 0, 1})), 1.0, 1e-12);
    EXPECT_EQ(cut_cells(m, 2, 2.5, {0.1, 0.9, 0.1, 0.9}).num_polygons(), 0);
    EXPECT_EQ(cut_cells(m, 2, 5.0, {-1, 4, -1, 4}).num_polygons(), 0);  // beyond the box
    test::expect_error<InputError>([&] { cut_cells(m, 3, 0.0, {0, 1, 0, 1}); }, {"axis 3"});
}

}  // namespace
}  // namespace strata
