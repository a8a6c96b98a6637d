#pragma once
/// \file
/// CAD input (STEP, IGES, BREP through Gmsh's OpenCASCADE kernel, and Gmsh .geo scripts),
/// surface-meshed with Gmsh.

#include <strata/geometry/surface_mesh.h>

#include <string>
#include <vector>

namespace strata {

enum class SurfaceElements {
    Triangles,  ///< all triangles (default)
    Quads,      ///< recombined into quadrilaterals everywhere (Blossom; a few triangles may remain)
    Mixed,      ///< quads on CadParams::quad_surfaces, triangles elsewhere
};

/// Parameters of CAD surface meshing. Sizes are in the model's units.
struct CadParams {
    double size = 0.0;                ///< target element size; 0 = 1/20 of the bounding-box diagonal
    double size_min = 0.0;            ///< lower bound for curvature refinement; 0 = size / 20
    int curvature_points = 0;         ///< elements per 2π of curvature radius (0 = off)
    SurfaceElements elements = SurfaceElements::Triangles;
    std::vector<int> quad_surfaces;   ///< CAD surface tags meshed with quads when Mixed
    bool fuse = false;                ///< fuse all solids into one body first (Boolean union)
    int algorithm = 6;                ///< Gmsh Mesh.Algorithm (6 = Frontal-Delaunay)
};

/// Read \p path (.step/.stp, .iges/.igs, .brep/.brp, .geo), optionally fuse its solids,
/// and mesh its surfaces. Patches: one per 2D physical group if the model has any, else one
/// per CAD surface ("surface_<tag>"). When solids are fused, internal faces disappear and
/// only the boundary of the union is meshed. Throws InputError for an unreadable or empty
/// model (naming the file), BackendError when Gmsh fails to mesh (naming the surface if known).
SurfaceMesh mesh_cad(const std::string& path, const CadParams& params);

/// True for the extensions mesh_cad understands.
bool is_cad_file(const std::string& path);

}  // namespace strata
