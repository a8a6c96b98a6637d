#pragma once
/// \file
/// Derived connectivity of a surface mesh: pure functions, nothing stored by hand.

#include <strata/core/surface_mesh.h>

#include <array>

namespace strata {

/// Merge nodes closer than \p rel_tol × bounding-box diagonal; drop nodes no face uses.
/// Faces that collapse (two equal corners) are kept so check_surface can report them.
/// Deterministic: the surviving node of a cluster is the lowest old id, order kept.
/// TopologyError if the used nodes span 1e100 or more (check_surface's bound: areas and volumes
/// would overflow), InputError for a node id out of range.
SurfaceMesh merge_coincident_nodes(const SurfaceMesh& mesh, double rel_tol = 1e-9);

/// Faces that repeat a node have no area and no shape: a triangle (a, a, b) or a quad whose
/// repeated nodes are opposite is removed, a quad (a, a, b, c) becomes the triangle (a, b, c).
/// Removing such a face leaves every other edge used as often as before less the two uses
/// (there and back) of its own edge, so a closed surface stays closed. CAD tools write them
/// at a surface's pole (OpenCASCADE's tessellation of a nose); merging close nodes makes
/// them too. Nodes no face uses any more are dropped, order kept. \p changed: how many faces
/// were removed or reduced. InputError for a node id out of range, or a face_patch without one
/// entry per face.
SurfaceMesh remove_collapsed_faces(const SurfaceMesh& mesh, Index* changed = nullptr);

/// \p mesh with every flat triangle (a cap: its apex within \p rel_height of its longest edge's
/// length from that edge, an angle near 180°) flipped with the triangle across that edge, where
/// that one is on the same patch and the flip makes no edge twice: the two become triangles
/// through the apex and the far node, oriented as the pair was. Mesh Booleans leave such faces
/// where two bodies' facets nearly coincide (an airliner's cylinder and tail cone, each
/// tessellated, meeting at one circle). Repeated while a flip happens, a bounded number of
/// times. \p flipped: how many flips.
SurfaceMesh flip_flat_triangles(const SurfaceMesh& mesh, double rel_height = 1e-6, Index* flipped = nullptr);

/// \p mesh with every edge longer than \p max_length bisected, by Rivara's longest-edge
/// bisection: an edge is split only where it is the longest edge of each triangle on it (ties
/// broken by node ids), and a triangle splits along its longest edge from the opposite corner,
/// so the mesh stays conforming and no corner gets sharper than half the sharpest it had. The
/// new nodes are the edges' midpoints: the surface is the same, its triangles shorter. Rounds
/// split every such edge whose triangles no split of the round touched yet, longest first, until
/// no edge is longer or the faces reach \p max_faces (then the mesh is as far as it got). A quad
/// is kept, and so are its edges. Each new triangle keeps its parent's patch and orientation; new
/// faces and nodes come after the old ones, in a deterministic order. \p splits: how many edges
/// were bisected. InputError for a max_length that is not positive.
SurfaceMesh split_long_edges(const SurfaceMesh& mesh, double max_length, Index max_faces, Index* splits = nullptr);

/// \p mesh without the faces where \p drop (one per face) is nonzero; nodes no face uses any
/// more are dropped, order kept.
SurfaceMesh remove_faces(const SurfaceMesh& mesh, const std::vector<char>& drop);

/// Node → incident faces, faces in increasing id order.
Csr vertex_faces(const SurfaceMesh& mesh);

/// Unique undirected edges and their incident faces.
struct EdgeTable {
    std::vector<std::array<Index, 2>> nodes;  ///< #edges, (low id, high id)
    Csr faces;                                ///< edge → incident faces (1 = boundary, 2 = manifold)
};
/// Edges sorted by (low, high) node id.
EdgeTable edge_table(const SurfaceMesh& mesh);
/// The edge of \p edges between nodes \p a and \p b (either order), kNone if there is none.
Index find_edge(const EdgeTable& edges, Index a, Index b);

/// \p mesh without the faces that repeat an earlier face: the same nodes in the same cyclic
/// order (any starting corner), as CAD exporters write a face twice. Such a pair makes every edge
/// of the face bound three or four faces; the first stays. Faces over the same nodes the other way
/// round are kept: two bodies back to back (touching.h). \p removed: how many went. Nodes are
/// kept as they are (each is still used).
SurfaceMesh remove_duplicate_faces(const SurfaceMesh& mesh, Index* removed = nullptr);
/// The same with \p mesh's edge_table, already made (prepare_mesh shares it with split_t_junctions).
SurfaceMesh remove_duplicate_faces(const SurfaceMesh& mesh, const EdgeTable& edges, Index* removed);

/// \p mesh with its T-junctions closed: where nodes lie inside an open edge (within 1e-6 of its
/// length of the segment, strictly between its ends), the edge's other side having been meshed
/// with them (an exporter that meshed two faces' common edge differently, or parts merged
/// side by side), and those nodes are on open edges themselves, the triangle on that edge is
/// split at them (a fan from its third corner), so that the edges on both sides match. A quad
/// there is left as it is. \p split: how many faces were split. Nodes are kept as they are.
SurfaceMesh split_t_junctions(const SurfaceMesh& mesh, Index* split = nullptr);
/// The same with \p mesh's edge_table, already made.
SurfaceMesh split_t_junctions(const SurfaceMesh& mesh, const EdgeTable& edges, Index* split);

/// What stitch_cracks did: faces split, and the widest gap closed and where (a node of it).
struct Stitching {
    Index split = 0;
    double widest = 0.0;
    Vec3 at = Vec3::Zero();
};

/// \p mesh with its cracks closed: where two sides of a curved edge were meshed each with nodes
/// of its own (an exporter that tessellated each face alone: one side's nodes lie off the other
/// side's chords by their sagitta), the T-junction split of split_t_junctions with nodes within
/// \p share of an open edge's length of it, kept only where every edge then bounds two faces;
/// else \p mesh unchanged and nothing in \p report.
SurfaceMesh stitch_cracks(const SurfaceMesh& mesh, double share, Stitching* report = nullptr);

/// What remove_hanging_sheets did: the sheets and faces removed, and a point of the first.
struct HangingSheets {
    Index sheets = 0;
    Index faces = 0;
    Vec3 at = Vec3::Zero();
};

/// \p mesh without the sheets that hang off it: faces joined across edges of two faces into
/// sheets, a sheet with both a free edge and an edge of three or more faces (a flap on an
/// edge, a zero-thickness fin) goes, kept only if no edge is then of three or more faces and no
/// edge of two faces became free; else \p mesh unchanged and nothing in \p report. Nodes no
/// face uses any more are dropped (remove_faces).
SurfaceMesh remove_hanging_sheets(const SurfaceMesh& mesh, HangingSheets* report = nullptr);

/// Closed loops of boundary edges (edges with one face) of an open surface, each loop a
/// node cycle in the direction of its face's orientation; empty for a closed surface.
/// Throws TopologyError at a node where boundary loops touch non-manifoldly.
Csr boundary_loops(const SurfaceMesh& mesh);

/// Connected components through shared edges: component id per face, ids from 0 in
/// order of their lowest face.
std::vector<Index> face_components(const SurfaceMesh& mesh, Index* num_components = nullptr);

/// Ordered ring of every node, as ALGORITHM.md section 3 needs it.
///
/// Row o of `neighbours` lists the M edge-neighbours of node o counter-clockwise seen from
/// the side its faces' normals point to. `faces[k]` and `diagonals[k]` (same layout) describe
/// the sector between neighbours[k] and neighbours[k+1] (cyclically): the face spanning it and,
/// if that face is a quad, its corner opposite o (kNone for a triangle). For a node on the
/// boundary of an open surface the ring is open: neighbours[0] and neighbours[M-1] are on the
/// boundary, and the last sector's face and diagonal are kNone.
struct NodeRings {
    Csr neighbours;
    std::vector<Index> faces;      ///< aligned with neighbours.values
    std::vector<Index> diagonals;  ///< aligned with neighbours.values
    std::vector<char> closed;      ///< #nodes; 1 if the ring goes all the way round
};
/// Requires a manifold, consistently oriented mesh (check_surface, orient_surface); throws
/// TopologyError naming the node otherwise.
NodeRings node_rings(const SurfaceMesh& mesh);

}  // namespace strata
