#pragma once
/// \file
/// The boundary-layer module: Poisson marching extrusion of prism and hexahedron layers
/// (Thompson, Chalasani & Soni; ALGORITHM.md).

#include <strata/core/progress.h>
#include <strata/core/surface_mesh.h>
#include <strata/core/volume_mesh.h>
#include <strata/geometry/normals.h>
#include <strata/module/distribution.h>
#include <strata/module/layer_report.h>
#include <strata/module/proximity.h>

#include <algorithm>
#include <memory>
#include <vector>

namespace strata {

/// What the layers do where the flow domain along a node's marching direction is shorter
/// than they need (a narrow gap, a facing wall, a nearby symmetry or farfield patch).
enum class ProximityMode {
    Off,    ///< march the full thickness everywhere (colliding layers are reported before TetGen)
    Scale,  ///< scale the node's layer heights down to its limit (thinner layers, all of them)
    Stop,   ///< keep the layer heights (the first height is the y+ asked) and stop the column
            ///< at the last layer that fits its limit: fewer layers where the gap is narrow
};

std::string_view to_string(ProximityMode mode);
/// "off", "scale" or "stop"; InputError naming LayerParams::proximity otherwise.
ProximityMode parse_proximity_mode(std::string_view text);

/// Parameters of layer generation. Lengths in model units.
struct LayerParams {
    DistributionParams distribution;  ///< number of layers and their heights
    /// Point-Jacobi sweeps per layer (the paper's ten), ≥ 0. A sweep updates only the nodes
    /// whose update reads a node that moved more than a tenth of tolerance × δ_k in the sweep
    /// before.
    int sweeps = 10;
    int max_sweeps = 50;              ///< more sweeps allowed while the residual is high; below sweeps it is sweeps
    double tolerance = 1e-3;          ///< stop extra sweeps when max update < tolerance × δ_k
    bool control_functions = true;    ///< Φ, Ψ from the wall, Θ from the distribution
    bool concave = true;              ///< the concave-region modification (Eqs. 15–18)
    /// Cap on ν_m in the literal reading ν_m = (g_m/g33 − 1) f(α_m); 0 selects the bounded
    /// reading (1 − g33/g_m) f(α_m). Measured on the notched box and the body-fin junction
    /// (ALGORITHM.md section 6 cases): a cap of 10 keeps every cell valid where the bounded
    /// reading lets the fin's leading-edge junction fold at layer 20.
    double concave_cap = 10.0;
    /// Node normals per level. The paper's area weighting tilts at sharp edges and corners
    /// (the fin's trailing edge inverts the first layer); the max-min normal does not.
    NormalMethod normals = NormalMethod::MaxMinDot;
    bool smoothing = true;  ///< false: plain normal extrusion (reference mesh only)
    /// Where a layer's cells would still invert after smoothing, stop the layer locally instead
    /// of throwing: the nodes of those cells drop their smoothing, march along the direction
    /// that is best for their cells' corners and are lowered until the cells are valid
    /// (LayerStats::held_nodes counts them). Only where smoothing runs (smoothing, max_sweeps
    /// > 0): plain extrusion stays the bare reference mesh. Never with keep_invalid.
    bool hold_back = true;
    /// Proximity limiting (proximity.h): each node's total thickness at most a share of the
    /// distance to the first surface along its marching direction, smoothed along the wall; in
    /// Stop mode neighbouring columns then differ by at most one layer.
    ProximityMode proximity = ProximityMode::Stop;
    /// Local stopping: a column stops (its node gets no further level) when a cell it would
    /// make has a scaled Jacobian below this times the best its wall face allows, or below half
    /// of this where the face allows this (columns.h, cell_bar), or cannot be computed. Where columns stop
    /// unevenly, the cells over a face close the step (ALGORITHM.md, "Local stopping"). 0 turns
    /// stopping off: every column marches every layer and a fold is an error.
    double min_quality = 0.2;
    /// A column also stops where its next segment would turn more than this (degrees) from
    /// its previous one: the front folding over.
    double max_turn_deg = 60.0;
    /// A column also stops where a cell it would make twists more than this (degrees): its top
    /// face turned about the cell's axis against its bottom face (the mean of the angles its
    /// edges turn, seen along the axis), which the scaled Jacobian of a prism hardly sees.
    double max_twist_deg = 30.0;
    /// A column also stops before a layer taller than this times the spacing of the layer front
    /// round it (the mean length of its edges on the level it would reach): past that its cells
    /// are taller than wide, the smoothing shears them and their stops spread, and the
    /// tetrahedra serve better (AFLR3 stops its layers by the same aspect ratio). Every column
    /// keeps its first layer. 0: never.
    double isotropy = 0.0;
    /// Fans (ALGORITHM.md, "Fans"): at a convex edge whose faces turn by this many degrees or
    /// more (a sharp trailing edge, a thin fin's tip), and at the convex edges of 30° or more
    /// that close its chain, each node gets a column per side of the edge and columns between
    /// them, at most 90° apart, so the cells beside the edge stay near-orthogonal where one
    /// direction per node would cap them near cos(turn / 2) (0.26 at 150°). 0: no fans. Only
    /// with local stopping (min_quality > 0). ALGORITHM.md says why 150° and not lower.
    double fan_angle_deg = 150.0;
    /// Where a convex edge whose faces turn by this many degrees or more gets no fan (its chain
    /// ends on a concave junction: a trailing edge on a fuselage or a tunnel wall; or the fan
    /// angle is higher), the columns of its nodes stop at the wall (ALGORITHM.md, "Sharp edges
    /// without a fan"): one direction there stands more than 60° off a face at the default 120°,
    /// and OpenFOAM finds the faces between the two sides' cells skewed by about 2 / sin(α/2) for
    /// a wedge of angle α = 180° − turn, above its limit of 4 from about 120° on. An edge of
    /// the wall on a symmetry or outflow plane counts with its mirror image. 0: never (such
    /// nodes keep one direction). Only with local stopping (min_quality > 0).
    double sharp_edge_stop_deg = 110.0;
    ProximityParams proximity_limits;
    /// Threads of the smoothing and the normals (0: OpenMP's default; negative: InputError); the
    /// layers are the same for any count. For extrude_layers called alone: build_hybrid_mesh sets it from
    /// HybridParams::threads.
    int threads = 0;
    /// Diagnostics only: return layers with inverted cells instead of throwing (the stats
    /// then show min_scaled_jacobian ≤ 0), as marched: nothing is held back or stopped. Never
    /// used for a mesh that is written.
    bool keep_invalid = false;
};

/// Each level's Poisson smoothing as the last march computed it (layers.cpp): what the marches
/// after it on the same walls and settings reuse where they reach a level from exactly the same
/// positions. make_smoothed_levels() gives an empty one.
struct SmoothedLevels;
std::shared_ptr<SmoothedLevels> make_smoothed_levels();

/// Per-node bounds on the layers of one surface, apart from the settings (LayerParams): what
/// build_hybrid_mesh's repair rounds change where a later stage failed, marching again.
struct LayerConstraints {
    /// Empty, or one per node of the surface given to extrude_layers: a further bound on the
    /// node's total thickness (infinity: none), smoothed along the wall like the proximity
    /// limit but at ProximityParams::front_slope. In Stop mode the column keeps its first
    /// height and its layers, their heights growing less from layer to layer to fit (down to
    /// equal heights; below that it loses layers); in Scale mode its heights are scaled.
    /// build_hybrid_mesh lowers it where the layer front intersects itself.
    std::vector<double> node_thickness_limit;
    /// Empty, or one per node of the surface given to extrude_layers: the slope (thickness per
    /// unit of wall distance, above 0) at which that node's node_thickness_limit spreads along
    /// the wall, in place of ProximityParams::front_slope. build_hybrid_mesh lowers it where its
    /// rounds lower the same columns again, and there only.
    std::vector<double> node_front_slope;
    /// Empty, or one per node of the surface given to extrude_layers: a bound on the node's
    /// thickness that does not spread along the wall (infinity: none), for the reason in
    /// node_stop_reason. extrude_layers sets both where a column stopped (its cells' quality,
    /// turning, twist, a neighbour's step) and marches again, each such column then keeping
    /// every layer up to where it stopped, its tallest layers capped (ALGORITHM.md, "Capped
    /// columns").
    std::vector<double> node_stop_limit;
    std::vector<Shortfall> node_stop_reason;  ///< per node with a node_stop_limit, why its column stopped
    int stop_marches = 0;                     ///< the marches extrude_layers has made again for them
    /// Empty, or one per node of the surface given to extrude_layers: 1 where no fan may be
    /// (build_hybrid_mesh marks the nodes of a fan whose face on the layer top no pyramid can cap).
    std::vector<char> no_fan_nodes;

    /// Speed only, the layers are the same bytes without it: the smoothing the marches before
    /// computed, shared by every copy of these constraints (the stop marches, build_hybrid_mesh's
    /// rounds). A stop march or a round changes where columns stop and how tall they are, not how
    /// the levels are smoothed until a stopped column's ghost is held back differently, so the
    /// levels below are not smoothed again (the airliner stand-in: 5 marches, ~6 s each).
    /// extrude_layers makes one for its own stop marches when none is given.
    std::shared_ptr<SmoothedLevels> smoothed;

    /// No fan at node \p v of a surface of \p nodes nodes from now on; false if there was none already.
    bool bar_fan(Index v, std::size_t nodes);
};

/// Quality of one layer's cells.
struct LayerStats {
    double height = 0.0;               ///< δ_k
    double min_scaled_jacobian = 0.0;  ///< over every corner of every cell of the layer
    double mean_scaled_jacobian = 0.0;
    double max_orthogonality_deg = 0.0;  ///< largest angle between a layer edge and the wall-side face normal
    double mean_orthogonality_deg = 0.0;
    int sweeps = 0;                        ///< sweeps done
    Index held_nodes = 0;                  ///< nodes held back (lowered, unsmoothed) to keep the layer valid
    Index columns = 0;                     ///< wall nodes that have this layer
    Index stopped_nodes = 0;               ///< columns that stopped below this layer (had the one before)
    Index transition_cells = 0;            ///< cells of the layer closing a step: pyramids, prisms on their side
    double min_transition_jacobian = 1.0;  ///< their smallest scaled Jacobian
};

/// The layers' figures a report carries: LayerMesh's own, kept by HybridReport as they are.
struct LayerCounts {
    std::vector<LayerStats> stats;  ///< one per layer asked
    /// Nodes extruded along their normal without smoothing (sharp convex edges, open-edge
    /// corners, degenerate stencils: ends of needle triangles).
    Index unsmoothed_nodes = 0;
    Index thinned_nodes = 0;           ///< nodes whose layers were scaled down (proximity, front rounds)
    double min_thickness_share = 1.0;  ///< the smallest share of the asked thickness a node got
    Index fan_edges = 0;               ///< edges of the input wall with a fan (LayerParams::fan_angle_deg)
    Index fan_nodes = 0;               ///< nodes of the input wall split into a fan's columns
    Index fan_corners = 0;             ///< of those, corners: three or more fan edges, or two turning sharply
    Index fan_plane_nodes = 0;         ///< of those, on a plane the chain ends on (a symmetry plane)
};

/// The layers: a volume mesh of prisms (on triangles) and hexahedra (on quads) over the wall
/// faces, level by level, columns of different heights where they stopped (LayerParams::
/// min_quality, proximity). Other stages reach its nodes through the accessors, never through
/// the numbering itself. The numbering: level 0 is the wall (node i is wall node i), then each
/// level holds the nodes of the columns that reach it, in wall order, so full columns give
/// level_node(k, i) = k × wall_nodes() + i.
class LayerMesh : public LayerCounts {
public:
    LayerMesh() = default;
    /// Layers over \p wall_nodes wall nodes, \p layers levels above the wall, every column full.
    LayerMesh(Index wall_nodes, int layers);

    VolumeMesh mesh;  ///< boundary: the wall patches, side faces on open-boundary patches, and top_patch
    /// The front for the next stage: each face the layers stand on (the wall's faces, quads
    /// split in two where their columns stop unevenly) with every node at the top of its
    /// column (top.points[i] = mesh.points[top_node(i)]), on the wall's patches.
    SurfaceMesh top;
    std::vector<int> face_layers;         ///< per face of top, the layers of cells over it
    std::vector<Index> input_node;        ///< wall node → node of the input surface
    Index top_patch = kNone;              ///< the patch of mesh.boundary ("layer_top") holding the outermost level
    double asked_thickness = 0.0;         ///< the sum of the layer heights
    std::vector<double> height_scale;     ///< per wall node, the share of the thickness asked its layers were asked
    std::vector<Shortfall> scale_reason;  ///< per wall node, why that share is below 1 (Proximity or Front)
    std::vector<Shortfall> stop_reason;   ///< per wall node, why its column stopped below layers() (None: it did not)
    std::vector<char> held_back;          ///< per wall node, 1 if some layer held it back (hold_back)
    std::vector<char> fan_column;         ///< empty, or per wall node 1 for a column of a fan
    /// Nodes of the input surface with no fan because its first cells would have been unusable
    /// (ascending; layer_report lists them with their positions).
    std::vector<Index> fans_dropped;
    /// Nodes of the input surface with no fan because its cells had faces checkMesh would fail
    /// as skewed (ascending; layer_report lists them with their positions).
    std::vector<Index> fans_skewed;
    /// The bounds of the columns capped where they stopped that these layers were marched with
    /// (LayerConstraints::node_stop_limit, node_stop_reason, stop_marches), for a caller that
    /// marches the same surface again (build_hybrid_mesh's rounds).
    std::vector<double> stop_limit;
    std::vector<Shortfall> stop_limit_reason;
    int stop_marches = 0;
    /// Wall nodes on an edge turning LayerParams::fan_angle_deg or more that got no fan: on the
    /// open boundary where no chain ends, or on a chain that could take none (NoFan::Open,
    /// NoFan::Unclosed), by input node id, with their positions.
    std::vector<NoFanNode> fans_unclosed;

    Index wall_nodes() const { return wall_nodes_; }
    /// Levels asked above the wall: the tallest a column can be.
    int layers() const { return layers_; }
    /// Levels above the wall that wall node \p i has.
    int node_layers(Index i) const {
        return node_layers_.empty() ? layers_ : node_layers_[static_cast<std::size_t>(i)];
    }
    /// The node of mesh.points that wall node \p i has on level \p k (0: the wall itself; above
    /// the node's column, its top).
    Index level_node(int k, Index i) const {
        if (ids_.empty()) return static_cast<Index>(k) * wall_nodes_ + i;
        return ids_[static_cast<std::size_t>(std::min(k, node_layers(i))) * static_cast<std::size_t>(wall_nodes_) +
                    static_cast<std::size_t>(i)];
    }
    /// The node of wall node \p i at the top of its column.
    Index top_node(Index i) const { return level_node(node_layers(i), i); }
    /// The level of node \p node of mesh.points.
    int level_of(Index node) const;
    /// Number the nodes for columns of \p node_layers levels (one per wall node, 0..layers()),
    /// level by level as above; mesh.points must hold them in that order. \p base: empty, or
    /// per wall node the node its column starts at on level 0, the wall nodes with base[i] = i
    /// first (a fan's columns share their wall node): level 0 then holds only those.
    void set_columns(std::vector<int> node_layers, std::vector<Index> base = {});

private:
    Index wall_nodes_ = 0;
    int layers_ = 0;
    std::vector<int> node_layers_;    ///< empty: every column full
    std::vector<Index> ids_;          ///< (layers + 1) × wall_nodes, level-major; empty: every column full
    std::vector<Index> level_start_;  ///< first node of each level, and the node count last
};

/// InputError saying to mark the body as a wall where no face of \p surface is on a wall patch.
void require_wall_faces(const SurfaceMesh& surface);

/// Per cell of \p lm.mesh in CellNumbering order, its layer: the highest level among its nodes
/// (a prism from level k - 1 to k is in layer k, a cell closing a step in the layer it reaches).
std::vector<std::int32_t> layer_of_cells(const LayerMesh& lm);

/// The coverage report of \p lm (layer_report.h): per wall patch (the patches of lm.top), the
/// layers and thickness each column reached (its length) against lm.asked_thickness, and
/// every node that something limited, with the reason: why it stopped if it did, else
/// HeldBack where a layer held it back (lowered where cells would have inverted), else the
/// reason its heights were scaled. A column that nothing limited counts as full even where
/// smoothing left it a little shorter or longer.
LayerReport layer_report(const LayerMesh& lm);

/// Extrude \p wall (oriented, normals into the flow; faces on Wall patches are extruded).
/// Open boundaries of the wall keep their nodes on the planar non-wall patches they meet (a
/// symmetry or outflow plane, a box side; along the line where two such planes meet), or, with
/// no such patch, in the plane of the open boundary loop if it is planar. Per layer, the paper's three steps: the
/// locally orthogonal reference levels (Eqs. 11–12), Poisson smoothing of the middle level (Eq. 3), which then
/// becomes the next wall. Then each column that would make a cell below LayerParams::min_quality (or turn,
/// reach its proximity limit, or leave the finite range) stops; the whole level is still marched (the stopped
/// nodes as ghosts the stencils see, ALGORITHM.md), only the columns that go on get nodes. With min_quality 0,
/// throws TopologyError naming the layer, face and position of the first cell that would invert (a
/// LocalTopologyError carrying its wall nodes as nodes of \p wall) or whose quality cannot be computed. \p
/// progress: stage "layers", checked after every layer. \p constraints: the per-node bounds (none
/// without them).
LayerMesh extrude_layers(const SurfaceMesh& wall, const LayerParams& params, const LayerConstraints& constraints,
                         Progress* progress = nullptr);
LayerMesh extrude_layers(const SurfaceMesh& wall, const LayerParams& params, Progress* progress = nullptr);

/// The columns of \p lm that are not a fan's and have a node on a face between two of its cells
/// that OpenFOAM's checkMesh would fail as skewed (above kFoamSkewness: a column bent at a
/// concave junction, a fin's trailing edge on a body, whose layers stretch beside its
/// neighbours'), bounded in \p constraints (for a surface of \p nodes nodes, lm's input) to the
/// thickness of the levels below the face's lowest node (node_stop_limit, reason quality), so
/// that extrude_layers with them caps those columns there and keeps their layers (ALGORITHM.md,
/// "Capped columns"); whether any bound was lowered. Nothing in Scale mode. build_hybrid_mesh
/// does it where its mesh has such faces and makes it again.
bool cap_skewed_columns(const LayerMesh& lm, const LayerParams& params, std::size_t nodes,
                        LayerConstraints& constraints, int threads);

/// The columns' levels that extrude_layers plans before marching, from the proximity limits
/// alone (LayerParams::proximity Stop; every column full otherwise): per node of \p wall, the
/// layers that fit its limit (neighbours within one layer; LayerConstraints::node_thickness_limit
/// included), and whether the proximity limit set them. Nothing is marched: the normals, the
/// rays and the envelope only. Nodes off the walls keep every layer. And the first wedge of
/// every fan the layers would build (fans.h; before any is dropped for unusable or skewed cells).
struct ProximityPlan {
    std::vector<int> levels;
    std::vector<char> proximity;  ///< 1: fewer layers than asked, for the proximity limit
    /// A fan's wedge along wall edge (a, b) (nodes of the surface), between the columns of
    /// directions d1 and d2 at a.
    struct FanWedge {
        Index a = kNone, b = kNone;
        Vec3 d1 = Vec3::Zero(), d2 = Vec3::Zero();
    };
    std::vector<FanWedge> fan_wedges;
};
ProximityPlan proximity_plan(const SurfaceMesh& wall, const LayerParams& params,
                             const LayerConstraints& constraints = {});

}  // namespace strata
