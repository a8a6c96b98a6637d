// Gmsh .msh reader through the Gmsh API, so every MSH version and encoding Gmsh reads
// (2.2, 4.1, ASCII, binary) is handled by Gmsh itself. Gmsh's 1-based size_t tags stay in
// this file: the mesh that leaves it is 0-based strata::Index.

#include <strata/error.h>
#include <strata/geometry/gmsh_session.h>
#include <strata/geometry/read_surface.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

namespace strata {
namespace {

constexpr int kTriangle3 = 2;  // Gmsh element types
constexpr int kQuad4 = 3;

/// gmsh::merge on a missing file logs an error but an open on one silently starts an empty
/// model, so the file is checked here with the system's own reason.
void check_readable(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw InputError("cannot open '" + path + "': it is a directory, not a .msh file");
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!f) throw InputError("cannot open '" + path + "': " + std::strerror(errno));
}

/// Gmsh node tag -> position in the sorted tag list. Dense when the tags are compact (the
/// usual case), binary search when they are very sparse.
class TagIndex {
public:
    explicit TagIndex(std::vector<std::size_t> sorted_tags) : tags_(std::move(sorted_tags)) {
        const std::size_t max_tag = tags_.empty() ? 0 : tags_.back();
        if (max_tag <= 4 * tags_.size() + (1u << 20)) {
            dense_.assign(max_tag + 1, kMissing);
            for (std::size_t i = 0; i < tags_.size(); ++i) dense_[tags_[i]] = i;
        }
    }
    static constexpr std::size_t kMissing = std::numeric_limits<std::size_t>::max();

    std::size_t find(std::size_t tag) const {
        if (!dense_.empty() || tags_.empty()) return tag < dense_.size() ? dense_[tag] : kMissing;
        auto it = std::lower_bound(tags_.begin(), tags_.end(), tag);
        return it != tags_.end() && *it == tag ? static_cast<std::size_t>(it - tags_.begin()) : kMissing;
    }

private:
    std::vector<std::size_t> tags_;
    std::vector<std::size_t> dense_;
};

/// One triangle or quad as Gmsh returned it, before node renumbering.
struct RawFace {
    std::size_t tag;     // Gmsh element tag: faces leave in this order (the file's order)
    std::size_t offset;  // into the collected node tags
    int surface;         // Gmsh surface entity
    Index patch;
    int size;  // 3 or 4
};

}  // namespace

SurfaceMesh read_msh(const std::string& path) {
    check_readable(path);
    GmshSession session("read_msh");
    // gmsh::merge, not gmsh::open: open may replace the current model (and rename it), which
    // would escape the session's scratch model.
    try {
        gmsh_call("reading '" + path + "'", [&] { gmsh::merge(path); });
    } catch (const BackendError& e) {
        // Gmsh fails to read a file that is not valid MSH: that is the user's input.
        throw InputError(std::string(e.what()) + " (is it a valid MSH 2.2 or 4.1 file?)");
    }

    SurfaceMesh mesh;
    std::vector<RawFace> faces;
    std::vector<std::size_t> face_node_tags;
    std::vector<std::size_t> node_tags;
    std::vector<double> coords;

    gmsh_call("reading '" + path + "'", [&] {
        gmsh::vectorpair surfaces;
        gmsh::model::getEntities(surfaces, 2);
        std::sort(surfaces.begin(), surfaces.end());

        // Patches: one per 2D physical group in tag order (same name = same patch); a surface
        // in several groups goes to the lowest-tagged one so the result is deterministic.
        gmsh::vectorpair groups;
        gmsh::model::getPhysicalGroups(groups, 2);
        std::sort(groups.begin(), groups.end());
        std::map<std::string, Index> patch_by_name;
        auto patch_named = [&](const std::string& name) {
            auto [it, added] = patch_by_name.emplace(name, static_cast<Index>(mesh.patches.size()));
            if (added) mesh.patches.push_back({name, PatchKind::Wall});
            return it->second;
        };
        std::map<int, Index> surface_patch;
        for (const auto& [dim, group] : groups) {
            std::string name;
            gmsh::model::getPhysicalName(dim, group, name);
            const Index patch = patch_named(name.empty() ? "physical_" + std::to_string(group) : name);
            std::vector<int> members;
            gmsh::model::getEntitiesForPhysicalGroup(dim, group, members);
            for (int s : members) surface_patch.emplace(s, patch);  // keeps the first group's
        }

        std::vector<int> types;
        std::vector<std::size_t> elem_tags, elem_nodes;
        for (const auto& [dim, surface] : surfaces) {
            types.clear();
            gmsh::model::mesh::getElementTypes(types, dim, surface);
            for (int type : types) {
                if (type != kTriangle3 && type != kQuad4) {
                    std::string name;
                    int edim = 0, order = 0, num_nodes = 0, num_primary = 0;
                    std::vector<double> local;
                    gmsh::model::mesh::getElementProperties(type, name, edim, order, num_nodes,
                                                            local, num_primary);
                    throw InputError("'" + path + "': surface " + std::to_string(surface) +
                                     " holds '" + name + "' elements (Gmsh type " + std::to_string(type) +
                                     ", " + std::to_string(num_nodes) +
                                     " nodes): only 3-node triangles and 4-node quadrangles are "
                                     "supported; convert the mesh to first order (Gmsh: "
                                     "Mesh.ElementOrder = 1) and export it again");
                }
            }
            if (types.empty()) continue;
            // Patch looked up only for surfaces that carry faces: an unnamed empty surface
            // would only add an empty patch.
            Index patch;
            if (auto it = surface_patch.find(surface); it != surface_patch.end())
                patch = it->second;
            else
                patch = patch_named("surface_" + std::to_string(surface));
            for (int type : types) {
                // Gmsh 4.8 takes non-empty output vectors as preallocated (and rejects them
                // when too small), so they must be emptied before every call.
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

    if (faces.empty())
        throw InputError("'" + path +
                         "' holds no triangles or quadrangles: mesh its surfaces (gmsh -2) and make "
                         "sure the surface elements are saved (Mesh.SaveAll, or 2D physical groups)");
    if (face_node_tags.size() >= static_cast<std::size_t>(std::numeric_limits<Index>::max()))
        throw InputError("'" + path + "': " + std::to_string(faces.size()) +
                         " faces exceed the 32-bit index range; rebuild Strata with -DSTRATA_INDEX64=ON");

    // Faces in element-tag order: the order of the file, and what write_surface wrote.
    auto by_tag = [](const RawFace& a, const RawFace& b) { return a.tag < b.tag; };
    if (!std::is_sorted(faces.begin(), faces.end(), by_tag)) std::stable_sort(faces.begin(), faces.end(), by_tag);

    // Nodes in tag order, only those the faces use (volume or curve-only nodes are dropped).
    std::vector<std::size_t> order(node_tags.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    if (!std::is_sorted(node_tags.begin(), node_tags.end()))
        std::sort(order.begin(), order.end(),
                  [&](std::size_t a, std::size_t b) { return node_tags[a] < node_tags[b]; });
    std::vector<std::size_t> sorted_tags(order.size());
    for (std::size_t i = 0; i < order.size(); ++i) sorted_tags[i] = node_tags[order[i]];
    TagIndex index(std::move(sorted_tags));

    std::vector<Index> renumber(order.size(), kNone);
    for (const RawFace& f : faces)
        for (int k = 0; k < f.size; ++k) {
            const std::size_t tag = face_node_tags[f.offset + k];
            const std::size_t i = index.find(tag);
            if (i == TagIndex::kMissing)
                throw InputError("'" + path + "': element " + std::to_string(f.tag) + " on surface " +
                                 std::to_string(f.surface) + " uses node " + std::to_string(tag) +
                                 ", which the file does not define; the file is corrupt");
            renumber[i] = 0;  // used; numbered below
        }
    Index next = 0;
    for (std::size_t i = 0; i < order.size(); ++i) {
        if (renumber[i] == kNone) continue;
        renumber[i] = next++;
        const double* x = &coords[3 * order[i]];
        mesh.points.emplace_back(x[0], x[1], x[2]);
    }

    mesh.face_offsets.reserve(faces.size() + 1);
    mesh.face_patch.reserve(faces.size());
    mesh.face_nodes.reserve(face_node_tags.size());
    for (const RawFace& f : faces) {
        Index nodes[4];
        for (int k = 0; k < f.size; ++k) nodes[k] = renumber[index.find(face_node_tags[f.offset + k])];
        mesh.add_face(nodes, f.size, f.patch);
    }
    return mesh;
}

}  // namespace strata
