// ASCII MSH 4.1 written by Strata; see msh41_writer.h. The layout is Gmsh 4.8's own for the
// model add_volume_to_gmsh_model builds (empty node blocks on the surfaces, every node on the
// volume), so a file reads back through Gmsh to the same model either way.

#include "msh41_writer.h"

#include "buffered_file.h"
#include "gmsh_element_types.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <utility>
#include <vector>

namespace strata {
namespace {

using namespace gmsh_types;

/// The patches that have faces, in patch order (their surfaces are tagged patch index + 1).
std::vector<Index> used_patches(const Csr& patch_faces) {
    std::vector<Index> used;
    for (Index p = 0; p < patch_faces.rows(); ++p)
        if (patch_faces.row_size(p) > 0) used.push_back(p);
    return used;
}

struct Box {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 hi = -Vec3::Constant(std::numeric_limits<double>::infinity());
    void add(const Vec3& x) { lo = lo.cwiseMin(x), hi = hi.cwiseMax(x); }
};

void put_box(BufferedFile& out, const Box& b) {
    out.put_point(b.lo);
    out.put(' ');
    out.put_point(b.hi);
}

/// Per name, its group tag (its first patch's index + 1) and its surfaces, in the order of
/// their first patches.
std::vector<std::pair<std::string, std::pair<int, std::vector<int>>>> patch_groups(const SurfaceMesh& b,
                                                                                   const std::vector<Index>& used) {
    std::vector<std::pair<std::string, std::pair<int, std::vector<int>>>> groups;
    std::map<std::string, std::size_t> at;
    for (const Index p : used) {
        const std::string& name = b.patches[static_cast<std::size_t>(p)].name;
        auto [it, added] = at.try_emplace(name, groups.size());
        if (added) groups.push_back({name, {static_cast<int>(p) + 1, {}}});
        groups[it->second].second.second.push_back(static_cast<int>(p) + 1);
    }
    return groups;
}

void put_header(BufferedFile& out, const VolumeMesh& mesh, const Csr& patch_faces, const std::vector<Index>& used) {
    const SurfaceMesh& b = mesh.boundary;
    const auto groups = patch_groups(b, used);
    out.put("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n");
    out.put(static_cast<std::int64_t>(groups.size() + 1));
    out.put('\n');
    for (const auto& [name, group] : groups) {
        out.put("2 ");
        out.put(static_cast<std::int64_t>(group.first));
        out.put(" \"");
        out.put(name);
        out.put("\"\n");
    }
    out.put("3 1 \"fluid\"\n$EndPhysicalNames\n$Entities\n0 0 ");
    out.put(static_cast<std::int64_t>(used.size()));
    out.put(" 1\n");
    std::map<int, int> group_of_surface;
    for (const auto& [name, group] : groups)
        for (const int s : group.second) group_of_surface[s] = group.first;
    for (const Index p : used) {
        Box box;
        for (const Index* f = patch_faces.row_begin(p); f != patch_faces.row_end(p); ++f)
            for (const Index* v = b.face_begin(*f); v != b.face_end(*f); ++v)
                box.add(mesh.points[static_cast<std::size_t>(*v)]);
        out.put(static_cast<std::int64_t>(p + 1));
        out.put(' ');
        put_box(out, box);
        out.put(" 1 ");
        out.put(static_cast<std::int64_t>(group_of_surface.at(static_cast<int>(p) + 1)));
        out.put(" 0\n");
    }
    Box all;
    for (const Vec3& x : mesh.points) all.add(x);
    out.put("1 ");
    put_box(out, all);
    out.put(" 1 1 ");
    out.put(static_cast<std::int64_t>(used.size()));
    for (const Index p : used) {
        out.put(' ');
        out.put(static_cast<std::int64_t>(p + 1));
    }
    out.put("\n$EndEntities\n");
}

void put_nodes(BufferedFile& out, const VolumeMesh& mesh, const std::vector<Index>& used) {
    const auto n = static_cast<std::int64_t>(mesh.points.size());
    out.put("$Nodes\n");
    out.put(static_cast<std::int64_t>(used.size() + 1));
    out.put(' ');
    out.put(n);
    out.put(n > 0 ? " 1 " : " 0 ");
    out.put(n);
    out.put('\n');
    for (const Index p : used) {
        out.put("2 ");
        out.put(static_cast<std::int64_t>(p + 1));
        out.put(" 0 0\n");
    }
    out.put("3 1 0 ");
    out.put(n);
    out.put('\n');
    for (std::int64_t i = 1; i <= n; ++i) {
        out.put(i);
        out.put('\n');
    }
    for (const Vec3& x : mesh.points) {
        out.put_point(x);
        out.put('\n');
    }
    out.put("$EndNodes\n");
}

/// One element block: "dim entity type count", then "tag node..." per element.
template <class Nodes>
void put_block(BufferedFile& out, int dim, std::int64_t entity, int type, std::size_t count, Nodes&& element) {
    out.put(static_cast<std::int64_t>(dim));
    out.put(' ');
    out.put(entity);
    out.put(' ');
    out.put(static_cast<std::int64_t>(type));
    out.put(' ');
    out.put(static_cast<std::int64_t>(count));
    out.put('\n');
    for (std::size_t e = 0; e < count; ++e) element(e);
}

template <std::size_t N>
void put_cells(BufferedFile& out, const std::vector<std::array<Index, N>>& cells, int type, std::int64_t& tag) {
    if (cells.empty()) return;
    put_block(out, 3, 1, type, cells.size(), [&](std::size_t c) {
        out.put(tag++);
        for (const Index v : cells[c]) {
            out.put(' ');
            out.put(static_cast<std::int64_t>(v) + 1);
        }
        out.put('\n');
    });
}

void put_elements(BufferedFile& out, const VolumeMesh& mesh, const Csr& patch_faces, const std::vector<Index>& used,
                  Progress* progress) {
    const SurfaceMesh& b = mesh.boundary;
    const auto cells = static_cast<std::int64_t>(mesh.num_cells());
    std::size_t blocks = mesh.tets.empty() + mesh.pyramids.empty() + mesh.prisms.empty() + mesh.hexes.empty();
    blocks = 4 - blocks;
    std::vector<std::vector<Index>> by_size(used.size() * 2);  // per used patch: triangles, quads
    for (std::size_t u = 0; u < used.size(); ++u)
        for (const Index* f = patch_faces.row_begin(used[u]); f != patch_faces.row_end(used[u]); ++f)
            by_size[2 * u + (b.face_size(*f) == 4 ? 1 : 0)].push_back(*f);
    for (const auto& faces : by_size) blocks += !faces.empty();
    const auto faces = static_cast<std::int64_t>(b.num_faces());
    out.put("$Elements\n");
    out.put(static_cast<std::int64_t>(blocks));
    out.put(' ');
    out.put(cells + faces);
    out.put(cells + faces > 0 ? " 1 " : " 0 ");
    out.put(cells + faces);
    out.put('\n');
    for (std::size_t u = 0; u < used.size(); ++u)
        for (int quads = 0; quads < 2; ++quads) {
            const std::vector<Index>& list = by_size[2 * u + static_cast<std::size_t>(quads)];
            if (list.empty()) continue;
            put_block(out, 2, used[u] + 1, quads ? kQuad4 : kTriangle3, list.size(), [&](std::size_t i) {
                out.put(cells + list[i] + 1);
                for (const Index* v = b.face_begin(list[i]); v != b.face_end(list[i]); ++v) {
                    out.put(' ');
                    out.put(static_cast<std::int64_t>(*v) + 1);
                }
                out.put('\n');
            });
        }
    report(progress, "writing", 0.5);
    std::int64_t tag = 1;
    put_cells(out, mesh.tets, kTet4, tag);
    put_cells(out, mesh.pyramids, kPyramid5, tag);
    put_cells(out, mesh.prisms, kPrism6, tag);
    put_cells(out, mesh.hexes, kHex8, tag);
    out.put("$EndElements\n");
}

}  // namespace

void write_msh41_ascii(const VolumeMesh& mesh, const std::string& path, Progress* progress, OutputSet* outputs) {
    report(progress, "writing", 0.0);
    OutputSet own;
    AtomicFile& file = (outputs ? *outputs : own).file(path);
    const Csr patch_faces = group_by_key(mesh.boundary.face_patch, mesh.boundary.patches.size());
    const std::vector<Index> used = used_patches(patch_faces);
    {
        BufferedFile out(file.temp_path(), path);
        put_header(out, mesh, patch_faces, used);
        put_nodes(out, mesh, used);
        put_elements(out, mesh, patch_faces, used, progress);
        out.close();
    }
    report(progress, "writing", 1.0);  // cancelled here: the temporary file goes, nothing is written
    if (!outputs) own.commit();
}

}  // namespace strata
