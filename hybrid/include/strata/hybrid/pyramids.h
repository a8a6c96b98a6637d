#pragma once
/// \file
/// The pyramid transition: over every quad of the outermost layer, a pyramid whose apex
/// sits along the quad's normal, so the tetrahedral region sees triangles only.

#include <strata/core/progress.h>
#include <strata/core/surface_mesh.h>

#include <array>
#include <vector>

namespace strata {

struct PyramidParams {
    /// Apex height relative to the quad's size (mean edge length): √2/2 gives equilateral
    /// triangle sides on a square. Shortened where it would hit something.
    double height = 0.5;
    double min_height =
        0.02;  ///< lowest apex, relative to the quad's shortest edge; below it the quad cannot be covered: error
};

struct PyramidLayer {
    std::vector<Vec3> apexes;  ///< one per pyramid
    std::vector<std::array<Index, 5>>
        pyramids;  ///< base = top-surface quad ids (surface node ids), apex = surface.num_points() + k; Gmsh order
    SurfaceMesh surface;  ///< the new outer surface: the top's triangles plus 4 triangles per pyramid; points = top
                          ///< points + apexes
};

/// Cap every quad of \p top (oriented with normals pointing away from the layers, into the
/// region still to mesh) with a pyramid. Apex at centroid + h × unit normal (beside a plane the
/// top's open boundary lies in, a symmetry plane, that the quad leans towards: the normal
/// without its part towards the plane, and the side over the plane keeps off it), with h shortened
/// (down to min_height) where the pyramid would intersect another pyramid or the surface
/// nearby or invert its side faces; throws TopologyError naming the quad if it cannot be
/// placed (a LocalTopologyError carrying the quad's nodes, and after them four nodes for each
/// other quad that cannot be placed against the top surface alone). Triangles of \p top pass
/// through unchanged. \p progress: stage "pyramids".
PyramidLayer build_pyramids(const SurfaceMesh& top, const PyramidParams& params, Progress* progress = nullptr);

}  // namespace strata
