#pragma once
/// \file
/// The tetrahedral fill: the region enclosed by a closed triangulated boundary is meshed with
/// tetrahedra, the boundary preserved exactly, by TetGen 1.5 (Debian's libtet, loaded privately
/// at run time, not linked: hybrid/src/tetgen_library.cpp says why) or by Gmsh's HXT (parallel;
/// hybrid/src/hxt_library.cpp says how it is called).

#include <strata/core/progress.h>
#include <strata/core/surface_mesh.h>

#include <array>
#include <string_view>
#include <vector>

namespace strata {

/// Which mesher fills the region. TetGen: one thread, the same bytes for any thread count.
/// HXT: Delaunay, refinement and improvement on every thread (Strata's thread count); the same
/// bytes for the same boundary and thread count, other tetrahedra for another count.
enum class TetMesher { TetGen, Hxt };
std::string_view to_string(TetMesher mesher);
/// "tetgen" or "hxt"; InputError otherwise.
TetMesher parse_tet_mesher(std::string_view text);

struct TetFillParams {
    TetMesher mesher = TetMesher::TetGen;
    /// HXT's threads (0: OpenMP's count, which Strata's --threads sets); TetGen has one.
    int threads = 0;
    double radius_edge = 1.5;   ///< quality bound (TetGen -q), ≥ 1.2 recommended; TetGen only
    double min_dihedral = 0.0;  ///< extra dihedral bound in degrees (-q/ratio/angle); 0 = TetGen's default
    /// Largest dihedral angle, degrees, TetGen's optimisation (flips, smoothing) works down to
    /// (-o/angle); 0 = TetGen's own (165). 150 lifts the worst free tetrahedra (sphere 0.063 ->
    /// 0.102, hemisphere-cylinder 0.035 -> 0.045, fused wing-fuselage 7e-6 -> 1.4e-4 scaled
    /// Jacobian) at no measurable cost; tetrahedra whose four corners are all on the layer top
    /// cannot be improved without points on it, which -Y forbids.
    double max_dihedral = 150.0;
    bool refine = true;       ///< add interior Steiner points for quality and size (never on the boundary)
    double max_volume = 0.0;  ///< global volume bound per tetrahedron (-a); 0 = none
    /// Size grading: target edge length grows linearly with distance from the boundary faces
    /// whose patch is not Farfield (the layer top): h(d) = h_wall + growth × d, capped at the
    /// farfield's own edge length. 0 = no sizing field (TetGen's quality bound alone
    /// then sets the sizes, which grow much faster).
    double growth = 0.3;
    /// Sample the size field on a background mesh (a quality-only TetGen run), so the growth
    /// holds throughout; false: at the boundary points only, TetGen interpolating linearly
    /// between them. TetGen locates every point in the background mesh, and a point on its hull
    /// (each point of a symmetry plane) costs a search of all its tets: with large planes on
    /// the boundary the background mesh takes minutes, and the boundary points (the planes'
    /// own points graded by the same field) carry the grading well enough.
    bool background_mesh = true;
};

/// The tetrahedra filling a region.
struct TetFill {
    std::vector<Vec3> points;                ///< the boundary's points first (same ids), then Steiner points
    std::vector<std::array<Index, 4>> tets;  ///< Gmsh order, positive volume
};

/// Mesh the region bounded by \p boundary (triangles only; closed, manifold; orientation
/// with normals pointing OUT of the region to fill). \p holes: one point inside each closed
/// part of the boundary that bounds a cavity not to mesh (e.g. inside the body with its
/// layers). The boundary is preserved: no Steiner point on it (TetGen -Y), its triangles are
/// exactly faces of the result. TetGen's failures become BackendError naming the cause
/// (self-intersecting boundary, ...) and what to do; where it stops on one of its internal
/// checks, or finds the boundary crossing or nearly touching itself, while recovering a
/// boundary face or edge, a LocalTopologyError whose nodes are that
/// face's (boundary ids; its run repeated with TetGen's trace finds it), so that a caller can
/// change the boundary there and try again. TetGen runs in a child process: its crash is a
/// BackendError (a LocalTopologyError where its trace places it), and \p progress can stop it
/// (Cancelled within 0.1 s) and hears TetGen's phases as they begin ("tetrahedra", each at its
/// usual share of the fill: the background mesh of the sizing up to 0.2, then of the main run
/// the boundary's recovery from 0.32, the refinement from 0.36, the optimisation from 0.94).
/// With params.mesher = Hxt the region filled is the one bounded by every connected part of the
/// boundary together (what one part encloses alone is left empty; \p holes are not needed), the
/// sizes those of TetGen's sizing (growth, max_volume; the TetGen bounds radius_edge and the
/// dihedral angles do not apply). HXT runs in this process
/// (\p progress is asked before and after it) and its failures, a boundary it cannot recover
/// without a point on it among them, are BackendError saying to use TetGen.
TetFill fill_with_tets(const SurfaceMesh& boundary, const std::vector<Vec3>& holes, const TetFillParams& params,
                       Progress* progress = nullptr);

}  // namespace strata
