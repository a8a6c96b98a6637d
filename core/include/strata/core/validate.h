#pragma once
/// \file
/// The validator every written volume mesh passes first: positive scaled Jacobian at every
/// corner of every cell, every interior face shared by exactly two cells with matching node
/// sets, boundary faces exactly the patch faces (and pointing out), and cell volumes summing
/// to the volume enclosed by the boundary (divergence theorem).

#include <strata/core/cell_quality.h>
#include <strata/core/progress.h>
#include <strata/core/solver_checks.h>
#include <strata/core/volume_mesh.h>

#include <array>
#include <string>
#include <vector>

namespace strata {

struct ValidationReport {
    Index cells = 0;
    double min_scaled_jacobian = 1.0;  ///< over all corners of all cells
    std::string worst_cell;            ///< the cell that has it: "prism 12 at (x, y, z)"; empty for no cells
    /// The same per cell type, indexed by CellType (tetrahedra, pyramids, prisms, hexahedra);
    /// worst_cell empty where the mesh has no cell of that type (min_scaled_jacobian 1 then).
    struct TypeQuality {
        double min_scaled_jacobian = 1.0;
        std::string worst_cell;
        /// Cells by their min scaled Jacobian in the fixed bins quality_bin (cell_quality.h);
        /// the counts sum to the cells of the type.
        std::array<Index, kQualityBins> histogram{};
    };
    std::array<TypeQuality, 4> by_type;
    double cell_volume = 0.0;      ///< Σ cell volumes
    double boundary_volume = 0.0;  ///< volume enclosed by the boundary faces
    Index interior_faces = 0;
    Index boundary_faces = 0;
    /// OpenFOAM checkMesh's figures (solver_checks.h): not problems of validity, but what a
    /// solver fed this mesh will say of it.
    SolverChecks solver;
    /// One line per problem found (at most a few per kind, then a count), each naming the
    /// cells or faces and where they are. Empty when the mesh is valid.
    std::vector<std::string> problems;
    bool ok() const { return problems.empty(); }
};

struct ValidateParams {
    double volume_tolerance = 1e-9;  ///< allowed |Σ cell volumes − boundary volume|, relative to the latter, plus
                                     ///< the boundary sum's rounding error (its terms cancel in a thin shell)
    int threads = 0;                 ///< 0: OpenMP's default (negative: InputError); same report for any count
    Progress* progress = nullptr;    ///< stage "validation", checked between the checks
};

/// Check \p mesh: its arrays (check_volume_arrays; with an id out of range nothing else is
/// checked), every corner's scaled Jacobian and every cell's volume, the faces (match_faces:
/// every problem it finds is one), the volume closure; and checkMesh's figures (solver). Works in fixed chunks merged
/// in order, so the report does not depend on the thread count.
ValidationReport validate_mesh(const VolumeMesh& mesh, const ValidateParams& params = {});

/// validate_mesh, and throw TopologyError "<what>: <n> problems: <first problems>" unless ok.
ValidationReport require_valid_mesh(const VolumeMesh& mesh, const std::string& what, const ValidateParams& params = {});

/// Signed volume of each cell type (Gmsh order), by the divergence theorem over its faces
/// (quads through their diagonal cross product), consistent with the boundary volume.
double cell_volume(const std::vector<Vec3>& p, const Index* cell, CellType type);

}  // namespace strata
