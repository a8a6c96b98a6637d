// OpenFOAM polyMesh writer (the layout OpenFOAM's utilities write: blockMesh, gmshToFoam).
//
// Faces come from match_faces (strata/core/face_match.h), the matcher the validator and the
// Cobalt60 writer use, so there is one definition of an interior and a boundary face. Cells are
// numbered in CellNumbering order; face slots are numbered cell by cell in that order, so an
// interior face seen from its lower-numbered cell (its first slot) has owner < neighbour, and
// its nodes as that cell lists them (cell_faces: outward) point out of the owner. OpenFOAM
// asks for the internal faces in upper-triangular order: owners ascending come from the slot
// order, and each owner's few faces (at most 6) are sorted by neighbour, ties (two cells
// sharing two faces, which only a degenerate mesh has) by slot. Boundary faces follow, patch
// by patch in patch-table order, each patch's faces in slot order (by owner). Nothing depends
// on the thread count: match_faces does not, and the rest is serial.
//
// Output: five ASCII files in a temporary directory next to the target (AtomicDirectory),
// numbers by std::to_chars (coordinates in their shortest exact form), then the directory is put
// in place whole.

#include <strata/core/cell_faces.h>
#include <strata/core/error.h>
#include <strata/core/face_match.h>
#include <strata/core/mesh_check.h>
#include <strata/io/files.h>
#include <strata/io/openfoam.h>

#include "buffered_file.h"
#include "foam_dictionary.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace strata {
namespace {

PolyMesh build_polymesh(const VolumeMesh& mesh, const std::string& where, int threads) {
    require_sound(check_volume_arrays(mesh), where);
    const FaceMatch match = match_faces(mesh, threads);
    if (!match.ok())
        throw TopologyError(where + describe(match, match.problems.front()) +
                            "; run validate_mesh (strata/core/validate.h) for a full report");
    const FaceSlots& slots = match.slots;
    const SurfaceMesh& b = mesh.boundary;

    PolyMesh pm;
    pm.num_cells = slots.cells().count();
    std::array<Index, 4> nodes{};
    auto add_face = [&](std::uint64_t slot) {
        const int n = slots.nodes(slot, nodes.data());
        pm.face_nodes.insert(pm.face_nodes.end(), nodes.begin(), nodes.begin() + n);
        pm.face_offsets.push_back(static_cast<std::int64_t>(pm.face_nodes.size()));
        pm.owner.push_back(static_cast<Index>(slots.cell(slot)));
    };

    // Internal faces: (owner, neighbour, slot) in slot order, then each owner's run sorted.
    struct Internal {
        std::int64_t owner, neighbour;
        std::uint64_t slot;
    };
    std::vector<Internal> internal;
    internal.reserve(static_cast<std::size_t>(match.interior));
    std::vector<std::vector<std::uint64_t>> on_patch(b.patches.size());
    for (std::uint64_t slot = 0; slot < slots.count(); ++slot) {
        const std::int64_t across = match.across[slot];
        if (across >= 0 && static_cast<std::uint64_t>(across) > slot)
            internal.push_back({slots.cell(slot), slots.cell(static_cast<std::uint64_t>(across)), slot});
        else if (across < 0)
            on_patch[static_cast<std::size_t>(b.face_patch[static_cast<Index>(-1 - across)])].push_back(slot);
    }
    for (std::size_t i = 0; i < internal.size();) {
        std::size_t j = i + 1;
        while (j < internal.size() && internal[j].owner == internal[i].owner) ++j;
        std::sort(internal.begin() + static_cast<std::ptrdiff_t>(i), internal.begin() + static_cast<std::ptrdiff_t>(j),
                  [](const Internal& x, const Internal& y) {
                      return x.neighbour != y.neighbour ? x.neighbour < y.neighbour : x.slot < y.slot;
                  });
        i = j;
    }
    pm.face_offsets.reserve(internal.size() + static_cast<std::size_t>(match.boundary) + 1);
    pm.neighbour.reserve(internal.size());
    for (const Internal& f : internal) {
        add_face(f.slot);
        pm.neighbour.push_back(static_cast<Index>(f.neighbour));
    }

    std::vector<std::string> names;
    for (const Patch& p : b.patches) names.push_back(p.name);
    names = foam_patch_names(names);
    for (std::size_t p = 0; p < b.patches.size(); ++p) {
        if (on_patch[p].empty()) continue;
        pm.patches.push_back(
            {names[p], b.patches[p].kind, pm.num_faces(), static_cast<std::int64_t>(on_patch[p].size())});
        for (std::uint64_t slot : on_patch[p]) add_face(slot);
    }
    return pm;
}

// ---------------------------------------------------------------------------------------
// The files.

void put_header(BufferedFile& out, std::string_view cls, std::string_view object, std::string_view note = {}) {
    out.put(foam_header(cls, "constant/polyMesh", object, note));
}

void put_labels(BufferedFile& out, const std::vector<Index>& labels) {
    out.put('\n');
    out.put(static_cast<std::int64_t>(labels.size()));
    out.put("\n(\n");
    for (Index l : labels) {
        out.put(static_cast<std::int64_t>(l));
        out.put('\n');
    }
    out.put(")\n\n\n");
    out.put(kFoamFooter);
}

void write_points(BufferedFile& out, const VolumeMesh& mesh) {
    put_header(out, "vectorField", "points");
    out.put('\n');
    out.put(static_cast<std::int64_t>(mesh.points.size()));
    out.put("\n(\n");
    for (const Vec3& x : mesh.points) {
        out.put('(');
        out.put_point(x);
        out.put(")\n");
    }
    out.put(")\n\n\n");
    out.put(kFoamFooter);
}

void write_faces(BufferedFile& out, const PolyMesh& pm, Progress* progress) {
    put_header(out, "faceList", "faces");
    out.put('\n');
    out.put(pm.num_faces());
    out.put("\n(\n");
    for (std::int64_t f = 0; f < pm.num_faces(); ++f) {
        if (f % (1 << 16) == 0)
            report(progress, "writing", 0.1 + 0.5 * static_cast<double>(f) / static_cast<double>(pm.num_faces()));
        const auto b = static_cast<std::size_t>(pm.face_offsets[static_cast<std::size_t>(f)]);
        const auto e = static_cast<std::size_t>(pm.face_offsets[static_cast<std::size_t>(f) + 1]);
        out.put(static_cast<std::int64_t>(e - b));
        out.put('(');
        for (std::size_t k = b; k < e; ++k) {
            if (k != b) out.put(' ');
            out.put(static_cast<std::int64_t>(pm.face_nodes[k]));
        }
        out.put(")\n");
    }
    out.put(")\n\n\n");
    out.put(kFoamFooter);
}

void write_boundary(BufferedFile& out, const PolyMesh& pm) {
    put_header(out, "polyBoundaryMesh", "boundary");
    out.put(static_cast<std::int64_t>(pm.patches.size()));
    out.put("\n(\n");
    for (const PolyPatch& p : pm.patches) {
        const std::string_view type = openfoam_patch_type(p.kind);
        out.put("    ");
        out.put(p.name);
        out.put("\n    {\n        type            ");
        out.put(type);
        out.put(";\n");
        // As OpenFOAM writes them: wall and constraint types (symmetry) carry their type as group.
        if (type != "patch") {
            out.put("        inGroups        1(");
            out.put(type);
            out.put(");\n");
        }
        out.put("        nFaces          ");
        out.put(p.size);
        out.put(";\n        startFace       ");
        out.put(p.start);
        out.put(";\n    }\n");
    }
    out.put(")\n\n");
    out.put(kFoamFooter);
}

}  // namespace

std::string_view openfoam_patch_type(PatchKind kind) {
    switch (kind) {
        case PatchKind::Wall:
            return "wall";
        case PatchKind::Symmetry:
            return "symmetry";
        case PatchKind::Farfield:
        case PatchKind::Other:
            break;
    }
    return "patch";
}

std::vector<std::string> foam_patch_names(const std::vector<std::string>& names) {
    std::vector<std::string> out;
    std::set<std::string> taken;
    for (std::size_t i = 0; i < names.size(); ++i) {
        const std::string w = patch_word(names[i], i);
        std::string unique = w;
        for (int k = 2; taken.count(unique); ++k) unique = w + "_" + std::to_string(k);
        taken.insert(unique);
        out.push_back(unique);
    }
    return out;
}

PolyMesh to_polymesh(const VolumeMesh& mesh, int threads) {
    return build_polymesh(mesh, "cannot convert to an OpenFOAM polyMesh: ", threads);
}

std::vector<PolyPatch> write_polymesh(const VolumeMesh& mesh, const std::string& path, Progress* progress,
                                      OutputSet* outputs) {
    report(progress, "writing", 0.0);
    const std::string where = "cannot write OpenFOAM polyMesh '" + path + "': ";
    check_output_directory(path);  // before the work: a bad path should not cost the conversion
    const PolyMesh pm = build_polymesh(mesh, where, 0);

    OutputSet own;
    AtomicDirectory& dir = (outputs ? *outputs : own).directory(path);
    const std::string target = dir.target() + "/";
    const std::string note = "nPoints:" + std::to_string(mesh.points.size()) +
                             "  nCells:" + std::to_string(pm.num_cells) + "  nFaces:" + std::to_string(pm.num_faces()) +
                             "  nInternalFaces:" + std::to_string(pm.num_internal_faces());
    {
        BufferedFile out(dir.file("points"), target + "points");
        write_points(out, mesh);
        out.close();
    }
    {
        BufferedFile out(dir.file("faces"), target + "faces");
        write_faces(out, pm, progress);
        out.close();
    }
    report(progress, "writing", 0.7);
    {
        BufferedFile out(dir.file("owner"), target + "owner");
        put_header(out, "labelList", "owner", note);
        put_labels(out, pm.owner);
        out.close();
    }
    {
        BufferedFile out(dir.file("neighbour"), target + "neighbour");
        put_header(out, "labelList", "neighbour", note);
        put_labels(out, pm.neighbour);
        out.close();
    }
    {
        BufferedFile out(dir.file("boundary"), target + "boundary");
        write_boundary(out, pm);
        out.close();
    }
    report(progress, "writing", 1.0);  // cancelled here: the temporary directory goes, nothing is written
    if (!outputs) own.commit();
    return pm.patches;
}

}  // namespace strata
