#pragma once
/// \file
/// Private to strata_hybrid: Gmsh's HXT tetrahedral mesher (Marot, Pellerin & Remacle 2019),
/// called directly in the libgmsh Strata links, not through Gmsh's model. Why directly, and
/// what is assumed of libgmsh: hxt_library.cpp.

#include <strata/core/progress.h>

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace strata::hxt {

/// A closed triangulated boundary as HXT takes it: points, triangles, and each triangle's
/// surface (any numbers); the one volume to fill is the region bounded by all of \p surfaces.
struct Input {
    std::vector<std::array<double, 3>> points;
    std::vector<double> sizes;  ///< target edge length at each point (> 0)
    std::vector<std::array<std::uint32_t, 3>> triangles;
    std::vector<std::uint32_t> triangle_surface;
    std::vector<std::uint32_t> surfaces;  ///< the surfaces bounding the volume to fill (each once)
};

/// The volume's tetrahedra: the input's points first (unchanged, same ids), then the points HXT
/// added, in its order; the tets as HXT orients them, those of other regions (a cavity bounded by
/// fewer surfaces, the outside) left out.
struct Output {
    std::vector<std::array<double, 3>> points;
    std::vector<std::array<std::uint32_t, 4>> tets;
};

/// Target edge length at each of \p n points (x, y, z at 3i..3i+2) into \p sizes[i]; what it
/// throws stops HXT (at its next round of refinement) and run() throws it.
using SizeFunction = std::function<void(const double* xyz, std::size_t n, double* sizes)>;

/// HXT's own improvement (its `optimize`) is not run: on the layer top it spends its time on
/// tets whose four corners are on the boundary, which no flip of the interior can mend (the
/// airliner stand-in's tetrahedra: 37.2 s with it, 9.8 s without), and Strata's improve_tets follows either mesher.
struct Options {
    int threads = 1;     ///< HXT's threads for every phase; the output repeats for the same count
    bool refine = true;  ///< insert interior points down to the sizes
};

/// HXT on \p in: Delaunay of its points, boundary recovery, refinement with \p size at each new
/// point (none: sizes interpolated from the input's). Under a process-wide lock, in a forked child
/// process (run_in_child; in this one where fork() fails): HXT ends its process with exit() where
/// it fails inside a parallel loop, and \p progress can stop it (Cancelled within 0.1 s).
/// BackendError with HXT's own message where it fails (a boundary it cannot recover, a
/// degenerate configuration, out of memory), crashes, or where this libgmsh is not the one whose
/// HXT this was written for.
Output run(const Input& in, const SizeFunction& size, const Options& options, const Progress* progress = nullptr);

/// True where this build can call HXT (it was built against the Gmsh whose HXT it declares).
bool available();

}  // namespace strata::hxt
