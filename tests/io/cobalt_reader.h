#pragma once
// Test helper: a strict, independent Cobalt60 ASCII reader (FORMATS.md) and its companion
// `.bc` patch map, and the volume mesh rebuilt from the file's faces alone (cells recovered from
// the faces around them, corners put in Gmsh order from the faces' orientation), so that a
// written file can be checked with validate_mesh and against the mesh it came from.
//
// Strict on layout: one header line of 3 integers, one of 5, one line per node (3 numbers),
// one line per face ("nv v1..vnv c1 c2"), nothing but blank space after. Errors throw
// std::runtime_error naming the file and line.

#include <strata/core/volume_mesh.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace strata::test {

/// The file as written: node ids and cell ids exactly as in the file (1-based, c2 < 0 a patch).
struct CobaltGrid {
    std::int64_t ndim = 0, nzones = 0, npatches = 0;
    std::int64_t nnodes = 0, nfaces = 0, ncells = 0;
    std::int64_t max_nodes_per_face = 0, max_faces_per_cell = 0;
    std::vector<Vec3> points;                   ///< nnodes
    std::vector<std::int64_t> face_offsets{0};  ///< nfaces + 1
    std::vector<std::int64_t> face_nodes;       ///< 1-based node ids, file order
    std::vector<std::int64_t> c1, c2;           ///< nfaces each, as in the file

    std::int64_t face_size(std::int64_t f) const { return face_offsets[f + 1] - face_offsets[f]; }
    /// 0-based node k of face f.
    Index node(std::int64_t f, std::int64_t k) const { return static_cast<Index>(face_nodes[face_offsets[f] + k] - 1); }
};

struct CobaltPatch {
    std::int64_t number = 0;
    std::string name;
    std::string kind;
};

namespace detail {

inline std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot open '" + path + "'");
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// Whitespace-separated tokens of one line.
inline std::vector<std::string_view> tokens(std::string_view line) {
    std::vector<std::string_view> t;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        std::size_t j = i;
        while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
        if (j > i) t.push_back(line.substr(i, j - i));
        i = j;
    }
    return t;
}

class Lines {
public:
    Lines(std::string text, std::string path) : text_(std::move(text)), path_(std::move(path)) {}
    bool next(std::string_view& line) {
        if (pos_ >= text_.size()) return false;
        const std::size_t e = text_.find('\n', pos_);
        const std::size_t end = e == std::string::npos ? text_.size() : e;
        line = std::string_view(text_).substr(pos_, end - pos_);
        pos_ = end + 1;
        ++number_;
        return true;
    }
    /// The next line's tokens; exactly \p count of them unless count < 0.
    std::vector<std::string_view> expect(int count, const char* what) {
        std::string_view line;
        if (!next(line)) fail(std::string("file ends before ") + what);
        auto t = tokens(line);
        if (count >= 0 && static_cast<int>(t.size()) != count)
            fail(std::string(what) + ": expected " + std::to_string(count) + " fields, got " +
                 std::to_string(t.size()) + " in '" + std::string(line) + "'");
        return t;
    }
    std::int64_t integer(std::string_view s) const {
        std::int64_t v = 0;
        const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
        if (r.ec != std::errc() || r.ptr != s.data() + s.size()) fail("'" + std::string(s) + "' is not an integer");
        return v;
    }
    double real(std::string_view s) const {
        double v = 0;
        const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
        if (r.ec != std::errc() || r.ptr != s.data() + s.size()) fail("'" + std::string(s) + "' is not a number");
        return v;
    }
    [[noreturn]] void fail(const std::string& what) const {
        throw std::runtime_error(path_ + ":" + std::to_string(number_) + ": " + what);
    }

private:
    std::string text_, path_;
    std::size_t pos_ = 0;
    std::int64_t number_ = 0;
};

}  // namespace detail

/// Read a Cobalt60 ASCII grid. Checks the layout and the ranges of ids (nodes 1..nnodes, c1 in
/// 1..ncells, c2 in 1..ncells or −npatches..−1) but nothing topological: that is the tests' job.
inline CobaltGrid read_cobalt(const std::string& path) {
    detail::Lines in(detail::slurp(path), path);
    CobaltGrid g;
    auto h1 = in.expect(3, "header line 1 (ndim nzones npatches)");
    g.ndim = in.integer(h1[0]);
    g.nzones = in.integer(h1[1]);
    g.npatches = in.integer(h1[2]);
    auto h2 = in.expect(5, "header line 2 (nnodes nfaces ncells maxNodesPerFace maxFacesPerCell)");
    g.nnodes = in.integer(h2[0]);
    g.nfaces = in.integer(h2[1]);
    g.ncells = in.integer(h2[2]);
    g.max_nodes_per_face = in.integer(h2[3]);
    g.max_faces_per_cell = in.integer(h2[4]);
    if (g.nnodes < 0 || g.nfaces < 0 || g.ncells < 0) in.fail("negative count");
    g.points.reserve(static_cast<std::size_t>(g.nnodes));
    for (std::int64_t i = 0; i < g.nnodes; ++i) {
        auto t = in.expect(3, "node coordinates");
        g.points.emplace_back(in.real(t[0]), in.real(t[1]), in.real(t[2]));
    }
    for (std::int64_t f = 0; f < g.nfaces; ++f) {
        auto t = in.expect(-1, "a face line");
        if (t.empty()) in.fail("empty face line");
        const std::int64_t nv = in.integer(t[0]);
        if (nv < 3 || nv > g.max_nodes_per_face)
            in.fail("face with " + std::to_string(nv) + " nodes (maxNodesPerFace " +
                    std::to_string(g.max_nodes_per_face) + ")");
        if (static_cast<std::int64_t>(t.size()) != nv + 3)
            in.fail("face line with " + std::to_string(t.size()) + " fields, expected " + std::to_string(nv + 3));
        for (std::int64_t k = 1; k <= nv; ++k) {
            const std::int64_t v = in.integer(t[k]);
            if (v < 1 || v > g.nnodes)
                in.fail("node id " + std::to_string(v) + " out of 1.." + std::to_string(g.nnodes));
            g.face_nodes.push_back(v);
        }
        g.face_offsets.push_back(static_cast<std::int64_t>(g.face_nodes.size()));
        const std::int64_t a = in.integer(t[nv + 1]), b = in.integer(t[nv + 2]);
        if (a < 1 || a > g.ncells) in.fail("c1 = " + std::to_string(a) + " out of 1.." + std::to_string(g.ncells));
        if (b == 0 || b > g.ncells || b < -g.npatches)
            in.fail("c2 = " + std::to_string(b) + " is neither a cell nor -1..-" + std::to_string(g.npatches));
        g.c1.push_back(a);
        g.c2.push_back(b);
    }
    std::string_view rest;
    while (in.next(rest))
        if (!detail::tokens(rest).empty()) in.fail("unexpected text after the last face");
    return g;
}

/// Read `<grid>.bc`: "<number> <name> <kind>" per non-comment line; the name is everything
/// between the number and the kind.
inline std::vector<CobaltPatch> read_cobalt_bc(const std::string& path) {
    detail::Lines in(detail::slurp(path), path);
    std::vector<CobaltPatch> patches;
    std::string_view line;
    while (in.next(line)) {
        const std::size_t b = line.find_first_not_of(" \t\r");
        if (b == std::string_view::npos || line[b] == '#') continue;
        const auto t = detail::tokens(line);
        if (t.size() < 3) in.fail("expected '<number> <name> <kind>'");
        CobaltPatch p;
        p.number = in.integer(t[0]);
        p.kind = std::string(t.back());
        const std::size_t name_begin = static_cast<std::size_t>(t[1].data() - line.data());
        const std::size_t name_end = static_cast<std::size_t>(t.back().data() - line.data());
        std::string_view name = line.substr(name_begin, name_end - name_begin);
        name = name.substr(0, name.find_last_not_of(" \t") + 1);
        p.name = std::string(name);
        patches.push_back(std::move(p));
    }
    return patches;
}

/// The volume mesh rebuilt from a grid's faces.
struct RebuiltMesh {
    VolumeMesh mesh;                  ///< cells per type in file cell order; boundary = c2 < 0 faces
    std::vector<CellType> cell_type;  ///< per file cell (0-based)
    std::vector<Index> cell_index;    ///< per file cell: its index within mesh's block of its type
    std::vector<Vec3> cell_centroid;  ///< per file cell: mean of its nodes
};

namespace detail {

/// Corners in Gmsh order of one cell from its faces, each given outward (right-hand normal out
/// of the cell). The face tables of validate.cpp are not used: the order follows from the
/// definitions in volume_mesh.h. The right-hand normal of the bottom v0-v1-v2(-v3) points into
/// the cell, towards the top or apex (positive Jacobian), so the bottom listed outward is
/// v0, v2, v1 (triangle) or v0, v3, v2, v1 (quad); the top corners follow along the side quads.
inline std::vector<Index> gmsh_corners(const std::vector<std::vector<Index>>& faces, CellType& type) {
    int tris = 0, quads = 0;
    for (const auto& f : faces) (f.size() == 3 ? tris : quads) += 1;
    std::set<Index> all;
    for (const auto& f : faces) all.insert(f.begin(), f.end());
    auto first_of_size = [&](std::size_t n) -> const std::vector<Index>& {
        for (const auto& f : faces)
            if (f.size() == n) return f;
        throw std::runtime_error("no face of that size");
    };
    // Nodes of a prism/hex "top": the neighbour of each bottom node along a side quad.
    auto lift = [&](const std::vector<Index>& bottom) {
        std::map<Index, Index> up;
        const std::set<Index> in_bottom(bottom.begin(), bottom.end());
        for (const auto& f : faces) {
            if (f.size() != 4 || (f.size() == bottom.size() && std::set<Index>(f.begin(), f.end()) == in_bottom))
                continue;
            for (std::size_t k = 0; k < 4; ++k) {
                const Index a = f[k], b = f[(k + 1) % 4];
                if (in_bottom.count(a) && !in_bottom.count(b)) up[a] = b;
                if (in_bottom.count(b) && !in_bottom.count(a)) up[b] = a;
            }
        }
        std::vector<Index> top;
        for (Index v : bottom) {
            if (!up.count(v)) throw std::runtime_error("cannot find the node above a bottom node");
            top.push_back(up[v]);
        }
        return top;
    };
    if (tris == 4 && quads == 0 && all.size() == 4) {
        type = CellType::Tet;
        const auto& f = faces[0];
        Index apex = kNone;
        for (Index v : all)
            if (std::find(f.begin(), f.end(), v) == f.end()) apex = v;
        return {f[0], f[2], f[1], apex};
    }
    if (tris == 4 && quads == 1 && all.size() == 5) {
        type = CellType::Pyramid;
        const auto& q = first_of_size(4);
        Index apex = kNone;
        for (Index v : all)
            if (std::find(q.begin(), q.end(), v) == q.end()) apex = v;
        return {q[0], q[3], q[2], q[1], apex};
    }
    if (tris == 2 && quads == 3 && all.size() == 6) {
        type = CellType::Prism;
        const auto& t = first_of_size(3);
        std::vector<Index> c{t[0], t[2], t[1]};
        const auto top = lift(c);
        c.insert(c.end(), top.begin(), top.end());
        return c;
    }
    if (tris == 0 && quads == 6 && all.size() == 8) {
        type = CellType::Hex;
        const auto& q = faces[0];
        std::vector<Index> c{q[0], q[3], q[2], q[1]};
        const auto top = lift(c);
        c.insert(c.end(), top.begin(), top.end());
        return c;
    }
    throw std::runtime_error("a cell with " + std::to_string(tris) + " triangles, " + std::to_string(quads) +
                             " quads and " + std::to_string(all.size()) + " nodes is no tet, pyramid, prism or hex");
}

}  // namespace detail

/// Rebuild cells from the faces (a cell's faces: c1 faces as written, c2 faces reversed) and the
/// boundary from the c2 < 0 faces, patch index = position of −c2 in \p patches (from the .bc
/// file; kinds parsed with parse_patch_kind). Throws std::runtime_error if a cell's faces do
/// not make a tet, pyramid, prism or hex, or a patch number is not in \p patches.
inline RebuiltMesh rebuild_mesh(const CobaltGrid& g, const std::vector<CobaltPatch>& patches) {
    RebuiltMesh r;
    r.mesh.points = g.points;
    std::map<std::int64_t, Index> patch_index;
    for (const CobaltPatch& p : patches) {
        patch_index[p.number] = static_cast<Index>(r.mesh.boundary.patches.size());
        r.mesh.boundary.patches.push_back({p.name, parse_patch_kind(p.kind)});
    }
    std::vector<std::vector<std::vector<Index>>> cell_faces(static_cast<std::size_t>(g.ncells));
    for (std::int64_t f = 0; f < g.nfaces; ++f) {
        std::vector<Index> v;
        for (std::int64_t k = 0; k < g.face_size(f); ++k) v.push_back(g.node(f, k));
        cell_faces[g.c1[f] - 1].push_back(v);
        if (g.c2[f] > 0) {
            std::reverse(v.begin(), v.end());
            cell_faces[g.c2[f] - 1].push_back(v);
        } else {
            const auto it = patch_index.find(-g.c2[f]);
            if (it == patch_index.end())
                throw std::runtime_error("face " + std::to_string(f + 1) + " is on patch " + std::to_string(-g.c2[f]) +
                                         " which the .bc file does not list");
            r.mesh.boundary.add_face(v.data(), static_cast<Index>(v.size()), it->second);
        }
    }
    for (std::int64_t c = 0; c < g.ncells; ++c) {
        CellType type{};
        std::vector<Index> v;
        try {
            v = detail::gmsh_corners(cell_faces[c], type);
        } catch (const std::runtime_error& e) {
            throw std::runtime_error("cell " + std::to_string(c + 1) + ": " + e.what());
        }
        Vec3 centre = Vec3::Zero();
        for (Index x : v) centre += g.points[x];
        r.cell_centroid.push_back(centre / static_cast<double>(v.size()));
        r.cell_type.push_back(type);
        switch (type) {
            case CellType::Tet:
                r.cell_index.push_back(static_cast<Index>(r.mesh.tets.size()));
                r.mesh.tets.push_back({v[0], v[1], v[2], v[3]});
                break;
            case CellType::Pyramid:
                r.cell_index.push_back(static_cast<Index>(r.mesh.pyramids.size()));
                r.mesh.pyramids.push_back({v[0], v[1], v[2], v[3], v[4]});
                break;
            case CellType::Prism:
                r.cell_index.push_back(static_cast<Index>(r.mesh.prisms.size()));
                r.mesh.prisms.push_back({v[0], v[1], v[2], v[3], v[4], v[5]});
                break;
            case CellType::Hex:
                r.cell_index.push_back(static_cast<Index>(r.mesh.hexes.size()));
                r.mesh.hexes.push_back({v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]});
                break;
        }
    }
    return r;
}

}  // namespace strata::test
