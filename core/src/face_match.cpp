// The face matcher (face_match.h). Every face gets a code: its slot, or slots.count() + its
// boundary face index. Faces are bucketed by their smallest node (a counting sort of the codes,
// no strings or hash maps) and each bucket is sorted by the full sorted node set, so 5M cells
// cost a few hundred MB and a few seconds. A node set held by two cell faces is an interior
// face, by one cell face and one boundary face a boundary face; everything else is a problem.
// Buckets are judged in fixed chunks of nodes; each chunk writes only the slots of its own
// faces and keeps its own problems, which are concatenated in chunk order afterwards.

#include <strata/core/cell_faces.h>
#include <strata/core/face_match.h>
#include <strata/core/format.h>
#include <strata/core/parallel.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>

namespace strata {

FaceSlots::FaceSlots(const VolumeMesh& mesh) : mesh_(&mesh), cells_(mesh) {
    for (std::size_t k = 0; k < kCellTypes.size(); ++k) {
        const CellType t = kCellTypes[k];
        start_[k + 1] =
            start_[k] + static_cast<std::uint64_t>(cells_.count(t)) * static_cast<std::uint64_t>(cell_faces(t).count);
    }
}

FaceSlots::Slot FaceSlots::locate(std::uint64_t slot) const {
    std::size_t k = 0;
    while (k < 3 && slot >= start_[k + 1]) ++k;
    const CellType t = kCellTypes[k];
    const std::uint64_t r = slot - start_[k];
    const auto per = static_cast<std::uint64_t>(cell_faces(t).count);
    return {t, static_cast<std::int64_t>(r / per), static_cast<int>(r % per)};
}

std::int64_t FaceSlots::cell(std::uint64_t slot) const {
    const Slot s = locate(slot);
    return cells_.start(s.type) + s.index;
}

int FaceSlots::nodes(std::uint64_t slot, Index* out) const {
    const Slot s = locate(slot);
    const CellFaceTable& table = cell_faces(s.type);
    const Index* v = mesh_->cell(s.type, static_cast<std::size_t>(s.index));
    const int n = table.size[static_cast<std::size_t>(s.face)];
    for (int k = 0; k < n; ++k) out[k] = v[table.node[static_cast<std::size_t>(s.face)][static_cast<std::size_t>(k)]];
    return n;
}

namespace {

constexpr std::size_t kNodeChunk = 1 << 14;

/// Face codes grouped by their smallest node: group k is codes[offsets[k], offsets[k+1]), in
/// ascending code order (cell faces in slot order, then boundary faces).
template <class Code>
struct Buckets {
    std::vector<std::size_t> offsets;  ///< #nodes + 1
    std::vector<Code> codes;
};

/// The nodes of the face with code \p code; returns their count.
int face_nodes(const FaceSlots& slots, std::uint64_t code, Index* out) {
    if (code < slots.count()) return slots.nodes(code, out);
    const SurfaceMesh& b = slots.mesh().boundary;
    const auto f = static_cast<Index>(code - slots.count());
    std::copy(b.face_begin(f), b.face_end(f), out);
    return static_cast<int>(b.face_size(f));
}

/// Counting sort of every face code by the face's smallest node: cells in slot order, then the
/// boundary faces, so each bucket comes out in ascending code order.
template <class Code>
Buckets<Code> bucket_faces(const FaceSlots& slots) {
    const VolumeMesh& mesh = slots.mesh();
    const SurfaceMesh& bnd = mesh.boundary;
    auto for_each_face = [&](auto&& visit) {
        std::uint64_t slot = 0;
        for (CellType t : kCellTypes) {
            const CellFaceTable& table = cell_faces(t);
            for (std::size_t i = 0; i < mesh.num_cells(t); ++i) {
                const Index* v = mesh.cell(t, i);
                for (std::size_t f = 0; f < static_cast<std::size_t>(table.count); ++f, ++slot) {
                    Index m = v[table.node[f][0]];
                    for (std::size_t k = 1; k < static_cast<std::size_t>(table.size[f]); ++k)
                        m = std::min(m, v[table.node[f][k]]);
                    visit(m, slot);
                }
            }
        }
        for (Index f = 0; f < bnd.num_faces(); ++f)
            visit(*std::min_element(bnd.face_begin(f), bnd.face_end(f)), slots.count() + static_cast<std::uint64_t>(f));
    };
    Buckets<Code> b;
    b.offsets.assign(mesh.points.size() + 1, 0);
    for_each_face([&](Index key, std::uint64_t) { ++b.offsets[static_cast<std::size_t>(key) + 1]; });
    for (std::size_t i = 1; i < b.offsets.size(); ++i) b.offsets[i] += b.offsets[i - 1];
    b.codes.resize(b.offsets.back());
    std::vector<std::size_t> fill(b.offsets.begin(), b.offsets.end() - 1);
    for_each_face([&](Index key, std::uint64_t code) {
        b.codes[fill[static_cast<std::size_t>(key)]++] = static_cast<Code>(code);
    });
    return b;
}

/// A face for sorting: its nodes sorted (a triangle's 4th entry kNone), then its code.
struct KeyedFace {
    std::array<Index, 4> key;
    std::uint64_t code;
    bool operator<(const KeyedFace& o) const { return key != o.key ? key < o.key : code < o.code; }
};

/// What one chunk of buckets found.
struct ChunkResult {
    std::int64_t interior = 0, boundary = 0;
    std::vector<FaceMatch::Problem> problems;
    std::vector<std::uint64_t> unmatched;  ///< faces present once, neither matched nor in a problem
};

/// Judge the faces of one node set: \p cs cell faces, \p bs boundary faces (ascending codes).
void judge(FaceMatch& m, const std::vector<std::uint64_t>& cs, const std::vector<std::uint64_t>& bs, ChunkResult& r) {
    auto problem = [&](FaceIssue issue) {
        std::vector<std::uint64_t> faces(cs);
        faces.insert(faces.end(), bs.begin(), bs.end());
        r.problems.push_back({issue, std::move(faces)});
    };
    Index a[4], b[4];
    if (cs.size() >= 3) return problem(FaceIssue::SharedByThreeOrMoreCells);
    if (cs.size() == 2) {
        if (!bs.empty()) return problem(FaceIssue::InteriorOnBoundary);
        ++r.interior;
        m.across[cs[0]] = static_cast<std::int64_t>(cs[1]);
        m.across[cs[1]] = static_cast<std::int64_t>(cs[0]);
        if (m.slots.cell(cs[0]) == m.slots.cell(cs[1])) return problem(FaceIssue::SameCell);
        const int n = m.slots.nodes(cs[0], a);
        m.slots.nodes(cs[1], b);
        if (relative_orientation(a, b, n) != -1) problem(FaceIssue::NotOpposite);
        return;
    }
    if (cs.size() == 1) {
        if (bs.empty()) return r.unmatched.push_back(cs[0]);
        ++r.boundary;
        m.across[cs[0]] = -1 - static_cast<std::int64_t>(m.boundary_face(bs[0]));
        if (bs.size() >= 2) return problem(FaceIssue::BoundaryDuplicated);
        const int n = m.slots.nodes(cs[0], a);
        face_nodes(m.slots, bs[0], b);
        if (relative_orientation(a, b, n) != 1) problem(FaceIssue::BoundaryMisoriented);
        return;
    }
    if (bs.size() >= 2) return problem(FaceIssue::BoundaryDuplicated);
    r.unmatched.push_back(bs[0]);
}

template <class Code>
std::vector<ChunkResult> match_chunks(FaceMatch& m, int threads) {
    const Buckets<Code> buckets = bucket_faces<Code>(m.slots);
    const std::size_t num_nodes = m.slots.mesh().points.size();
    const std::size_t chunks = (num_nodes + kNodeChunk - 1) / kNodeChunk;
    std::vector<ChunkResult> results(chunks);
    const int team = thread_count(threads);
#pragma omp parallel if (chunks > 1) num_threads(team)
    {
        std::vector<KeyedFace> items;
        std::vector<std::uint64_t> cs, bs;
        Index v[4];
#pragma omp for schedule(dynamic, 1)
        for (std::size_t c = 0; c < chunks; ++c) {
            const std::size_t end = std::min(num_nodes, (c + 1) * kNodeChunk);
            for (std::size_t node = c * kNodeChunk; node < end; ++node) {
                items.clear();
                for (std::size_t e = buckets.offsets[node]; e < buckets.offsets[node + 1]; ++e) {
                    const std::uint64_t code = buckets.codes[e];
                    const int n = face_nodes(m.slots, code, v);
                    items.push_back({sorted_face_key(v, n), code});
                }
                std::sort(items.begin(), items.end());
                for (std::size_t g = 0; g < items.size();) {
                    std::size_t h = g;
                    cs.clear();
                    bs.clear();
                    for (; h < items.size() && items[h].key == items[g].key; ++h)
                        (m.is_slot(items[h].code) ? cs : bs).push_back(items[h].code);
                    judge(m, cs, bs, results[c]);
                    g = h;
                }
            }
        }
    }
    return results;
}

/// Faces present once: a quad whose two halves are unmatched triangles is a non-conforming
/// quad/triangle junction; what remains is a hole (cell face) or a stray boundary face.
void explain_unmatched(FaceMatch& m, const std::vector<std::uint64_t>& unmatched) {
    std::vector<KeyedFace> triangles;
    Index v[4];
    for (std::uint64_t code : unmatched)
        if (face_nodes(m.slots, code, v) == 3) triangles.push_back({sorted_face_key(v, 3), code});
    std::sort(triangles.begin(), triangles.end());
    std::vector<char> used(triangles.size(), 0);
    auto find = [&](Index a, Index b, Index c) -> std::ptrdiff_t {
        const Index t[3] = {a, b, c};
        const KeyedFace probe{sorted_face_key(t, 3), 0};
        auto it = std::lower_bound(triangles.begin(), triangles.end(), probe);
        while (it != triangles.end() && it->key == probe.key && used[static_cast<std::size_t>(it - triangles.begin())])
            ++it;
        return it != triangles.end() && it->key == probe.key ? it - triangles.begin() : -1;
    };
    std::vector<char> excused(unmatched.size(), 0);  // quads explained by two triangles
    std::vector<std::uint64_t> consumed;             // those triangles
    for (std::size_t u = 0; u < unmatched.size(); ++u) {
        if (face_nodes(m.slots, unmatched[u], v) != 4) continue;
        for (int s = 0; s < 2; ++s) {  // s = 0: diagonal v0–v2; s = 1: diagonal v1–v3
            const std::ptrdiff_t t1 = find(v[s], v[s + 1], v[(s + 2) % 4]);
            if (t1 < 0) continue;
            used[static_cast<std::size_t>(t1)] = 1;
            const std::ptrdiff_t t2 = find(v[(s + 2) % 4], v[(s + 3) % 4], v[s]);
            if (t2 < 0) {
                used[static_cast<std::size_t>(t1)] = 0;
                continue;
            }
            used[static_cast<std::size_t>(t2)] = 1;
            excused[u] = 1;
            const std::uint64_t c1 = triangles[static_cast<std::size_t>(t1)].code;
            const std::uint64_t c2 = triangles[static_cast<std::size_t>(t2)].code;
            consumed.push_back(c1);
            consumed.push_back(c2);
            m.problems.push_back({FaceIssue::QuadAgainstTriangles, {unmatched[u], c1, c2}});
            break;
        }
    }
    std::sort(consumed.begin(), consumed.end());
    for (std::size_t u = 0; u < unmatched.size(); ++u) {
        if (excused[u] || std::binary_search(consumed.begin(), consumed.end(), unmatched[u])) continue;
        m.problems.push_back({m.is_slot(unmatched[u]) ? FaceIssue::Hole : FaceIssue::StrayBoundary, {unmatched[u]}});
    }
}

}  // namespace

FaceMatch match_faces(const VolumeMesh& mesh, int threads) {
    FaceMatch m{FaceSlots(mesh), {}, 0, 0, {}};
    m.across.assign(m.slots.count(), FaceMatch::kUnmatched);
    const std::uint64_t codes = m.slots.count() + static_cast<std::uint64_t>(mesh.boundary.num_faces());
    std::vector<ChunkResult> chunks = codes < (std::uint64_t{1} << 32) ? match_chunks<std::uint32_t>(m, threads)
                                                                       : match_chunks<std::uint64_t>(m, threads);
    std::vector<std::uint64_t> unmatched;
    for (ChunkResult& r : chunks) {  // chunk order: independent of the thread count
        m.interior += r.interior;
        m.boundary += r.boundary;
        for (FaceMatch::Problem& p : r.problems) m.problems.push_back(std::move(p));
        unmatched.insert(unmatched.end(), r.unmatched.begin(), r.unmatched.end());
    }
    explain_unmatched(m, unmatched);
    return m;
}

namespace {

/// "patch 'wall'" for boundary face \p f.
std::string patch_of(const SurfaceMesh& b, Index f) {
    const Index p = b.face_patch[f];
    if (p >= 0 && p < static_cast<Index>(b.patches.size())) return "patch '" + b.patches[p].name + "'";
    return "patch " + std::to_string(p) + " (no such patch)";
}

/// "face (a b c) of hexahedron 3 at (x, y, z)" or "boundary face 7 (a b c) of patch 'wall' at (x, y, z)".
std::string face_text(const FaceMatch& m, std::uint64_t code) {
    const VolumeMesh& mesh = m.slots.mesh();
    Index v[4];
    const int n = face_nodes(m.slots, code, v);
    if (m.is_slot(code)) {
        const FaceSlots::Slot s = m.slots.locate(code);
        return "face " + format_nodes(v, n) + " of " + describe_cell(mesh, s.type, s.index);
    }
    const Index f = m.boundary_face(code);
    Vec3 c = Vec3::Zero();
    for (int k = 0; k < n; ++k) c += mesh.points[v[k]];
    return "boundary face " + std::to_string(f) + " " + format_nodes(v, n) + " of " + patch_of(mesh.boundary, f) +
           " at " + format_point(c / static_cast<double>(n));
}

/// "hexahedron 3 at (x, y, z)" or "boundary face 7 of patch 'wall'".
std::string owner_text(const FaceMatch& m, std::uint64_t code) {
    if (m.is_slot(code)) {
        const FaceSlots::Slot s = m.slots.locate(code);
        return describe_cell(m.slots.mesh(), s.type, s.index);
    }
    const Index f = m.boundary_face(code);
    return "boundary face " + std::to_string(f) + " of " + patch_of(m.slots.mesh().boundary, f);
}

/// "a, b, c": the owners of faces[from, to).
std::string owners_text(const FaceMatch& m, const std::vector<std::uint64_t>& faces, std::size_t from, std::size_t to) {
    std::string s;
    for (std::size_t k = from; k < to; ++k) s += (k > from ? ", " : "") + owner_text(m, faces[k]);
    return s;
}

}  // namespace

std::string describe(const FaceMatch& m, const FaceMatch::Problem& p) {
    const std::vector<std::uint64_t>& f = p.faces;
    Index a[4], b[4];
    const int n = face_nodes(m.slots, f[0], a);
    switch (p.issue) {
        case FaceIssue::SharedByThreeOrMoreCells: {
            std::size_t cells = 0;
            while (cells < f.size() && m.is_slot(f[cells])) ++cells;
            return "face " + format_nodes(a, n) + " is shared by " + std::to_string(cells) +
                   " cells: " + owners_text(m, f, 0, cells) +
                   " (a face joins at most two cells: duplicated or overlapping cells)";
        }
        case FaceIssue::NotOpposite: {
            face_nodes(m.slots, f[1], b);
            const bool same = relative_orientation(a, b, n) == 1;
            return owner_text(m, f[0]) + " and " + owner_text(m, f[1]) + " overlap or are misoriented at face " +
                   format_nodes(a, n) +
                   (same ? ": both have it with the same orientation (one cell is inverted, or the cells lie on the "
                           "same side of it)"
                         : ": they list its nodes as " + format_nodes(a, n) + " and " + format_nodes(b, n) +
                               ", not one the reverse of the other");
        }
        case FaceIssue::SameCell:
            return owner_text(m, f[0]) + " has two faces with the same nodes " + format_nodes(a, n) +
                   " (a degenerate cell)";
        case FaceIssue::InteriorOnBoundary:
            return face_text(m, f[2]) + " is an interior face between " + owner_text(m, f[0]) + " and " +
                   owner_text(m, f[1]) + "; remove it from the boundary";
        case FaceIssue::BoundaryDuplicated: {
            if (!m.is_slot(f[0]))
                return face_text(m, f[0]) + " is listed " + std::to_string(f.size()) +
                       " times in the boundary and is no cell face";
            return face_text(m, f[1]) + " is listed " + std::to_string(f.size() - 1) + " times in the boundary (also " +
                   owners_text(m, f, 2, f.size()) + ")";
        }
        case FaceIssue::BoundaryMisoriented: {
            face_nodes(m.slots, f[1], b);
            if (relative_orientation(a, b, n) == -1)
                return face_text(m, f[1]) + " points into " + owner_text(m, f[0]) +
                       " instead of out of the mesh; reverse its node order";
            return face_text(m, f[1]) + " lists the nodes of " + face_text(m, f[0]) + " in another order";
        }
        case FaceIssue::QuadAgainstTriangles: {
            face_nodes(m.slots, f[1], a);
            face_nodes(m.slots, f[2], b);
            return "quad " + face_text(m, f[0]) +
                   " is not matched: its neighbour has different faces (a quad never against two triangles): " +
                   owner_text(m, f[1]) + " has triangle " + format_nodes(a, 3) + " and " + owner_text(m, f[2]) +
                   " has triangle " + format_nodes(b, 3) +
                   " there; split the quad's cell or use a pyramid between them";
        }
        case FaceIssue::Hole:
            return face_text(m, f[0]) +
                   " has no neighbouring cell and is no boundary face (a hole in the mesh, or a missing boundary face)";
        case FaceIssue::StrayBoundary:
            return face_text(m, f[0]) + " is no face of any cell (a missing cell, or a stray boundary face)";
    }
    return face_text(m, f[0]);
}

}  // namespace strata
