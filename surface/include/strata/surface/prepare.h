#pragma once
/// \file
/// The geometry stage as one call: read whatever the user has, assign patch kinds, merge,
/// check, orient. The result is what module/ extrudes.

#include <strata/core/progress.h>
#include <strata/core/surface_mesh.h>
#include <strata/geometry/check.h>
#include <strata/geometry/fill_holes.h>
#include <strata/geometry/fuse.h>
#include <strata/geometry/short_edges.h>
#include <strata/geometry/topology.h>
#include <strata/geometry/wrap.h>
#include <strata/surface/cad.h>
#include <strata/surface/remesh.h>

#include <string>
#include <utility>
#include <vector>

namespace strata {

struct PrepareParams {
    CadParams cad;                                               ///< used for CAD input only
    std::vector<std::pair<std::string, PatchKind>> patch_kinds;  ///< --patch NAME=KIND
    /// Patches renamed (--patch NAME=KIND:NEW), after their kinds are set: the new name a valid
    /// OpenFOAM and CGNS one (a letter or _, then letters, digits, _ or -, at most 32); patches
    /// given one name become one patch (their kinds must agree).
    std::vector<std::pair<std::string, std::string>> patch_names;
    double merge_tolerance = 1e-9;                               ///< relative to the bounding-box diagonal
    /// The fluid is inside the closed walls (a duct, a wind tunnel), not around them: the
    /// outermost closed surface points inward (orient_surface), and build_hybrid_mesh fills it
    /// instead of generating a farfield around it.
    bool internal_flow = false;
    /// Every coordinate multiplied by this after reading (any input, after CAD units): for a
    /// surface mesh in another unit than wanted (STL and MSH carry none). Positive, finite.
    double scale = 1.0;
    /// Closed components of walls that overlap (separate STL parts, several inputs) are replaced
    /// by their union (fuse_components, exact corefinement), each face keeping its patch; where
    /// bodies touch along a common face, the faces there go first (touching_faces). CAD
    /// solids of one file are fused by CadParams::fuse (OpenCASCADE) before meshing.
    bool fuse = false;
    /// Mesh the surface again with Gmsh (remesh_surface, with \p remeshing), after fusing: for
    /// a dirty STL or MSH whose needle faces would stop the layers, and for the cuts a union
    /// leaves. CAD input is meshed well by Gmsh in the first place; the option applies to it too.
    bool remesh = false;
    RemeshParams remeshing;
    /// Replace the surface by its alpha wrap (wrap_surface, with \p wrapping) before anything
    /// else checks it: for a surface that cannot be repaired in place (non-manifold edges, holes,
    /// self-intersections, parts through or against each other, faces given twice). Walls only
    /// (a wrap closes a symmetry plane's cut). The wrap is one closed body round all the input.
    bool wrap = false;
    WrapParams wrapping;
    /// Edges shorter than this share of their local size are collapsed (collapse_short_edges),
    /// after fusing: the small edges of a CAD model's sliver faces and Boolean seams, whose
    /// needle faces cap the layer cells on them. Not with \p remesh, which rebuilds the surface
    /// from the input's own edges (and made worse surfaces of collapsed ones). In [0, 0.5]; 0: off.
    double collapse_ratio = 0.01;
    /// Boundary loops of at most this many edges are closed by triangles (fill_holes, after the
    /// checks and before orienting): the few triangles an STL lost. 0 (default): none, as a
    /// surface's openings may be meant (a half model's cut). At most 10000.
    int fill_holes = 0;
    /// With fill_holes: each loop closed by a cap of its own (cap_holes: patches cap_1, cap_2,
    /// ... of kind Other, refined inside), for the openings of a vessel or a duct; patch_kinds
    /// and patch_names may name the caps.
    bool caps = false;
};

/// What prepare_surface did, for the CLI's summary.
struct PrepareReport {
    Index merged_nodes = 0;             ///< nodes removed by merging
    Index collapsed_faces = 0;          ///< faces with a repeated node removed (remove_collapsed_faces)
    Index duplicate_faces = 0;          ///< faces written twice, the copies removed (remove_duplicate_faces)
    Index t_junctions = 0;              ///< faces split where a node lay inside their open edge (split_t_junctions)
    /// Cracks closed where a surface left open by them alone (every edge then bounds two faces)
    /// had each side of an edge meshed with nodes of its own (stitch_cracks, nodes within a
    /// tenth of the edge beside them).
    Stitching cracks;
    /// Sheets hanging off the surface on edges of three or more faces (a flap, a zero-thickness
    /// fin) removed where that leaves every edge of two faces at most (remove_hanging_sheets).
    HangingSheets hanging;
    CadUnits units;                     ///< CAD input: the unit read in and the one the file declares
    WallSizeReport walls;               ///< CAD input: what CadParams::max_aspect_ratio did (sizes as CadParams's)
    SewReport sew;                      ///< CAD input: what CadParams::sew_tolerance did (several files: summed)
    RecombinationReport recombination;  ///< quads asked (CAD or PrepareParams::remesh): what Gmsh's recombination did
    StepSizeReport steps;               ///< CAD input: what CadParams::step_quality did (prepare_for_layers)
    AspectRemeshReport aspect_remesh;   ///< CAD input: the walls meshed again for the mesh's flat cells (run)
    double scale = 1.0;                 ///< PrepareParams::scale applied
    Index fused_components = 0;         ///< components replaced by their union (PrepareParams::fuse)
    Index fused_slivers = 0;            ///< flat slivers of the union flipped away (flip_flat_triangles)
    Index touching_faces = 0;           ///< faces removed where bodies touch back to back (PrepareParams::fuse)
    bool internal_flow = false;         ///< PrepareParams::internal_flow: oriented for the fluid inside the walls
    ShortEdgeReport short_edges;        ///< PrepareParams::collapse_ratio: the edges collapsed
    HoleReport holes;                   ///< PrepareParams::fill_holes: the loops closed and left
    bool wrapped = false;               ///< PrepareParams::wrap done; \p wrap says how far from the input
    /// PrepareParams::fuse met parts that touch along a line or a point only, which no union
    /// joins, and wrapped the walls instead (\p wrapped and \p wrap say how)
    bool touching_wrapped = false;
    WrapReport wrap;
    bool remeshed = false;              ///< PrepareParams::remesh done; \p remesh says how
    RemeshReport remesh;
    OrientReport orient;
};

/// Read \p path (CAD: mesh_cad; .stl: read_stl; .msh: read_msh), then apply patch kinds:
/// a patch whose name contains "symmetry" or "farfield" (any case) gets that kind, every
/// other patch is a wall, and --patch mappings override (an unknown name is an InputError
/// listing the patches). Then merge_coincident_nodes, check_surface, orient_surface (all of
/// this after reading is prepare_mesh). Throws InputError for a missing file or an unknown
/// extension.
SurfaceMesh prepare_surface(const std::string& path, const PrepareParams& params, PrepareReport* report = nullptr,
                            Progress* progress = nullptr);

/// Several inputs as one surface (any mix of CAD and surface meshes): each read as
/// prepare_surface reads it, their faces and patches put together (a patch keeps its name; one
/// that an earlier input already has gets the file's name after it), then prepare_mesh on the
/// whole, so components that touch share their nodes. CAD files are read in the unit of the
/// first one that declares a unit (CadParams::units, if given, for all); \p report->units is
/// that unit. InputError naming the file for any that cannot be read; none given: InputError.
SurfaceMesh prepare_surfaces(const std::vector<std::string>& paths, const PrepareParams& params,
                             PrepareReport* report = nullptr, Progress* progress = nullptr);

/// The part of prepare_surface after reading, for a mesh that comes from elsewhere (the
/// current Gmsh model, a caller's own reader): assign_patch_kinds with \p params.patch_kinds,
/// with \p params.wrap the alpha wrap (InputError if a patch is not a wall's), then merge_coincident_nodes (\p params.merge_tolerance), remove_collapsed_faces (counted in
/// \p report->collapsed_faces), remove_duplicate_faces (\p report->duplicate_faces), split_t_junctions
/// (\p report->t_junctions), stitch_cracks where that alone closes the surface (\p report->cracks), remove_hanging_sheets (\p report->hanging), with \p params.fuse the
/// touching_faces removed (counted in \p report->touching_faces), check_surface (whose TopologyError, without \p
/// params.fuse, says where bodies touch and suggests fusing them), fill_holes (\p params.fill_holes, \p
/// report->holes), orient_surface, and if asked fuse_components, then
/// collapse_short_edges (\p params.collapse_ratio, unless remeshing) and remesh_surface (each followed by the checks).
/// \p source names the mesh in errors ("wing.stl", "Gmsh model 'sphere'"). InputError if
/// \p raw has no faces.
SurfaceMesh prepare_mesh(SurfaceMesh raw, const PrepareParams& params, const std::string& source,
                         PrepareReport* report = nullptr, Progress* progress = nullptr);

/// The kind of the patch named \p name by the rule of prepare_surface: the last mapping of
/// \p kinds that names it, else symmetry or farfield if the name contains the word (any case),
/// else a wall.
PatchKind patch_kind_of(const std::string& name, const std::vector<std::pair<std::string, PatchKind>>& kinds);

/// Rename \p mesh's patches by \p names (old name, new name), merging patches given one name;
/// InputError naming \p source for an unknown patch, a name OpenFOAM or CGNS would not take, or
/// patches of different kinds given one name.
void rename_patches(SurfaceMesh& mesh, const std::vector<std::pair<std::string, std::string>>& names,
                    const std::string& source);

/// Apply the naming rule and mappings above to \p mesh's patch table.
void assign_patch_kinds(SurfaceMesh& mesh, const std::vector<std::pair<std::string, PatchKind>>& kinds,
                        const std::string& source);

}  // namespace strata
