// Cobalt60 ASCII writer (FORMATS.md, "Cobalt60").
//
// Numbering. Nodes are VolumeMesh::points, 1-based. Cells are 1-based in the order tetrahedra,
// pyramids, prisms, hexahedra, each block in VolumeMesh order: cell number = global cell index
// + 1, the same global order as validate.h and write_volume.h. Patches are numbered 1..npatches
// over the patches that have at least one boundary face, in patch-table order.
//
// Faces. Every local face of every cell (Gmsh-order face tables below, the same tables and
// orientation as module/src/validate.cpp: right-hand normal out of the cell) is matched with the
// other cell faces and the boundary faces by its sorted node set. Faces are bucketed by their
// smallest node (counting sort, one small integer code per face) and each bucket is sorted by
// the sorted node set, so 5M cells cost a few hundred MB and a few seconds, O(n log n). A node
// set held by exactly two cells is an interior face; by one cell and one boundary face, a
// boundary face; anything else is a TopologyError naming the face (the file is never written).
//
// Orientation and order. Each face is written once, as its first cell c1 lists it (outward from
// c1): c1 is the lower-numbered cell of an interior face, so the right-hand normal points from
// c1 to c2, and the cell of a boundary face, so the normal points out of the domain (the
// boundary face's own node order is not used; validate_mesh checks it agrees). Faces are written
// in the order of (c1, c1's local face), so the file depends only on the mesh.
//
// Output. Both the grid and its `<path>.bc` patch map are written to temporary files through one
// large buffer (std::to_chars, one fwrite per MB) and renamed onto their targets only once both
// are complete. Coordinates use the shortest decimal form that reads back to the same double
// (std::to_chars), which round-trips exactly like %.17g but is shorter.

#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/io/atomic_file.h>
#include <strata/io/cobalt.h>
#include <strata/core/cell_faces.h>

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

// ---------------------------------------------------------------------------------------
// Local faces of each cell type, Gmsh node order, right-hand normal pointing out of the cell.
// Identical to validate.cpp's tables (tests/hybrid/test_cobalt.cpp checks every written face
// geometrically and runs validate_mesh on the mesh rebuilt from the file).

using FaceTable = CellFaceTable;  // module/cell_faces.h
constexpr const auto& kTypes = kCellTypes;

// ---------------------------------------------------------------------------------------
// Messages.

std::string fmt_nodes(const Index* v, int n) {
    std::string s = "(";
    for (int i = 0; i < n; ++i) {
        if (i) s += ' ';
        s += std::to_string(v[i]);
    }
    return s + ')';
}

// ---------------------------------------------------------------------------------------
// Cells and their face slots. Global cell g (0-based, tets first) has its local faces in
// consecutive slots; slot = slot_start[type] + (index within type) × faces per cell + local face.
// Slot order is therefore (cell, local face) order, the order faces are written in.

class Cells {
public:
    explicit Cells(const VolumeMesh& m) : m_(m) {
        const std::array<std::size_t, 4> sizes{m.tets.size(), m.pyramids.size(), m.prisms.size(), m.hexes.size()};
        for (int t = 0; t < 4; ++t) {
            start_[t + 1] = start_[t] + static_cast<std::int64_t>(sizes[t]);
            slot_start_[t + 1] = slot_start_[t] + static_cast<std::uint64_t>(sizes[t]) *
                                                      static_cast<std::uint64_t>(cell_faces(kTypes[t]).count);
        }
    }
    std::int64_t count() const { return start_[4]; }
    std::int64_t count(int t) const { return start_[t + 1] - start_[t]; }
    std::int64_t start(int t) const { return start_[t]; }
    std::uint64_t num_slots() const { return slot_start_[4]; }
    std::uint64_t slot_start(int t) const { return slot_start_[t]; }

    const Index* nodes(int t, std::int64_t i) const { return cell_nodes(m_, t, i); }

    struct Slot {
        int type;
        std::int64_t index;  // within the type
        int face;            // local face
    };
    Slot locate(std::uint64_t slot) const {
        int t = 0;
        while (t < 3 && slot >= slot_start_[t + 1]) ++t;
        const std::uint64_t r = slot - slot_start_[t];
        const auto per = static_cast<std::uint64_t>(cell_faces(kTypes[t]).count);
        return {t, static_cast<std::int64_t>(r / per), static_cast<int>(r % per)};
    }
    std::int64_t global_cell(const Slot& s) const { return start_[s.type] + s.index; }

    /// Nodes of the face in \p slot, outward from its cell; returns the node count.
    int face_nodes(std::uint64_t slot, Index* out) const {
        const Slot s = locate(slot);
        const FaceTable& table = cell_faces(kTypes[s.type]);
        const Index* v = nodes(s.type, s.index);
        const int n = table.size[s.face];
        for (int k = 0; k < n; ++k) out[k] = v[table.node[s.face][k]];
        return n;
    }

    /// "hexahedron 3 (cell 12 in the file) at (x, y, z)".
    std::string describe(int t, std::int64_t i) const {
        const Index* v = nodes(t, i);
        const int n = cell_corners(kTypes[t]);
        Vec3 c = Vec3::Zero();
        for (int k = 0; k < n; ++k) c += m_.points[v[k]];
        return std::string(to_string(kTypes[t])) + " " + std::to_string(i) + " (cell " +
               std::to_string(start_[t] + i + 1) + " in the file) at " + format_point(c / static_cast<double>(n));
    }
    std::string describe_slot(std::uint64_t slot) const {
        const Slot s = locate(slot);
        return describe(s.type, s.index);
    }

private:
    const VolumeMesh& m_;
    std::array<std::int64_t, 5> start_{};
    std::array<std::uint64_t, 5> slot_start_{};
};

// ---------------------------------------------------------------------------------------
// Input sanity: indices in range, face sizes, finite coordinates. Matching dereferences
// without looking afterwards.

// ---------------------------------------------------------------------------------------
// Face matching. A face code is a slot (< num_slots) or num_slots + boundary face index.

template <class Code>
FaceBuckets<Code> bucket_faces(const VolumeMesh& mesh, const Cells& cells) {
    // Codes in ascending order within each bucket: the slot order.
    return bucket_faces_by_min_node<Code>(
        mesh,
        [&](int t, std::int64_t i, int f) {
            return cells.slot_start(t) +
                   static_cast<std::uint64_t>(i) * static_cast<std::uint64_t>(cell_faces(kTypes[t]).count) +
                   static_cast<std::uint64_t>(f);
        },
        [&](Index f) { return cells.num_slots() + static_cast<std::uint64_t>(f); });
}

using Item = KeyedFace;  // module/cell_faces.h

/// For each slot, the second cell of the face as written (1-based cell, or −patch number)
/// when the slot's cell is the face's c1, and 0 when the face is written from the other cell.
class Matcher {
public:
    Matcher(const VolumeMesh& mesh, const Cells& cells, const std::vector<Index>& patch_number, std::string where)
        : mesh_(mesh), cells_(cells), patch_number_(patch_number), where_(std::move(where)) {}

    std::vector<Index> run() {
        const std::uint64_t codes = cells_.num_slots() + static_cast<std::uint64_t>(mesh_.boundary.num_faces());
        if (codes < (std::uint64_t{1} << 32)) return run_with<std::uint32_t>();  // half the memory
        return run_with<std::uint64_t>();
    }

private:
    template <class Code>
    std::vector<Index> run_with() {
        std::vector<Index> other(cells_.num_slots(), 0);
        const FaceBuckets<Code> buckets = bucket_faces<Code>(mesh_, cells_);
        std::vector<Item> items;
        std::vector<std::uint64_t> cs, bs;
        Index v[4];
        for (std::size_t node = 0; node + 1 < buckets.offsets.size(); ++node) {
            const std::size_t begin = buckets.offsets[node], end = buckets.offsets[node + 1];
            if (begin == end) continue;
            items.clear();
            for (std::size_t e = begin; e < end; ++e) {
                const std::uint64_t code = buckets.codes[e];
                const int n = nodes(code, v);
                items.push_back({sorted_face_key(v, n), code});
            }
            std::sort(items.begin(), items.end());
            for (std::size_t g = 0; g < items.size();) {
                std::size_t h = g;
                cs.clear();
                bs.clear();
                for (; h < items.size() && items[h].key == items[g].key; ++h)
                    (is_cell(items[h].code) ? cs : bs).push_back(items[h].code);
                judge(cs, bs, other);
                g = h;
            }
        }
        return other;
    }

    bool is_cell(std::uint64_t code) const { return code < cells_.num_slots(); }
    Index boundary_face(std::uint64_t code) const { return static_cast<Index>(code - cells_.num_slots()); }

    int nodes(std::uint64_t code, Index* out) const {
        if (is_cell(code)) return cells_.face_nodes(code, out);
        const Index f = boundary_face(code);
        std::copy(mesh_.boundary.face_begin(f), mesh_.boundary.face_end(f), out);
        return static_cast<int>(mesh_.boundary.face_size(f));
    }

    std::string describe_boundary(Index f) const {
        const SurfaceMesh& b = mesh_.boundary;
        return "boundary face " + std::to_string(f) + " " +
               fmt_nodes(b.face_begin(f), static_cast<int>(b.face_size(f))) + " of patch '" +
               b.patches[b.face_patch[f]].name + "'";
    }
    /// "face (a b c) of hexahedron 3 (cell 12 in the file) at (x, y, z)".
    std::string describe_face(std::uint64_t slot) const {
        Index v[4];
        const int n = cells_.face_nodes(slot, v);
        return "face " + fmt_nodes(v, n) + " of " + cells_.describe_slot(slot);
    }

    [[noreturn]] void fail(const std::string& what) const {
        throw TopologyError(where_ + what + "; run validate_mesh (strata/module/validate.h) for a full report");
    }

    void judge(const std::vector<std::uint64_t>& cs, const std::vector<std::uint64_t>& bs, std::vector<Index>& other) {
        if (cs.size() == 2 && bs.empty()) {
            // cs is ascending (items sort by code within a key): cs[0] is the lower cell, c1.
            const Cells::Slot a = cells_.locate(cs[0]), b = cells_.locate(cs[1]);
            const std::int64_t ga = cells_.global_cell(a), gb = cells_.global_cell(b);
            Index fa[4], fb[4];
            const int n = cells_.face_nodes(cs[0], fa);
            cells_.face_nodes(cs[1], fb);
            if (ga == gb)
                fail(cells_.describe(a.type, a.index) + " has two faces with the same nodes " + fmt_nodes(fa, n) +
                     " (a degenerate cell)");
            if (relative_orientation(fa, fb, n) != -1)
                fail(cells_.describe(a.type, a.index) + " and " + cells_.describe(b.type, b.index) +
                     " overlap or one is inverted at face " + fmt_nodes(fa, n) + " (they list it as " +
                     fmt_nodes(fa, n) + " and " + fmt_nodes(fb, n) +
                     ", not one the reverse of the other), so no face orientation fits both");
            other[cs[0]] = static_cast<Index>(gb + 1);
            return;
        }
        if (cs.size() == 1 && bs.size() == 1) {
            const Index f = boundary_face(bs[0]);
            other[cs[0]] = -patch_number_[mesh_.boundary.face_patch[f]];
            return;
        }
        if (cs.size() >= 3) {
            Index fa[4];
            const int n = cells_.face_nodes(cs[0], fa);
            std::string s = "face " + fmt_nodes(fa, n) + " is shared by " + std::to_string(cs.size()) + " cells:";
            for (std::size_t k = 0; k < cs.size(); ++k) s += (k ? ", " : " ") + cells_.describe_slot(cs[k]);
            fail(s + " (a face joins at most two cells: duplicated or overlapping cells)");
        }
        if (cs.size() == 2)
            fail(describe_boundary(boundary_face(bs[0])) + " is an interior face between " +
                 cells_.describe_slot(cs[0]) + " and " + cells_.describe_slot(cs[1]) + "; remove it from the boundary");
        if (cs.size() == 1) {
            if (bs.empty())
                fail(describe_face(cs[0]) +
                     " has no neighbouring cell and is no boundary face (a hole in the mesh, or a missing boundary "
                     "face)");
            std::string s = describe_boundary(boundary_face(bs[0])) + " is listed " + std::to_string(bs.size()) +
                            " times in the boundary (also";
            for (std::size_t k = 1; k < bs.size(); ++k)
                s += (k > 1 ? ", " : " ") + describe_boundary(boundary_face(bs[k]));
            fail(s + ")");
        }
        fail(describe_boundary(boundary_face(bs[0])) +
             " is no face of any cell (a missing cell, or a stray boundary face)");
    }

    const VolumeMesh& mesh_;
    const Cells& cells_;
    const std::vector<Index>& patch_number_;
    std::string where_;
};

// ---------------------------------------------------------------------------------------
// Buffered output: numbers formatted with std::to_chars into a 1 MB buffer, one fwrite each.

class BufferedFile {
public:
    BufferedFile(const std::string& temp, const std::string& target) : path_(temp), target_(target) {
        file_ = std::fopen(temp.c_str(), "wb");
        if (!file_)
            throw InputError("cannot write '" + target + "': cannot create '" + temp + "': " + std::strerror(errno) +
                             "; check that the directory is writable");
        buf_.resize(kCapacity);
    }
    ~BufferedFile() {
        if (file_) std::fclose(file_);
    }
    BufferedFile(const BufferedFile&) = delete;
    BufferedFile& operator=(const BufferedFile&) = delete;

    void put(char c) {
        reserve(1);
        buf_[n_++] = c;
    }
    void put(std::string_view s) {
        if (s.size() > kCapacity / 2) {  // long text: straight through
            flush();
            write(s.data(), s.size());
            return;
        }
        reserve(s.size());
        std::memcpy(buf_.data() + n_, s.data(), s.size());
        n_ += s.size();
    }
    void put(std::int64_t v) {
        reserve(kMaxNumber);
        n_ = static_cast<std::size_t>(std::to_chars(buf_.data() + n_, buf_.data() + buf_.size(), v).ptr - buf_.data());
    }
    /// Shortest decimal form that reads back to exactly \p v.
    void put(double v) {
        reserve(kMaxNumber);
        n_ = static_cast<std::size_t>(std::to_chars(buf_.data() + n_, buf_.data() + buf_.size(), v).ptr - buf_.data());
    }

    /// Flush and close; throws InputError if anything could not be written (disk full, ...).
    void close() {
        flush();
        std::FILE* f = file_;
        file_ = nullptr;
        if (std::fclose(f) != 0) fail();
    }

private:
    static constexpr std::size_t kCapacity = std::size_t{1} << 20;
    static constexpr std::size_t kMaxNumber = 32;  // "-2.2250738585072014e-308" is 24

    void reserve(std::size_t k) {
        if (n_ + k > buf_.size()) flush();
    }
    void flush() {
        write(buf_.data(), n_);
        n_ = 0;
    }
    void write(const char* data, std::size_t size) {
        if (size != 0 && std::fwrite(data, 1, size, file_) != size) fail();
    }
    [[noreturn]] void fail() const {
        throw InputError("cannot write '" + target_ + "': writing '" + path_ + "' failed: " + std::strerror(errno) +
                         " (disk full?)");
    }

    std::FILE* file_ = nullptr;
    std::string path_, target_;
    std::vector<char> buf_;
    std::size_t n_ = 0;
};

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

void check_not_directory(const std::string& target) {
    std::error_code ec;
    if (std::filesystem::is_directory(target, ec))
        throw InputError("cannot write '" + target + "': it is a directory; choose a file name");
}

}  // namespace

void write_cobalt(const VolumeMesh& mesh, const std::string& path) {
    const std::string where = "cannot write Cobalt grid '" + path + "': ";
    const Cells cells(mesh);
    check_volume_mesh(mesh, where);

    // Patch numbers 1..npatches over the patches with faces, in patch-table order.
    const SurfaceMesh& b = mesh.boundary;
    std::vector<Index> patch_number(b.patches.size(), 0);
    for (Index p : b.face_patch) patch_number[p] = 1;
    Index npatches = 0;
    for (Index& p : patch_number) p = p ? ++npatches : 0;

    const std::vector<Index> other = Matcher(mesh, cells, patch_number, where).run();
    std::int64_t nfaces = 0;
    for (Index c : other) nfaces += c != 0;

    // Targets: checked before anything is written, then both files complete before either is
    // renamed into place.
    const std::string bc_path = path + ".bc";
    check_not_directory(path);
    check_not_directory(bc_path);
    AtomicFile grid_file(path);
    AtomicFile bc_file(bc_path);

    {
        BufferedFile out(grid_file.temp_path(), path);
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
            out.put(x.x());
            out.put(' ');
            out.put(x.y());
            out.put(' ');
            out.put(x.z());
            out.put('\n');
        }
        for (int t = 0; t < 4; ++t) {
            const FaceTable& table = cell_faces(kTypes[t]);
            std::uint64_t slot = cells.slot_start(t);
            for (std::int64_t i = 0; i < cells.count(t); ++i) {
                const Index* v = cells.nodes(t, i);
                const std::int64_t c1 = cells.start(t) + i + 1;
                for (int f = 0; f < table.count; ++f, ++slot) {
                    const Index c2 = other[slot];
                    if (c2 == 0) continue;  // written from its other cell
                    out.put(static_cast<std::int64_t>(table.size[f]));
                    for (int k = 0; k < table.size[f]; ++k) {
                        out.put(' ');
                        out.put(static_cast<std::int64_t>(v[table.node[f][k]]) + 1);
                    }
                    out.put(' ');
                    out.put(c1);
                    out.put(' ');
                    out.put(static_cast<std::int64_t>(c2));
                    out.put('\n');
                }
            }
        }
        out.close();
    }
    {
        BufferedFile out(bc_file.temp_path(), bc_path);
        const std::string grid_name = std::filesystem::path(path).filename().string();
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
        out.close();
    }

    // The patch map first, then the grid: if the grid cannot be renamed into place, the new
    // patch map is removed again so no grid is ever left with another grid's patch map.
    bc_file.commit();
    try {
        grid_file.commit();
    } catch (...) {
        std::error_code ec;
        std::filesystem::remove(bc_path, ec);
        throw;
    }
}

}  // namespace strata
