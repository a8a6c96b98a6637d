#pragma once
/// \file
/// ξ, η derivatives on an unstructured surface in Knupp's local logical space
/// (ALGORITHM.md section 3), as fixed linear weights per node.

#include <strata/core/surface_mesh.h>
#include <strata/geometry/topology.h>

#include <array>

namespace strata {

/// A point of a stencil: a mesh node, or its mirror image across plane `mirror` (the
/// ghost nodes that complete the ring of a node on a symmetry or outflow plane).
struct StencilPoint {
    Index node = kNone;
    Index mirror = kNone;  ///< index into the planes the caller holds, or kNone
};

/// Derivative weights per node: for node o and derivative d ∈ {ξ, η, ξξ, ξη, ηη},
/// f_d(o) = centre[o][d] f_o + Σ_j weight[j][d] f(point[j]), j over o's row.
struct Stencils {
    enum { Xi = 0, Eta = 1, XiXi = 2, XiEta = 3, EtaEta = 4 };
    std::vector<Index> offsets{0};                 ///< #nodes + 1
    std::vector<StencilPoint> points;              ///< stencil points (neighbours, diagonals, ghosts)
    std::vector<std::array<double, 5>> weights;    ///< aligned with points
    std::vector<std::array<double, 5>> centre;     ///< #nodes
    std::vector<std::array<double, 2>> direction;  ///< aligned with points: (cos θ, sin θ) of edge
                                                   ///< neighbours, (0,0) for diagonals
    std::vector<char> valid;                       ///< #nodes: 0 where no stencil could be built
};

/// A plane that open-boundary nodes stay in, and across which their rings are mirrored.
struct MirrorPlane {
    Vec3 point = Vec3::Zero();
    Vec3 normal = Vec3::UnitZ();  ///< unit
    Vec3 reflect(const Vec3& p) const { return p - 2.0 * (p - point).dot(normal) * normal; }
    Vec3 project(const Vec3& p) const { return p - (p - point).dot(normal) * normal; }
};

/// Build the stencils of every node from its ordered ring:
/// M ≥ 5: Eq. 8. M = 4: Eq. 9 with the four diagonal nodes (Eq. 10); where a sector is a
/// triangle, its "diagonal" is the far vertex of the triangle across the ring's outer edge.
/// M = 3: the three edge neighbours interleaved with three diagonals, Eq. 8 with M = 6.
/// A diagonal more than four of its sector's edge lengths from where a parallelogram would put
/// it (the far apex of a needle triangle) is dropped: for M = 4 f_ξη then averages the one-
/// sided estimates of the other sectors (valid = 0 if none is left), M = 3 gets valid = 0.
/// An open ring whose node has a plane in \p node_plane (index into \p planes, kNone for none)
/// is completed with the mirror images of its interior neighbours; other open-ring nodes
/// get valid = 0 (the marcher keeps them on their extrusion line).
Stencils build_stencils(const SurfaceMesh& mesh, const NodeRings& rings, const std::vector<Index>& node_plane,
                        const std::vector<MirrorPlane>& planes);

}  // namespace strata
