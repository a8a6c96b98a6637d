#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/core/mesh_check.h>

#include <algorithm>
#include <utility>

namespace strata {

void MeshProblems::add(std::string line, bool non_finite) {
    if (count == 0) first_non_finite = non_finite;
    if (count++ < kMaxLines) lines.push_back(std::move(line));
}

namespace {

void check_points(const std::vector<Vec3>& points, MeshProblems& out) {
    for (std::size_t i = 0; i < points.size(); ++i)
        if (!points[i].allFinite())
            out.add("node " + std::to_string(i) + " has a non-finite coordinate " + format_point(points[i], 9), true);
}

}  // namespace

MeshProblems check_face_arrays(const SurfaceMesh& mesh, const std::vector<Vec3>& points, const FaceRules& rules) {
    MeshProblems out;
    const std::string word = rules.word;
    const bool triangles_only = rules.triangles_only;
    // Non-decreasing from 0 to the end: every face's range then lies in face_nodes.
    if (mesh.face_offsets.empty() || mesh.face_offsets.front() != 0 ||
        static_cast<std::size_t>(mesh.face_offsets.back()) != mesh.face_nodes.size() ||
        !std::is_sorted(mesh.face_offsets.begin(), mesh.face_offsets.end())) {
        out.add(word +
                " offsets are malformed (they must start at 0, never decrease and end at the number of "
                "face nodes)");
        out.indexable = false;
        return out;
    }
    const Index nf = mesh.num_faces();
    if (nf == 0 && rules.require_faces)
        out.add("no faces; the surface mesh is empty, check that the input holds triangles or quadrilaterals");
    if (rules.patches && mesh.face_patch.size() != static_cast<std::size_t>(nf)) {
        out.add(word + " patches: " + std::to_string(mesh.face_patch.size()) + " entries for " + std::to_string(nf) +
                " faces");
        out.indexable = false;
    }
    const auto np = static_cast<Index>(points.size());
    const auto npatch = static_cast<Index>(mesh.patches.size());
    for (Index f = 0; f < nf; ++f) {
        const Index n = mesh.face_size(f);
        if (n != 3 && (triangles_only || n != 4)) {
            out.add(word + " " + std::to_string(f) + " has " + std::to_string(n) + " nodes; only " +
                    (triangles_only ? "triangles are" : "triangles and quadrilaterals are") + " supported");
            if (n < 3 || n > 4) out.indexable = false;
            continue;
        }
        for (const Index* v = mesh.face_begin(f); v != mesh.face_end(f); ++v)
            if (*v < 0 || *v >= np) {
                out.add(word + " " + std::to_string(f) + " " + format_nodes(mesh.face_begin(f), static_cast<int>(n)) +
                        " uses node " + std::to_string(*v) + ", but the mesh has " + std::to_string(np) + " nodes");
                out.indexable = false;
                break;
            }
        if (rules.patches && static_cast<std::size_t>(f) < mesh.face_patch.size()) {
            const Index p = mesh.face_patch[f];
            if (p < 0 || p >= npatch) {
                out.add(word + " " + std::to_string(f) + " is on patch " + std::to_string(p) + ", but there are " +
                        std::to_string(npatch) + " patches");
                out.indexable = false;
            }
        }
    }
    if (rules.coordinates) check_points(points, out);
    return out;
}

MeshProblems check_volume_arrays(const VolumeMesh& mesh) {
    MeshProblems out;
    if (mesh.num_cells() == 0) out.add("the mesh has no cells");
    const auto np = static_cast<Index>(mesh.points.size());
    for (CellType t : kCellTypes) {
        const int n = cell_corners(t);
        for (std::size_t i = 0; i < mesh.num_cells(t); ++i) {
            const Index* v = mesh.cell(t, i);
            for (int k = 0; k < n; ++k)
                if (v[k] < 0 || v[k] >= np) {
                    out.add(std::string(to_string(t)) + " " + std::to_string(i) + " " + format_nodes(v, n) +
                            " uses node " + std::to_string(v[k]) + " but the mesh has " + std::to_string(np) +
                            " nodes");
                    out.indexable = false;
                    break;
                }
        }
    }
    const MeshProblems faces =
        check_face_arrays(mesh.boundary, mesh.points, {.require_faces = false, .word = "boundary face"});
    for (std::size_t i = 0; i < faces.lines.size(); ++i) out.add(faces.lines[i], i == 0 && faces.first_non_finite);
    out.count += faces.count - faces.lines.size();
    out.indexable = out.indexable && faces.indexable;
    return out;
}

void require_sound(const MeshProblems& problems, const std::string& where) {
    if (problems.ok()) return;
    const std::string more =
        problems.count > 1 ? " (and " + std::to_string(problems.count - 1) + " more problems)" : "";
    if (problems.first_non_finite) throw TopologyError(where + problems.lines.front() + more);
    throw InputError(where + problems.lines.front() + more);
}

}  // namespace strata
