// The Gmsh-API entry point: the user's current model in, the same model out with a hybrid
// volume mesh. Unlike Strata's readers and writers it does not use a GmshSession (whose scratch
// model would hide the user's) but only Gmsh's lock, and it never initialises Gmsh itself.

#include <strata/gmsh_api/gmsh_api.h>
#include <strata/io/gmsh_model.h>
#include <strata/io/gmsh_session.h>

#include <set>
#include <string>

namespace strata {

HybridReport mesh_current_gmsh_model(const HybridParams& params, const PrepareParams& prepare, Progress* progress) {
    GmshLock lock("strata::mesh_current_gmsh_model");
    std::string model;
    gmsh_call("strata::mesh_current_gmsh_model", [&] { gmsh::model::getCurrent(model); });
    const std::string source = model.empty() ? std::string("the current Gmsh model") : "Gmsh model '" + model + "'";

    // Everything that can fail on the user's input runs before the model is touched.
    SurfaceMesh surface = prepare_mesh(surface_from_gmsh_model(source), prepare, source);
    HybridReport report;
    const VolumeMesh mesh = build_hybrid_mesh(surface, params, progress, &report);
    surface = SurfaceMesh{};  // freed before Gmsh gets its copy of the volume mesh

    gmsh_call("replacing the mesh of " + source, [] {
        // Gmsh 4.8's removePhysicalGroups keeps the groups' names, and a kept name silently
        // blocks setPhysicalName for a new group (the user's "hull" patch would come back
        // unnamed): the names go too.
        gmsh::vectorpair groups;
        gmsh::model::getPhysicalGroups(groups);
        std::set<std::string> names;
        for (const auto& [dim, tag] : groups) {
            std::string name;
            gmsh::model::getPhysicalName(dim, tag, name);
            if (!name.empty()) names.insert(name);
        }
        gmsh::model::mesh::clear();
        gmsh::model::removePhysicalGroups();
        for (const std::string& name : names) gmsh::model::removePhysicalName(name);
    });
    add_volume_to_gmsh_model(mesh);
    return report;
}

}  // namespace strata
