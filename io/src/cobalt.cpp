// Cobalt60 ASCII writer (FORMATS.md, "Cobalt60").
//
// Numbering. Nodes are VolumeMesh::points, 1-based. Cells are 1-based in CellNumbering order
// (tetrahedra, pyramids, prisms, hexahedra, each block in VolumeMesh order): cell number =
// global cell index + 1, the same order as the validator and write_volume. Patches are numbered
// 1..npatches over the patches that have at least one boundary face, in patch-table order.
//
// Faces come from match_faces (strata/core/face_match.h), the matcher the validator uses: a
// node set held by two cells is an interior face, by one cell and one boundary face a boundary
// face; any other group is a TopologyError naming the face (the file is never written).
//
// Orientation and order. Each face is written once, as its first cell c1 lists it (outward from
// c1): c1 is the lower-numbered cell of an interior face, so the right-hand normal points from
// c1 to c2, and the cell of a boundary face, so the normal points out of the domain. Faces are
// written in slot order, (c1, c1's local face), so the file depends only on the mesh.
//
// Output. Both the grid and its `<path>.bc` patch map are written to temporary files through one
// large buffer (std::to_chars, one fwrite per MB) and renamed onto their targets only once both
// are complete. Coordinates use the shortest decimal form that reads back to the same double
// (std::to_chars), which round-trips exactly like %.17g but is shorter.

#include <strata/core/cell_faces.h>
#include <strata/core/error.h>
#include <strata/core/face_match.h>
#include <strata/core/format.h>
#include <strata/core/mesh_check.h>
#include <strata/io/cobalt.h>
#include <strata/io/files.h>

#include "buffered_file.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace strata {
namespace {

/// A patch name on one line of the .bc file: control characters become '_', an empty name
/// becomes "patch_<number>" so every line has three fields.
std::string bc_name(const std::string& name, Index number) {
    std::string s = name;
    for (char& c : s)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '_';
    if (s.find_first_not_of(" \t") == std::string::npos) return "patch_" + std::to_string(number);
    // Leading/trailing blanks would be lost by a reader that trims.
    const std::size_t b = s.find_first_not_of(' '), e = s.find_last_not_of(' ');
    return s.substr(b, e - b + 1);
}

/// Cells written between two checks for cancellation.
constexpr std::int64_t kCellsPerCheck = 1 << 16;

/// The second cell of every face as written, per slot: the 1-based cell across an interior
/// face when the slot's cell is the lower-numbered one (c1), −patch number on a boundary face,
/// and 0 when the face is written from the other cell.
std::vector<Index> second_cells(const FaceMatch& match, const std::vector<Index>& patch_number) {
    const SurfaceMesh& b = match.slots.mesh().boundary;
    std::vector<Index> c2(match.slots.count(), 0);
    for (std::uint64_t slot = 0; slot < match.slots.count(); ++slot) {
        const std::int64_t across = match.across[slot];
        if (across >= 0 && static_cast<std::uint64_t>(across) > slot)
            c2[slot] = static_cast<Index>(match.slots.cell(static_cast<std::uint64_t>(across)) + 1);
        else if (across < 0)
            c2[slot] = -patch_number[static_cast<std::size_t>(b.face_patch[static_cast<Index>(-1 - across)])];
    }
    return c2;
}

void write_grid(BufferedFile& out, const VolumeMesh& mesh, const std::vector<Index>& c2, Index npatches,
                Progress* progress) {
    std::int64_t nfaces = 0;
    for (Index c : c2) nfaces += c != 0;
    const CellNumbering cells(mesh);
    const bool hexes = !mesh.hexes.empty();
    const bool quads = hexes || !mesh.prisms.empty() || !mesh.pyramids.empty();
    out.put("3 1 ");
    out.put(static_cast<std::int64_t>(npatches));
    out.put('\n');
    out.put(static_cast<std::int64_t>(mesh.points.size()));
    out.put(' ');
    out.put(nfaces);
    out.put(' ');
    out.put(cells.count());
    out.put(quads ? " 4" : " 3");
    out.put(hexes ? " 6\n" : quads ? " 5\n" : " 4\n");
    for (const Vec3& x : mesh.points) {
        out.put_point(x);
        out.put('\n');
    }
    std::uint64_t slot = 0;
    for (CellType t : kCellTypes) {
        const CellFaceTable& table = cell_faces(t);
        for (std::size_t i = 0; i < mesh.num_cells(t); ++i) {
            const Index* v = mesh.cell(t, i);
            const std::int64_t c1 = cells.start(t) + static_cast<std::int64_t>(i) + 1;
            if (c1 % kCellsPerCheck == 0)
                report(progress, "writing", static_cast<double>(c1) / static_cast<double>(cells.count()));
            for (std::size_t f = 0; f < static_cast<std::size_t>(table.count); ++f, ++slot) {
                if (c2[slot] == 0) continue;  // written from its other cell
                out.put(static_cast<std::int64_t>(table.size[f]));
                for (std::size_t k = 0; k < static_cast<std::size_t>(table.size[f]); ++k) {
                    out.put(' ');
                    out.put(static_cast<std::int64_t>(v[table.node[f][k]]) + 1);
                }
                out.put(' ');
                out.put(c1);
                out.put(' ');
                out.put(static_cast<std::int64_t>(c2[slot]));
                out.put('\n');
            }
        }
    }
}

void write_bc(BufferedFile& out, const std::string& grid_path, const SurfaceMesh& b,
              const std::vector<Index>& patch_number) {
    const std::string grid_name = std::filesystem::path(grid_path).filename().string();
    out.put("# Boundary patches of the Cobalt60 grid '" + grid_name + "' (written by Strata).\n");
    out.put("# One line per patch: <number> <name> <kind>\n");
    out.put("#   number: the grid's patch number; its boundary faces have c2 = -number.\n");
    out.put("#   name:   everything between the number and the kind (may contain spaces).\n");
    out.put("#   kind:   wall, symmetry, farfield or other.\n");
    out.put("# Lines starting with '#' are comments.\n");
    for (std::size_t p = 0; p < b.patches.size(); ++p) {
        if (patch_number[p] == 0) continue;
        out.put(static_cast<std::int64_t>(patch_number[p]));
        out.put(' ');
        out.put(bc_name(b.patches[p].name, patch_number[p]));
        out.put(' ');
        out.put(to_string(b.patches[p].kind));
        out.put('\n');
    }
}

}  // namespace

void write_cobalt(const VolumeMesh& mesh, const std::string& path, Progress* progress, OutputSet* outputs) {
    report(progress, "writing", 0.0);
    const std::string where = "cannot write Cobalt grid '" + path + "': ";
    require_sound(check_volume_arrays(mesh), where);
    const FaceMatch match = match_faces(mesh);
    if (!match.ok())
        throw TopologyError(where + describe(match, match.problems.front()) +
                            "; run validate_mesh (strata/core/validate.h) for a full report");

    // Patch numbers 1..npatches over the patches with faces, in patch-table order.
    const SurfaceMesh& b = mesh.boundary;
    std::vector<Index> patch_number(b.patches.size(), 0);
    for (Index p : b.face_patch) patch_number[static_cast<std::size_t>(p)] = 1;
    Index npatches = 0;
    for (Index& p : patch_number) p = p ? ++npatches : 0;
    const std::vector<Index> c2 = second_cells(match, patch_number);

    // Targets: checked before anything is written, then both files complete before either is
    // renamed into place (with the caller's other outputs when it gives \p outputs).
    const std::string bc_path = path + ".bc";
    OutputSet own;
    OutputSet& set = outputs ? *outputs : own;
    AtomicFile& grid_file = set.file(path);
    AtomicFile& bc_file = set.file(bc_path);
    {
        BufferedFile out(grid_file.temp_path(), path);
        write_grid(out, mesh, c2, npatches, progress);
        out.close();
    }
    {
        BufferedFile out(bc_file.temp_path(), bc_path);
        write_bc(out, path, b, patch_number);
        out.close();
    }

    report(progress, "writing", 1.0);  // cancelled here: the temporary files go, nothing is written
    if (!outputs) own.commit();        // both or neither: no grid is left with another grid's patch map
}

}  // namespace strata
