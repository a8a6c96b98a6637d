#pragma once
// Private to the layer module: the columns of the layers and where they stop (LayerParams::
// min_quality, max_turn_deg, the proximity limit), the faces they stand on, and the cells,
// boundary and front of a ragged LayerMesh. ALGORITHM.md, "Local stopping", says why.

#include <strata/core/surface_mesh.h>
#include <strata/module/layer_report.h>
#include <strata/module/layers.h>

#include <array>
#include <cstdint>
#include <vector>

namespace strata {

/// The faces the columns stand on: the wall's faces, a quad split into two triangles (through
/// a node that stopped) where three of its columns go on, so every step can be closed by
/// standard cells.
struct ColumnFaces {
    std::vector<std::array<Index, 4>> nodes;
    std::vector<std::uint8_t> size;  ///< 3 or 4
    std::vector<Index> patch;

    explicit ColumnFaces(const SurfaceMesh& wall);
    Index count() const { return static_cast<Index>(size.size()); }
    /// Quad \p f becomes the triangle (c, c+1, c+2) and a new face (c, c+2, c+3), c its corner \p c.
    void split(Index f, int c);
};

/// The columns' state while the layers march.
struct Columns {
    ColumnFaces faces;
    std::vector<int> levels;        ///< per wall node, the levels it has so far
    std::vector<int> max_levels;    ///< per wall node, the most it may have (proximity in Stop mode)
    std::vector<Shortfall> limit;   ///< per wall node, what set max_levels below the layers (Proximity, Front)
    std::vector<char> active;       ///< per wall node, 1 while it marches
    std::vector<Shortfall> reason;  ///< per wall node, why it stopped below the layers asked
    std::vector<Vec3> top;          ///< per wall node, its highest node's position
    /// Per wall node, how squarely one direction can see all the wall faces around it (the
    /// largest smallest cosine to their normals, wall_reach): 1 on a smooth wall, cos(turn/2) on
    /// a sharp edge without a fan. A cell's corner there can be no better than this times the
    /// sine of its face's angle, so face_corner_quality counts it.
    std::vector<double> reach;
    /// Per column face, face_corner_quality as computed once (it depends on the wall alone);
    /// stop_columns extends it to faces split since.
    std::vector<double> best;
    /// The wall's edges between distinct positions (a fan's columns, which start at one node,
    /// are not apart on the wall): the front's spacing round each column (StopRules::isotropy).
    /// Empty until find_edges.
    std::vector<std::array<Index, 2>> edges;
    /// Pairs of column faces that share an edge (its two nodes, then the two faces), as found
    /// for side_pairs_faces faces; stop_columns finds them again once faces are split.
    std::vector<std::array<Index, 4>> side_pairs;
    Index side_pairs_faces = -1;
    /// Empty, or per wall node 1 where it cannot stop (a fan's column, first layer); stop_columns
    /// sets 2 where it would have stopped.
    std::vector<char> pinned;
    /// Node of *points of wall node i on level l (≤ levels[i]): point[l × wall nodes + i].
    std::vector<Index> point;
    const std::vector<Vec3>* points;  ///< the layers' points so far (LayerMesh::mesh.points)

    /// \p mesh_points: where the levels go, level 0 (the wall) first; the caller appends each
    /// level's moving nodes in wall order after stop_columns.
    /// \p plane_normal, \p line: the planes and lines wall nodes are held in (wall_reach).
    Columns(const SurfaceMesh& wall, int layers, const std::vector<Vec3>& mesh_points,
            const std::vector<Vec3>& plane_normal = {}, const std::vector<Vec3>& line = {});
    /// Fills edges from \p wall (the surface given to the constructor): only the isotropy stop needs them.
    void find_edges(const SurfaceMesh& wall);
    /// Position of wall node \p i on \p level (its top above its column).
    Vec3 at_level(Index i, int level) const;
};

/// What stopping needs to know besides the columns.
struct StopRules {
    double min_quality = 0.2;
    double max_turn_deg = 60.0;
    double max_twist_deg = 30.0;
    double isotropy = 0.0;  ///< LayerParams::isotropy (0: never)
    bool quality = true;    ///< stop on min_quality, max_turn_deg and max_twist_deg (off: only limits and non-finite)
    int threads = 0;        ///< threads of the quality test (0: OpenMP's default); the result is the same for any count
};

/// The scaled Jacobian below which a cell over a face whose best is \p best (face_corner_quality)
/// stops its columns: \p min_quality times the best, and at least half of min_quality on a
/// face whose best reaches min_quality. The relative bar lets a needle face (best 1e-3), or a
/// sharp edge without a fan, be judged on what the marching does to it; the floor keeps a fair
/// face's cells from shearing to nearly flat (a concave corner's prisms, best about 0.45, fell
/// to 0.09 under the relative bar alone; ALGORITHM.md, "Local stopping").
double cell_bar(double min_quality, double best);

/// Decide which columns go on from level \p k to k + 1, \p next holding the marched level k + 1
/// of every node (ghosts too). A column stops at its max_levels, where its position is not
/// finite, where a cell of its own over a face whose columns all go on would be below
/// cell_bar(min_quality, face_corner_quality) (the best a cell on that face can be) or twist more
/// than max_twist_deg (cell_twist_deg), or it would turn more than max_turn_deg; then, until
/// nothing changes, where the
/// cell closing a step would be unusable (a triangle with one column going on, a quad with one or
/// two opposite ones; a pyramid or side-on prism with a corner of a moving node below min_quality
/// or any corner not positive), splitting quads with three moving columns. Returns the columns
/// that stopped.
Index stop_columns(Columns& col, const StopRules& rules, int k, const std::vector<Vec3>& next);

/// How far the top face of a cell (corners \p top, \p n of them) is turned against its bottom
/// face (\p bottom) about the cell's axis (the mean of its columns), in degrees: the mean of
/// the signed angles from each bottom edge to its top edge seen along the axis, weighted by
/// the edges' lengths there, as a magnitude. 0 for a cell whose top is its bottom moved or
/// sheared, the rotation for a top turned rigidly about the axis.
double cell_twist_deg(const std::array<Vec3, 4>& bottom, const std::array<Vec3, 4>& top, int n);

/// cell_twist_deg(bottom, top, n) > \p bound_deg, \p tan_bound its tangent: without an arc
/// tangent where every edge turns less than the bound (the usual case), so the stopping test
/// stays cheap.
bool twists_more_than(const std::array<Vec3, 4>& bottom, const std::array<Vec3, 4>& top, int n, double bound_deg,
                      double tan_bound);

/// The best a cell over column face \p f can be: over its corners on the wall, the sine of
/// the corner's angle (the scaled Jacobian of the right prism or hexahedron on it) times the
/// corner node's reach (one direction per node: at a sharp edge without a fan no column stands
/// square on both sides), the smallest. The wall's, not the tops': a front that the marching
/// distorts must not lower the bar its own cells are judged by.
double face_corner_quality(const Columns& col, Index f);

/// Per node of \p wall, the largest smallest cosine between one direction and the unit normals
/// of the faces around it (zero-area faces, such as a fan's strips, left out), at least
/// kMinReach; 1 where no face counts. A node held in a plane (\p plane_normal, unit, zero or
/// empty for none) can only take a direction in it: the faces' mirror images across the plane
/// count too. A node held on a line (\p line, unit, zero or empty for none) has that direction.
std::vector<double> wall_reach(const SurfaceMesh& wall, const std::vector<Vec3>& plane_normal = {},
                               const std::vector<Vec3>& line = {});

/// The reach below which a node counts as kMinReach (one direction within 60° of every face
/// around it): a sharper edge without a fan lowers what its cells must reach by half at most,
/// so its columns grow where the first cells are fair (a wing's trailing edge ending on a
/// fuselage, where no fan can be built) and stop where the cells get worse than that.
inline constexpr double kMinReach = 0.5;

/// Scaled Jacobian of the cell column face \p f would make between its nodes' tops and \p next,
/// every column going on (a prism or hexahedron, as cell_quality.h measures them).
double column_cell_jacobian(const Columns& col, Index f, const std::vector<Vec3>& next,
                            std::array<Vec3, 8>* corners = nullptr);

/// The cells, boundary (the wall reversed, the top on top_patch, side faces over the wall's
/// open edges \p loops) and front (top, face_layers) of \p out, whose points hold every level
/// and whose columns are numbered (set_columns). \p edge_patch: per edge of \p loops in order
/// (loop by loop, node i to i + 1), the patch of its side faces, kNone for one "layer_side".
void build_layer_cells(const Columns& col, const SurfaceMesh& wall, const Csr& loops,
                       const std::vector<Index>& edge_patch, LayerMesh& out);

}  // namespace strata
