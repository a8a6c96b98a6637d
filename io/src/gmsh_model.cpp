// The current Gmsh model -> Strata meshes (gmsh_model.h): the one place that turns Gmsh's
// elements and physical groups into faces, cells and patches, for read_msh, read_volume_msh,
// the CAD import and the Gmsh-API entry point. Gmsh's 1-based size_t tags stay in this file.

#include <strata/io/gmsh_model.h>
#include <strata/io/gmsh_session.h>
#include <strata/io/input_file.h>
#include <strata/io/msh_counts.h>

#include "gmsh_element_types.h"

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <new>
#include <numeric>
#include <utility>

namespace strata {
namespace {

using namespace gmsh_types;

std::string index_range_hint() {
    return "exceed the 32-bit index range; rebuild Strata with -DSTRATA_INDEX64=ON";
}

/// The error for an element type a reader does not take: "<context>: volume 3 holds 'Tetrahedron
/// 10' elements (Gmsh type 11, 10 nodes): only <supported> are supported; convert the mesh to
/// first order ...". \p dim is the entity's dimension (2 or 3). Call with Gmsh's lock held.
InputError unsupported_element(const std::string& context, int dim, int entity, int type,
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

/// One triangle or quad as Gmsh returned it, before node renumbering.
struct RawFace {
    std::size_t tag;     // Gmsh element tag: faces leave in this order (a file's order)
    std::size_t offset;  // into the collected node tags
    int surface;         // Gmsh surface entity
    int size;            // 3 or 4
};

/// The 2D elements of the current model, surface by surface in tag order.
struct RawFaces {
    std::vector<RawFace> faces;
    std::vector<std::size_t> node_tags;
    std::vector<int> surfaces_with_faces;  // ascending
};

RawFaces read_raw_faces(const std::string& context) {
    RawFaces raw;
    gmsh::vectorpair surfaces;
    gmsh::model::getEntities(surfaces, 2);
    std::sort(surfaces.begin(), surfaces.end());
    std::vector<int> types;
    std::vector<std::size_t> elem_tags, elem_nodes;
    for (const auto& [dim, surface] : surfaces) {
        types.clear();
        gmsh::model::mesh::getElementTypes(types, dim, surface);
        for (int type : types)
            if (type != kTriangle3 && type != kQuad4)
                throw unsupported_element(context, dim, surface, type, "3-node triangles and 4-node quadrangles");
        if (types.empty()) continue;
        raw.surfaces_with_faces.push_back(surface);
        for (int type : types) {
            // Gmsh 4.8 takes non-empty output vectors as preallocated (and rejects them when too
            // small), so they must be emptied before every call.
            elem_tags.clear();
            elem_nodes.clear();
            gmsh::model::mesh::getElementsByType(type, elem_tags, elem_nodes, surface);
            const int n = type == kTriangle3 ? 3 : 4;
            for (std::size_t e = 0; e < elem_tags.size(); ++e)
                raw.faces.push_back({elem_tags[e], raw.node_tags.size() + static_cast<std::size_t>(n) * e, surface, n});
            raw.node_tags.insert(raw.node_tags.end(), elem_nodes.begin(), elem_nodes.end());
        }
    }
    return raw;
}

/// The patch rule of gmsh_model.h: the patch of every surface that carries faces, and the
/// patch table.
std::map<int, Index> plan_patches(const std::vector<int>& surfaces_with_faces, std::vector<Patch>& patches) {
    gmsh::vectorpair groups;
    gmsh::model::getPhysicalGroups(groups, 2);
    std::sort(groups.begin(), groups.end());
    std::map<int, std::size_t> group_of;  // surface -> its lowest-tagged group (index into groups)
    for (std::size_t g = 0; g < groups.size(); ++g) {
        std::vector<int> members;
        gmsh::model::getEntitiesForPhysicalGroup(groups[g].first, groups[g].second, members);
        for (int s : members) group_of.emplace(s, g);
    }
    std::map<std::string, Index> patch_by_name;
    auto patch_named = [&](const std::string& name) {
        auto [it, added] = patch_by_name.emplace(name, static_cast<Index>(patches.size()));
        if (added) patches.push_back({name, PatchKind::Wall});
        return it->second;
    };
    std::map<int, Index> patch_of;
    for (std::size_t g = 0; g < groups.size(); ++g) {
        Index patch = kNone;
        for (int s : surfaces_with_faces) {
            const auto it = group_of.find(s);
            if (it == group_of.end() || it->second != g) continue;
            if (patch == kNone) {
                std::string name;
                gmsh::model::getPhysicalName(groups[g].first, groups[g].second, name);
                patch = patch_named(name.empty() ? "physical_" + std::to_string(groups[g].second) : name);
            }
            patch_of.emplace(s, patch);
        }
    }
    for (int s : surfaces_with_faces)
        if (!patch_of.count(s)) patch_of.emplace(s, patch_named("surface_" + std::to_string(s)));
    return patch_of;
}

/// The current model's 2D elements with every node numbered as in \p nodes (so points stay
/// empty and faces index nodes.points()). A model without triangles or quadrangles gives an
/// empty mesh.
SurfaceMesh surface_faces(const std::string& context, const GmshNodes& nodes, std::vector<int>* face_surface) {
    const std::string reading = "reading " + context;
    GmshLock lock(reading);
    SurfaceMesh mesh;
    RawFaces raw;
    std::map<int, Index> patch_of;
    gmsh_call(reading, [&] {
        raw = read_raw_faces(context);
        patch_of = plan_patches(raw.surfaces_with_faces, mesh.patches);
    });
    if (raw.node_tags.size() >= static_cast<std::size_t>(std::numeric_limits<Index>::max()))
        throw InputError(context + ": " + std::to_string(raw.faces.size()) + " faces " + index_range_hint());

    // Faces in element-tag order: the order of a file, and what add_surface_to_gmsh_model wrote.
    auto by_tag = [](const RawFace& a, const RawFace& b) { return a.tag < b.tag; };
    if (!std::is_sorted(raw.faces.begin(), raw.faces.end(), by_tag))
        std::stable_sort(raw.faces.begin(), raw.faces.end(), by_tag);
    mesh.face_offsets.reserve(raw.faces.size() + 1);
    mesh.face_patch.reserve(raw.faces.size());
    mesh.face_nodes.reserve(raw.node_tags.size());
    if (face_surface) face_surface->clear();
    for (const RawFace& f : raw.faces) {
        std::array<Index, 4> v{};
        for (std::size_t k = 0; k < static_cast<std::size_t>(f.size); ++k) {
            const std::size_t tag = raw.node_tags[f.offset + k];
            v[k] = nodes.index_of(tag);
            if (v[k] == kNone)
                throw InputError(context + ": element " + std::to_string(f.tag) + " on surface " +
                                 std::to_string(f.surface) + " uses node " + std::to_string(tag) +
                                 ", which is not among its nodes; the mesh is corrupt");
        }
        mesh.add_face(v.data(), f.size, patch_of.at(f.surface));
        if (face_surface) face_surface->push_back(f.surface);
    }
    return mesh;
}

/// Keep only the nodes \p mesh's faces use, numbered as \p order says.
void compact_nodes(SurfaceMesh& mesh, const std::vector<Vec3>& all, NodeOrder order) {
    std::vector<Index> renumber(all.size(), kNone);
    Index next = 0;
    if (order == NodeOrder::FirstUse) {
        for (Index v : mesh.face_nodes)
            if (renumber[static_cast<std::size_t>(v)] == kNone) renumber[static_cast<std::size_t>(v)] = next++;
    } else {
        for (Index v : mesh.face_nodes) renumber[static_cast<std::size_t>(v)] = 0;
        for (Index& r : renumber)
            if (r != kNone) r = next++;
    }
    mesh.points.assign(static_cast<std::size_t>(next), Vec3::Zero());
    for (std::size_t i = 0; i < renumber.size(); ++i)
        if (renumber[i] != kNone) mesh.points[static_cast<std::size_t>(renumber[i])] = all[i];
    for (Index& v : mesh.face_nodes) v = renumber[static_cast<std::size_t>(v)];
}

/// Elements of one Gmsh type as read: tags and node tags (n per element).
struct RawBlock {
    std::vector<std::size_t> tags;
    std::vector<std::size_t> nodes;
};

std::map<int, RawBlock> read_cell_blocks(const std::string& context) {
    std::map<int, RawBlock> blocks;  // Gmsh type -> cells
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
                throw unsupported_element(context, dim, volume, type,
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
    return blocks;
}

/// Cells of one type, ordered by element tag, node tags turned into 0-based indices.
template <std::size_t N>
std::vector<std::array<Index, N>> to_cells(const std::map<int, RawBlock>& blocks, int type, const GmshNodes& nodes,
                                           const std::string& context) {
    const auto it = blocks.find(type);
    if (it == blocks.end()) return {};
    const RawBlock& block = it->second;
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

SurfaceMesh surface_from_gmsh_model(const std::string& context, NodeOrder order, std::vector<int>* face_surface) {
    GmshLock lock("reading " + context);
    GmshNodes nodes(context);
    SurfaceMesh mesh = surface_faces(context, nodes, face_surface);
    if (mesh.num_faces() == 0)
        throw InputError(context +
                         " holds no triangles or quadrangles: mesh its surfaces (gmsh -2, or "
                         "gmsh::model::mesh::generate(2)); a .msh file must also keep its surface "
                         "elements (Mesh.SaveAll, or 2D physical groups)");
    // Only the nodes the faces use (volume or curve-only nodes are dropped).
    compact_nodes(mesh, nodes.points(), order);
    return mesh;
}

VolumeMesh volume_from_gmsh_model(const std::string& context) {
    const std::string reading = "reading " + context;
    GmshLock lock(reading);
    std::map<int, RawBlock> blocks;
    gmsh_call(reading, [&] { blocks = read_cell_blocks(context); });
    std::size_t num_cells = 0;
    for (const auto& [type, block] : blocks) num_cells += block.tags.size();
    if (num_cells == 0)
        throw InputError(context +
                         " holds no tetrahedra, pyramids, prisms or hexahedra: it is not a volume mesh (mesh it "
                         "in 3D, gmsh -3, and make sure the volume elements are saved)");
    if (num_cells >= static_cast<std::size_t>(std::numeric_limits<Index>::max()) / 8)
        throw InputError(context + ": " + std::to_string(num_cells) + " cells " + index_range_hint());

    // Every node in tag order (add_volume_to_gmsh_model's nodes come back with their indices);
    // the boundary faces (patches from the 2D physical groups) index them.
    GmshNodes nodes(context);
    VolumeMesh mesh;
    mesh.boundary = surface_faces(context, nodes, nullptr);
    mesh.tets = to_cells<4>(blocks, kTet4, nodes, context);
    mesh.pyramids = to_cells<5>(blocks, kPyramid5, nodes, context);
    mesh.prisms = to_cells<6>(blocks, kPrism6, nodes, context);
    mesh.hexes = to_cells<8>(blocks, kHex8, nodes, context);
    mesh.points = nodes.take_points();
    return mesh;
}

void merge_msh_file(const std::string& path) {
    // gmsh::merge on a missing file logs an error but an open on one silently starts an empty
    // model, so the file is checked first with the system's own reason. Gmsh opens it by name
    // (a pipe would be read here first), and sizes its arrays from the counts it claims.
    require_regular_input(path, "Gmsh");
    check_msh_counts(path);
    const std::string reading = "reading '" + path + "'";
    GmshLock lock(reading);
    const auto read = [&] {
        try {
            gmsh_call(reading, [&] {
                try {
                    gmsh::merge(path);
                } catch (const std::bad_alloc&) {
                    throw out_of_memory(path);
                }
            });
        } catch (const BackendError& e) {
            // Gmsh fails to read a file that is not valid MSH: that is the user's input.
            throw InputError(std::string(e.what()) + " (is it a valid MSH 2.2 or 4.1 file?)");
        }
    };
    // Gmsh 4.8's MSH reader crashes or corrupts its heap on some damaged files
    // (fuzz/regressions/msh): the read is tried in a child first, so that such a file is an
    // error and the process (a Python or FreeCAD session) goes on; a file it fails on is not
    // read here at all. Costs the read's time once more. Not in the fuzz build: clang's OpenMP
    // runtime, which it links beside Gmsh's GCC one, crashes in the parent after the fork, so
    // there the msh target fuzzes Gmsh's reader itself.
#ifndef STRATA_FUZZ_BUILD
    const GmshProbe trial = gmsh_probe(read);
    if (trial.ran && trial.threw) throw InputError(trial.message);
    if (trial.ran && !trial.returned)
        throw InputError(reading + ": Gmsh's MSH reader " + how_it_failed(trial) +
                         " on it: the file is damaged or not MSH 2.2 or 4.1; write it again");
#endif
    read();
}

std::vector<std::pair<int, std::string>> surface_patch_names(const std::vector<int>& surfaces) {
    const GmshLock lock("surface_patch_names");
    std::vector<Patch> patches;
    std::map<int, Index> patch_of;
    gmsh_call("naming the patches of the surfaces", [&] { patch_of = plan_patches(surfaces, patches); });
    std::vector<std::pair<int, std::string>> out;
    for (const auto& [s, p] : patch_of) out.emplace_back(s, patches[static_cast<std::size_t>(p)].name);
    return out;
}

}  // namespace strata
