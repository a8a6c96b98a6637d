// Strata's meshes -> the current Gmsh model (gmsh_model.h): discrete entities, nodes, elements
// and physical groups, for the writers (a scratch model written to a file) and the Gmsh-API
// entry point (the user's model). Gmsh's 1-based size_t tags stay in this file.

#include <strata/core/mesh_check.h>
#include <strata/io/gmsh_model.h>
#include <strata/io/gmsh_session.h>

#include "gmsh_element_types.h"

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <utility>

namespace strata {
namespace {

using namespace gmsh_types;

/// Add the faces \p faces of \p mesh to surface \p surface as triangles, then quadrangles;
/// element tag = element_base + face index + 1, node tag = node_base + node index + 1.
void add_faces(const SurfaceMesh& mesh, const Index* faces, const Index* end, int surface, std::size_t element_base,
               std::size_t node_base) {
    std::vector<std::size_t> tags, nodes;
    for (Index n : {3, 4}) {
        tags.clear();
        nodes.clear();
        for (const Index* f = faces; f != end; ++f) {
            if (mesh.face_size(*f) != n) continue;
            tags.push_back(element_base + static_cast<std::size_t>(*f) + 1);
            for (const Index* v = mesh.face_begin(*f); v != mesh.face_end(*f); ++v)
                nodes.push_back(node_base + static_cast<std::size_t>(*v) + 1);
        }
        if (!tags.empty()) gmsh::model::mesh::addElementsByType(surface, n == 3 ? kTriangle3 : kQuad4, tags, nodes);
    }
}

/// Add one block of cells to volume \p volume as Gmsh elements of \p type; tags first_tag,
/// first_tag + 1, ...; node i is Gmsh node node_base + i + 1.
template <std::size_t N>
void add_cells(const std::vector<std::array<Index, N>>& cells, int volume, int type, std::size_t first_tag,
               std::size_t node_base) {
    if (cells.empty()) return;
    std::vector<std::size_t> tags(cells.size());
    std::iota(tags.begin(), tags.end(), first_tag);
    std::vector<std::size_t> nodes;
    nodes.reserve(cells.size() * N);
    for (const auto& c : cells)
        for (Index v : c) nodes.push_back(node_base + static_cast<std::size_t>(v) + 1);  // Gmsh order already
    gmsh::model::mesh::addElementsByType(volume, type, tags, nodes);
}

/// Largest tag in \p dim_tags (0 if empty).
int max_tag(const gmsh::vectorpair& dim_tags) {
    int m = 0;
    for (const auto& dt : dim_tags) m = std::max(m, dt.second);
    return m;
}

/// The current model's named physical groups: (dim, name) -> tag.
using GroupNames = std::map<std::pair<int, std::string>, int>;
GroupNames named_groups() {
    gmsh::vectorpair groups;
    gmsh::model::getPhysicalGroups(groups);
    GroupNames names;
    for (const auto& [dim, tag] : groups) {
        std::string name;
        gmsh::model::getPhysicalName(dim, tag, name);
        if (!name.empty()) names.emplace(std::make_pair(dim, name), tag);
    }
    return names;
}

/// Name physical group (\p dim, \p tag) \p name. Gmsh 4.8 keeps one group per name and
/// dimension and silently ignores setPhysicalName for a name it already knows, including a
/// stale one: removePhysicalGroups keeps the removed groups' names. So the result is checked,
/// and a stale name is removed (removePhysicalName drops it in every dimension: the live groups
/// of other dimensions in \p live that carry it get it back).
void name_group(int dim, int tag, const std::string& name, const GroupNames& live) {
    gmsh::model::setPhysicalName(dim, tag, name);
    std::string got;
    gmsh::model::getPhysicalName(dim, tag, got);
    if (got == name) return;
    gmsh::model::removePhysicalName(name);
    gmsh::model::setPhysicalName(dim, tag, name);
    for (const auto& [key, other] : live)
        if (key.second == name) gmsh::model::setPhysicalName(key.first, other, name);
    got.clear();
    gmsh::model::getPhysicalName(dim, tag, got);
    if (got != name)
        throw BackendError("Gmsh did not name physical group " + std::to_string(tag) + " (dimension " +
                           std::to_string(dim) + ") '" + name + "'");
}

/// The tags a volume added to the current model starts after: Gmsh 4.8 has no getMaxNodeTag,
/// so the node and element tags are read, which costs only when a mesh exists. In a fresh
/// model (write_volume) every base is 0.
struct TagBases {
    std::size_t node = 0, element = 0;
    int surface = 0, volume = 0, group2 = 0, group3 = 0;
};

TagBases tags_in_use() {
    TagBases b;
    std::vector<std::size_t> tags;
    std::vector<double> xyz, parametric;
    gmsh::model::mesh::getNodes(tags, xyz, parametric, -1, -1, false, false);
    for (std::size_t t : tags) b.node = std::max(b.node, t);
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> elem_tags, elem_nodes;
    gmsh::model::mesh::getElements(types, elem_tags, elem_nodes, -1, -1);
    for (const auto& block : elem_tags)
        for (std::size_t t : block) b.element = std::max(b.element, t);
    gmsh::vectorpair surfaces, volumes, groups2, groups3;
    gmsh::model::getEntities(surfaces, 2);
    gmsh::model::getEntities(volumes, 3);
    gmsh::model::getPhysicalGroups(groups2, 2);
    gmsh::model::getPhysicalGroups(groups3, 3);
    b.surface = max_tag(surfaces);
    b.volume = max_tag(volumes);
    b.group2 = max_tag(groups2);
    b.group3 = max_tag(groups3);
    return b;
}

/// A name is one group per dimension in Gmsh: a patch (or "fluid") cannot join a group the
/// model already has.
void check_names_free(const SurfaceMesh& b, const Csr& patch_faces, const GroupNames& live) {
    auto check_free = [&](int dim, const std::string& name) {
        if (auto it = live.find({dim, name}); it != live.end())
            throw InputError("the current Gmsh model already has a " + std::to_string(dim) +
                             "D physical group named '" + name + "' (tag " + std::to_string(it->second) +
                             "): remove it (gmsh::model::removePhysicalGroups) or rename the patch");
    };
    check_free(3, "fluid");
    for (Index p = 0; p < patch_faces.rows(); ++p)
        if (patch_faces.row_size(p) > 0) check_free(2, b.patches[static_cast<std::size_t>(p)].name);
}

/// One 2D group per patch name (tag = its first patch's index + 1 past the base): in Gmsh a
/// name is one group per dimension, and the readers map a name to one patch.
void add_patch_groups(const SurfaceMesh& b, const Csr& patch_faces, const TagBases& base, const GroupNames& live) {
    std::map<std::string, std::vector<int>> name_surfaces;
    std::vector<std::pair<int, std::string>> group_names;  // in patch order
    for (Index p = 0; p < patch_faces.rows(); ++p) {
        if (patch_faces.row_size(p) == 0) continue;
        const std::string& name = b.patches[static_cast<std::size_t>(p)].name;
        auto [it, added] = name_surfaces.try_emplace(name);
        if (added) group_names.emplace_back(base.group2 + static_cast<int>(p) + 1, name);
        it->second.push_back(base.surface + static_cast<int>(p) + 1);
    }
    for (const auto& [group, name] : group_names) {
        gmsh::model::addPhysicalGroup(2, name_surfaces.at(name), group);
        name_group(2, group, name, live);
    }
}

/// The mesh as Gmsh entities, nodes, elements and physical groups in the current model (the
/// tags of add_volume_to_gmsh_model, offset past those in use). Call inside gmsh_call with
/// Gmsh's lock held, the arrays checked.
void add_volume(const VolumeMesh& mesh) {
    const SurfaceMesh& b = mesh.boundary;
    const TagBases base = tags_in_use();
    const int volume = base.volume + 1, fluid_group = base.group3 + 1;
    const Csr patch_faces = group_by_key(b.face_patch, b.patches.size());
    const GroupNames live = named_groups();
    check_names_free(b, patch_faces, live);

    // Surfaces first, so the volume can name its boundary (Gmsh builds the topology).
    std::vector<int> surfaces;
    for (Index p = 0; p < patch_faces.rows(); ++p)
        if (patch_faces.row_size(p) > 0) {
            surfaces.push_back(base.surface + static_cast<int>(p) + 1);
            gmsh::model::addDiscreteEntity(2, surfaces.back());
        }
    gmsh::model::addDiscreteEntity(3, volume, surfaces);

    // Every node on the volume (the faces' nodes too: elements may use any entity's nodes).
    std::vector<std::size_t> node_tags(mesh.points.size());
    std::iota(node_tags.begin(), node_tags.end(), base.node + 1);
    std::vector<double> xyz;
    xyz.reserve(3 * mesh.points.size());
    for (const Vec3& x : mesh.points) xyz.insert(xyz.end(), {x.x(), x.y(), x.z()});
    gmsh::model::mesh::addNodes(3, volume, node_tags, xyz);

    // Cells in CellNumbering order, then the boundary faces patch by patch.
    std::size_t next = base.element + 1;
    add_cells(mesh.tets, volume, kTet4, next, base.node);
    next += mesh.tets.size();
    add_cells(mesh.pyramids, volume, kPyramid5, next, base.node);
    next += mesh.pyramids.size();
    add_cells(mesh.prisms, volume, kPrism6, next, base.node);
    next += mesh.prisms.size();
    add_cells(mesh.hexes, volume, kHex8, next, base.node);
    gmsh::model::addPhysicalGroup(3, {volume}, fluid_group);
    name_group(3, fluid_group, "fluid", live);

    const auto num_cells = static_cast<std::size_t>(mesh.num_cells());
    for (Index p = 0; p < patch_faces.rows(); ++p)
        if (patch_faces.row_size(p) > 0)
            add_faces(b, patch_faces.row_begin(p), patch_faces.row_end(p), base.surface + static_cast<int>(p) + 1,
                      base.element + num_cells, base.node);
    add_patch_groups(b, patch_faces, base, live);
}

}  // namespace

void add_surface_to_gmsh_model(const SurfaceMesh& mesh) {
    const std::size_t num_patches = mesh.patches.size();
    // Each node is classified on the lowest-numbered patch surface that uses it; unused nodes
    // are not written (a reader would drop them anyway).
    std::vector<Index> owner(mesh.points.size(), kNone);
    for (Index f = 0; f < mesh.num_faces(); ++f) {
        const Index p = mesh.face_patch[f];
        for (const Index* v = mesh.face_begin(f); v != mesh.face_end(f); ++v) {
            Index& o = owner[static_cast<std::size_t>(*v)];
            if (o == kNone || p < o) o = p;
        }
    }
    // Faces and nodes grouped by patch (ascending ids within a patch), so many patches cost no
    // more than one.
    const Csr patch_faces = group_by_key(mesh.face_patch, num_patches);
    const Csr patch_nodes = group_by_key(owner, num_patches);
    std::vector<std::size_t> node_tags;
    std::vector<double> xyz;
    for (Index p = 0; p < static_cast<Index>(num_patches); ++p) {
        if (patch_faces.row_size(p) == 0) continue;
        const int tag = static_cast<int>(p) + 1;
        gmsh::model::addDiscreteEntity(2, tag);
        node_tags.clear();
        xyz.clear();
        for (const Index* v = patch_nodes.row_begin(p); v != patch_nodes.row_end(p); ++v) {
            node_tags.push_back(static_cast<std::size_t>(*v) + 1);
            const Vec3& x = mesh.points[static_cast<std::size_t>(*v)];
            xyz.insert(xyz.end(), {x.x(), x.y(), x.z()});
        }
        gmsh::model::mesh::addNodes(2, tag, node_tags, xyz);
        add_faces(mesh, patch_faces.row_begin(p), patch_faces.row_end(p), tag, 0, 0);
        gmsh::model::addPhysicalGroup(2, {tag}, tag);
        gmsh::model::setPhysicalName(2, tag, mesh.patches[static_cast<std::size_t>(p)].name);
    }
}

void add_volume_to_gmsh_model(const VolumeMesh& mesh) {
    const std::string context = "adding the volume mesh to the current Gmsh model";
    GmshLock lock(context);
    require_sound(check_volume_arrays(mesh), "cannot add the volume mesh to the current Gmsh model: ");
    gmsh_call(context, [&] { add_volume(mesh); });
}

}  // namespace strata
