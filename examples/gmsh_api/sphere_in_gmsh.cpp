// A Gmsh user's pipeline with Strata in the middle: build the geometry and its surface mesh
// with Gmsh, let Strata turn the model's mesh into a hybrid volume mesh (prism layers on the
// sphere, pyramids where needed, tetrahedra out to a generated spherical farfield), write it
// with Gmsh. Usage: gmsh_api_example [output.msh]   (default sphere_hybrid.msh)

#include <strata/core/error.h>
#include <strata/gmsh_api/gmsh_api.h>

#include <gmsh.h>

#include <cstdio>
#include <exception>
#include <string>

int main(int argc, char** argv) {
    const std::string output = argc > 1 ? argv[1] : "sphere_hybrid.msh";
    gmsh::initialize();
    int status = 0;
    try {
        gmsh::option::setNumber("General.Terminal", 1);
        gmsh::model::add("sphere");
        gmsh::model::occ::addSphere(0, 0, 0, 1.0);
        gmsh::model::occ::synchronize();
        gmsh::option::setNumber("Mesh.MeshSizeMax", 0.15);  // ~2000 triangles on the unit sphere
        gmsh::model::mesh::generate(2);

        strata::HybridParams params;
        params.layers.distribution.layers = 10;
        params.layers.distribution.first_height = 1e-3;  // model units (the sphere's radius is 1)
        params.layers.distribution.growth = 1.2;
        const strata::HybridReport report = strata::mesh_current_gmsh_model(params);

        gmsh::write(output);
        std::printf("wrote %s: %zu layers, %d nodes kept unsmoothed, %.2f s layers, %.2f s tetrahedra\n",
                    output.c_str(), report.layers.stats.size(), static_cast<int>(report.layers.unsmoothed_nodes),
                    report.seconds_layers, report.seconds_tets);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "gmsh_api_example: %s\n", e.what());
        status = 1;
    }
    gmsh::finalize();
    return status;
}
