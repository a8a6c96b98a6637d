// Surface-mesh writer through the Gmsh API (FORMATS.md: never write .msh by hand). The mesh
// becomes one discrete surface and one physical group per patch, both tagged patch index + 1,
// so the output is deterministic and read_msh gives the patches back by name.

#include <strata/core/error.h>
#include <strata/core/mesh_check.h>
#include <strata/io/atomic_file.h>
#include <strata/io/gmsh_session.h>
#include <strata/io/write_surface.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace strata {
namespace {

constexpr int kTriangle3 = 2;  // Gmsh element types
constexpr int kQuad4 = 3;

/// Mesh formats Gmsh 4.8 writes from a file extension (GuessFileFormatFromFileName). Images,
/// .geo and post-processing formats are left out: they are not meshes.
constexpr std::array<const char*, 20> kMeshExtensions = {
    ".msh", ".vtk", ".stl", ".su2", ".unv", ".mesh", ".bdf", ".nas", ".inp", ".cgns",
    ".med", ".mail", ".p3d", ".wrl", ".vrml", ".ply2", ".off", ".x3d", ".neu", ".key"};

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

void check_extension(const std::string& path) {
    const std::string ext = lower(std::filesystem::path(path).extension().string());
    for (const char* e : kMeshExtensions)
        if (ext == e) return;
    std::string list;
    for (const char* e : kMeshExtensions) list += (list.empty() ? "" : ", ") + std::string(e);
    throw InputError("cannot write '" + path + "': unknown mesh extension '" + ext + "'; use one of " + list);
}

void check_msh_version(const std::string& path, double version) {
    for (double v : {1.0, 2.0, 2.2, 4.0, 4.1})
        if (version == v) return;
    throw InputError("cannot write '" + path + "': MSH version " + std::to_string(version) +
                     " does not exist; use 4.1 (default) or 2.2");
}

/// Row p lists, ascending, the ids i with key[i] == p (keys kNone are left out).
Csr bucket(const std::vector<Index>& key, std::size_t rows) {
    Csr out;
    out.offsets.assign(rows + 1, 0);
    for (Index k : key)
        if (k != kNone) ++out.offsets[k + 1];
    for (std::size_t r = 0; r < rows; ++r) out.offsets[r + 1] += out.offsets[r];
    out.values.resize(out.offsets.back());
    std::vector<Index> fill(out.offsets.begin(), out.offsets.end() - 1);
    for (std::size_t i = 0; i < key.size(); ++i)
        if (key[i] != kNone) out.values[fill[key[i]]++] = static_cast<Index>(i);
    return out;
}

}  // namespace

void write_surface(const SurfaceMesh& mesh, const std::string& path, double msh_version) {
    check_extension(path);
    const bool is_msh = lower(std::filesystem::path(path).extension().string()) == ".msh";
    if (is_msh) check_msh_version(path, msh_version);
    require_sound(check_surface_arrays(mesh), "cannot write '" + path + "': ");

    const std::size_t num_patches = mesh.patches.size();
    const Index num_faces = mesh.num_faces();

    // Each node is classified on the lowest-numbered patch surface that uses it; unused nodes
    // are not written (a reader would drop them anyway).
    std::vector<Index> owner(mesh.points.size(), kNone);
    for (Index f = 0; f < num_faces; ++f) {
        const Index p = mesh.face_patch[f];
        for (const Index* v = mesh.face_begin(f); v != mesh.face_end(f); ++v)
            if (owner[*v] == kNone || p < owner[*v]) owner[*v] = p;
    }
    // Faces and nodes bucketed by patch (counting sort, ascending ids within a patch), so
    // many patches cost no more than one.
    const Csr patch_faces = bucket(mesh.face_patch, num_patches);
    const Csr patch_nodes = bucket(owner, num_patches);

    AtomicFile out(path);  // InputError now if the directory does not exist
    GmshSession session("write_surface");
    GmshOptionScope options;  // declared after the session: restored before the session ends
    gmsh_call("writing '" + path + "'", [&] {
        options.set("Mesh.MshFileVersion", msh_version);
        options.set("Mesh.Binary", 0);
        options.set("Mesh.SaveAll", 0);  // every written face is in a physical group anyway
        options.set("Mesh.ScalingFactor", 1);

        std::vector<std::size_t> node_tags, elem_tags, elem_nodes;
        std::vector<double> xyz;
        for (Index p = 0; p < static_cast<Index>(num_patches); ++p) {
            if (patch_faces.row_size(p) == 0) continue;
            const int tag = static_cast<int>(p) + 1;
            gmsh::model::addDiscreteEntity(2, tag);

            node_tags.clear();
            xyz.clear();
            for (const Index* v = patch_nodes.row_begin(p); v != patch_nodes.row_end(p); ++v) {
                node_tags.push_back(static_cast<std::size_t>(*v) + 1);
                const Vec3& x = mesh.points[*v];
                xyz.insert(xyz.end(), {x.x(), x.y(), x.z()});
            }
            gmsh::model::mesh::addNodes(2, tag, node_tags, xyz);

            for (Index n : {3, 4}) {
                elem_tags.clear();
                elem_nodes.clear();
                for (const Index* f = patch_faces.row_begin(p); f != patch_faces.row_end(p); ++f) {
                    if (mesh.face_size(*f) != n) continue;
                    // Element tag = face index + 1: read_msh restores the face order from it.
                    elem_tags.push_back(static_cast<std::size_t>(*f) + 1);
                    for (const Index* v = mesh.face_begin(*f); v != mesh.face_end(*f); ++v)
                        elem_nodes.push_back(static_cast<std::size_t>(*v) + 1);
                }
                if (!elem_tags.empty())
                    gmsh::model::mesh::addElementsByType(tag, n == 3 ? kTriangle3 : kQuad4, elem_tags,
                                                         elem_nodes);
            }

            gmsh::model::addPhysicalGroup(2, {tag}, tag);
            gmsh::model::setPhysicalName(2, tag, mesh.patches[p].name);
        }
        gmsh::write(out.temp_path());
    });
    out.commit();
}

}  // namespace strata
