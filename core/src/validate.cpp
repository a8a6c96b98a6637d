// The volume-mesh validator. Three independent checks:
//  1. every cell has a positive scaled Jacobian at every corner (cell_quality.h);
//  2. face conformity: every cell face, oriented out of its cell, is matched by node set.
//     Faces are bucketed by their smallest node (counting sort, one small integer code per
//     face, no strings or hash maps) and each bucket is sorted by the full sorted node set,
//     so 5M cells cost a few hundred MB and a few seconds. Two cell faces with one node set
//     = an interior face (opposite orientations), one cell face = a boundary face (listed in
//     mesh.boundary with the same orientation), anything else is a problem;
//  3. the cell volumes sum to the volume the boundary encloses (divergence theorem, the
//     same face formula for both so a conforming mesh agrees to rounding).
// Work is cut into fixed chunks whose results are merged in chunk order, so the report
// (problems, sums) does not depend on the number of threads.

#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/core/face_geometry.h>
#include <strata/core/cell_faces.h>
#include <strata/core/cell_quality.h>
#include <strata/core/validate.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace strata {
namespace {

// ---------------------------------------------------------------------------------------
// Local faces of each cell type, Gmsh node order, right-hand normal pointing out of the cell
// (checked against Gmsh's reference elements in tests/module/test_validate.cpp).

using FaceTable = CellFaceTable;  // module/cell_faces.h
constexpr const auto& kTypes = kCellTypes;

/// (1/3) (c − r)·A of one face, A its area vector (quads: ½ d1×d2), c the mean of its
/// corners: the face's share of the enclosed volume. Shared by cells and the boundary.
double face_volume_term(const Vec3* x, int n) {
    if (n == 3) {
        const Vec3 a = 0.5 * (x[1] - x[0]).cross(x[2] - x[0]);
        return (x[0] + x[1] + x[2]).dot(a) / 9.0;
    }
    const Vec3 a = 0.5 * (x[2] - x[0]).cross(x[3] - x[1]);
    return (x[0] + x[1] + x[2] + x[3]).dot(a) / 12.0;
}

std::string fmt(const char* format, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
}

std::string fmt_nodes(const Index* v, int n) {
    std::string s = "(";
    for (int i = 0; i < n; ++i) {
        if (i) s += ' ';
        s += std::to_string(v[i]);
    }
    s += ')';
    return s;
}

// ---------------------------------------------------------------------------------------
// Problems: at most kMaxPerKind lines per kind, then a count.

enum Kind : int {
    kBadInput,
    kJacobian,
    kOverlap,
    kNonConforming,
    kQuadTriangles,
    kHole,
    kBoundaryUnmatched,
    kBoundaryInterior,
    kBoundaryOrientation,
    kBoundaryDuplicate,
    kVolume,
    kNumKinds
};

constexpr std::size_t kMaxPerKind = 5;

constexpr std::array<const char*, kNumKinds> kKindNoun{"input problems",
                                                       "inverted or degenerate cells",
                                                       "misoriented interior faces",
                                                       "faces shared by three or more cells",
                                                       "quad faces against two triangles",
                                                       "unmatched cell faces (holes)",
                                                       "boundary faces that are no cell face",
                                                       "boundary faces on interior faces",
                                                       "misoriented boundary faces",
                                                       "duplicated boundary faces",
                                                       "volume mismatches"};

struct Problems {
    std::array<std::vector<std::string>, kNumKinds> lines;
    std::array<std::size_t, kNumKinds> count{};

    /// \p make builds the message only when it will be kept (millions of problems are cheap).
    template <class F>
    void add(Kind k, F&& make) {
        if (count[k]++ < kMaxPerKind) lines[k].push_back(make());
    }
    void merge(Problems&& o) {
        for (int k = 0; k < kNumKinds; ++k) {
            for (std::string& s : o.lines[k])
                if (lines[k].size() < kMaxPerKind) lines[k].push_back(std::move(s));
            count[k] += o.count[k];
        }
    }
    std::size_t total() const {
        std::size_t t = 0;
        for (std::size_t c : count) t += c;
        return t;
    }
    std::vector<std::string> flatten() const {
        std::vector<std::string> out;
        for (int k = 0; k < kNumKinds; ++k) {
            out.insert(out.end(), lines[k].begin(), lines[k].end());
            if (count[k] > lines[k].size())
                out.push_back("... and " + std::to_string(count[k] - lines[k].size()) + " more " + kKindNoun[k]);
        }
        return out;
    }
};

// ---------------------------------------------------------------------------------------
// Global cell numbering: tets, then pyramids, prisms, hexes. A face is coded
// id * 8 + local face, id < #cells a cell, id ≥ #cells boundary face id − #cells.

class Cells {
public:
    explicit Cells(const VolumeMesh& m) : m_(m) {
        start_[0] = 0;
        start_[1] = start_[0] + static_cast<std::int64_t>(m.tets.size());
        start_[2] = start_[1] + static_cast<std::int64_t>(m.pyramids.size());
        start_[3] = start_[2] + static_cast<std::int64_t>(m.prisms.size());
        start_[4] = start_[3] + static_cast<std::int64_t>(m.hexes.size());
    }
    std::int64_t count() const { return start_[4]; }
    std::int64_t start(int t) const { return start_[t]; }
    std::int64_t count(int t) const { return start_[t + 1] - start_[t]; }

    const Index* nodes(int t, std::int64_t i) const { return cell_nodes(m_, t, i); }
    /// Type index (0..3) and index within the type of global cell \p g.
    std::pair<int, std::int64_t> locate(std::int64_t g) const {
        int t = 0;
        while (t < 3 && g >= start_[t + 1]) ++t;
        return {t, g - start_[t]};
    }
    Vec3 centroid(int t, std::int64_t i) const {
        const Index* v = nodes(t, i);
        const int n = cell_corners(kTypes[t]);
        Vec3 c = Vec3::Zero();
        for (int k = 0; k < n; ++k) c += m_.points[v[k]];
        return c / static_cast<double>(n);
    }
    std::string describe(int t, std::int64_t i) const {
        return std::string(to_string(kTypes[t])) + " " + std::to_string(i) + " at " + format_point(centroid(t, i));
    }

private:
    const VolumeMesh& m_;
    std::array<std::int64_t, 5> start_{};
};

/// The nodes (owner's order) of the face with code \p code; returns the node count.
struct FaceCodec {
    const VolumeMesh& mesh;
    const Cells& cells;

    bool is_cell(std::uint64_t code) const { return static_cast<std::int64_t>(code >> 3) < cells.count(); }
    std::int64_t boundary_face(std::uint64_t code) const {
        return static_cast<std::int64_t>(code >> 3) - cells.count();
    }

    int nodes(std::uint64_t code, Index* out) const {
        const auto id = static_cast<std::int64_t>(code >> 3);
        if (id < cells.count()) {
            const auto [t, i] = cells.locate(id);
            const FaceTable& table = cell_faces(kTypes[t]);
            const int local = static_cast<int>(code & 7u);
            const Index* v = cells.nodes(t, i);
            const int n = table.size[local];
            for (int k = 0; k < n; ++k) out[k] = v[table.node[local][k]];
            return n;
        }
        const auto f = static_cast<Index>(id - cells.count());
        const int n = static_cast<int>(mesh.boundary.face_size(f));
        std::copy(mesh.boundary.face_begin(f), mesh.boundary.face_end(f), out);
        return n;
    }

    std::string patch_name(Index f) const {
        const SurfaceMesh& b = mesh.boundary;
        if (f < static_cast<Index>(b.face_patch.size())) {
            const Index p = b.face_patch[f];
            if (p >= 0 && p < static_cast<Index>(b.patches.size())) return "'" + b.patches[p].name + "'";
            return std::to_string(p) + " (no such patch)";
        }
        return "(none)";
    }

    /// "face (a b c) of hexahedron 3 at (x, y, z)" or
    /// "boundary face 7 (a b c) of patch 'wall' at (x, y, z)".
    std::string describe(std::uint64_t code) const {
        Index v[4];
        const int n = nodes(code, v);
        if (is_cell(code)) {
            const auto [t, i] = cells.locate(static_cast<std::int64_t>(code >> 3));
            return "face " + fmt_nodes(v, n) + " of " + cells.describe(t, i);
        }
        const auto f = static_cast<Index>(boundary_face(code));
        Vec3 c = Vec3::Zero();
        for (int k = 0; k < n; ++k) c += mesh.points[v[k]];
        return "boundary face " + std::to_string(f) + " " + fmt_nodes(v, n) + " of patch " + patch_name(f) + " at " +
               format_point(c / static_cast<double>(n));
    }
    /// "hexahedron 3 at (x, y, z)" or "boundary face 7 of patch 'wall'".
    std::string owner(std::uint64_t code) const {
        if (is_cell(code)) {
            const auto [t, i] = cells.locate(static_cast<std::int64_t>(code >> 3));
            return cells.describe(t, i);
        }
        const auto f = static_cast<Index>(boundary_face(code));
        return "boundary face " + std::to_string(f) + " of patch " + patch_name(f);
    }
};

// ---------------------------------------------------------------------------------------
// Input sanity: indices in range, face sizes. Later checks dereference without looking.

bool check_input(const VolumeMesh& mesh, const Cells& cells, Problems& problems) {
    const Index num_points = static_cast<Index>(mesh.points.size());
    bool safe = true;
    if (cells.count() == 0) problems.add(kBadInput, [] { return std::string("the mesh has no cells"); });
    for (int t = 0; t < 4; ++t) {
        const int n = cell_corners(kTypes[t]);
        for (std::int64_t i = 0; i < cells.count(t); ++i) {
            const Index* v = cells.nodes(t, i);
            for (int k = 0; k < n; ++k)
                if (v[k] < 0 || v[k] >= num_points) {
                    safe = false;
                    problems.add(kBadInput, [&] {
                        return std::string(to_string(kTypes[t])) + " " + std::to_string(i) + " " + fmt_nodes(v, n) +
                               " uses node " + std::to_string(v[k]) + " but the mesh has " +
                               std::to_string(num_points) + " nodes";
                    });
                    break;
                }
        }
    }
    const SurfaceMesh& b = mesh.boundary;
    if (b.face_offsets.empty() || b.face_offsets.front() != 0 ||
        static_cast<std::size_t>(b.face_offsets.back()) != b.face_nodes.size()) {
        problems.add(kBadInput, [] {
            return std::string("boundary.face_offsets is malformed (must start at 0 and end at face_nodes.size())");
        });
        return false;
    }
    for (Index f = 0; f < b.num_faces(); ++f) {
        const Index n = b.face_size(f);
        if (n != 3 && n != 4) {
            safe = false;
            problems.add(kBadInput, [&] {
                return "boundary face " + std::to_string(f) + " has " + std::to_string(n) +
                       " nodes; boundary faces are triangles or quads";
            });
            continue;
        }
        for (const Index* v = b.face_begin(f); v != b.face_end(f); ++v)
            if (*v < 0 || *v >= num_points) {
                safe = false;
                problems.add(kBadInput, [&] {
                    return "boundary face " + std::to_string(f) + " " +
                           fmt_nodes(b.face_begin(f), static_cast<int>(n)) + " uses node " + std::to_string(*v) +
                           " but the mesh has " + std::to_string(num_points) + " nodes";
                });
                break;
            }
    }
    if (b.face_patch.size() != static_cast<std::size_t>(b.num_faces())) {
        problems.add(kBadInput, [&] {
            return "boundary.face_patch has " + std::to_string(b.face_patch.size()) + " entries for " +
                   std::to_string(b.num_faces()) + " boundary faces";
        });
    } else {
        for (Index f = 0; f < b.num_faces(); ++f) {
            const Index p = b.face_patch[f];
            if (p < 0 || p >= static_cast<Index>(b.patches.size()))
                problems.add(kBadInput, [&] {
                    return "boundary face " + std::to_string(f) + " is on patch " + std::to_string(p) +
                           " but the mesh has " + std::to_string(b.patches.size()) + " patches";
                });
        }
    }
    for (std::size_t i = 0; i < mesh.points.size(); ++i)
        if (!mesh.points[i].allFinite())
            problems.add(kBadInput, [&] {
                return "node " + std::to_string(i) + " has a non-finite coordinate " + format_point(mesh.points[i]);
            });
    return safe;
}

// ---------------------------------------------------------------------------------------
// Check 1: scaled Jacobians and cell volumes, in fixed chunks of cells.

constexpr std::int64_t kCellChunk = 1 << 15;

struct CellResult {
    double min_jacobian = 1.0;
    std::int64_t worst = -1;  ///< the first cell with min_jacobian (global cell number)
    double volume = 0.0;
    Problems problems;
};

void sticky_min(double& m, double v) {  // NaN wins, so a NaN anywhere shows in the report
    if (std::isnan(v) || v < m) m = v;
}

template <std::size_t N>
double min_jacobian(const std::vector<Vec3>& p, const Index* v) {
    std::array<Index, N> a;
    std::copy(v, v + N, a.begin());
    if constexpr (N == 4) return tet_min_scaled_jacobian(p, a);
    if constexpr (N == 5) return pyramid_min_scaled_jacobian(p, a);
    if constexpr (N == 6) return prism_min_scaled_jacobian(p, a);
    if constexpr (N == 8) return hex_min_scaled_jacobian(p, a);
    return 0.0;
}

double cell_min_jacobian(const std::vector<Vec3>& p, const Index* v, int t) {
    switch (t) {
        case 0:
            return min_jacobian<4>(p, v);
        case 1:
            return min_jacobian<5>(p, v);
        case 2:
            return min_jacobian<6>(p, v);
        default:
            return min_jacobian<8>(p, v);
    }
}

CellResult check_cells(const VolumeMesh& mesh, const Cells& cells) {
    const std::int64_t n = cells.count();
    const std::int64_t chunks = (n + kCellChunk - 1) / kCellChunk;
    std::vector<CellResult> results(static_cast<std::size_t>(chunks));
#pragma omp parallel for schedule(dynamic, 1)
    for (std::int64_t c = 0; c < chunks; ++c) {
        CellResult& r = results[c];
        const std::int64_t end = std::min(n, (c + 1) * kCellChunk);
        for (std::int64_t g = c * kCellChunk; g < end; ++g) {
            const auto [t, i] = cells.locate(g);
            const Index* v = cells.nodes(t, i);
            const double j = cell_min_jacobian(mesh.points, v, t);
            const double vol = cell_volume(mesh.points, v, kTypes[t]);
            if (r.worst < 0 || j < r.min_jacobian) r.worst = g;
            sticky_min(r.min_jacobian, j);
            r.volume += vol;
            if (!(j > 0.0))
                r.problems.add(kJacobian, [&, t = t, i = i] {
                    return cells.describe(t, i) + " has min scaled Jacobian " + fmt("%.3g", j) +
                           " (inverted or degenerate: corners must be in Gmsh order, the bottom face "
                           "seen from inside the cell ordered as in Gmsh's reference element)";
                });
            else if (!(vol > 0.0))
                r.problems.add(kJacobian, [&, t = t, i = i] {
                    return cells.describe(t, i) + " has volume " + fmt("%.6g", vol) +
                           " though its corners are positive (a strongly warped cell)";
                });
        }
    }
    CellResult out;
    for (CellResult& r : results) {  // chunk order: independent of the thread count
        if (out.worst < 0 || r.min_jacobian < out.min_jacobian) out.worst = r.worst;
        sticky_min(out.min_jacobian, r.min_jacobian);
        out.volume += r.volume;
        out.problems.merge(std::move(r.problems));
    }
    return out;
}

// ---------------------------------------------------------------------------------------
// Check 2: face matching.

struct MatchResult {
    Index interior = 0;
    Index boundary = 0;
    std::vector<std::uint64_t> unmatched;  // faces present once, neither matched nor excused
    Problems problems;
};

template <class Code>
FaceBuckets<Code> bucket_faces(const VolumeMesh& mesh, const Cells& cells) {
    return bucket_faces_by_min_node<Code>(
        mesh,
        [&](int t, std::int64_t i, int f) {
            return (static_cast<std::uint64_t>(cells.start(t) + i) << 3) | static_cast<std::uint64_t>(f);
        },
        [&](Index f) { return static_cast<std::uint64_t>(cells.count() + f) << 3; });
}

using Item = KeyedFace;  // module/cell_faces.h

/// Judge one group of faces with the same node set: \p cs cell faces, \p bs boundary faces.
void judge_group(const FaceCodec& codec, const std::vector<std::uint64_t>& cs, const std::vector<std::uint64_t>& bs,
                 MatchResult& r) {
    Index a[4], b[4];
    if (cs.size() >= 3) {
        r.problems.add(kNonConforming, [&] {
            const int n = codec.nodes(cs[0], a);
            std::string s = "face " + fmt_nodes(a, n) + " is shared by " + std::to_string(cs.size()) + " cells:";
            for (std::size_t k = 0; k < cs.size(); ++k) {
                s += k ? ", " : " ";
                s += codec.owner(cs[k]);
            }
            return s + " (a face joins at most two cells: duplicated or overlapping cells)";
        });
        return;
    }
    if (cs.size() == 2) {
        if (!bs.empty()) {
            r.problems.add(kBoundaryInterior, [&] {
                return codec.describe(bs[0]) + " is an interior face between " + codec.owner(cs[0]) + " and " +
                       codec.owner(cs[1]) + "; remove it from the boundary";
            });
            return;
        }
        ++r.interior;
        const int n = codec.nodes(cs[0], a);
        codec.nodes(cs[1], b);
        const int o = relative_orientation(a, b, n);
        if (o != -1)
            r.problems.add(kOverlap, [&] {
                return codec.owner(cs[0]) + " and " + codec.owner(cs[1]) + " overlap or are misoriented at face " +
                       fmt_nodes(a, n) +
                       (o == 1 ? ": both have it with the same orientation (one cell is inverted, or the cells "
                                 "lie on the same side of it)"
                               : ": they list its nodes as " + fmt_nodes(a, n) + " and " + fmt_nodes(b, n) +
                                     ", not one the reverse of the other");
            });
        return;
    }
    if (cs.size() == 1) {
        if (bs.empty()) {
            r.unmatched.push_back(cs[0]);
            return;
        }
        ++r.boundary;
        if (bs.size() >= 2) {
            r.problems.add(kBoundaryDuplicate, [&] {
                std::string s =
                    codec.describe(bs[0]) + " is listed " + std::to_string(bs.size()) + " times in the boundary (also";
                for (std::size_t k = 1; k < bs.size(); ++k) {
                    s += k > 1 ? ", " : " ";
                    s += codec.owner(bs[k]);
                }
                s += ')';
                return s;
            });
            return;
        }
        const int n = codec.nodes(cs[0], a);
        codec.nodes(bs[0], b);
        const int o = relative_orientation(a, b, n);
        if (o != 1)
            r.problems.add(kBoundaryOrientation, [&] {
                return codec.describe(bs[0]) +
                       (o == -1 ? " points into " + codec.owner(cs[0]) +
                                      " instead of out of the mesh; reverse its node order"
                                : " lists the nodes of " + codec.describe(cs[0]) + " in another order");
            });
        return;
    }
    // Boundary faces only.
    if (bs.size() >= 2)
        r.problems.add(kBoundaryDuplicate, [&] {
            return codec.describe(bs[0]) + " is listed " + std::to_string(bs.size()) +
                   " times in the boundary and is no cell face";
        });
    else
        r.unmatched.push_back(bs[0]);
}

constexpr std::size_t kNodeChunk = 1 << 14;

template <class Code>
MatchResult match_faces_with(const VolumeMesh& mesh, const Cells& cells) {
    const FaceBuckets<Code> buckets = bucket_faces<Code>(mesh, cells);
    const FaceCodec codec{mesh, cells};
    const std::size_t num_nodes = mesh.points.size();
    const std::size_t chunks = (num_nodes + kNodeChunk - 1) / kNodeChunk;
    std::vector<MatchResult> results(chunks);

#pragma omp parallel
    {
        std::vector<Item> items;
        std::vector<std::uint64_t> cs, bs;
#pragma omp for schedule(dynamic, 1)
        for (std::size_t c = 0; c < chunks; ++c) {
            MatchResult& r = results[c];
            const std::size_t end = std::min(num_nodes, (c + 1) * kNodeChunk);
            for (std::size_t node = c * kNodeChunk; node < end; ++node) {
                const std::size_t begin = buckets.offsets[node], stop = buckets.offsets[node + 1];
                if (begin == stop) continue;
                items.clear();
                Index v[4];
                for (std::size_t e = begin; e < stop; ++e) {
                    const std::uint64_t code = buckets.codes[e];
                    const int n = codec.nodes(code, v);
                    items.push_back({sorted_face_key(v, n), code});
                }
                std::sort(items.begin(), items.end());
                for (std::size_t g = 0; g < items.size();) {
                    std::size_t h = g;
                    cs.clear();
                    bs.clear();
                    for (; h < items.size() && items[h].key == items[g].key; ++h)
                        (codec.is_cell(items[h].code) ? cs : bs).push_back(items[h].code);
                    judge_group(codec, cs, bs, r);
                    g = h;
                }
            }
        }
    }

    MatchResult out;
    for (MatchResult& r : results) {
        out.interior += r.interior;
        out.boundary += r.boundary;
        out.unmatched.insert(out.unmatched.end(), r.unmatched.begin(), r.unmatched.end());
        out.problems.merge(std::move(r.problems));
    }
    return out;
}

MatchResult match_faces(const VolumeMesh& mesh, const Cells& cells) {
    const std::uint64_t ids = static_cast<std::uint64_t>(cells.count()) + mesh.boundary.face_offsets.size();
    if (ids < (std::uint64_t{1} << 29)) return match_faces_with<std::uint32_t>(mesh, cells);  // half the memory
    return match_faces_with<std::uint64_t>(mesh, cells);
}

/// Faces present once: a quad whose two halves are unmatched triangles is a non-conforming
/// quad/triangle junction; what remains is a hole (cell face) or a stray boundary face.
void explain_unmatched(const FaceCodec& codec, const std::vector<std::uint64_t>& unmatched, Problems& problems) {
    std::vector<Item> triangles;
    Index v[4];
    for (std::uint64_t code : unmatched)
        if (codec.nodes(code, v) == 3) triangles.push_back({sorted_face_key(v, 3), code});
    std::sort(triangles.begin(), triangles.end());
    std::vector<char> used(triangles.size(), 0);
    auto find = [&](Index a, Index b, Index c) -> std::ptrdiff_t {
        const Index t[3] = {a, b, c};
        const Item probe{sorted_face_key(t, 3), 0};
        auto it = std::lower_bound(triangles.begin(), triangles.end(), probe);
        while (it != triangles.end() && it->key == probe.key && used[it - triangles.begin()]) ++it;
        return it != triangles.end() && it->key == probe.key ? it - triangles.begin() : -1;
    };

    std::vector<char> excused(unmatched.size(), 0);  // quads explained by two triangles
    std::vector<std::uint64_t> consumed;             // those triangles
    for (std::size_t u = 0; u < unmatched.size(); ++u) {
        if (codec.nodes(unmatched[u], v) != 4) continue;
        for (int s = 0; s < 2; ++s) {  // s = 0: diagonal v0–v2; s = 1: diagonal v1–v3
            const std::ptrdiff_t t1 = find(v[s], v[s + 1], v[(s + 2) % 4]);
            if (t1 < 0) continue;
            used[t1] = 1;
            const std::ptrdiff_t t2 = find(v[(s + 2) % 4], v[(s + 3) % 4], v[s]);
            if (t2 < 0) {
                used[t1] = 0;
                continue;
            }
            used[t2] = 1;
            excused[u] = 1;
            consumed.push_back(triangles[t1].code);
            consumed.push_back(triangles[t2].code);
            problems.add(kQuadTriangles, [&] {
                Index a[4], b[4];
                codec.nodes(triangles[t1].code, a);
                codec.nodes(triangles[t2].code, b);
                return "quad " + codec.describe(unmatched[u]) +
                       " is not matched: its neighbour has different faces (a quad never against two "
                       "triangles): " +
                       codec.owner(triangles[t1].code) + " has triangle " + fmt_nodes(a, 3) + " and " +
                       codec.owner(triangles[t2].code) + " has triangle " + fmt_nodes(b, 3) +
                       " there; split the quad's cell or use a pyramid between them";
            });
            break;
        }
    }
    std::sort(consumed.begin(), consumed.end());
    for (std::size_t u = 0; u < unmatched.size(); ++u) {
        if (excused[u] || std::binary_search(consumed.begin(), consumed.end(), unmatched[u])) continue;
        const std::uint64_t code = unmatched[u];
        if (codec.is_cell(code))
            problems.add(kHole, [&] {
                return codec.describe(code) +
                       " has no neighbouring cell and is no boundary face (a hole in the mesh, or a "
                       "missing boundary face)";
            });
        else
            problems.add(kBoundaryUnmatched, [&] {
                return codec.describe(code) + " is no face of any cell (a missing cell, or a stray boundary face)";
            });
    }
}

// ---------------------------------------------------------------------------------------
// Check 3: the volume the boundary encloses, relative to the bounding-box centre.

double boundary_volume(const VolumeMesh& mesh) {
    const SurfaceMesh& b = mesh.boundary;
    const BoundingBox box = bounding_box(mesh.points);
    const Vec3 r = 0.5 * (box.min + box.max);
    double sum = 0.0;
    Vec3 x[4];
    for (Index f = 0; f < b.num_faces(); ++f) {
        const int n = static_cast<int>(b.face_size(f));
        for (int k = 0; k < n; ++k) x[k] = mesh.points[b.face_node(f, k)] - r;
        sum += face_volume_term(x, n);
    }
    return sum;
}

ValidationReport validate(const VolumeMesh& mesh, double volume_tolerance, std::size_t& total) {
    ValidationReport report;
    const Cells cells(mesh);
    report.cells = static_cast<Index>(cells.count());
    Problems problems;
    if (!check_input(mesh, cells, problems)) {  // indices out of range: stop before using them
        total = problems.total();
        report.problems = problems.flatten();
        return report;
    }

    CellResult cr = check_cells(mesh, cells);
    report.min_scaled_jacobian = cr.min_jacobian;
    if (cr.worst >= 0) {
        const auto [t, i] = cells.locate(cr.worst);
        report.worst_cell = cells.describe(t, i);
    }
    report.cell_volume = cr.volume;
    problems.merge(std::move(cr.problems));

    MatchResult mr = match_faces(mesh, cells);
    report.interior_faces = mr.interior;
    report.boundary_faces = mr.boundary;
    problems.merge(std::move(mr.problems));
    explain_unmatched(FaceCodec{mesh, cells}, mr.unmatched, problems);

    report.boundary_volume = boundary_volume(mesh);
    const double diff = std::abs(report.cell_volume - report.boundary_volume);
    if (!(diff <= volume_tolerance * std::abs(report.boundary_volume)))
        problems.add(kVolume, [&] {
            return "the cells' volumes sum to " + fmt("%.12g", report.cell_volume) + " but the boundary encloses " +
                   fmt("%.12g", report.boundary_volume) + " (relative difference " +
                   fmt("%.3g", diff / std::abs(report.boundary_volume)) + " > tolerance " +
                   fmt("%.3g", volume_tolerance) +
                   "): cells are missing or overlap, or the boundary is incomplete or misoriented";
        });

    total = problems.total();
    report.problems = problems.flatten();
    return report;
}

}  // namespace

double cell_volume(const std::vector<Vec3>& p, const Index* cell, CellType type) {
    // Coordinates relative to the cell's centroid: the face terms are then of the cell's own
    // size, not of its distance from the origin (Σ area vectors = 0, so the result does not
    // depend on the reference point in exact arithmetic).
    const int n = cell_corners(type);
    Vec3 r = Vec3::Zero();
    for (int k = 0; k < n; ++k) r += p[cell[k]];
    r /= static_cast<double>(n);
    std::array<Vec3, 8> x;
    for (int k = 0; k < n; ++k) x[k] = p[cell[k]] - r;
    const FaceTable& table = cell_faces(type);
    double sum = 0.0;
    Vec3 f[4];
    for (int i = 0; i < table.count; ++i) {
        for (int k = 0; k < table.size[i]; ++k) f[k] = x[table.node[i][k]];
        sum += face_volume_term(f, table.size[i]);
    }
    return sum;
}

ValidationReport validate_mesh(const VolumeMesh& mesh, double volume_tolerance) {
    std::size_t total = 0;
    return validate(mesh, volume_tolerance, total);
}

ValidationReport require_valid_mesh(const VolumeMesh& mesh, const std::string& what) {
    std::size_t total = 0;
    ValidationReport report = validate(mesh, 1e-9, total);
    if (report.ok()) return report;
    std::string first;
    for (std::size_t i = 0; i < std::min<std::size_t>(3, report.problems.size()); ++i)
        first += (i ? "; " : "") + report.problems[i];
    throw TopologyError(what + ": invalid mesh: " + std::to_string(total) +
                        (total == 1 ? " problem: " : " problems: ") + first);
}

}  // namespace strata
