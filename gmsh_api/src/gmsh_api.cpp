// The Gmsh-API entry point: the user's current model in, the same model out with a hybrid
// volume mesh. Unlike Strata's readers and writers it does not use a GmshSession (whose scratch
// model would hide the user's) but only Gmsh's lock, and it never initialises Gmsh itself.

#include <strata/frontend/pipeline.h>
#include <strata/gmsh_api/gmsh_api.h>
#include <strata/io/gmsh_model.h>
#include <strata/io/gmsh_session.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

namespace strata {
namespace {

/// The current model's surfaces are all CAD (none discrete, whose mesh may be its only
/// geometry), so Gmsh can mesh them again.
bool model_is_cad(const std::string& source) {
    return gmsh_call(source + ": reading its surfaces", [] {
        gmsh::vectorpair surfaces;
        gmsh::model::getEntities(surfaces, 2);
        for (const auto& [dim, tag] : surfaces) {
            std::string type;
            gmsh::model::getType(dim, tag, type);
            if (type == "Discrete surface") return false;
        }
        return !surfaces.empty();
    });
}

/// The current model's surfaces meshed again, each point's size the smaller of the model's own
/// and what \p points ask there (Gmsh's size callback, divided by Mesh.MeshSizeFactor, which
/// Gmsh multiplies it by), in a child process (generate_in_child); its surface mesh.
SurfaceMesh remesh_model(const std::string& source, const std::vector<SizePoint>& points, double growth,
                         const Progress* progress) {
    const PointSizes sizes(points, growth);
    double factor = 1.0;
    gmsh_call(source + ": reading Mesh.MeshSizeFactor",
              [&] { gmsh::option::getNumber("Mesh.MeshSizeFactor", factor); });
    const std::string context = source + ": meshing the walls again finer for the layers' steps and fans";
    gmsh_call(context, [&] {
        generate_in_child(
            context,
            [&] {
                gmsh::model::mesh::setSizeCallback(
                    [&](int, int, double x, double y, double z) { return sizes(Vec3(x, y, z)) / factor; });
                try {
                    gmsh::model::mesh::clear();
                    gmsh::model::mesh::generate(2);
                } catch (...) {
                    gmsh::model::mesh::removeSizeCallback();
                    throw;
                }
                gmsh::model::mesh::removeSizeCallback();
            },
            progress);
    });
    return surface_from_gmsh_model(source);
}

}  // namespace

HybridReport mesh_current_gmsh_model(const HybridParams& params, const PrepareParams& prepare, Progress* progress,
                                     FirstHeightChoice* first_height) {
    GmshLock lock("strata::mesh_current_gmsh_model");
    std::string model;
    gmsh_call("strata::mesh_current_gmsh_model", [&] { gmsh::model::getCurrent(model); });
    const std::string source = model.empty() ? std::string("the current Gmsh model") : "Gmsh model '" + model + "'";

    // Everything that can fail on the user's input runs before the model is replaced; where its
    // CAD is meshed again for the layers, a failure puts the user's mesh back.
    Request request;
    request.surface = surface_from_gmsh_model(source);
    request.source = source;
    request.prepare = prepare;
    request.mesh = params;
    request.options = options_of(params, prepare);
    std::vector<char> user_mesh;
    if (model_is_cad(source))
        request.remesh = [&](const std::vector<SizePoint>& points, double growth) {
            if (user_mesh.empty()) user_mesh = gmsh_call(source, [] { return pack_model_mesh(); });
            return remesh_model(source, points, growth, progress);
        };
    Result result;
    try {
        result = run(request, progress);
    } catch (...) {
        if (!user_mesh.empty()) gmsh_call("putting back the mesh of " + source, [&] { unpack_model_mesh(user_mesh); });
        throw;
    }
    user_mesh = {};
    request.surface.reset();  // both surfaces freed before Gmsh gets its copy of the volume mesh
    result.surface = SurfaceMesh{};

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
    add_volume_to_gmsh_model(result.mesh);
    if (first_height) *first_height = result.first_height;
    return std::move(result.hybrid);
}

}  // namespace strata
