#pragma once
/// \file
/// CAD input (STEP, IGES, BREP through Gmsh's OpenCASCADE kernel, and Gmsh .geo scripts),
/// surface-meshed with Gmsh.

#include <strata/core/progress.h>
#include <strata/core/surface_mesh.h>
#include <strata/geometry/point_sizes.h>

#include <string>
#include <utility>
#include <vector>

namespace strata {

/// Which faces Gmsh makes on the CAD surfaces.
enum class SurfaceElements {
    Triangles,  ///< all triangles (default)
    Quads,      ///< recombined into quadrilaterals everywhere (Blossom; a few triangles remain,
                ///< mostly on small or strongly curved faces: ~88 % quads on the ONERA M6
                ///< at size 40)
    Mixed,      ///< quads on CadParams::quad_surfaces, triangles elsewhere
};

/// Parameters of CAD surface meshing. Sizes are in the unit of the result: for STEP and IGES
/// the unit the file declares (io/cad_units.h; OpenCASCADE alone would give millimetres
/// whatever the file declares, and a STEP in metres came out 1000 times larger), or the one
/// asked in \p units; BREP and .geo have no unit: their numbers are kept.
///
/// A .geo script is the authority on its own mesh settings: point sizes, fields, Recombine
/// Surface and the Mesh.* options it sets stand, unless a field here is away from its default
/// (then the field wins). Mesh.ElementOrder is always forced to 1 (Strata needs linear faces),
/// and a mesh the script made itself ("Mesh 2;") is cleared and made again with these settings
/// (kept if the model has discrete entities, whose mesh may be their only geometry).
struct CadParams {
    /// Maximum element size (Mesh.MeshSizeMax). 0 = 1/20 of the model's bounding-box diagonal,
    /// or for a .geo that sets Mesh.MeshSizeMax itself, the script's value. Sizes a .geo gives
    /// its points are respected below this bound.
    double size = 0.0;
    /// Minimum element size (Mesh.MeshSizeMin), a floor for curvature refinement so that a
    /// sharp edge's tiny radius does not give needle-small elements. 0 = size / 20 when
    /// curvature refinement is on, no floor otherwise.
    double size_min = 0.0;
    /// Curvature refinement: target elements per 2π radians of curvature
    /// (Mesh.MeshSizeFromCurvature); 0 = off.
    int curvature_points = 0;
    SurfaceElements elements = SurfaceElements::Triangles;
    /// With quads (elements Quads or Mixed): Gmsh's simple recombination
    /// (Mesh.RecombinationAlgorithm 0, which pairs fewer triangles and leaves more of them)
    /// instead of Blossom (1), over a .geo script's own choice too. prepare_for_layers asks it
    /// where Blossom's quads fold (RecombinationReport::folded).
    bool simple_recombination = false;
    /// CAD surface tags (as Gmsh numbers them, after fuse if fuse is set) meshed with quads when
    /// elements is Mixed; ignored otherwise. A tag that is not a surface → InputError listing
    /// the valid tags.
    std::vector<int> quad_surfaces;
    /// Fuse all solids into one body first (OpenCASCADE Boolean union, first solid as object,
    /// the others as tools): faces inside the union disappear. Without it several solids are
    /// meshed as they are, so overlapping solids give intersecting surfaces that later checks
    /// reject. Needs OpenCASCADE entities (STEP/IGES/BREP, or SetFactory("OpenCASCADE") in a
    /// .geo). Faces the union changes lose their physical group.
    bool fuse = false;
    /// Threads (0: all cores). Above one, OpenCASCADE's Boolean operations (fuse, and those a
    /// .geo script makes) run in parallel on its own thread pool (Gmsh's Geometry.OCCParallel);
    /// their result is the same for any count. Gmsh's surface meshing stays on one thread: its
    /// meshes differ with the thread count.
    int threads = 0;
    /// Gmsh 2D algorithm (Mesh.Algorithm): 1 MeshAdapt, 2 Automatic, 5 Delaunay,
    /// 6 Frontal-Delaunay (default), 9 packing of parallelograms. 7 (BAMG) and 8 (Frontal-
    /// Delaunay for quads) are refused: in Gmsh 4.8.4 they abort the process (BAMG on curved
    /// surfaces, algorithm 8 on every surface). Quads come from recombination instead; a .geo
    /// that sets Mesh.Algorithm 7 or 8 gets 6.
    int algorithm = 6;
    /// STEP and IGES only: the length unit of the result ("mm", "m", "in", ...; see
    /// parse_length_unit); empty: the unit the file declares (millimetres if it declares none
    /// Strata knows). InputError for an unknown unit, or for a BREP or .geo file (no unit).
    std::string units;
    /// The first boundary-layer height, in the unit of the result, and the largest OpenFOAM
    /// aspect ratio its cells may have (checkMesh fails a mesh above 1000); either 0: no limit.
    /// A first layer much thinner than its wall face is flatter than checkMesh accepts (about
    /// the face's longest edge over the height, right_prism_aspect_ratio). After meshing, every
    /// wall surface with a face whose right prism of this height would exceed
    /// max_aspect_ratio is meshed again (with all the others, so shared curves stay
    /// conforming) at 0.7 max_aspect_ratio first_height there: a Gmsh size callback on
    /// those surfaces, their curves and points, below the sizes they would get. A surface is a
    /// wall if its patch is one by patch_kind_of with \p wall_patch_kinds (prepare.h): farfield,
    /// symmetry and other surfaces are not capped (Gmsh grades them from their curves, finer
    /// where they meet a capped wall).
    double first_height = 0.0;
    double max_aspect_ratio = 1000.0;
    /// The layers' fan angle (LayerParams::fan_angle_deg, set by the front-ends; 0: no fans):
    /// a wall edge whose faces turn by this much or more gets a fan, whose first cells are about
    /// twice the edge's length over the height (fan_wedge_aspect_ratio), so a curve carrying
    /// such edges is meshed finer where they would exceed max_aspect_ratio (the surfaces beside
    /// it grade from it).
    double fan_angle_deg = 0.0;
    std::vector<std::pair<std::string, PatchKind>> wall_patch_kinds;
    /// The walls are not meshed again (WallSizeReport says so) when they would get more than
    /// about this many faces from it, estimated from the surfaces' areas: a 20 x 10 x 20 tunnel
    /// lined with layers from 1e-4 would need 370,000 (and tens of millions of tetrahedra).
    double wall_faces_budget = 200000;
    /// STEP, IGES and BREP: faces that bound no solid (a surface model, as IGES files and many
    /// STEP exports are: each face with its own edges, which miss their neighbours' by the CAD
    /// tool's tolerance) are sewn by OpenCASCADE (BRepBuilderAPI_Sewing through Gmsh's
    /// healShapes, closed shells made solids; degenerate edges, and edges and faces smaller than
    /// the tolerance, fixed) before meshing; unsewn, each face would be meshed on its own and
    /// the surface left open along every edge. The tolerance is this share of the model's
    /// bounding-box diagonal, raised to twice the widest gap measured between the faces' edges
    /// up to 1e-5 of it. In [0, 0.001]; 0: not sewn. Models whose faces all bound solids are
    /// never touched.
    double sew_tolerance = 1e-6;
    /// Sizes asked at points (in the unit of the result), each rising by size_point_growth per
    /// unit of distance from its point (PointSizes), below the sizes the surfaces would get
    /// (a Gmsh size callback on every surface, curve and point). The front-ends ask them where
    /// the layers step at a gap (step_sizes, through prepare_for_layers); empty: none.
    std::vector<SizePoint> size_points;
    double size_point_growth = 0.25;
    /// A face narrower than size / this (its width: twice its area over its perimeter, seams left
    /// out; a strip's width) and longer than this many times its width is meshed with triangles
    /// about this many times its width long, by size points along its boundary curves rising
    /// at 0.5 per unit of distance into the faces around: meshed at the size, a CAD model's
    /// strip along a trailing edge gets one row of slivers, and the layer cells on them faces
    /// far from orthogonal (checkMesh's non-orthogonality above 70°). Not a face that would
    /// need sizes below the larger of size / 8 and size_min (a thin plate's edge: its triangles
    /// would stay slivers, only more of them), nor when the faces this adds would exceed
    /// wall_faces_budget (WallSizeReport::narrow_over_budget), nor on a .geo's built-in
    /// kernel, which cannot measure a face. 0: off; else at least 1.
    double narrow_face_ratio = 4.0;
    /// For the front-ends' prepare_for_layers (not read here): where the layers step at a
    /// proximity limit (a column of k layers beside a taller one), the cells closing the step
    /// have a corner of scaled Jacobian about the layer height h_k over the wall spacing L; the
    /// model is meshed again with size_points there (step_sizes) so that h_k / L reaches this
    /// (the cells then reach about half of it). In [0, 1); 0: not.
    double step_quality = 0.1;
    /// A .geo script is a program: Gmsh runs the shell commands it gives (SystemCall), the
    /// programs it starts (OnelabRun), and writes the files it names (Save, Printf > file), with
    /// the rights of whoever reads it. Such a script, or one that reads such a script (Include,
    /// Merge), is refused (InputError naming the file, the line and the command:
    /// check_geo_script, io/geo_script.h) unless this is set, for a script whose author is trusted.
    bool trust_geo = false;
};

/// What the front-ends' prepare_for_layers did for CadParams::step_quality.
struct StepSizeReport {
    double quality = 0.0;  ///< asked (0: off, or no CAD input or no layers)
    Index points = 0;      ///< wall nodes whose steps asked a finer wall (0: none)
    /// Wall nodes at the ends of fan edges whose first wedges would exceed
    /// CadParams::max_aspect_ratio (fan_wedge_sizes), also meshed finer; with \p points 0 and
    /// this 0, nothing is meshed again.
    Index fan_points = 0;
    double smallest = 0.0;      ///< the smallest size asked, in the result's unit
    Index faces_before = 0;     ///< wall and other faces of the surface before
    Index faces_after = 0;      ///< and after meshing again
    double faces_estimate = 0;  ///< the faces estimated from the sizes (before any raise)
    double raised = 1.0;        ///< the sizes were multiplied by this to stay within the faces budget
    bool over_budget = false;   ///< not meshed again: even raised 100-fold the sizes exceeded the faces budget
    /// The thickness the layers' plan gives the walls (a share of the thickness asked, weighted
    /// by wall area), on the first surface and on the finer one.
    double thickness_before = 1.0, thickness_after = 1.0;
    /// The finer surface was dropped: its plan gave the walls less thickness (a gap resolved
    /// better limits the layers round it more), and the first one is returned.
    bool kept = false;
    /// Gmsh could not mesh the finer surface (its error): the first one is returned.
    std::string failure;
    double seconds = 0.0;  ///< the layers planned to find the steps, and the surface made again
};

/// What the cells of the mesh above checkMesh's aspect ratio asked of the CAD walls (the
/// front-end's run: the walls meshed again finer round them and the mesh made again, once).
struct AspectRemeshReport {
    Index cells = 0;          ///< cells of the first mesh above the limit (0: nothing done)
    double worst = 0.0;       ///< the largest aspect ratio among them
    std::string worst_cell;   ///< where (SolverChecks::worst_aspect)
    double smallest = 0.0;    ///< the smallest size asked, in the result's unit
    double faces_estimate = 0.0;  ///< the faces estimated from the sizes
    bool over_budget = false;     ///< not meshed again: the estimate exceeded the faces budget
    Index faces_before = 0;   ///< the first surface's faces
    Index faces_after = 0;    ///< and the one meshed again
    Index cells_after = 0;    ///< cells above the limit in the mesh made again
    double worst_after = 0.0;
    std::string failure;   ///< making them again failed (its error): the first mesh is kept
    double seconds = 0.0;  ///< the surface and the mesh made again
};

/// What CadParams::sew_tolerance did.
struct SewReport {
    Index faces = 0;  ///< faces that bounded no solid, sewn (0: nothing to sew)
    /// Faces that bounded no solid written twice (the same bounding box, area and normal as
    /// another), the copies removed before sewing (also when there was nothing to sew).
    Index written_twice = 0;
    double tolerance = 0.0;  ///< the sewing tolerance used, model units
    /// The first tolerance tried, if edges it left apart (by a gap up to 1e-5 of the diagonal)
    /// made the faces sewn again from the file at \p tolerance; else 0.
    double first_tolerance = 0.0;
    double gap_before = 0.0;  ///< the widest gap measured between those faces' edges before sewing
    Index free_before = 0;    ///< edges of those faces that bounded one face only, before sewing
    Index free_after = 0;     ///< and after (a seam, which bounds one face twice, is not one)
    Index solids = 0;         ///< closed shells made solids
    /// Free edges left that lie within 0.001 of the model's size of another (a gap wider than
    /// the tolerance): how many, the widest gap, where, and the tolerance (a share of the
    /// diagonal, as CadParams::sew_tolerance) that would sew them (0: none such).
    Index cracks = 0;
    double widest_gap = 0.0;
    Vec3 gap_at = Vec3::Zero();
    double suggested_tolerance = 0.0;
    bool renumbered = false;  ///< the sewn faces could not all be matched to the file's (patches by the new tags)
    /// How far the healing moved a face (the largest distance of a face's bounding box from the
    /// nearest of the file's), model units; beyond 1e-4 of the diagonal the sewn model is
    /// \p rejected and the file meshed unsewn, as it is.
    double moved = 0.0;
    bool rejected = false;
    /// In a model with solids: faces that bound none and are open where they stand (sewn or
    /// not, a free edge left in their group of loose faces): a construction profile or a loose
    /// sheet beside the solids, which no layer can grow on. Not meshed: how many, and the first's
    /// tag and centre.
    Index ignored = 0;
    int ignored_surface = 0;
    Vec3 ignored_at = Vec3::Zero();
    /// Faces the model holds twice with geometry of their own: bounded by exactly the same
    /// edges as another face and lying on it (within 1e-6 of the model's size), the copy of a
    /// pair not meshed (the loose one, else the higher tag; the faces of two touching solids
    /// stay). How many, the first's tag, the face it copies, a point on it, and the largest
    /// distance measured between a pair.
    Index coincident = 0;
    int coincident_surface = 0;
    int coincident_with = 0;
    Vec3 coincident_at = Vec3::Zero();
    double coincident_distance = 0.0;
};

/// What CadParams::max_aspect_ratio did.
struct WallSizeReport {
    double max_aspect_ratio = 0.0;  ///< asked (0: no limit)
    double worst_before = 0.0;      ///< the largest first-layer aspect ratio of the first mesh's wall faces
    double worst_after = 0.0;       ///< and of the mesh returned
    double cap = 0.0;               ///< the surfaces' size (else the finest fan curve's) the walls needed (0: none)
    Index surfaces = 0;             ///< wall surfaces meshed again at \p cap (0: none)
    Index curves = 0;               ///< fan curves meshed again finer (0: none)
    double faces_estimate = 0.0;    ///< faces those surfaces were estimated to get
    bool over_budget = false;       ///< not meshed again: faces_estimate above CadParams::wall_faces_budget
    /// Where the default size (none asked: CadParams::size 0, no size in a .geo script) left a
    /// part thinner than it (a propeller blade's tip, a thin fin) with its two sides meshed
    /// through the same nodes, one chord across (edges of four faces: not a surface layers can
    /// stand on), or faces crossing where two parts meet closer than it (a nacelle on its
    /// pylon), the surfaces were meshed again at half the size, up to three times: the size
    /// used (0: the default served), and the default.
    double thin_size = 0.0;
    double default_size = 0.0;
    /// Where the default size served a model whose walls are less than half its size (an air
    /// domain round its body: its farfield, symmetry and outflow faces), the walls' own default,
    /// a twentieth of their bounding box's diagonal as the model's is, on the wall surfaces, their
    /// curves and points (the other faces grade from them); 0: not (\p default_size is then 0
    /// unless thin_size says otherwise).
    double walls_default_size = 0.0;
    /// CadParams::narrow_face_ratio: the ratio asked (0: off), the faces narrower than the size
    /// over it, the narrowest's width and surface tag, the smallest size asked along them, the
    /// faces estimated to be added (an upper bound) and whether that exceeded the budget (then
    /// they were meshed at the size).
    double narrow_ratio = 0.0;
    Index narrow_faces = 0;
    double narrowest = 0.0;
    int narrowest_surface = 0;
    double narrow_size = 0.0;
    double narrow_faces_estimate = 0.0;
    bool narrow_over_budget = false;
};

/// What Gmsh's recombination into quadrilaterals did, where quads were asked
/// (CadParams::elements, RemeshParams::quads).
struct RecombinationReport {
    /// Gmsh's Blossom algorithm would have ended the process on this model (a std::terminate
    /// out of Gmsh 4.8's meshing loop; gmsh_session.h, generate_surfaces_in_child): its message. The surfaces
    /// were then recombined with Gmsh's simple algorithm, which leaves more triangles. Empty:
    /// Blossom did it (or no quads were asked).
    std::string blossom_failure;
    /// Blossom's quads folded where the surface nearly touches itself (two of its faces
    /// intersect: \p blossom_failure names them), so the surfaces were meshed again with the
    /// simple recombination (CadParams::simple_recombination; prepare_for_layers).
    bool folded = false;
};

/// What mesh_cad read the coordinates in.
struct CadUnits {
    std::string unit;      ///< the unit of the result ("m", "mm", ...); empty for BREP and .geo (none)
    std::string declared;  ///< the unit the file declares; empty if none (or BREP, .geo)
};

/// Read \p path (.step/.stp, .iges/.igs, .brep/.brp, .geo; extension case-insensitive),
/// sew the faces that bound no solid (CadParams::sew_tolerance; not for a .geo, whose script
/// decides), optionally fuse its solids, and mesh its surfaces with Gmsh (surfaces only: generate(2)).
/// Surfaces sharing a curve share its nodes, so a closed solid gives a closed, conforming mesh.
///
/// Patches: one per 2D physical group if the model has any (named by the group, or
/// "physical_<tag>"; a surface in several groups goes to the lowest group tag), and one per
/// surface in no group ("surface_<tag>"); without physical groups, one per CAD surface
/// ("surface_<tag>"); sewn faces keep the tags the file gave them (matched by centre and area),
/// unless the matching fails (SewReport::renumbered). All patches are PatchKind::Wall (the caller assigns kinds). Face
/// node order is Gmsh's (the caller orients). Nodes are numbered in order of first use, faces surface by surface in tag
/// order: the same file and parameters give the same mesh.
///
/// Throws InputError for bad parameters, a missing, unreadable or corrupt file, a .geo script
/// that reaches outside Gmsh's model (CadParams::trust_geo), or a model without surfaces (each
/// naming the file); BackendError when Gmsh fails to mesh or leaves a
/// surface without elements (naming the surface).
/// \p walls, if given, receives what the wall-size cap did; \p sew what the sewing did;
/// \p recombination what the recombination into quads did. Gmsh meshes the surfaces in a child
/// process (generate_in_child, io/gmsh_session.h): its abort or crash is a BackendError naming
/// it, and \p progress stops it at once: Cancelled.
SurfaceMesh mesh_cad(const std::string& path, const CadParams& params, CadUnits* units = nullptr,
                     WallSizeReport* walls = nullptr, SewReport* sew = nullptr,
                     RecombinationReport* recombination = nullptr, const Progress* progress = nullptr);

/// True for the extensions mesh_cad understands (case-insensitive); looks at the name only.
bool is_cad_file(const std::string& path);

}  // namespace strata
