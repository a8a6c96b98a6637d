// The current Gmsh model -> Strata meshes: the one place that turns Gmsh's 2D elements and
// physical groups into patches, shared by read_msh, read_volume_msh and the Gmsh-API entry
// point. Gmsh's 1-based size_t tags stay in this file.

#include <strata/io/gmsh_model.h>
#include <strata/io/gmsh_session.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <utility>

namespace strata {
namespace {

constexpr int kTriangle3 = 2;  // Gmsh element types
constexpr int kQuad4 = 3;

/// One triangle or quad as Gmsh returned it, before node renumbering.
struct RawFace {
    std::size_t tag;     // Gmsh element tag: faces leave in this order (a file's order)
    std::size_t offset;  // into the collected node tags
    int surface;         // Gmsh surface entity
    Index patch;
    int size;  // 3 or 4
};

std::string index_range_hint() {
    return "exceed the 32-bit index range; rebuild Strata with -DSTRATA_INDEX64=ON";
}

}  // namespace

GmshNodes::GmshNodes(const std::string& context) {
    const std::string reading = "reading " + context;
    GmshLock lock(reading);
    std::vector<std::size_t> node_tags;
    std::vector<double> coords;
    gmsh_call(reading, [&] {
        std::vector<double> parametric;
        gmsh::model::mesh::getNodes(node_tags, coords, parametric, -1, -1, false, false);
    });
    if (node_tags.size() >= static_cast<std::size_t>(std::numeric_limits<Index>::max()))
        throw InputError(context + ": " + std::to_string(node_tags.size()) + " nodes " + index_range_hint());

    std::vector<std::size_t> order(node_tags.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    if (!std::is_sorted(node_tags.begin(), node_tags.end()))
        std::sort(order.begin(), order.end(),
                  [&](std::size_t a, std::size_t b) { return node_tags[a] < node_tags[b]; });
    tags_.resize(order.size());
    points_.reserve(order.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
        tags_[i] = node_tags[order[i]];
        const double* x = &coords[3 * order[i]];
        points_.emplace_back(x[0], x[1], x[2]);
    }
    const std::size_t max_tag = tags_.empty() ? 0 : tags_.back();
    if (max_tag <= 4 * tags_.size() + (1u << 20)) {
        dense_.assign(max_tag + 1, kNone);
        for (std::size_t i = 0; i < tags_.size(); ++i) dense_[tags_[i]] = static_cast<Index>(i);
    }
}

Index GmshNodes::index_of(std::size_t tag) const {
    if (!dense_.empty() || tags_.empty()) return tag < dense_.size() ? dense_[tag] : kNone;
    auto it = std::lower_bound(tags_.begin(), tags_.end(), tag);
    return it != tags_.end() && *it == tag ? static_cast<Index>(it - tags_.begin()) : kNone;
}

SurfaceMesh surface_faces_from_gmsh_model(const std::string& context, const GmshNodes& nodes) {
    const std::string reading = "reading " + context;
    GmshLock lock(reading);
    SurfaceMesh mesh;
    std::vector<RawFace> faces;
    std::vector<std::size_t> face_node_tags;

    gmsh_call(reading, [&] {
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
            for (int type : types)
                if (type != kTriangle3 && type != kQuad4)
                    throw unsupported_gmsh_element(context, dim, surface, type,
                                                   "3-node triangles and 4-node quadrangles");
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
    });

    if (face_node_tags.size() >= static_cast<std::size_t>(std::numeric_limits<Index>::max()))
        throw InputError(context + ": " + std::to_string(faces.size()) + " faces " + index_range_hint());

    // Faces in element-tag order: the order of a file, and what write_surface wrote.
    auto by_tag = [](const RawFace& a, const RawFace& b) { return a.tag < b.tag; };
    if (!std::is_sorted(faces.begin(), faces.end(), by_tag)) std::stable_sort(faces.begin(), faces.end(), by_tag);

    mesh.face_offsets.reserve(faces.size() + 1);
    mesh.face_patch.reserve(faces.size());
    mesh.face_nodes.reserve(face_node_tags.size());
    for (const RawFace& f : faces) {
        Index v[4];
        for (int k = 0; k < f.size; ++k) {
            const std::size_t tag = face_node_tags[f.offset + static_cast<std::size_t>(k)];
            v[k] = nodes.index_of(tag);
            if (v[k] == kNone)
                throw InputError(context + ": element " + std::to_string(f.tag) + " on surface " +
                                 std::to_string(f.surface) + " uses node " + std::to_string(tag) +
                                 ", which is not among its nodes; the mesh is corrupt");
        }
        mesh.add_face(v, f.size, f.patch);
    }
    return mesh;
}

SurfaceMesh surface_from_gmsh_model(const std::string& context) {
    GmshLock lock("reading " + context);
    GmshNodes nodes(context);
    SurfaceMesh mesh = surface_faces_from_gmsh_model(context, nodes);
    if (mesh.num_faces() == 0)
        throw InputError(context +
                         " holds no triangles or quadrangles: mesh its surfaces (gmsh -2, or "
                         "gmsh::model::mesh::generate(2)); a .msh file must also keep its surface "
                         "elements (Mesh.SaveAll, or 2D physical groups)");

    // Only the nodes the faces use (volume or curve-only nodes are dropped), in tag order.
    std::vector<Index> renumber(nodes.points().size(), kNone);
    for (Index v : mesh.face_nodes) renumber[static_cast<std::size_t>(v)] = 0;
    Index next = 0;
    for (std::size_t i = 0; i < renumber.size(); ++i) {
        if (renumber[i] == kNone) continue;
        renumber[i] = next++;
        mesh.points.push_back(nodes.points()[i]);
    }
    for (Index& v : mesh.face_nodes) v = renumber[static_cast<std::size_t>(v)];
    return mesh;
}

void merge_msh_file(const std::string& path) {
    // gmsh::merge on a missing file logs an error but an open on one silently starts an empty
    // model, so the file is checked here with the system's own reason.
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw InputError("cannot open '" + path + "': it is a directory, not a .msh file");
    {
        std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
        if (!f) throw InputError("cannot open '" + path + "': " + std::strerror(errno));
    }
    const std::string reading = "reading '" + path + "'";
    GmshLock lock(reading);
    try {
        gmsh_call(reading, [&] { gmsh::merge(path); });
    } catch (const BackendError& e) {
        // Gmsh fails to read a file that is not valid MSH: that is the user's input.
        throw InputError(std::string(e.what()) + " (is it a valid MSH 2.2 or 4.1 file?)");
    }
}

InputError unsupported_gmsh_element(const std::string& context, int dim, int entity, int type,
                                    const std::string& supported) {
    std::string name;
    int edim = 0, order = 0, num_nodes = 0, num_primary = 0;
    std::vector<double> local;
    gmsh_call("reading " + context,
              [&] { gmsh::model::mesh::getElementProperties(type, name, edim, order, num_nodes, local, num_primary); });
    return InputError(context + ": " + (dim == 3 ? "volume " : "surface ") + std::to_string(entity) + " holds '" +
                      name + "' elements (Gmsh type " + std::to_string(type) + ", " + std::to_string(num_nodes) +
                      " nodes): only " + supported +
                      " are supported; convert the mesh to first order (Gmsh: Mesh.ElementOrder = 1) and export it "
                      "again");
}

}  // namespace strata
