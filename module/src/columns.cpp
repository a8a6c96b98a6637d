// The columns of the layers, where they stop, and the cells of a ragged LayerMesh: columns.h.

#include "columns.h"
#include "fans.h"

#include <strata/core/cell_quality.h>
#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/parallel.h>
#include <strata/core/solver_checks.h>
#include <strata/geometry/normals.h>
#include <strata/geometry/topology.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

namespace strata {

ColumnFaces::ColumnFaces(const SurfaceMesh& wall) {
    const auto n = static_cast<std::size_t>(wall.num_faces());
    nodes.resize(n);
    size.resize(n);
    patch.resize(n);
    for (Index f = 0; f < wall.num_faces(); ++f) {
        const auto u = static_cast<std::size_t>(f);
        size[u] = static_cast<std::uint8_t>(wall.face_size(f));
        patch[u] = wall.face_patch[f];
        nodes[u] = {kNone, kNone, kNone, kNone};
        std::copy(wall.face_begin(f), wall.face_end(f), nodes[u].begin());
    }
}

void ColumnFaces::split(Index f, int c) {
    const auto u = static_cast<std::size_t>(f);
    const std::array<Index, 4> v = nodes[u];
    auto at = [&](int i) { return v[static_cast<std::size_t>((c + i) % 4)]; };
    nodes[u] = {at(0), at(1), at(2), kNone};
    size[u] = 3;
    nodes.push_back({at(0), at(2), at(3), kNone});
    size.push_back(3);
    patch.push_back(patch[u]);
}

Columns::Columns(const SurfaceMesh& wall, int layers, const std::vector<Vec3>& mesh_points,
                 const std::vector<Vec3>& plane_normal, const std::vector<Vec3>& line)
    : faces(wall), points(&mesh_points) {
    const auto n = static_cast<std::size_t>(wall.num_points());
    point.assign(n * (static_cast<std::size_t>(layers) + 1), kNone);
    for (std::size_t i = 0; i < n; ++i) point[i] = static_cast<Index>(i);
    levels.assign(n, 0);
    max_levels.assign(n, layers);
    limit.assign(n, Shortfall::None);
    active.assign(n, 1);
    reason.assign(n, Shortfall::None);
    top = wall.points;
    reach = wall_reach(wall, plane_normal, line);
}

void Columns::find_edges(const SurfaceMesh& wall) {
    const EdgeTable et = edge_table(wall);
    edges.clear();
    for (const auto& e : et.nodes)
        if (wall.points[e[0]] != wall.points[e[1]]) edges.push_back({e[0], e[1]});
}

std::vector<double> wall_reach(const SurfaceMesh& wall, const std::vector<Vec3>& plane_normal,
                               const std::vector<Vec3>& line) {
    const auto n = static_cast<std::size_t>(wall.num_points());
    std::vector<std::vector<Vec3>> normals(n);
    for (Index f = 0; f < wall.num_faces(); ++f) {
        const Vec3 a = face_area_vector(wall, f);
        double edges2 = 0.0;
        for (Index i = 0; i < wall.face_size(f); ++i)
            edges2 += (wall.points[wall.face_node(f, (i + 1) % wall.face_size(f))] - wall.points[wall.face_node(f, i)])
                          .squaredNorm();
        if (!(a.norm() > 1e-12 * edges2)) continue;  // a fan's strip, a collapsed face: no direction of its own
        for (const Index* v = wall.face_begin(f); v != wall.face_end(f); ++v)
            normals[static_cast<std::size_t>(*v)].push_back(a.normalized());
    }
    std::vector<double> reach(n, 1.0);
    for (std::size_t i = 0; i < n; ++i) {
        if (normals[i].empty()) continue;
        double lowest = 1.0;
        if (i < line.size() && line[i] != Vec3::Zero()) {
            // Held on a line: that line is its one direction.
            for (const Vec3& v : normals[i]) lowest = std::min(lowest, v.dot(line[i]));
        } else {
            if (i < plane_normal.size() && plane_normal[i] != Vec3::Zero()) {
                // Held in a plane: its direction is mirror-symmetric, as good for the faces'
                // mirror images as for the faces (a fin cut along its mid-plane: the edge
                // that the cut leaves on the plane is as sharp as the whole fin's).
                const Vec3& p = plane_normal[i];
                const std::size_t m = normals[i].size();
                for (std::size_t k = 0; k < m; ++k)
                    normals[i].push_back(normals[i][k] - 2.0 * normals[i][k].dot(p) * p);
            }
            max_min_dot_direction(normals[i], &lowest);
        }
        reach[i] = std::clamp(lowest, kMinReach, 1.0);
    }
    return reach;
}

namespace {

/// The smallest sine of a corner angle of the polygon \p x (n corners), each times its
/// \p weight (1 if none).
double corner_sines(const std::array<Vec3, 4>& x, int n, const std::array<double, 4>* weight = nullptr) {
    double q = 1.0;
    for (int c = 0; c < n; ++c) {
        const Vec3& o = x[static_cast<std::size_t>(c)];
        const Vec3 a = x[static_cast<std::size_t>((c + 1) % n)] - o;
        const Vec3 b = x[static_cast<std::size_t>((c + n - 1) % n)] - o;
        const double l = a.norm() * b.norm();
        const double w = weight ? (*weight)[static_cast<std::size_t>(c)] : 1.0;
        q = std::min(q, l > 0.0 ? w * a.cross(b).norm() / l : 0.0);
    }
    return q;
}

}  // namespace

double cell_twist_deg(const std::array<Vec3, 4>& bottom, const std::array<Vec3, 4>& top, int n) {
    Vec3 axis = Vec3::Zero();
    for (int c = 0; c < n; ++c) axis += top[static_cast<std::size_t>(c)] - bottom[static_cast<std::size_t>(c)];
    if (!(axis.norm() > 0.0)) return 0.0;
    axis.normalize();
    double sum = 0.0, weight = 0.0;
    for (int c = 0; c < n; ++c) {
        const auto a = static_cast<std::size_t>(c), b = static_cast<std::size_t>((c + 1) % n);
        Vec3 eb = bottom[b] - bottom[a], et = top[b] - top[a];
        eb -= eb.dot(axis) * axis;
        et -= et.dot(axis) * axis;
        const double w = eb.norm();
        if (!(w > 0.0) || !(et.norm() > 0.0)) continue;
        sum += w * std::atan2(eb.cross(et).dot(axis), eb.dot(et));
        weight += w;
    }
    return weight > 0.0 ? std::abs(sum / weight) * 180.0 / std::numbers::pi : 0.0;
}

bool twists_more_than(const std::array<Vec3, 4>& bottom, const std::array<Vec3, 4>& top, int n, double bound_deg,
                      double tan_bound) {
    // Every edge turned less than the bound (positive cosine, |tan| under it): so is their
    // weighted mean, and no arc tangent is needed; the usual case.
    if (bound_deg < 90.0) {
        Vec3 axis = Vec3::Zero();
        for (int c = 0; c < n; ++c) axis += top[static_cast<std::size_t>(c)] - bottom[static_cast<std::size_t>(c)];
        const double an = axis.squaredNorm();
        bool small = an > 0.0;
        for (int c = 0; c < n && small; ++c) {
            const auto a = static_cast<std::size_t>(c), b = static_cast<std::size_t>((c + 1) % n);
            const Vec3 eb = bottom[b] - bottom[a], et = top[b] - top[a];
            // Projections onto the plane across the axis change neither the sign of the cosine
            // nor the ratio's bound: (eb x et) . axis and the projected dot product.
            const Vec3 ebp = eb - (eb.dot(axis) / an) * axis, etp = et - (et.dot(axis) / an) * axis;
            const double cosine = ebp.dot(etp), sine = std::abs(ebp.cross(etp).dot(axis)) / std::sqrt(an);
            small = cosine > 0.0 && sine <= tan_bound * cosine;
        }
        if (small) return false;
    }
    return cell_twist_deg(bottom, top, n) > bound_deg;
}

double face_corner_quality(const Columns& col, Index f) {
    const auto u = static_cast<std::size_t>(f);
    std::array<Vec3, 4> x;
    std::array<double, 4> w{1.0, 1.0, 1.0, 1.0};
    for (int c = 0; c < col.faces.size[u]; ++c) {
        const auto v = static_cast<std::size_t>(col.faces.nodes[u][static_cast<std::size_t>(c)]);
        x[static_cast<std::size_t>(c)] = col.at_level(static_cast<Index>(v), 0);  // on the wall
        if (v < col.reach.size()) w[static_cast<std::size_t>(c)] = col.reach[v];
    }
    return corner_sines(x, col.faces.size[u], &w);
}

namespace {

/// The least share of what its wall face allows that a front grown over it may lower a cell's
/// bar to (front_quality): round a cone's tip the front's faces stretch a hundredfold, and judged
/// against them alone the cells beside the stopped tip grow on until the layer top crosses
/// itself (ALGORITHM.md, "The bar over a grown front").
constexpr double kFrontShare = 0.25;

/// The best a cell over column face \p f can be in layer \p k: what its wall face allows
/// (\p wall), or less where the front has grown over it (its face at the columns' tops
/// larger than on the wall) into a worse shape: a front round a leading edge or a thin rod
/// spreads its faces round the edge only, so faces the wall meshed square come out long and
/// thin however straight the columns (twelve times as long round a rod of radius r at 11 r);
/// those are the geometry's, as a needle wall face is, and the cells are judged relative to the
/// right cell on them, down to kFrontShare of the wall's. Where the front shrinks (a concave
/// region) the wall's bar holds.
double front_quality(const Columns& col, Index f, int k, double wall) {
    const auto u = static_cast<std::size_t>(f);
    if (k == 0) return wall;
    const int n = col.faces.size[u];
    std::array<Vec3, 4> fb, wb;
    for (int c = 0; c < n; ++c) {
        const Index v = col.faces.nodes[u][static_cast<std::size_t>(c)];
        fb[static_cast<std::size_t>(c)] = col.top[static_cast<std::size_t>(v)];
        wb[static_cast<std::size_t>(c)] = col.at_level(v, 0);
    }
    auto area2 = [&](const std::array<Vec3, 4>& x) {  // twice the vector area, squared
        Vec3 a = Vec3::Zero();
        for (int c = 1; c + 1 < n; ++c) a += (x[c] - x[0]).cross(x[c + 1] - x[0]);
        return a.squaredNorm();
    };
    return area2(fb) > area2(wb) ? std::min(wall, std::max(corner_sines(fb, n), kFrontShare * wall)) : wall;
}

}  // namespace

Vec3 Columns::at_level(Index i, int level) const {
    const auto u = static_cast<std::size_t>(i);
    const int l = std::min(level, levels[u]);
    return (*points)[static_cast<std::size_t>(point[static_cast<std::size_t>(l) * levels.size() + u])];
}

namespace {

/// The corners (positions or node ids, T) of the cell over the column face \p v (\p n nodes) from \p lo (each node's
/// top) to \p hi, its columns that stop (\p moving[c] = 0) collapsed to their top: a prism or hexahedron when all move,
/// a pyramid on the side face of the two that move in a triangle, a tetrahedron on the segment of the one that moves in
/// a triangle, a prism lying on its side over the two adjacent ones that move in a quad. Gmsh order; \p type says
/// which. False where no standard cell closes the step (one, three or two opposite columns moving in a quad: split it
/// first) or nothing moves.
template <class T, class Lo, class Hi>
bool closing_cell(const std::array<Index, 4>& v, int n, const bool* moving, Lo&& lo, Hi&& hi, CellType& type,
                  std::array<T, 8>& p) {
    int m = 0;
    for (int c = 0; c < n; ++c) m += moving[c] ? 1 : 0;
    if (m == n) {
        for (int c = 0; c < n; ++c) p[static_cast<std::size_t>(c)] = lo(v[static_cast<std::size_t>(c)]);
        for (int c = 0; c < n; ++c) p[static_cast<std::size_t>(c + n)] = hi(v[static_cast<std::size_t>(c)]);
        type = n == 3 ? CellType::Prism : CellType::Hex;
        return true;
    }
    if (n == 3 && m == 1) {  // the moving column's segment and the stopped two: a tetrahedron
        int c = 0;
        while (!moving[c]) ++c;
        auto at = [&](int i) { return v[static_cast<std::size_t>((c + i) % 3)]; };
        p[0] = lo(at(0)), p[1] = lo(at(1)), p[2] = lo(at(2)), p[3] = hi(at(0));
        type = CellType::Tet;
        return true;
    }
    if (m != 2) return false;
    // The first moving corner j whose successor moves too: the side face j, j + 1 stays.
    int j = -1;
    for (int c = 0; c < n && j < 0; ++c)
        if (moving[c] && moving[(c + 1) % n]) j = c;
    if (j < 0) return false;  // two opposite corners of a quad
    auto at = [&](int i) { return v[static_cast<std::size_t>((j + i) % n)]; };
    if (n == 3) {  // base: the side face p, q (normal towards the stopped apex s)
        p[0] = lo(at(0)), p[1] = hi(at(0)), p[2] = hi(at(1)), p[3] = lo(at(1)), p[4] = lo(at(2));
        type = CellType::Pyramid;
        return true;
    }
    // Quad p, q, s, t with s, t stopped: triangles (p, t, p') and (q, s, q').
    p[0] = lo(at(0)), p[1] = lo(at(3)), p[2] = hi(at(0)), p[3] = lo(at(1)), p[4] = lo(at(2)), p[5] = hi(at(1));
    type = CellType::Prism;
    return true;
}

/// The scaled Jacobian of a cell from closing_cell (\p full: every column moves), and (\p
/// moving_min) its smallest over the corners at nodes of moving columns: a stopped column's
/// corner sees the thin side face of the step edge-on, its value about layer height / edge
/// length however good the step, so the steepness of a step is judged at the others.
double closing_quality(CellType type, bool full, const std::array<Vec3, 8>& p, double& moving_min) {
    const std::array<Vec3, 8>& pts = p;
    const double all = min_scaled_jacobian(pts.data(), type);
    moving_min = all;
    if (full) return all;
    auto corner = [&](int o, int a, int b, int c) {
        return corner_scaled_jacobian(pts[static_cast<std::size_t>(o)], pts[static_cast<std::size_t>(a)],
                                      pts[static_cast<std::size_t>(b)], pts[static_cast<std::size_t>(c)]);
    };
    if (type == CellType::Tet) {  // corners 0 and 3: the moving column (as cell_quality.h)
        moving_min = std::min(corner(0, 1, 2, 3), corner(3, 0, 2, 1));
        return all;
    }
    if (type == CellType::Pyramid) {  // base corners: the moving columns
        moving_min = 1.0;
        for (int i = 0; i < 4; ++i) moving_min = std::min(moving_min, corner(i, (i + 1) % 4, (i + 3) % 4, 4));
        return all;
    }
    // The side-on prism p, t, p', q, s, q': corners p (0), p' (2), q (3), q' (5), as cell_quality.h.
    moving_min = std::min({corner(0, 1, 2, 3), corner(2, 0, 1, 5), corner(3, 5, 4, 0), corner(5, 4, 3, 2)});
    return all;
}

/// Whether cell \p p of \p type has corners at one position (a fan's columns on the wall, where
/// they all start at their node) and, if so, in \p valid whether the standard cell of its
/// distinct corners (collapse_cell) has every corner positive.
bool collapsed(CellType type, const std::array<Vec3, 8>& p, bool& valid) {
    const int n = type == CellType::Tet ? 4 : type == CellType::Pyramid ? 5 : type == CellType::Prism ? 6 : 8;
    std::array<Index, 8> id{};
    bool any = false;
    for (int c = 0; c < n; ++c) {
        id[static_cast<std::size_t>(c)] = c;
        for (int d = 0; d < c && id[static_cast<std::size_t>(c)] == c; ++d)
            if (p[static_cast<std::size_t>(d)] == p[static_cast<std::size_t>(c)]) id[static_cast<std::size_t>(c)] = d;
        any |= id[static_cast<std::size_t>(c)] != c;
    }
    if (!any) return false;
    CellType t = type;
    valid = collapse_cell(t, id);
    if (!valid) return true;
    std::array<Vec3, 8> q{};
    const int m = t == CellType::Tet ? 4 : t == CellType::Pyramid ? 5 : t == CellType::Prism ? 6 : 8;
    for (int c = 0; c < m; ++c)
        q[static_cast<std::size_t>(c)] = p[static_cast<std::size_t>(id[static_cast<std::size_t>(c)])];
    valid = min_scaled_jacobian(q.data(), t) > 0.0;
    return true;
}

/// The steepest a step may be: its drop at most this many times its distance on the wall from
/// the column going on (ALGORITHM.md, "The cells that close a step"); past it the columns beside
/// it stop too, and the layer top round a sharp tip stopped at the wall does not meet itself.
constexpr double kMaxStepSlope = 5.0;

/// The share of LayerParams::min_quality a cell closing a step is held to, against what its face
/// and its step allow (usable): half, as cell_bar holds a whole cell over a fair face to half of
/// min_quality at least: a step cell is a transition, not a layer cell, and held to the whole bar
/// the columns round a stop would stop ring by ring (ALGORITHM.md, "The cells that close a step").
constexpr double kStepShare = 0.5;

/// How a step's drop lowers the best its closing cell \p p (closing_cell's corners, of \p type,
/// at least one column stopped) can be: per column going on, the product over the stopped tops
/// its corner meets of |e⊥| / |e|, e from the column's bottom to that top and e⊥ its part across
/// the column (a right step of drop D at wall distance L: L / sqrt(L² + D²), 1 for a step of one
/// layer's height over a long edge); the least over the moving columns. \p steepest: the least
/// single factor, the steepest pair.
double step_steepness(CellType type, const std::array<Vec3, 8>& p, double& steepest) {
    steepest = 1.0;
    auto factor = [&](int lo, int hi, int top) {
        const Vec3 u = p[static_cast<std::size_t>(hi)] - p[static_cast<std::size_t>(lo)];
        const Vec3 e = p[static_cast<std::size_t>(top)] - p[static_cast<std::size_t>(lo)];
        const double ul = u.norm(), el = e.norm();
        if (!(ul > 0.0) || !(el > 0.0)) return 1.0;
        const double r = (e - e.dot(u / ul) * (u / ul)).norm() / el;
        steepest = std::min(steepest, r);
        return r;
    };
    if (type == CellType::Tet) return factor(0, 3, 1) * factor(0, 3, 2);               // one column, two stopped
    if (type == CellType::Pyramid) return std::min(factor(0, 1, 4), factor(3, 2, 4));  // apex: the stopped top
    return std::min(factor(0, 2, 1), factor(3, 5, 4));  // side-on prism: p meets t, q meets s
}

/// Whether the closing cell of \p type at \p p is usable: every corner positive, the corners of
/// moving columns at least min_quality times \p face_quality (the best a cell on the face can be),
/// and above the first layer (\p first false) kStepShare of that times what the step's drop
/// allows them (step_steepness), the drop at most kMaxStepSlope times its wall distance. In the
/// first layer the whole bar holds: prisms beside a column stopped at the wall can lean far over
/// small wall faces, which checkMesh then finds skewed.
/// A cell over a fan's face on the wall, whose columns start at one node, is judged as the cell
/// it collapses to, and only on being valid: such a face has no area, so nothing to be relative to.
bool usable(CellType type, bool full, const std::array<Vec3, 8>& p, double face_quality, const StopRules& rules,
            bool first) {
    if (bool valid = false; !full && collapsed(type, p, valid)) return valid;
    double moving_min = 0.0, steepest = 1.0;
    const double all = closing_quality(type, full, p, moving_min);
    const double steep = full ? 1.0 : step_steepness(type, p, steepest);
    const double bar = (full || first ? 1.0 : kStepShare * steep) * rules.min_quality * face_quality;
    if (!(all > 0.0) || moving_min < bar) return false;
    if (full) return true;
    if (steepest < 1.0 / std::hypot(1.0, kMaxStepSlope)) return false;
    // The stopped corners see the step's side edge-on: at best about segment / distance (the
    // segments' length over their distance from the stopped node). Judged relative to that,
    // so a step whose apex lies nearly in its base's plane stops the columns too.
    double seg = 0.0, dist = 0.0;
    const std::array<std::pair<int, int>, 3> segments =
        type == CellType::Pyramid ? std::array<std::pair<int, int>, 3>{{{0, 1}, {3, 2}, {0, 1}}}
        : type == CellType::Tet   ? std::array<std::pair<int, int>, 3>{{{0, 3}, {0, 3}, {0, 3}}}
                                  : std::array<std::pair<int, int>, 3>{{{0, 2}, {3, 5}, {0, 2}}};
    const Vec3 apex = type == CellType::Pyramid ? p[4] : type == CellType::Tet ? p[1] : p[1];
    for (const auto& [a, b] : segments) {
        seg = std::max(seg, (p[static_cast<std::size_t>(b)] - p[static_cast<std::size_t>(a)]).norm());
        dist = std::max(dist, (p[static_cast<std::size_t>(a)] - apex).norm());
    }
    const double ideal = dist > 0.0 ? std::min(1.0, seg / dist) : 0.0;
    return !(all < bar * ideal);
}

/// Whether splitting quad \p f through its corner \p c keeps every cell below level \p k usable
/// (they were judged as the quad's; two prisms of a warped hexahedron can invert), and with
/// \p next (every corner moving on to it) the two prisms of level \p k too.
bool split_keeps_cells(const Columns& col, Index f, int c, int k, const StopRules& rules,
                       const std::vector<Vec3>* next = nullptr) {
    const auto& q = col.faces.nodes[static_cast<std::size_t>(f)];
    auto at = [&](int i) { return q[static_cast<std::size_t>((c + i) % 4)]; };
    const std::array<std::array<Index, 4>, 2> tris{{{at(0), at(1), at(2), kNone}, {at(0), at(2), at(3), kNone}}};
    for (int j = 0; j < (next ? k + 1 : k); ++j)
        for (const auto& t : tris) {
            bool moving[3];
            int m = 0;
            for (int i = 0; i < 3; ++i)
                m += (moving[i] = j == k || col.levels[static_cast<std::size_t>(t[static_cast<std::size_t>(i)])] > j)
                         ? 1
                         : 0;
            if (m == 0) continue;
            auto lo = [&](Index i) { return col.at_level(i, j); };
            auto hi = [&](Index i) { return j == k ? (*next)[static_cast<std::size_t>(i)] : col.at_level(i, j + 1); };
            CellType type{};
            std::array<Vec3, 8> p{};
            if (!closing_cell(t, 3, moving, lo, hi, type, p)) return false;
            const std::array<double, 4> w{col.reach[static_cast<std::size_t>(t[0])],
                                          col.reach[static_cast<std::size_t>(t[1])],
                                          col.reach[static_cast<std::size_t>(t[2])], 1.0};
            const double fq = corner_sines({lo(t[0]), lo(t[1]), lo(t[2]), Vec3::Zero()}, 3, &w);
            if (!usable(type, m == 3, p, fq, rules, j == 0) || face_pyramids_inverted(p.data(), type)) return false;
        }
    return true;
}

/// Whether the bottom or top quad of hexahedron \p p (bottom 0-3, top 4-7) is warped by a
/// quarter of its shortest column segment or more (its diagonals' midpoints that far apart
/// along its normal): only then can a face's pyramid to the cell's centre invert, so only then
/// is face_pyramids_inverted worth its cost (it doubled the stopping tests' share of the layer
/// benchmark's cubed sphere).
bool warped_against_height(const std::array<Vec3, 8>& p) {
    double h = std::numeric_limits<double>::infinity();
    for (int c = 0; c < 4; ++c)
        h = std::min(h, (p[static_cast<std::size_t>(c + 4)] - p[static_cast<std::size_t>(c)]).squaredNorm());
    h = std::sqrt(h);
    for (int o : {0, 4}) {
        const auto at = [&](int i) { return p[static_cast<std::size_t>(o + i)]; };
        const Vec3 n = (at(2) - at(0)).cross(at(3) - at(1));
        const double len = n.norm();
        if (!(len > 0.0)) return true;  // a degenerate quad: let the full test judge it
        if (std::abs((at(0) + at(2) - at(1) - at(3)).dot(n)) / (2.0 * len) >= 0.25 * h) return true;
    }
    return false;
}

/// Whether each corner of column face \p f moves on, by \p moving per wall node.
std::array<bool, 4> moving_corners(const ColumnFaces& faces, Index f, const std::vector<char>& moving) {
    std::array<bool, 4> m{false, false, false, false};
    const auto u = static_cast<std::size_t>(f);
    for (int c = 0; c < faces.size[u]; ++c)
        m[static_cast<std::size_t>(c)] =
            moving[static_cast<std::size_t>(faces.nodes[u][static_cast<std::size_t>(c)])] != 0;
    return m;
}

/// The angle in degrees between \p a and \p b (0 where either vanishes).
double angle_deg(const Vec3& a, const Vec3& b) {
    const double l = a.norm() * b.norm();
    if (!(l > 0.0)) return 0.0;
    return std::acos(std::clamp(a.dot(b) / l, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

/// Stop wall node \p i (if it still moves) for \p why; true if it did move.
bool stop(Columns& col, std::vector<char>& go, Index i, Shortfall why) {
    auto& g = go[static_cast<std::size_t>(i)];
    if (!g) return false;
    if (!col.pinned.empty() && col.pinned[static_cast<std::size_t>(i)]) {
        col.pinned[static_cast<std::size_t>(i)] = 2;  // it would have stopped: the caller builds no fan there
        return false;
    }
    g = 0;
    col.reason[static_cast<std::size_t>(i)] = why;
    return true;
}

/// The skewness above which two cells of a layer are not kept side by side: checkMesh fails a
/// mesh above kFoamSkewness (4); the margin is the tetrahedra's (kTetSkewTarget), for the
/// cells the later layers and the front rounds still change round them.
constexpr double kLayerSkewTarget = 0.9 * kFoamSkewness;

/// col.side_pairs for the column faces as they are now (found again only once faces are split):
/// the manifold edges of edge_table over them.
void find_side_pairs(Columns& col) {
    const Index nf = col.faces.count();
    if (col.side_pairs_faces == nf) return;
    SurfaceMesh m;
    m.points = col.top;  // for the node count only
    m.patches.push_back({"columns", PatchKind::Wall});
    for (Index f = 0; f < nf; ++f)
        m.add_face(col.faces.nodes[static_cast<std::size_t>(f)].data(), col.faces.size[static_cast<std::size_t>(f)], 0);
    const EdgeTable edges = edge_table(m);
    col.side_pairs.clear();
    for (std::size_t e = 0; e < edges.nodes.size(); ++e) {
        const auto i = static_cast<Index>(e);
        if (edges.faces.row_end(i) - edges.faces.row_begin(i) != 2) continue;  // open or non-manifold
        const Index* g = edges.faces.row_begin(i);
        col.side_pairs.push_back({edges.nodes[e][0], edges.nodes[e][1], g[0], g[1]});
    }
    col.side_pairs_faces = nf;
}

/// Whether the faces \p f and \p g, at their columns' tops, turn by more than 90° from each
/// other: only there do cells over them lie stacked rather than side by side.
bool folded(const Columns& col, Index f, Index g) {
    auto normal = [&](Index h) {
        const auto& v = col.faces.nodes[static_cast<std::size_t>(h)];
        auto x = [&](int c) { return col.top[static_cast<std::size_t>(v[static_cast<std::size_t>(c)])]; };
        return col.faces.size[static_cast<std::size_t>(h)] == 3 ? Vec3((x(1) - x(0)).cross(x(2) - x(0)))
                                                                : Vec3((x(2) - x(0)).cross(x(3) - x(1)));
    };
    return normal(f).dot(normal(g)) < 0.0;
}

/// checkMesh's skewness of the face between the cells of this layer over the faces \p f and
/// \p g that share the edge \p a, \p b (at least one of whose columns moves), the columns that
/// stop (\p go 0) collapsed to their tops: a quad where both move, a triangle where one does.
/// 0 where either face has no cell.
template <class Lo, class Hi>
double shared_side_skewness(const Columns& col, Index a, Index b, Index f, Index g, const std::vector<char>& go,
                            Lo&& lo, Hi&& hi) {
    Vec3 centre[2];
    const Index faces[2] = {f, g};
    for (int s = 0; s < 2; ++s) {
        const auto u = static_cast<std::size_t>(faces[s]);
        const int n = col.faces.size[u];
        bool moving[4] = {false, false, false, false};
        for (int c = 0; c < n; ++c)
            moving[c] = go[static_cast<std::size_t>(col.faces.nodes[u][static_cast<std::size_t>(c)])] != 0;
        CellType type{};
        std::array<Vec3, 8> p{};
        if (!closing_cell(col.faces.nodes[u], n, moving, lo, hi, type, p)) return 0.0;
        centre[s] = foam_cell_centre(p.data(), type);
    }
    const bool ma = go[static_cast<std::size_t>(a)] != 0, mb = go[static_cast<std::size_t>(b)] != 0;
    std::array<Vec3, 4> q{lo(a), lo(b), hi(b), hi(a)};
    int n = 4;
    if (!ma) q = {lo(a), lo(b), hi(b), Vec3::Zero()}, n = 3;
    if (!mb) q = {lo(b), lo(a), hi(a), Vec3::Zero()}, n = 3;
    static constexpr std::array<Index, 4> kFace{0, 1, 2, 3};
    return face_skewness(q.data(), kFace.data(), n, centre[0], &centre[1]);
}

/// Close every step the stops so far leave, stopping more columns where it cannot be closed
/// with usable cells, until nothing changes (only ever stopping: it ends).
void close_steps(Columns& col, const StopRules& rules, int k, const std::vector<Vec3>& next, std::vector<char>& go) {
    auto lo = [&](Index i) { return col.top[static_cast<std::size_t>(i)]; };
    auto hi = [&](Index i) { return go[static_cast<std::size_t>(i)] ? next[static_cast<std::size_t>(i)] : lo(i); };
    for (bool changed = true; changed;) {
        changed = false;
        for (Index f = 0; f < col.faces.count(); ++f) {
            const auto u = static_cast<std::size_t>(f);
            const int n = col.faces.size[u];
            const std::array<bool, 4> m = moving_corners(col.faces, f, go);
            const int moving = static_cast<int>(std::count(m.begin(), m.begin() + n, true));
            if (moving == 0 || moving == n) continue;
            const bool adjacent_pair = moving == 2 && m[0] != m[2];  // not 0 and 2, not 1 and 3
            if (n == 4 && !adjacent_pair) {
                // One, three or two opposite moving: split along a diagonal (either leaves
                // triangles every step of which a cell closes), the first that keeps the cells
                // below usable; with neither, the quad's columns stop.
                int c = 0;
                while (m[static_cast<std::size_t>(c)] ||
                       (moving == 1 && m[static_cast<std::size_t>((c + 3) % 4)] == false))
                    ++c;  // a stopped corner; with one moving, the one after it
                if (!split_keeps_cells(col, f, c, k, rules)) c = (c + 1) % 4;
                if (split_keeps_cells(col, f, c, k, rules)) {
                    col.faces.split(f, c);
                    changed = true;
                } else {
                    // Only a stop that happened is a change: a pinned fan column does not stop
                    // (stop marks it for the caller), and counting it would loop for ever.
                    for (int i = 0; i < 4; ++i)
                        changed |=
                            stop(col, go, col.faces.nodes[u][static_cast<std::size_t>(i)], Shortfall::Neighbours);
                }
                continue;
            }
            CellType type{};
            std::array<Vec3, 8> p{};
            // As for whole cells, relative to the best a cell on the face can be.
            const bool fair = closing_cell(col.faces.nodes[u], n, m.data(), lo, hi, type, p) &&
                              usable(type, false, p, front_quality(col, f, k, face_corner_quality(col, f)), rules, k == 0);
            // A cell thinner than one of its faces is warped can have every corner positive and
            // its centre on the wrong side of that face, which checkMesh fails ("incorrectly
            // oriented faces"): a step's side-on prism in the first layer over a quad that Gmsh
            // bent round a leading edge.
            const bool inverted = fair && face_pyramids_inverted(p.data(), type);
            if (fair && !inverted) continue;
            if (inverted && n == 4) {
                // The quad split through a stopped corner instead (a pyramid and a tetrahedron
                // over planar triangles), where that keeps the cells below usable.
                bool split = false;
                for (int c = 0; c < 4 && !split; ++c)
                    if (!m[static_cast<std::size_t>(c)] && split_keeps_cells(col, f, c, k, rules)) {
                        col.faces.split(f, c);
                        split = true;
                    }
                if (split) {
                    changed = true;
                    continue;
                }
            }
            for (int c = 0; c < n; ++c)
                changed |= stop(col, go, col.faces.nodes[u][static_cast<std::size_t>(c)], Shortfall::Neighbours);
        }
        if (changed) continue;  // every step closable first
        // Two cells closing steps across a folded edge (stacked, as across an acute concave
        // junction whose columns stop on one end) whose face between them checkMesh would find
        // skewed: that edge's moving columns stop too, and the cells no longer share a face.
        find_side_pairs(col);
        for (const auto& [a, b, f, g] : col.side_pairs) {
            const bool ma = go[static_cast<std::size_t>(a)] != 0, mb = go[static_cast<std::size_t>(b)] != 0;
            if (!ma && !mb) continue;
            const std::array<bool, 4> mf = moving_corners(col.faces, f, go), mg = moving_corners(col.faces, g, go);
            const int nf = col.faces.size[static_cast<std::size_t>(f)],
                      ng = col.faces.size[static_cast<std::size_t>(g)];
            if (std::count(mf.begin(), mf.begin() + nf, true) == nf &&
                std::count(mg.begin(), mg.begin() + ng, true) == ng)
                continue;  // two whole cells: stop_columns judged them
            if (!folded(col, f, g) || !(shared_side_skewness(col, a, b, f, g, go, lo, hi) > kLayerSkewTarget)) continue;
            changed |= stop(col, go, a, Shortfall::Neighbours);
            changed |= stop(col, go, b, Shortfall::Neighbours);
        }
    }
}

/// The faces between two sound cells of this layer (over wall faces sharing an edge, every
/// column of both moving on) that OpenFOAM's checkMesh would find skewed beyond
/// kLayerSkewTarget: two cells stacked rather than side by side, as over the two faces of an
/// acute concave edge (a rod through a plate at 15°: 4.15 between the first prisms on either
/// side of the junction). Only pairs of faces folded by more than 90° are measured (folded).
/// Returns their edges (in edge order) and marks their cells poor 4; the caller stops the
/// edges' two columns, so the cells on either side close the step onto the stopped edge and no
/// longer share a face.
std::vector<std::pair<Index, Index>> skewed_sides(Columns& col, const std::vector<Vec3>& next,
                                                  const std::vector<char>& full, std::vector<char>& poor) {
    find_side_pairs(col);
    auto lo = [&](Index i) { return col.top[static_cast<std::size_t>(i)]; };
    auto hi = [&](Index i) { return next[static_cast<std::size_t>(i)]; };
    std::vector<std::pair<Index, Index>> edges;
    for (const auto& [a, b, f, g] : col.side_pairs) {
        const auto uf = static_cast<std::size_t>(f), ug = static_cast<std::size_t>(g);
        if (!full[uf] || !full[ug] || poor[uf] || poor[ug] || !folded(col, f, g)) continue;
        if (!(shared_side_skewness(col, a, b, f, g, col.active, lo, hi) > kLayerSkewTarget)) continue;
        edges.emplace_back(a, b);
        poor[uf] = 4;
        poor[ug] = 4;
    }
    return edges;
}

}  // namespace

double column_cell_jacobian(const Columns& col, Index f, const std::vector<Vec3>& next, std::array<Vec3, 8>* corners) {
    static constexpr std::array<bool, 4> kAll{true, true, true, true};
    CellType type{};
    std::array<Vec3, 8> p{};
    auto lo = [&](Index i) { return col.top[static_cast<std::size_t>(i)]; };
    auto hi = [&](Index i) { return next[static_cast<std::size_t>(i)]; };
    closing_cell(col.faces.nodes[static_cast<std::size_t>(f)], col.faces.size[static_cast<std::size_t>(f)], kAll.data(),
                 lo, hi, type, p);
    double unused = 0.0;
    if (corners) *corners = p;
    return closing_quality(type, true, p, unused);
}

double cell_bar(double min_quality, double best) {
    return best >= min_quality ? std::max(min_quality * best, 0.5 * min_quality) : min_quality * best;
}

namespace {

/// Per wall node, the mean length of its edges (Columns::edges) on the level \p next.
std::vector<double> front_spacing(const Columns& col, const std::vector<Vec3>& next) {
    std::vector<double> sum(col.levels.size(), 0.0);
    std::vector<int> count(col.levels.size(), 0);
    for (const auto& [a, b] : col.edges) {
        const double l = (next[static_cast<std::size_t>(a)] - next[static_cast<std::size_t>(b)]).norm();
        for (const Index v : {a, b}) sum[static_cast<std::size_t>(v)] += l, ++count[static_cast<std::size_t>(v)];
    }
    for (std::size_t i = 0; i < sum.size(); ++i)
        sum[i] = count[i] > 0 ? sum[i] / count[i] : std::numeric_limits<double>::infinity();
    return sum;
}

}  // namespace

Index stop_columns(Columns& col, const StopRules& rules, int k, const std::vector<Vec3>& next) {
    const Index nw = static_cast<Index>(col.levels.size());
    std::vector<char> go = col.active;
    const bool isotropy = rules.quality && rules.isotropy > 0.0 && k > 0;
    const std::vector<double> spacing = isotropy ? front_spacing(col, next) : std::vector<double>{};
    for (Index i = 0; i < nw; ++i) {
        const auto u = static_cast<std::size_t>(i);
        if (!go[u]) continue;
        if (k >= col.max_levels[u]) {
            stop(col, go, i, col.limit[u] == Shortfall::None ? Shortfall::Proximity : col.limit[u]);
        } else if (!next[u].allFinite()) {
            stop(col, go, i, Shortfall::NonFinite);
        } else if (rules.quality && k > 0 &&
                   angle_deg(next[u] - col.top[u], col.top[u] - col.at_level(i, k - 1)) > rules.max_turn_deg) {
            stop(col, go, i, Shortfall::Turning);
        } else if (isotropy && (next[u] - col.top[u]).norm() > rules.isotropy * spacing[u]) {
            stop(col, go, i, Shortfall::Isotropic);
        }
    }
    if (rules.quality) {
        // Each face's cell judged alone (in parallel), then its columns stopped in face order.
        const Index nf = col.faces.count();
        std::vector<char> poor(static_cast<std::size_t>(nf), 0), full(static_cast<std::size_t>(nf), 0);
        const double tan_twist = std::tan(rules.max_twist_deg * std::numbers::pi / 180.0);
        for (auto f = static_cast<Index>(col.best.size()); f < nf; ++f) col.best.push_back(face_corner_quality(col, f));
#pragma omp parallel for schedule(static) num_threads(thread_count(rules.threads, nf))
        for (Index f = 0; f < nf; ++f) {
            const auto u = static_cast<std::size_t>(f);
            const int n = col.faces.size[u];
            // A column stopped above (at its limit: the layers it may have, the wall for a sharp
            // edge's node) makes this face a step too, not a cell over its ghost.
            const std::array<bool, 4> m = moving_corners(col.faces, f, go);
            if (std::count(m.begin(), m.begin() + n, true) != n) continue;  // a step: close_steps judges it
            full[u] = 1;
            bool finite = true;
            for (int c = 0; c < n; ++c)
                finite &= next[static_cast<std::size_t>(col.faces.nodes[u][static_cast<std::size_t>(c)])].allFinite();
            // Relative to the right cell on the same face: a needle triangle's cells are as good
            // as the face allows, and only what the marching does to them stops a column; a
            // face that allows a fair cell keeps its cells at half of min_quality (cell_bar).
            std::array<Vec3, 8> p;  // the cell's corners, bottom then top, in the face's order
            const double q = finite ? column_cell_jacobian(col, f, next, &p) : std::nan("");
            const double best_here = front_quality(col, f, k, col.best[u]);
            poor[u] = q >= cell_bar(rules.min_quality, best_here) ? 0 : 1;
            if (!poor[u]) {
                std::array<Vec3, 4> bottom, top;
                for (int c = 0; c < n; ++c) {
                    bottom[static_cast<std::size_t>(c)] = p[static_cast<std::size_t>(c)];
                    top[static_cast<std::size_t>(c)] = p[static_cast<std::size_t>(c + n)];
                }
                if (twists_more_than(bottom, top, n, rules.max_twist_deg, tan_twist)) poor[u] = 2;
                // A hexahedron over a quad warped more than the layer is thin (Gmsh's coarse
                // quads round a slender body) can have every corner fair and a face whose
                // pyramid to its centre is inverted, which checkMesh fails: split below.
                else if (n == 4 && warped_against_height(p) && face_pyramids_inverted(p.data(), CellType::Hex))
                    poor[u] = 3;
            }
        }
        const std::vector<std::pair<Index, Index>> skewed = skewed_sides(col, next, full, poor);
        for (Index f = 0; f < nf; ++f) {
            if (poor[static_cast<std::size_t>(f)] == 3) {
                // Split along the diagonal that gives two sound prisms (here and below); with
                // neither, the hexahedron stays as it was (the summary's checkMesh line names it).
                for (int c = 0; c < 2; ++c)
                    if (split_keeps_cells(col, f, c, k, rules, &next)) {
                        col.faces.split(f, c);
                        break;
                    }
                continue;
            }
            if (poor[static_cast<std::size_t>(f)] == 4) continue;  // its skewed side's columns, below
            if (poor[static_cast<std::size_t>(f)])
                for (int c = 0; c < col.faces.size[static_cast<std::size_t>(f)]; ++c)
                    stop(col, go, col.faces.nodes[static_cast<std::size_t>(f)][static_cast<std::size_t>(c)],
                         poor[static_cast<std::size_t>(f)] == 2 ? Shortfall::Twist : Shortfall::Quality);
        }
        for (const auto& [a, b] : skewed) {
            stop(col, go, a, Shortfall::Quality);
            stop(col, go, b, Shortfall::Quality);
        }
    }
    close_steps(col, rules, k, next, go);
    Index stopped = 0, materialised = 0;  // the caller appends next[i] of the moving nodes in order
    for (Index i = 0; i < nw; ++i) {
        const auto u = static_cast<std::size_t>(i);
        if (col.active[u] && !go[u]) ++stopped;
        if (!go[u]) continue;
        col.point[static_cast<std::size_t>(k + 1) * static_cast<std::size_t>(nw) + u] =
            static_cast<Index>(col.points->size() + static_cast<std::size_t>(materialised++));
        col.top[u] = next[u];
        col.levels[u] = k + 1;
    }
    col.active = std::move(go);
    return stopped;
}

namespace {

/// The cells of layer \p k over column face \p f (none where its columns have stopped), in the
/// numbering of \p out; their quality into \p stats.
void add_layer_cells(const Columns& col, Index f, int k, LayerMesh& out, LayerStats& stats, double& jsum, Index& full) {
    const auto u = static_cast<std::size_t>(f);
    const int n = col.faces.size[u];
    std::array<bool, 4> m{};
    for (int c = 0; c < n; ++c)
        m[static_cast<std::size_t>(c)] =
            col.levels[static_cast<std::size_t>(col.faces.nodes[u][static_cast<std::size_t>(c)])] > k;
    const int moving = static_cast<int>(std::count(m.begin(), m.begin() + n, true));
    if (moving == 0) return;
    CellType type{};
    std::array<Index, 8> id{};
    auto lo = [&](Index i) { return out.level_node(k, i); };
    auto hi = [&](Index i) { return out.level_node(k + 1, i); };
    const std::vector<Vec3>& pts = out.mesh.points;
    if (!closing_cell(col.faces.nodes[u], n, m.data(), lo, hi, type, id) || !collapse_cell(type, id))
        throw TopologyError("internal: layer " + std::to_string(k + 1) +
                            " has a step over a wall face that no cell closes");
    const double j = min_scaled_jacobian(pts, id.data(), type);
    if (moving == n) {
        stats.min_scaled_jacobian = std::isnan(j) || std::isnan(stats.min_scaled_jacobian)
                                        ? std::nan("")
                                        : std::min(stats.min_scaled_jacobian, j);
        jsum += j;
        ++full;
    } else {
        ++stats.transition_cells;
        stats.min_transition_jacobian = std::min(stats.min_transition_jacobian, j);
    }
    switch (type) {
        case CellType::Prism:
            out.mesh.prisms.push_back({id[0], id[1], id[2], id[3], id[4], id[5]});
            break;
        case CellType::Hex:
            out.mesh.hexes.push_back({id[0], id[1], id[2], id[3], id[4], id[5], id[6], id[7]});
            break;
        case CellType::Pyramid:
            out.mesh.pyramids.push_back({id[0], id[1], id[2], id[3], id[4]});
            break;
        case CellType::Tet:
            out.mesh.tets.push_back({id[0], id[1], id[2], id[3]});
            break;
    }
    ++out.face_layers[u];
}

}  // namespace

void build_layer_cells(const Columns& col, const SurfaceMesh& wall, const Csr& loops,
                       const std::vector<Index>& edge_patch, LayerMesh& out) {
    const ColumnFaces& faces = col.faces;
    out.face_layers.assign(static_cast<std::size_t>(faces.count()), 0);
    for (int k = 0; k < out.layers(); ++k) {
        LayerStats& s = out.stats[static_cast<std::size_t>(k)];
        s.min_scaled_jacobian = 1.0;
        double jsum = 0.0;
        Index full = 0;
        for (Index f = 0; f < faces.count(); ++f) add_layer_cells(col, f, k, out, s, jsum, full);
        s.mean_scaled_jacobian = full > 0 ? jsum / static_cast<double>(full) : 0.0;
    }

    // The boundary: the wall reversed (out of the layers), the top, the side faces on open edges.
    SurfaceMesh& bnd = out.mesh.boundary;
    bnd.patches = wall.patches;
    out.top_patch = static_cast<Index>(bnd.patches.size());
    bnd.patches.push_back({"layer_top", PatchKind::Other});
    // A face no column over grew from carries no cell: neither its wall nor its top is a face of
    // the layers (build_hybrid_mesh keeps it as wall).
    // A face of a fan collapses on the wall (its nodes' columns start at one node): only its
    // distinct nodes make a face, if three or more.
    auto add_distinct = [&](Index* v, Index n, Index patch) {
        Index m = 0;
        for (Index i = 0; i < n; ++i)
            if (v[i] != v[(i + n - 1) % n]) v[m++] = v[i];
        if (m >= 3) bnd.add_face(v, m, patch);
    };
    for (Index f = 0; f < faces.count(); ++f) {
        if (out.face_layers[static_cast<std::size_t>(f)] == 0) continue;
        const auto& v = faces.nodes[static_cast<std::size_t>(f)];
        const Index n = faces.size[static_cast<std::size_t>(f)];
        Index r[4];
        r[0] = out.level_node(0, v[0]);
        for (Index i = 1; i < n; ++i) r[i] = out.level_node(0, v[static_cast<std::size_t>(n - i)]);
        add_distinct(r, n, faces.patch[static_cast<std::size_t>(f)]);
    }
    for (Index f = 0; f < faces.count(); ++f) {
        if (out.face_layers[static_cast<std::size_t>(f)] == 0) continue;
        const auto& v = faces.nodes[static_cast<std::size_t>(f)];
        const Index n = faces.size[static_cast<std::size_t>(f)];
        Index t[4];
        for (Index i = 0; i < n; ++i) t[i] = out.top_node(v[static_cast<std::size_t>(i)]);
        add_distinct(t, n, out.top_patch);
    }
    Index side_patch = kNone, edge = 0;
    for (Index l = 0; l < loops.rows(); ++l) {
        const Index m = loops.row_size(l);
        for (Index i = 0; i < m; ++i, ++edge) {
            const Index a = loops.row_begin(l)[i], b = loops.row_begin(l)[(i + 1) % m];
            Index patch = edge_patch[static_cast<std::size_t>(edge)];
            if (patch == kNone) {
                if (side_patch == kNone) {
                    side_patch = static_cast<Index>(bnd.patches.size());
                    bnd.patches.push_back({"layer_side", PatchKind::Other});
                }
                patch = side_patch;
            }
            for (int k = 0; k < out.layers(); ++k) {
                const bool ma = out.node_layers(a) > k, mb = out.node_layers(b) > k;
                const Index a0 = out.level_node(k, a), b0 = out.level_node(k, b);
                const Index a1 = out.level_node(k + 1, a), b1 = out.level_node(k + 1, b);
                // Between two columns of a plane node's fan, collapsed on the wall: a triangle.
                Index q[4] = {a0, b0, b1, a1};
                if (ma && mb)
                    add_distinct(q, 4, patch);
                else if (ma)
                    bnd.add_face({a0, b0, a1}, patch);
                else if (mb)
                    bnd.add_face({a0, b0, b1}, patch);
            }
        }
    }

    // The front: the column faces at the top of their columns.
    out.top = SurfaceMesh{};
    out.top.patches = wall.patches;
    out.top.points.resize(static_cast<std::size_t>(wall.num_points()));
    for (Index i = 0; i < wall.num_points(); ++i)
        out.top.points[static_cast<std::size_t>(i)] = out.mesh.points[static_cast<std::size_t>(out.top_node(i))];
    for (Index f = 0; f < faces.count(); ++f)
        out.top.add_face(faces.nodes[static_cast<std::size_t>(f)].data(), faces.size[static_cast<std::size_t>(f)],
                         faces.patch[static_cast<std::size_t>(f)]);
}

}  // namespace strata

namespace strata {

LayerMesh::LayerMesh(Index wall_nodes, int layers) : wall_nodes_(wall_nodes), layers_(layers) {}

int LayerMesh::level_of(Index node) const {
    if (level_start_.empty()) return static_cast<int>(node / wall_nodes_);
    const auto it = std::upper_bound(level_start_.begin(), level_start_.end(), node);
    return static_cast<int>(it - level_start_.begin()) - 1;
}

void LayerMesh::set_columns(std::vector<int> node_layers, std::vector<Index> base) {
    const auto nw = static_cast<std::size_t>(wall_nodes_);
    if (node_layers.size() != nw || (!base.empty() && base.size() != nw))
        throw InputError("LayerMesh::set_columns: " + std::to_string(node_layers.size()) + " column heights and " +
                         std::to_string(base.size()) + " bases for " + std::to_string(nw) + " wall nodes");
    if (base.empty() && std::all_of(node_layers.begin(), node_layers.end(), [&](int l) { return l == layers_; })) {
        node_layers_.clear(), ids_.clear(), level_start_.clear();  // full columns: k × nw + i
        return;
    }
    node_layers_ = std::move(node_layers);
    ids_.assign((static_cast<std::size_t>(layers_) + 1) * nw, kNone);
    level_start_.assign(static_cast<std::size_t>(layers_) + 2, 0);
    Index next = 0;
    for (int k = 0; k <= layers_; ++k) {
        level_start_[static_cast<std::size_t>(k)] = next;
        const std::size_t row = static_cast<std::size_t>(k) * nw;
        for (std::size_t i = 0; i < nw; ++i) {
            if (k == 0 && !base.empty() && base[i] != static_cast<Index>(i))
                ids_[i] = base[i];  // a fan's column: from its wall node
            else
                ids_[row + i] = node_layers_[i] >= k ? next++ : ids_[row - nw + i];
        }
    }
    level_start_.back() = next;
}

}  // namespace strata
