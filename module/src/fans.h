#pragma once
// Private to the layer module: fans at sharp convex edges and corners (ALGORITHM.md, "Fans").
// One marching direction per wall node caps the scaled Jacobian of the cells beside an edge
// of turning angle t near cos(t / 2) (0.09 at a trailing edge whose faces turn 170°). A fan
// node instead gets a column per side of its sharp edges (along that side's normal) and
// columns between them; the wall given to the marching gets, along each sharp edge, a strip
// of quads of zero area between those columns, and at a corner where three or more such
// edges meet (or two, where their chain turns sharply) a polygon closing them. On the wall
// (level 0) all of a node's columns start at the node itself, so the cells there collapse to
// standard ones (collapse_cell): wedges (prisms) along the edges, a tetrahedron or pyramid at
// a corner; above, they are ordinary prisms and hexahedra.

#include <strata/core/cell_quality.h>
#include <strata/core/surface_mesh.h>
#include <strata/core/types.h>
#include <strata/module/layer_report.h>

#include <array>
#include <vector>

namespace strata {

struct FanWall {
    SurfaceMesh mesh;             ///< the wall with its fan nodes split; its first faces are the wall's, in order
    std::vector<Index> base;      ///< per node of mesh: the wall node it starts at (i for the wall's own nodes)
    std::vector<Vec3> direction;  ///< per node of mesh: its fixed marching direction, zero for a node not in a fan
    std::vector<char> fan_face;   ///< per face of mesh: 1 for a face of a fan (zero area on the wall)
    Index fan_edges = 0;          ///< wall edges with a fan
    Index fan_nodes = 0;          ///< wall nodes split into fans
    Index corners = 0;            ///< of those, corners (three or more fan edges, or two turning sharply)
    Index plane_nodes = 0;        ///< of those, on a plane the chain ends on (one fan edge, columns in the plane)
    Index columns = 0;            ///< columns added (mesh nodes beyond the wall's)
    /// The nodes where a chain ends with one fan edge off any plane (at a concave junction: a
    /// trailing edge on a fuselage; or where the edge fades into a smooth wall), ascending. Such
    /// a node has one sector, so one column, on which every column of its fan edge closes (the
    /// fan's last quads are triangles): one direction there cannot stand off both sides of the
    /// edge, and the cells between the two sides would be flat at it, so its column stops at the
    /// wall and the fan's last cells close onto it as steps.
    std::vector<Index> terminals;
    /// The wall's nodes on an edge turning fan_angle_deg or more that got no fan, ascending, and
    /// why: NoFan::Open where its chain reaches the open boundary other than at a plane node
    /// with one fan edge, NoFan::Unclosed where it ends without closing otherwise (at a concave
    /// junction, on a smooth wall, at a node \p excluded, or where a corner's edge was dropped).
    /// Nodes \p excluded are not listed (their caller says why).
    std::vector<std::pair<Index, NoFan>> unfanned;
    bool empty() const { return fan_edges == 0; }
};

/// Fans on \p wall (oriented, normals into the flow): at every convex edge whose faces turn by
/// \p fan_angle_deg or more, and at the convex edges turning 30° or more that are connected
/// to one (so a trailing edge's fan closes into the tip's and root's edges), minus the nodes on
/// the wall's open boundary \p loops and the nodes \p excluded marks (empty or one per wall
/// node), and the fan edges of corners whose sides' normals lie nearly in one plane. A chain
/// may end at any other node with one fan edge that is on an edge turning \p fan_angle_deg or
/// more, a terminal (FanWall::terminals), but for a lone edge between two terminals (nothing
/// there splits), which gets none. A chain may also end
/// at a node of the open boundary held in one plane (\p plane_normal, unit, zero where none or
/// empty: a half model's symmetry plane) by one fan edge: its open ring splits into two
/// sectors, and its columns lie in the plane; with more fan edges it gets none. Along the
/// chain from it, the columns lean into the plane by 1 - (their node's distance from it) /
/// \p plane_reach (twice the layers' thickness: none then cross it). Each edge gets
/// ceil(turn / 90°) wedges. A node with two fan edges whose outward bisectors are more than 90°
/// apart (a delta wing's apex) is closed like a corner, each edge with its own columns.
/// Empty (fan_edges 0) if no edge qualifies or \p fan_angle_deg is 0.
FanWall build_fans(const SurfaceMesh& wall, const Csr& loops, const std::vector<Vec3>& plane_normal, double plane_reach,
                   double fan_angle_deg, const std::vector<char>& excluded);

/// The nodes of \p wall (a fan wall: FanWall::mesh, or the wall itself) on a convex edge whose
/// faces turn by \p min_turn_deg or more and that has no fan (ALGORITHM.md, "Sharp edges
/// without a fan"): an edge between two faces (a fan's strips, of zero area, keep the two sides
/// of a fanned edge apart, so it is not one), or an edge of the wall's open boundary whose nodes
/// are held in one plane (\p plane_normal, unit, zero where none) with the face's mirror image
/// in that plane. A fan's column on such an edge (a trailing edge without a fan that meets a
/// tip's fan loop) is one too: its fan's first cells are then unusable, and extrude_layers
/// drops that fan and marches again.
std::vector<char> sharp_single_nodes(const SurfaceMesh& wall, const std::vector<Vec3>& plane_normal,
                                     double min_turn_deg);

/// A cell of \p type over node ids \p id (Gmsh order) some of which repeat (columns of a fan
/// on the wall) as the standard cell of its distinct nodes: a hexahedron whose bottom is a
/// collapsed edge pair becomes a prism, whose bottom is one node a pyramid; a prism or pyramid
/// with four distinct nodes a tetrahedron; a prism with one collapsed vertical edge a
/// pyramid; each oriented as the cell it collapses. In place; false for a pattern no standard
/// cell represents.
bool collapse_cell(CellType& type, std::array<Index, 8>& id);

}  // namespace strata
