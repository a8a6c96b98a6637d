#pragma once
/// \file
/// The cuts that make every long sharp edge of a triangulated surface a boundary between two
/// regions. Gmsh's classifySurfaces (the remeshing route, remesh.h) floods triangles across
/// smooth edges and makes curves only where two of its surfaces meet: a sharp edge with the
/// same region on both sides is dropped. A wing's sharp trailing edge is such an edge, for its
/// upper and lower sides join round the leading edge; the new mesh then runs across the thin
/// wedge and folds (the M6 STL remeshed at 10 mm: 43 faces folded at the trailing edge).
///
/// feature_cuts splits each such region into the part nearer one side of the edge and the part
/// nearer the other (a multi-source Dijkstra over the triangles, from the triangles on each
/// side): the edges where the two parts meet (round the leading edge) are returned, to be given
/// to Gmsh as lines it may not flood across, with the sharp edge itself.

#include <strata/core/surface_mesh.h>

#include <array>
#include <vector>

namespace strata {

/// Edges (smaller node first, sorted, each once) that, added to \p barriers, separate the two
/// triangles of every sharp edge lying in chains of total length ≥ \p min_length.
///
/// \p triangles must be consistently oriented (each interior edge once in each direction). An
/// edge is sharp where its two triangles' normals differ by more than \p feature_angle_deg;
/// regions are the triangles connected across edges that are neither sharp, nor in
/// \p barriers (patch seams, which already separate), nor shared by other than two triangles.
/// A sharp edge inside one region belongs to a chain (a path of such edges through nodes that
/// have two of them); shorter chains are left (a short crease the new mesh may smooth out).
/// Empty when no region holds a long sharp edge. Deterministic.
std::vector<std::array<Index, 2>> feature_cuts(const std::vector<Vec3>& points,
                                               const std::vector<std::array<Index, 3>>& triangles,
                                               const std::vector<std::array<Index, 2>>& barriers,
                                               double feature_angle_deg, double min_length);

}  // namespace strata
