// apollo_example: the paper's first example (section 5.1) end to end. Builds the notional
// Apollo command + service module, extrudes 30 layers of hexahedra and prisms, validates
// them, writes them, and prints what the paper shows: the 20-valent nose, the cell counts,
// the quality per layer, and the nozzle-exit nodes held in the exit plane.
//   apollo_example [OUT.msh]        (default apollo_layers.msh)

#include "apollo/apollo_surface.h"

#include <strata/core/cell_quality.h>
#include <strata/core/error.h>
#include <strata/core/validate.h>
#include <strata/geometry/topology.h>
#include <strata/io/write_volume.h>
#include <strata/module/layers.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    using namespace strata;
    const std::string out = argc > 1 ? argv[1] : "apollo_layers.msh";
    try {
        const SurfaceMesh wall = apollo_surface();
        // The nose apex is node 0: its valence is the number of faces around it.
        Index nose_valence = 0;
        for (Index f = 0; f < wall.num_faces(); ++f)
            nose_valence += static_cast<Index>(std::count(wall.face_begin(f), wall.face_end(f), Index{0}));
        std::printf("surface: %d nodes, %d quads, %d triangles, nose node valence %d\n",
                    static_cast<int>(wall.num_points()), static_cast<int>(wall.num_quads()),
                    static_cast<int>(wall.num_triangles()), static_cast<int>(nose_valence));

        const LayerParams params = apollo_layer_params();
        const LayerMesh lm = extrude_layers(wall, params);
        const auto& d = params.distribution;
        std::printf("layers: %d (%s, first height %.3g m, total %.3g m, %d-%d sweeps), %zu hexahedra, %zu prisms\n",
                    lm.layers(), std::string(to_string(d.kind)).c_str(), d.first_height, d.thickness, params.sweeps,
                    params.max_sweeps, lm.mesh.hexes.size(), lm.mesh.prisms.size());
        // Per layer, the hexahedra and the nose prisms apart: the prisms' sharpest corner is
        // the nose triangles' 18° apex angle (scaled Jacobian sin 18° = 0.309 at best).
        const std::size_t nl = static_cast<std::size_t>(lm.layers());
        std::vector<double> hex_min(nl, 1.0), prism_min(nl, 1.0);
        for (const auto& c : lm.mesh.hexes) {
            const std::size_t k = static_cast<std::size_t>(lm.level_of(c[0]));  // level of the bottom face
            hex_min[k] = std::min(hex_min[k], hex_min_scaled_jacobian(lm.mesh.points, c));
        }
        for (const auto& c : lm.mesh.prisms) {
            const std::size_t k = static_cast<std::size_t>(lm.level_of(c[0]));
            prism_min[k] = std::min(prism_min[k], prism_min_scaled_jacobian(lm.mesh.points, c));
        }
        std::printf("layer  height [m]  sweeps  min SJ  (hexes  prisms)  mean SJ  max orth [deg]\n");
        for (std::size_t k = 0; k < nl; ++k) {
            const LayerStats& s = lm.stats[k];
            std::printf("%5zu  %10.4e  %6d  %6.4f  (%6.4f  %6.4f)  %7.4f  %8.2f\n", k + 1, s.height, s.sweeps,
                        s.min_scaled_jacobian, hex_min[k], prism_min[k], s.mean_scaled_jacobian,
                        s.max_orthogonality_deg);
        }

        const ValidationReport report = require_valid_mesh(lm.mesh, "apollo layers");
        std::printf("valid: %d cells, min scaled Jacobian %.4f, volume %.6g m^3 (boundary %.6g m^3)\n",
                    static_cast<int>(report.cells), report.min_scaled_jacobian, report.cell_volume,
                    report.boundary_volume);

        // The nozzle exit lip is the surface's one open boundary; its nodes stay in x = x_exit.
        const Csr loops = boundary_loops(wall);
        if (loops.rows() != 1) throw TopologyError("apollo surface: expected one open boundary (the nozzle exit)");
        const double x_exit = wall.points[loops.values.front()].x();
        double deviation = 0.0;
        for (int k = 0; k <= lm.layers(); ++k)
            for (const Index i : loops.values)
                deviation = std::max(
                    deviation, std::abs(lm.mesh.points[static_cast<std::size_t>(lm.level_node(k, i))].x() - x_exit));
        std::printf("nozzle exit: %d nodes at x = %.6f m, max |x - x_exit| over all %d levels = %.3g m\n",
                    static_cast<int>(loops.values.size()), x_exit, lm.layers() + 1, deviation);

        write_volume(lm.mesh, out);
        std::printf("wrote %s\n", out.c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "apollo_example: %s\n", e.what());
        return 1;
    }
    return 0;
}
