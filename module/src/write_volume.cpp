// Volume-mesh writer and reader through the Gmsh API (FORMATS.md: never write .msh by hand).
// The mesh becomes one discrete volume (tag 1) holding every node and cell, and one discrete
// surface per boundary patch (tag = patch index + 1) holding its faces; physical groups: 3D
// "fluid" (tag 1), 2D one per patch (tag = patch index + 1, named after the patch). Element
// tags are the cell's global index + 1 (tets, pyramids, prisms, hexes) then #cells + boundary
// face index + 1, so read_volume_msh restores both orders. Gmsh's 1-based size_t tags stay
// in this file.

#include <strata/error.h>
#include <strata/geometry/atomic_file.h>
#include <strata/geometry/gmsh_session.h>
#include <strata/module/write_volume.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
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

constexpr int kVolumeTag = 1;

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

/// Catch a malformed mesh here, with the cell or face named, rather than as a Gmsh error.
void check_mesh(const VolumeMesh& mesh, const std::string& path) {
    const std::string where = "cannot write '" + path + "': ";
    if (mesh.num_cells() == 0) throw InputError(where + "the mesh has no cells");
    const Index num_points = static_cast<Index>(mesh.points.size());
    auto check_cells = [&](const auto& cells, CellType type) {
        for (std::size_t c = 0; c < cells.size(); ++c)
            for (Index v : cells[c])
                if (v < 0 || v >= num_points)
                    throw InputError(where + std::string(to_string(type)) + " " + std::to_string(c) + " uses node " +
                                     std::to_string(v) + " but the mesh has " + std::to_string(num_points) + " nodes");
    };
    check_cells(mesh.tets, CellType::Tet);
    check_cells(mesh.pyramids, CellType::Pyramid);
    check_cells(mesh.prisms, CellType::Prism);
    check_cells(mesh.hexes, CellType::Hex);

    const SurfaceMesh& b = mesh.boundary;
    if (b.face_offsets.empty() || b.face_offsets.front() != 0 ||
        static_cast<std::size_t>(b.face_offsets.back()) != b.face_nodes.size())
        throw InputError(where + "boundary.face_offsets is malformed");
    if (b.face_patch.size() != static_cast<std::size_t>(b.num_faces()))
        throw InputError(where + "boundary.face_patch has " + std::to_string(b.face_patch.size()) + " entries for " +
                         std::to_string(b.num_faces()) + " boundary faces");
    for (Index f = 0; f < b.num_faces(); ++f) {
        const Index n = b.face_size(f);
        if (n != 3 && n != 4)
            throw InputError(where + "boundary face " + std::to_string(f) + " has " + std::to_string(n) +
                             " nodes; only triangles and quadrangles can be written");
        for (const Index* v = b.face_begin(f); v != b.face_end(f); ++v)
            if (*v < 0 || *v >= num_points)
                throw InputError(where + "boundary face " + std::to_string(f) + " uses node " + std::to_string(*v) +
                                 " but the mesh has " + std::to_string(num_points) + " nodes");
        const Index p = b.face_patch[f];
        if (p < 0 || p >= static_cast<Index>(b.patches.size()))
            throw InputError(where + "boundary face " + std::to_string(f) + " is on patch " + std::to_string(p) +
                             " but the mesh has " + std::to_string(b.patches.size()) + " patches");
    }
}

/// Add one block of cells as Gmsh elements of \p type; tags first_tag, first_tag + 1, ...
template <std::size_t N>
void add_cells(const std::vector<std::array<Index, N>>& cells, int type, std::size_t first_tag) {
    if (cells.empty()) return;
    std::vector<std::size_t> tags(cells.size());
    std::iota(tags.begin(), tags.end(), first_tag);
    std::vector<std::size_t> nodes;
    nodes.reserve(cells.size() * N);
    for (const auto& c : cells)
        for (Index v : c) nodes.push_back(static_cast<std::size_t>(v) + 1);  // Gmsh order already
    gmsh::model::mesh::addElementsByType(kVolumeTag, type, tags, nodes);
}

// ---------------------------------------------------------------------------------------
// Reading

/// gmsh::merge on a missing file only logs an error, so the file is checked here with the
/// system's own reason.
void check_readable(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw InputError("cannot open '" + path + "': it is a directory, not a .msh file");
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!f) throw InputError("cannot open '" + path + "': " + std::strerror(errno));
}

/// Gmsh node tag -> 0-based node index (position in the sorted tag list). Dense when the
/// tags are compact (the usual case), binary search when they are very sparse.
class TagIndex {
public:
    static constexpr std::size_t kMissing = std::numeric_limits<std::size_t>::max();
    explicit TagIndex(std::vector<std::size_t> sorted_tags) : tags_(std::move(sorted_tags)) {
        const std::size_t max_tag = tags_.empty() ? 0 : tags_.back();
        if (max_tag <= 4 * tags_.size() + (1u << 20)) {
            dense_.assign(max_tag + 1, kMissing);
            for (std::size_t i = 0; i < tags_.size(); ++i) dense_[tags_[i]] = i;
        }
    }
    std::size_t find(std::size_t tag) const {
        if (!dense_.empty() || tags_.empty()) return tag < dense_.size() ? dense_[tag] : kMissing;
        auto it = std::lower_bound(tags_.begin(), tags_.end(), tag);
        return it != tags_.end() && *it == tag ? static_cast<std::size_t>(it - tags_.begin()) : kMissing;
    }

private:
    std::vector<std::size_t> tags_;
    std::vector<std::size_t> dense_;
};

/// Elements of one Gmsh type as read: tags and node tags (n per element).
struct RawBlock {
    std::vector<std::size_t> tags;
    std::vector<std::size_t> nodes;
};

/// One boundary face as Gmsh returned it.
struct RawFace {
    std::size_t tag;     // element tag: faces leave in this order
    std::size_t offset;  // into the collected node tags
    int surface;
    Index patch;
    int size;
};

[[noreturn]] void unsupported_type(const std::string& path, int dim, int entity, int type, const char* supported) {
    std::string name;
    int edim = 0, order = 0, num_nodes = 0, num_primary = 0;
    std::vector<double> local;
    gmsh::model::mesh::getElementProperties(type, name, edim, order, num_nodes, local, num_primary);
    throw InputError("'" + path + "': " + (dim == 3 ? "volume " : "surface ") + std::to_string(entity) + " holds '" +
                     name + "' elements (Gmsh type " + std::to_string(type) + ", " + std::to_string(num_nodes) +
                     " nodes): only " + supported +
                     " are supported; convert the mesh to first order (Gmsh: Mesh.ElementOrder = 1) and export it "
                     "again");
}

/// Cells of one type, ordered by element tag, node tags turned into 0-based indices.
template <std::size_t N>
std::vector<std::array<Index, N>> to_cells(const RawBlock& block, const TagIndex& index, const std::string& path) {
    std::vector<std::size_t> order(block.tags.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return block.tags[a] < block.tags[b]; });
    std::vector<std::array<Index, N>> cells(order.size());
    for (std::size_t c = 0; c < order.size(); ++c)
        for (std::size_t k = 0; k < N; ++k) {
            const std::size_t tag = block.nodes[N * order[c] + k];
            const std::size_t i = index.find(tag);
            if (i == TagIndex::kMissing)
                throw InputError("'" + path + "': element " + std::to_string(block.tags[order[c]]) + " uses node " +
                                 std::to_string(tag) + ", which the file does not define; the file is corrupt");
            cells[c][k] = static_cast<Index>(i);
        }
    return cells;
}

}  // namespace

void write_volume(const VolumeMesh& mesh, const std::string& path, double msh_version) {
    check_extension(path);
    if (extension_of(path) == ".msh") check_msh_version(path, msh_version);
    check_mesh(mesh, path);

    const SurfaceMesh& b = mesh.boundary;
    const std::size_t num_patches = b.patches.size();
    const auto num_cells = static_cast<std::size_t>(mesh.num_cells());

    // Boundary faces bucketed by patch (counting sort: ascending face ids within a patch).
    std::vector<std::size_t> patch_start(num_patches + 1, 0);
    for (Index p : b.face_patch) ++patch_start[p + 1];
    for (std::size_t p = 0; p < num_patches; ++p) patch_start[p + 1] += patch_start[p];
    std::vector<Index> patch_faces(b.face_patch.size());
    {
        std::vector<std::size_t> fill(patch_start.begin(), patch_start.end() - 1);
        for (Index f = 0; f < b.num_faces(); ++f) patch_faces[fill[b.face_patch[f]]++] = f;
    }

    AtomicFile out(path);  // InputError now if the directory does not exist
    GmshSession session("write_volume");
    GmshOptionScope options;  // declared after the session: restored before the session ends
    gmsh_call("writing '" + path + "'", [&] {
        options.set("Mesh.MshFileVersion", msh_version);
        options.set("Mesh.Binary", 0);
        options.set("Mesh.SaveAll", 0);  // every element is in a physical group
        options.set("Mesh.ScalingFactor", 1);

        // Surfaces first, so the volume can name its boundary (Gmsh builds the topology).
        std::vector<int> surfaces;
        for (std::size_t p = 0; p < num_patches; ++p)
            if (patch_start[p + 1] > patch_start[p]) {
                surfaces.push_back(static_cast<int>(p) + 1);
                gmsh::model::addDiscreteEntity(2, surfaces.back());
            }
        gmsh::model::addDiscreteEntity(3, kVolumeTag, surfaces);

        // Every node on the volume (the faces' nodes too: elements may use any entity's nodes).
        {
            std::vector<std::size_t> node_tags(mesh.points.size());
            std::iota(node_tags.begin(), node_tags.end(), std::size_t{1});
            std::vector<double> xyz;
            xyz.reserve(3 * mesh.points.size());
            for (const Vec3& x : mesh.points) xyz.insert(xyz.end(), {x.x(), x.y(), x.z()});
            gmsh::model::mesh::addNodes(3, kVolumeTag, node_tags, xyz);
        }

        std::size_t next = 1;
        add_cells(mesh.tets, kTet4, next);
        next += mesh.tets.size();
        add_cells(mesh.pyramids, kPyramid5, next);
        next += mesh.pyramids.size();
        add_cells(mesh.prisms, kPrism6, next);
        next += mesh.prisms.size();
        add_cells(mesh.hexes, kHex8, next);
        gmsh::model::addPhysicalGroup(3, {kVolumeTag}, 1);
        gmsh::model::setPhysicalName(3, 1, "fluid");

        std::vector<std::size_t> tags, nodes;
        for (std::size_t p = 0; p < num_patches; ++p) {
            if (patch_start[p + 1] == patch_start[p]) continue;  // an empty patch has no entity
            const int tag = static_cast<int>(p) + 1;
            for (Index n : {3, 4}) {
                tags.clear();
                nodes.clear();
                for (std::size_t i = patch_start[p]; i < patch_start[p + 1]; ++i) {
                    const Index f = patch_faces[i];
                    if (b.face_size(f) != n) continue;
                    tags.push_back(num_cells + static_cast<std::size_t>(f) + 1);
                    for (const Index* v = b.face_begin(f); v != b.face_end(f); ++v)
                        nodes.push_back(static_cast<std::size_t>(*v) + 1);
                }
                if (!tags.empty())
                    gmsh::model::mesh::addElementsByType(tag, n == 3 ? kTriangle3 : kQuad4, tags, nodes);
            }
            gmsh::model::addPhysicalGroup(2, {tag}, tag);
            gmsh::model::setPhysicalName(2, tag, b.patches[p].name);
        }
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
    check_readable(path);
    GmshSession session("read_volume_msh");
    // gmsh::merge, not gmsh::open: open may replace the current model, escaping the session.
    try {
        gmsh_call("reading '" + path + "'", [&] { gmsh::merge(path); });
    } catch (const BackendError& e) {
        throw InputError(std::string(e.what()) + " (is it a valid MSH 2.2 or 4.1 file?)");
    }

    VolumeMesh mesh;
    SurfaceMesh& boundary = mesh.boundary;
    std::map<int, RawBlock> blocks;  // Gmsh type -> cells
    std::vector<RawFace> faces;
    std::vector<std::size_t> face_node_tags;
    std::vector<std::size_t> node_tags;
    std::vector<double> coords;

    gmsh_call("reading '" + path + "'", [&] {
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
                    unsupported_type(path, dim, volume, type,
                                     "4-node tetrahedra, 5-node pyramids, 6-node prisms and 8-node hexahedra");
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

        // Patches: one per 2D physical group in tag order (same name = same patch); a surface
        // in several groups goes to the lowest-tagged one; a surface in none gets its own.
        gmsh::vectorpair groups;
        gmsh::model::getPhysicalGroups(groups, 2);
        std::sort(groups.begin(), groups.end());
        std::map<std::string, Index> patch_by_name;
        auto patch_named = [&](const std::string& name) {
            auto [it, added] = patch_by_name.emplace(name, static_cast<Index>(boundary.patches.size()));
            if (added) boundary.patches.push_back({name, PatchKind::Wall});
            return it->second;
        };
        std::map<int, Index> surface_patch;
        for (const auto& [dim, group] : groups) {
            std::string name;
            gmsh::model::getPhysicalName(dim, group, name);
            const Index patch = patch_named(name.empty() ? "physical_" + std::to_string(group) : name);
            std::vector<int> members;
            gmsh::model::getEntitiesForPhysicalGroup(dim, group, members);
            for (int s : members) surface_patch.emplace(s, patch);
        }

        gmsh::vectorpair surfaces;
        gmsh::model::getEntities(surfaces, 2);
        std::sort(surfaces.begin(), surfaces.end());
        for (const auto& [dim, surface] : surfaces) {
            types.clear();
            gmsh::model::mesh::getElementTypes(types, dim, surface);
            for (int type : types)
                if (type != kTriangle3 && type != kQuad4)
                    unsupported_type(path, dim, surface, type, "3-node triangles and 4-node quadrangles");
            if (types.empty()) continue;
            Index patch;
            if (auto it = surface_patch.find(surface); it != surface_patch.end())
                patch = it->second;
            else
                patch = patch_named("surface_" + std::to_string(surface));
            for (int type : types) {
                elem_tags.clear();
                elem_nodes.clear();
                gmsh::model::mesh::getElementsByType(type, elem_tags, elem_nodes, surface);
                const int n = type == kTriangle3 ? 3 : 4;
                for (std::size_t e = 0; e < elem_tags.size(); ++e)
                    faces.push_back({elem_tags[e], face_node_tags.size() + n * e, surface, patch, n});
                face_node_tags.insert(face_node_tags.end(), elem_nodes.begin(), elem_nodes.end());
            }
        }

        std::vector<double> parametric;
        gmsh::model::mesh::getNodes(node_tags, coords, parametric, -1, -1, false, false);
    });

    std::size_t num_cells = 0;
    for (const auto& [type, block] : blocks) num_cells += block.tags.size();
    if (num_cells == 0)
        throw InputError("'" + path +
                         "' holds no tetrahedra, pyramids, prisms or hexahedra: it is not a volume mesh (mesh it "
                         "in 3D, gmsh -3, and make sure the volume elements are saved)");
    if (node_tags.size() >= static_cast<std::size_t>(std::numeric_limits<Index>::max()) ||
        face_node_tags.size() >= static_cast<std::size_t>(std::numeric_limits<Index>::max()) ||
        num_cells >= static_cast<std::size_t>(std::numeric_limits<Index>::max()) / 8)
        throw InputError("'" + path + "': " + std::to_string(node_tags.size()) + " nodes and " +
                         std::to_string(num_cells) +
                         " cells exceed the 32-bit index range; rebuild Strata with -DSTRATA_INDEX64=ON");

    // Every node, in tag order (write_volume's nodes come back with their indices).
    std::vector<std::size_t> order(node_tags.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    if (!std::is_sorted(node_tags.begin(), node_tags.end()))
        std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return node_tags[a] < node_tags[b]; });
    std::vector<std::size_t> sorted_tags(order.size());
    for (std::size_t i = 0; i < order.size(); ++i) sorted_tags[i] = node_tags[order[i]];
    TagIndex index(std::move(sorted_tags));
    mesh.points.reserve(order.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
        const double* x = &coords[3 * order[i]];
        mesh.points.emplace_back(x[0], x[1], x[2]);
    }

    if (auto it = blocks.find(kTet4); it != blocks.end()) mesh.tets = to_cells<4>(it->second, index, path);
    if (auto it = blocks.find(kPyramid5); it != blocks.end())
        mesh.pyramids = to_cells<5>(it->second, index, path);
    if (auto it = blocks.find(kPrism6); it != blocks.end()) mesh.prisms = to_cells<6>(it->second, index, path);
    if (auto it = blocks.find(kHex8); it != blocks.end()) mesh.hexes = to_cells<8>(it->second, index, path);

    // Boundary faces in element-tag order: the file's order, and what write_volume wrote.
    auto by_tag = [](const RawFace& a, const RawFace& b) { return a.tag < b.tag; };
    if (!std::is_sorted(faces.begin(), faces.end(), by_tag)) std::stable_sort(faces.begin(), faces.end(), by_tag);
    boundary.face_offsets.reserve(faces.size() + 1);
    boundary.face_patch.reserve(faces.size());
    boundary.face_nodes.reserve(face_node_tags.size());
    for (const RawFace& f : faces) {
        Index nodes[4];
        for (int k = 0; k < f.size; ++k) {
            const std::size_t tag = face_node_tags[f.offset + k];
            const std::size_t i = index.find(tag);
            if (i == TagIndex::kMissing)
                throw InputError("'" + path + "': element " + std::to_string(f.tag) + " on surface " +
                                 std::to_string(f.surface) + " uses node " + std::to_string(tag) +
                                 ", which the file does not define; the file is corrupt");
            nodes[k] = static_cast<Index>(i);
        }
        boundary.add_face(nodes, f.size, f.patch);
    }
    return mesh;
}

}  // namespace strata
