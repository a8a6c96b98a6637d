#pragma once
/// \file
/// Private to strata_hybrid: what fill_with_tets asks of TetGen (its switches) and the size
/// field h(x) = min(h_wall + growth · d(x), h_far) it hands over as TetGen -m sizes, sampled on
/// a background mesh. The reasoning and the calibration: tetgen_sizing.cpp.

#include "tetgen_library.h"

#include <strata/core/surface_mesh.h>
#include <strata/hybrid/tetgen_fill.h>

#include <memory>
#include <string>
#include <vector>

namespace strata::tetgen {

/// TetGen's -m size (a circumradius bound) per target edge length (calibration in the .cpp).
inline constexpr double kRadiusPerEdge = 0.75;
/// Radius-edge bound of the background mesh's quality-only refinement.
inline constexpr double kBackgroundRatio = 2.0;

/// TetGen's default tolerance (-T): among other things, it takes two points closer than this
/// times the diagonal of the input's bounding box for one (and drops one of them).
inline constexpr double kTetGenEpsilon = 1e-8;

/// Switches for one run, parsed by TetGen itself (so its consistency rules apply):
///  p Y z Q [q<ratio>[/<angle>]] [a<vol>] [m] [o/<max dihedral>] for the fill (\p sizing adds m), or
///  p Y z Q c q<kBackgroundRatio> for the background mesh (\p background); T<\p tolerance> after
///  either if \p tolerance > 0 (TetGen's default, kTetGenEpsilon, otherwise).
std::string switches(const TetFillParams& p, bool sizing, bool background, double tolerance = 0.0);

/// The tolerance (-T) TetGen needs to keep every point of \p points: 0 (its default will do)
/// unless two of them are closer than 10 × kTetGenEpsilon × the diagonal of their bounding
/// box, and then a hundredth of the closest such distance over that diagonal. Such points come
/// from a surface whose shortest edges are that short (a needle of a remeshed CAD surface:
/// 2.8e-7 m on a 32 m domain), and TetGen would otherwise merge them and renumber the rest.
double tolerance_keeping_points(const std::vector<Vec3>& points);

/// h(x) = min(h_wall(nearest wall node) + growth·|x − that node|, h_far), the wall being the
/// boundary faces whose patch is not Farfield. Nearest-node queries on a nanoflann k-d tree;
/// of equally near nodes the one of the smallest size counts, so h is a function of the
/// geometry alone.
class SizeField {
public:
    /// \p max_volume > 0 also caps h at the edge of the regular tet of that volume: TetGen's
    /// -m sizes are spacings too (a point closer to a vertex than its size is rejected), so
    /// without the cap -a could not be met where h is larger.
    SizeField(const SurfaceMesh& boundary, double growth, double max_volume);
    /// The same rule over given \p points and their \p sizes (no cap): a plane's loop points
    /// and their spacing, for mesh_plane_region.
    SizeField(std::vector<Vec3> points, std::vector<double> sizes, double growth);
    ~SizeField();
    SizeField(const SizeField&) = delete;
    SizeField& operator=(const SizeField&) = delete;

    /// Target edge length at boundary node \p i: its own mean edge length (capped by max_volume).
    double boundary_size(Index i) const;

    /// Target edge length at a point off the boundary.
    double operator()(const Vec3& x) const;

private:
    struct Tree;
    double growth_;
    double cap_ = 0.0;
    double volume_edge_;
    std::vector<double> node_size_;
    std::vector<Vec3> wall_points_;
    std::vector<double> wall_size_;
    std::unique_ptr<Tree> tree_;
};

/// TetGen -m sizes on \p io's points (kRadiusPerEdge × h): the first \p num_boundary (the
/// boundary's own nodes) their own size, the others h(x).
void set_sizes(tetgenio& io, Index num_boundary, const SizeField& h);

/// The boundary of the background mesh: \p b with its farfield 1 % larger about the
/// farfield's centroid, or, when there is no farfield or it shares a node with another patch,
/// \p b and after its nodes the 8 corners of a box round it (loose points, in no face), so the
/// convex hull lies outside every point of the final mesh. Why: tetgen_sizing.cpp.
SurfaceMesh background_boundary(const SurfaceMesh& b);

}  // namespace strata::tetgen
