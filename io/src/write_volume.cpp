// Volume-mesh writer and reader through the Gmsh API (FORMATS.md: never write .msh by hand).
// The mesh becomes one discrete volume (tag 1) holding every node and cell, and one discrete
// surface per boundary patch (tag = patch index + 1) holding its faces; physical groups: 3D
// "fluid" (tag 1), 2D one per patch (tag = patch index + 1, named after the patch). Element
// tags are the cell's global index + 1 (tets, pyramids, prisms, hexes) then #cells + boundary
// face index + 1, so read_volume_msh restores both orders. In a model that already holds
// entities, groups or mesh (add_volume_to_gmsh_model on a user's model), every tag is offset
// past the largest one in use. Gmsh's 1-based size_t tags stay in this file and in geometry's
// gmsh_model.cpp, whose surface reading read_volume_msh shares.

#include <strata/core/error.h>
#include <strata/core/mesh_check.h>
#include <strata/io/atomic_file.h>
#include <strata/io/gmsh_model.h>
#include <strata/io/gmsh_session.h>
#include <strata/io/write_volume.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <limits>
#include <map>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

namespace strata {
namespace {

// Gmsh element types.
constexpr int kTriangle3 = 2;
constexpr int kQuad4 = 3;
constexpr int kTet4 = 4;
constexpr int kHex8 = 5;
constexpr int kPrism6 = 6;
constexpr int kPyramid5 = 7;

/// Formats Gmsh 4.8 writes volume meshes to, by extension (.cgns and .med only if this Gmsh
/// was built with them: BackendError otherwise). Surface-only formats (.stl, .off, .ply2,
/// .wrl, ...) are left out, and so is Gambit .neu: Gmsh 4.8's writer corrupts the heap (the
/// process aborts) on a mesh mixing cell types.
constexpr std::array<const char*, 11> kVolumeExtensions = {".msh", ".vtk", ".su2", ".unv", ".mesh", ".bdf",
                                                           ".nas", ".inp", ".cgns", ".med", ".key"};

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

std::string extension_of(const std::string& path) { return lower(std::filesystem::path(path).extension().string()); }

void check_extension(const std::string& path) {
    const std::string ext = extension_of(path);
    for (const char* e : kVolumeExtensions)
        if (ext == e) return;
    std::string list;
    for (const char* e : kVolumeExtensions) {
        if (!list.empty()) list += ", ";
        list += e;
    }
    throw InputError("cannot write '" + path + "': unknown volume-mesh extension '" + ext + "'; use one of " + list);
}

void check_msh_version(const std::string& path, double version) {
    for (double v : {2.2, 4.1})
        if (version == v) return;
    throw InputError("cannot write '" + path + "': MSH version " + std::to_string(version) +
                     " is not supported for volume meshes; use 4.1 (default) or 2.2");
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

/// The mesh as Gmsh entities, nodes, elements and physical groups in the current model (the
/// tags of the file comment, offset past those in use). No checks: check_mesh first. Call
/// inside gmsh_call with Gmsh's lock held.
void add_volume(const VolumeMesh& mesh) {
    const SurfaceMesh& b = mesh.boundary;
    const std::size_t num_patches = b.patches.size();
    const auto num_cells = static_cast<std::size_t>(mesh.num_cells());

    // Tags in use. In a fresh model (write_volume) every base is 0; Gmsh 4.8 has no
    // getMaxNodeTag, so the node and element tags are read, which costs only when a mesh exists.
    std::size_t node_base = 0, element_base = 0;
    {
        std::vector<std::size_t> tags;
        std::vector<double> xyz, parametric;
        gmsh::model::mesh::getNodes(tags, xyz, parametric, -1, -1, false, false);
        for (std::size_t t : tags) node_base = std::max(node_base, t);
    }
    {
        std::vector<int> types;
        std::vector<std::vector<std::size_t>> tags, nodes;
        gmsh::model::mesh::getElements(types, tags, nodes, -1, -1);
        for (const auto& block : tags)
            for (std::size_t t : block) element_base = std::max(element_base, t);
    }
    gmsh::vectorpair surfaces_in_use, volumes_in_use, groups2_in_use, groups3_in_use;
    gmsh::model::getEntities(surfaces_in_use, 2);
    gmsh::model::getEntities(volumes_in_use, 3);
    gmsh::model::getPhysicalGroups(groups2_in_use, 2);
    gmsh::model::getPhysicalGroups(groups3_in_use, 3);
    const int surface_base = max_tag(surfaces_in_use);
    const int volume = max_tag(volumes_in_use) + 1;
    const int group2_base = max_tag(groups2_in_use);
    const int fluid_group = max_tag(groups3_in_use) + 1;

    // Boundary faces bucketed by patch (counting sort: ascending face ids within a patch).
    std::vector<std::size_t> patch_start(num_patches + 1, 0);
    for (Index p : b.face_patch) ++patch_start[static_cast<std::size_t>(p) + 1];
    for (std::size_t p = 0; p < num_patches; ++p) patch_start[p + 1] += patch_start[p];
    std::vector<Index> patch_faces(b.face_patch.size());
    {
        std::vector<std::size_t> fill(patch_start.begin(), patch_start.end() - 1);
        for (Index f = 0; f < b.num_faces(); ++f) patch_faces[fill[static_cast<std::size_t>(b.face_patch[f])]++] = f;
    }

    // A name is one group per dimension in Gmsh: a patch cannot join a group the model has.
    GroupNames live = named_groups();
    auto check_free = [&](int dim, const std::string& name) {
        if (auto it = live.find({dim, name}); it != live.end())
            throw InputError("the current Gmsh model already has a " + std::to_string(dim) +
                             "D physical group named '" + name + "' (tag " + std::to_string(it->second) +
                             "): remove it (gmsh::model::removePhysicalGroups) or rename the patch");
    };
    check_free(3, "fluid");
    for (std::size_t p = 0; p < num_patches; ++p)
        if (patch_start[p + 1] > patch_start[p]) check_free(2, b.patches[p].name);

    // Surfaces first, so the volume can name its boundary (Gmsh builds the topology).
    std::vector<int> surfaces;
    for (std::size_t p = 0; p < num_patches; ++p)
        if (patch_start[p + 1] > patch_start[p]) {
            surfaces.push_back(surface_base + static_cast<int>(p) + 1);
            gmsh::model::addDiscreteEntity(2, surfaces.back());
        }
    gmsh::model::addDiscreteEntity(3, volume, surfaces);

    // Every node on the volume (the faces' nodes too: elements may use any entity's nodes).
    {
        std::vector<std::size_t> node_tags(mesh.points.size());
        std::iota(node_tags.begin(), node_tags.end(), node_base + 1);
        std::vector<double> xyz;
        xyz.reserve(3 * mesh.points.size());
        for (const Vec3& x : mesh.points) xyz.insert(xyz.end(), {x.x(), x.y(), x.z()});
        gmsh::model::mesh::addNodes(3, volume, node_tags, xyz);
    }

    std::size_t next = element_base + 1;
    add_cells(mesh.tets, volume, kTet4, next, node_base);
    next += mesh.tets.size();
    add_cells(mesh.pyramids, volume, kPyramid5, next, node_base);
    next += mesh.pyramids.size();
    add_cells(mesh.prisms, volume, kPrism6, next, node_base);
    next += mesh.prisms.size();
    add_cells(mesh.hexes, volume, kHex8, next, node_base);
    gmsh::model::addPhysicalGroup(3, {volume}, fluid_group);
    name_group(3, fluid_group, "fluid", live);

    std::vector<std::size_t> tags, nodes;
    for (std::size_t p = 0; p < num_patches; ++p) {
        if (patch_start[p + 1] == patch_start[p]) continue;  // an empty patch has no entity
        const int surface = surface_base + static_cast<int>(p) + 1;
        for (Index n : {3, 4}) {
            tags.clear();
            nodes.clear();
            for (std::size_t i = patch_start[p]; i < patch_start[p + 1]; ++i) {
                const Index f = patch_faces[i];
                if (b.face_size(f) != n) continue;
                tags.push_back(element_base + num_cells + static_cast<std::size_t>(f) + 1);
                for (const Index* v = b.face_begin(f); v != b.face_end(f); ++v)
                    nodes.push_back(node_base + static_cast<std::size_t>(*v) + 1);
            }
            if (!tags.empty()) gmsh::model::mesh::addElementsByType(surface, n == 3 ? kTriangle3 : kQuad4, tags, nodes);
        }
    }

    // One 2D group per patch name (tag = its first patch's index + 1): in Gmsh a name is one
    // group per dimension, and readers (read_msh, read_volume_msh) map a name to one patch.
    std::map<std::string, std::vector<int>> name_surfaces;
    std::vector<std::pair<int, std::string>> group_names;  // in patch order
    for (std::size_t p = 0; p < num_patches; ++p) {
        if (patch_start[p + 1] == patch_start[p]) continue;
        auto [it, added] = name_surfaces.try_emplace(b.patches[p].name);
        if (added) group_names.emplace_back(group2_base + static_cast<int>(p) + 1, b.patches[p].name);
        it->second.push_back(surface_base + static_cast<int>(p) + 1);
    }
    for (const auto& [group, name] : group_names) {
        gmsh::model::addPhysicalGroup(2, name_surfaces.at(name), group);
        name_group(2, group, name, live);
    }
}

// ---------------------------------------------------------------------------------------
// Reading

/// Elements of one Gmsh type as read: tags and node tags (n per element).
struct RawBlock {
    std::vector<std::size_t> tags;
    std::vector<std::size_t> nodes;
};

/// Cells of one type, ordered by element tag, node tags turned into 0-based indices.
template <std::size_t N>
std::vector<std::array<Index, N>> to_cells(const RawBlock& block, const GmshNodes& nodes, const std::string& context) {
    std::vector<std::size_t> order(block.tags.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return block.tags[a] < block.tags[b]; });
    std::vector<std::array<Index, N>> cells(order.size());
    for (std::size_t c = 0; c < order.size(); ++c)
        for (std::size_t k = 0; k < N; ++k) {
            const std::size_t tag = block.nodes[N * order[c] + k];
            const Index i = nodes.index_of(tag);
            if (i == kNone)
                throw InputError(context + ": element " + std::to_string(block.tags[order[c]]) + " uses node " +
                                 std::to_string(tag) + ", which the file does not define; the file is corrupt");
            cells[c][k] = i;
        }
    return cells;
}

}  // namespace

void add_volume_to_gmsh_model(const VolumeMesh& mesh) {
    const std::string context = "adding the volume mesh to the current Gmsh model";
    GmshLock lock(context);
    require_sound(check_volume_arrays(mesh), "cannot add the volume mesh to the current Gmsh model: ");
    gmsh_call(context, [&] { add_volume(mesh); });
}

void write_volume(const VolumeMesh& mesh, const std::string& path, double msh_version) {
    check_extension(path);
    if (extension_of(path) == ".msh") check_msh_version(path, msh_version);
    require_sound(check_volume_arrays(mesh), "cannot write '" + path + "': ");

    AtomicFile out(path);  // InputError now if the directory does not exist
    GmshSession session("write_volume");
    GmshOptionScope options;  // declared after the session: restored before the session ends
    gmsh_call("writing '" + path + "'", [&] {
        options.set("Mesh.MshFileVersion", msh_version);
        options.set("Mesh.Binary", 0);
        options.set("Mesh.SaveAll", 0);  // every element is in a physical group
        options.set("Mesh.ScalingFactor", 1);
        add_volume(mesh);
        gmsh::write(out.temp_path());
    });
    // Gmsh only logs some failures (a format it was built without): say so, not "rename failed".
    std::error_code ec;
    if (!std::filesystem::exists(out.temp_path(), ec)) {
        const std::string last = GmshSession::last_error();
        throw BackendError("writing '" + path + "': Gmsh wrote nothing" + (last.empty() ? "" : ": " + last));
    }
    out.commit();
}

VolumeMesh read_volume_msh(const std::string& path) {
    GmshSession session("read_volume_msh");  // a scratch model: the caller's current model is untouched
    merge_msh_file(path);
    const std::string context = "'" + path + "'";

    VolumeMesh mesh;
    std::map<int, RawBlock> blocks;  // Gmsh type -> cells
    gmsh_call("reading " + context, [&] {
        std::vector<int> types;
        std::vector<std::size_t> elem_tags, elem_nodes;
        gmsh::vectorpair volumes;
        gmsh::model::getEntities(volumes, 3);
        std::sort(volumes.begin(), volumes.end());
        for (const auto& [dim, volume] : volumes) {
            types.clear();
            gmsh::model::mesh::getElementTypes(types, dim, volume);
            for (int type : types)
                if (type != kTet4 && type != kPyramid5 && type != kPrism6 && type != kHex8)
                    throw unsupported_gmsh_element(context, dim, volume, type,
                                                   "4-node tetrahedra, 5-node pyramids, 6-node prisms and 8-node "
                                                   "hexahedra");
            for (int type : types) {
                // Gmsh 4.8 takes non-empty output vectors as preallocated: empty them first.
                elem_tags.clear();
                elem_nodes.clear();
                gmsh::model::mesh::getElementsByType(type, elem_tags, elem_nodes, volume);
                RawBlock& block = blocks[type];
                block.tags.insert(block.tags.end(), elem_tags.begin(), elem_tags.end());
                block.nodes.insert(block.nodes.end(), elem_nodes.begin(), elem_nodes.end());
            }
        }
    });

    std::size_t num_cells = 0;
    for (const auto& [type, block] : blocks) num_cells += block.tags.size();
    if (num_cells == 0)
        throw InputError(context +
                         " holds no tetrahedra, pyramids, prisms or hexahedra: it is not a volume mesh (mesh it "
                         "in 3D, gmsh -3, and make sure the volume elements are saved)");
    if (num_cells >= static_cast<std::size_t>(std::numeric_limits<Index>::max()) / 8)
        throw InputError(context + ": " + std::to_string(num_cells) +
                         " cells exceed the 32-bit index range; rebuild Strata with -DSTRATA_INDEX64=ON");

    // Every node in tag order (write_volume's nodes come back with their indices); the boundary
    // faces (patches from the 2D physical groups, as read_msh) index them.
    GmshNodes nodes(context);
    mesh.boundary = surface_faces_from_gmsh_model(context, nodes);
    if (auto it = blocks.find(kTet4); it != blocks.end()) mesh.tets = to_cells<4>(it->second, nodes, context);
    if (auto it = blocks.find(kPyramid5); it != blocks.end())
        mesh.pyramids = to_cells<5>(it->second, nodes, context);
    if (auto it = blocks.find(kPrism6); it != blocks.end()) mesh.prisms = to_cells<6>(it->second, nodes, context);
    if (auto it = blocks.find(kHex8); it != blocks.end()) mesh.hexes = to_cells<8>(it->second, nodes, context);
    mesh.points = nodes.take_points();
    return mesh;
}

}  // namespace strata
