#pragma once
/// \file
/// A surface mesh made again with Gmsh: a dirty STL or MSH (needle triangles from a CAD tool's
/// export, the cuts of a Boolean union) rebuilt as a discrete CAD model and meshed anew, the
/// route of Gmsh's own STL-remeshing tutorial: classifySurfaces (sharp edges and patch
/// boundaries become curves, surfaces are split until each has one parametrization),
/// createGeometry, generate(2). The new nodes lie on the old faces: the shape is kept, its
/// triangulation is not.

#include <strata/core/surface_mesh.h>
#include <strata/surface/cad.h>

#include <string>

namespace strata {

/// Parameters of remesh_surface. Sizes are in the mesh's unit.
struct RemeshParams {
    /// Maximum element size (Gmsh's Mesh.MeshSizeMax). 0 = the median edge length of the input,
    /// so the surface keeps its resolution and loses its needles.
    double size = 0.0;
    /// Minimum element size; 0 = size / 20 with curvature refinement, no floor otherwise.
    double size_min = 0.0;
    /// Curvature refinement: elements per 2π radians (Mesh.MeshSizeFromCurvature); 0 = off.
    int curvature_points = 0;
    /// An edge whose two faces' normals differ by more than this (degrees) is a sharp feature
    /// the new mesh keeps as a curve. In (0, 180).
    double feature_angle_deg = 40.0;
    /// Recombine into quadrilaterals (Blossom), as CAD meshing does with quads asked.
    bool quads = false;
    /// With quads: Gmsh's simple recombination instead of Blossom (CadParams::simple_recombination).
    bool simple_recombination = false;
    /// Gmsh 2D algorithm: 1 MeshAdapt, 2 Automatic, 5 Delaunay, 6 Frontal-Delaunay, 9 packing of
    /// parallelograms (the values CadParams::algorithm accepts).
    int algorithm = 6;
    /// The first layer's height and the limit on its cells' OpenFOAM aspect ratio, in the
    /// mesh's unit, as for CAD (CadParams::first_height, max_aspect_ratio, fan_angle_deg,
    /// wall_faces_budget): the wall patches' new surfaces whose first layer would be flatter are
    /// meshed finer (the whole route run again with the sizes). Set by the front-ends from the
    /// layers; first_height 0: no limit.
    double first_height = 0.0;
    double max_aspect_ratio = 1000.0;
    double fan_angle_deg = 0.0;
    double wall_faces_budget = 200000;
    /// The time budget of Gmsh's split of the surface for its parametrization in each attempt
    /// (tried in a child process first: on poor triangles it can go on for ever), in CPU seconds
    /// of that child (DeadlineProgress: the same on a loaded machine as on an idle one, so the
    /// mesh does not depend on the load); 0: 20 s and 2 ms per triangle. Where two attempts in a
    /// row run out of it, no more are made: the input's triangles, not the angle, are at fault.
    double classify_seconds = 0.0;
    /// The time budget of Gmsh's meshing of the new surfaces in each attempt, in CPU seconds of
    /// its child process (whose mesh is brought back: where the surface is poorly parametrized
    /// Gmsh can refine for ever, or abort the process); 0: 60 s and 1 ms per face expected (four
    /// per size squared of the input's area, and the walls' budget where they are meshed finer).
    /// Runs out of it count with the classification's.
    double mesh_seconds = 0.0;
};

/// What remesh_surface did, for the summary.
struct RemeshReport {
    Index faces_before = 0;
    Index faces_after = 0;
    Index surfaces = 0;        ///< the discrete surfaces Gmsh meshed (≥ one per patch)
    double size = 0.0;         ///< the maximum element size used
    bool size_halved = false;  ///< size is half the input's median edge: at the median every feature angle failed
    double asked_feature_angle_deg = 0.0;  ///< RemeshParams::feature_angle_deg
    double feature_angle_deg = 0.0;        ///< the feature angle that gave the result
    int attempts = 0;                      ///< feature angles tried (1: the one asked worked)
    Index split_edges = 0;                 ///< input edges longer than the size, bisected first (split_long_edges)
    Index needles_before = 0;              ///< faces with a corner under kNeedleCornerDeg, before
    Index needles_after = 0;               ///< and after
    double sharpest_before_deg = 180.0;    ///< sharpest corner before
    double sharpest_after_deg = 180.0;     ///< and after
    WallSizeReport walls;                  ///< what RemeshParams::max_aspect_ratio did
    RecombinationReport recombination;     ///< RemeshParams::quads: what Gmsh's recombination did
};

/// Mesh the surface \p mesh again (triangles, or quadrilaterals if asked). Each patch keeps its
/// name and kind: patch boundaries are curves of the new model, which the new faces do not
/// cross, and the nodes on them are shared by the faces either side. Each new face keeps the
/// orientation of the old faces under it. Needs a surface that passed check_surface.
///
/// Gmsh keeps a sharp edge only where its two sides are different surfaces of its
/// classification; a wing's trailing edge, whose sides meet round the leading edge, would be
/// meshed across and fold. feature_cuts.h's cuts are given to Gmsh with the patch seams, so
/// every long sharp edge whose faces' normals differ by over 100 degrees is kept. Gmsh's
/// parametrization can still fold elsewhere: faces come out inverted against the old surface
/// or with no area. The result is checked for both, face by face against the old faces
/// of its surface; where it fails, the feature angle is lowered (×0.75, down to half the one
/// asked) so that more edges become curves, and the report says which angle gave the result.
/// Throws InputError for bad parameters, BackendError (naming \p source, how many faces and
/// where the first is) when every angle fails.
SurfaceMesh remesh_surface(const SurfaceMesh& mesh, const RemeshParams& params, const std::string& source,
                           RemeshReport* report = nullptr);

}  // namespace strata
