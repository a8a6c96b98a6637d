#pragma once
/// \file
/// The figures OpenFOAM's checkMesh judges a mesh by, computed as it computes them, so that a
/// mesh's summary says before any solver sees it whether checkMesh would pass it and where it
/// would not: face non-orthogonality and skewness, cell aspect ratio, face pyramids. A valid
/// mesh (validate.h) can still fail them: thin prisms on both sides of a sharp edge with one
/// marching direction have a shared face whose skewness is about 2.5 cot(α/2) for a wedge of
/// angle α (above checkMesh's 4 for α under 64°), which a fan (layers.h) lifts.
///
/// Definitions (OpenFOAM's primitiveMesh and primitiveMeshTools): a face's centre and area
/// vector from the triangles joining each edge to the mean of its corners; a cell's centre the
/// volume-weighted centre of the pyramids from its faces to the mean of its face centres. With
/// d from the owner's centre to the neighbour's and S the face's area vector, non-orthogonality
/// is the angle between d and S; skewness the distance from the face centre to where d crosses
/// the face's plane, over the larger of 0.2 |d| and the face's extent in that direction (a
/// boundary face: its centre's offset from the cell centre's projection, over the larger of
/// 0.4 × the cell centre's distance from the plane and the extent). A cell's aspect ratio is the
/// larger of its largest over its smallest Cartesian component of Σ|S|, and Σ|S| / (6 V^⅔).

#include <strata/core/face_match.h>
#include <strata/core/volume_mesh.h>

#include <cstdint>
#include <string>
#include <vector>

namespace strata {

/// checkMesh's bounds (its defaults): what it calls severe, and what fails it.
inline constexpr double kFoamNonOrthogonalDeg = 70.0;  ///< "severely non-orthogonal" (a warning)
inline constexpr double kFoamSkewness = 4.0;           ///< "highly skew faces" (fails)
inline constexpr double kFoamAspectRatio = 1000.0;     ///< "high aspect ratio cells" (fails)

/// A cell above kFoamAspectRatio (SolverChecks::high_aspect).
struct HighAspectCell {
    Vec3 centre = Vec3::Zero();  ///< OpenFOAM's centre of the cell
    double aspect_ratio = 0.0;
    double longest_edge = 0.0;  ///< the longest of its edges
};

struct SolverChecks {
    double max_non_orthogonality_deg = 0.0;  ///< over interior faces
    double mean_non_orthogonality_deg = 0.0;
    std::string worst_non_orthogonal;    ///< "face of prism 3 and tetrahedron 9 at (x, y, z)"
    Index severely_non_orthogonal = 0;   ///< interior faces above kFoamNonOrthogonalDeg
    Index non_orthogonality_errors = 0;  ///< interior faces at 90° or more (fails checkMesh)
    double max_skewness = 0.0;           ///< over all faces
    std::string worst_skew;
    Index skew_faces = 0;  ///< faces above kFoamSkewness
    double max_aspect_ratio = 0.0;
    std::string worst_aspect;
    CellType worst_aspect_type = CellType::Tet;  ///< the type of that cell
    Index high_aspect_cells = 0;                 ///< cells above kFoamAspectRatio
    std::vector<HighAspectCell> high_aspect;     ///< those cells, in cell order (tets, pyramids, prisms, hexes)
    Index negative_pyramids = 0;                 ///< faces whose pyramid to a cell's centre is not positive (fails)
    std::string worst_pyramid;                   ///< the first such face
    Index unused_points = 0;                     ///< points no cell uses ("Unused points", fails)
    std::string first_unused;                    ///< where the first is
    /// What checkMesh's default run would fail on, one line each, naming the worst place;
    /// empty if it would say "Mesh OK".
    std::vector<std::string> failures() const;
    bool ok() const { return failures().empty(); }
};

/// checkMesh's figures for \p mesh, whose faces \p match matched (match_faces; faces that are
/// not a clean interior or boundary match are skipped: the validator reports them). Fixed
/// chunks merged in order (ties to the lower face): the same for any \p threads. \p skewed:
/// if given, receives the face slots (FaceSlots of \p match) of the faces above kFoamSkewness,
/// ascending.
SolverChecks solver_checks(const VolumeMesh& mesh, const FaceMatch& match, int threads = 0,
                           std::vector<std::uint64_t>* skewed = nullptr);

/// checkMesh's figures per cell, in CellNumbering order (tetrahedra, pyramids, prisms,
/// hexahedra): for colouring a mesh by them (the .vtu writer's cell fields).
struct CellSolverFigures {
    std::vector<double> non_orthogonality_deg;  ///< the largest over the cell's interior faces, degrees (0: none)
    std::vector<double> skewness;               ///< the largest over all its faces
    std::vector<double> aspect_ratio;           ///< the cell's aspect ratio
};

/// checkMesh's non-orthogonality, skewness and aspect ratio per cell of \p mesh, whose faces
/// \p match matched: each face's figures exactly as solver_checks computes them (an interior
/// face from its lower slot, so both its cells see the same value), the cell's the largest over
/// its faces; faces that are not a clean match are skipped. The same for any \p threads.
CellSolverFigures cell_solver_figures(const VolumeMesh& mesh, const FaceMatch& match, int threads = 0);

/// checkMesh's skewness of the face with the \p n corners \p v of \p p between the cells whose
/// centres (OpenFOAM's) are \p owner and \p neighbour, or, \p neighbour null, of a boundary
/// face of the cell at \p owner: how far the line between the centres (at the boundary, the
/// face's normal through the owner's centre) passes from the face's centre, over the face's
/// extent that way. A tetrahedron's centre is the mean of its corners.
double face_skewness(const Vec3* p, const Index* v, int n, const Vec3& owner, const Vec3* neighbour);

/// OpenFOAM's centre of the cell of \p type with the corners \p corners (Gmsh's order): the
/// volume-weighted centroid of the pyramids from its faces to the mean of their centres, as
/// solver_checks computes it (a tetrahedron's is the mean of its corners).
Vec3 foam_cell_centre(const Vec3* corners, CellType type);

/// checkMesh's aspect ratio of the right prism (hexahedron for a quad) of height \p h standing
/// on the wall face with corners \p corners (3 or 4, either orientation): what the first layer
/// over that face will show, before the layers exist (for sizing the surface). A face without
/// area gives infinity.
double right_prism_aspect_ratio(const Vec3* corners, int n, double h);

/// checkMesh's aspect ratio of the first-layer cell on the wall face with corners \p corners (3
/// or 4, either orientation) whose top corner i is corners[i] + h directions[i] (unit, all on
/// the face's one side): a column on a convex or concave edge leans along the bisector of its
/// faces, and its cell stands only h cos(lean) off the face. right_prism_aspect_ratio when every
/// direction is the face's normal. A zero direction keeps that corner on the wall: a column
/// stopped there, the cell the pyramid or tetrahedron closing the step. Non-finite for a face
/// without area or a cell without volume.
double leaning_prism_aspect_ratio(const Vec3* corners, const Vec3* directions, int n, double h);

/// Whether checkMesh would find a face of the cell of \p type with corners \p corners (Gmsh
/// order, as cell_faces lists its faces) whose pyramid to the cell's centre is inverted
/// ("incorrectly oriented"): its centre, OpenFOAM's, on the wrong side of a face, as in a cell
/// thinner than one of its faces is warped. The test solver_checks makes on a whole mesh.
bool face_pyramids_inverted(const Vec3* corners, CellType type);

/// checkMesh's aspect ratio of the first cell of a fan (ALGORITHM.md, "Fans") on the wall edge
/// \p a - \p b: the wedge between the directions \p d1 and \p d2 (unit, square to the edge),
/// \p h long. Its end triangles are about h² small against sides of the edge's length, so it is
/// about twice the edge length over h sin(angle): fans want shorter edges than faces do.
double fan_wedge_aspect_ratio(const Vec3& a, const Vec3& b, const Vec3& d1, const Vec3& d2, double h);

}  // namespace strata
