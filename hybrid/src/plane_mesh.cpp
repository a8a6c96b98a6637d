// Planar regions meshed with Gmsh's 2D mesher: plane_mesh.h.

#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/hybrid/plane_mesh.h>
#include <strata/io/gmsh_session.h>

#include "tetgen_sizing.h"

#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Surface_sweep_2_algorithms.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <map>
#include <memory>
#include <unordered_map>
#include <utility>

namespace strata {

namespace {

/// The plane's frame: coordinates (u, v) of the outer points and of the points Gmsh adds.
struct Frame {
    const std::vector<Vec3>& points;  ///< the outer points
    const PlaneMesh& out;             ///< its new_points follow the outer points
    Vec3 origin, u, v;

    Frame(const std::vector<Vec3>& pts, const PlaneMesh& o, const Vec3& origin_, const Vec3& normal)
        : points(pts), out(o), origin(origin_) {
        const Vec3 n = normal.normalized();
        u = (std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
        v = n.cross(u);
    }
    /// Point \p p in 3D: an outer point, or one Gmsh gave.
    const Vec3& at(Index p) const {
        const auto i = static_cast<std::size_t>(p);
        return i < points.size() ? points[i] : out.new_points[i - points.size()];
    }
    Eigen::Vector2d uv(Index p) const {
        const Vec3 d = at(p) - origin;
        return {d.dot(u), d.dot(v)};
    }
};

/// Signed area of each loop about the normal (outer loops positive, holes negative).
std::vector<double> loop_areas(const Frame& f, const std::vector<std::vector<Index>>& loops) {
    std::vector<double> area(loops.size(), 0.0);
    for (std::size_t l = 0; l < loops.size(); ++l)
        for (std::size_t i = 0; i < loops[l].size(); ++i) {
            const Eigen::Vector2d p = f.uv(loops[l][i]), q = f.uv(loops[l][(i + 1) % loops[l].size()]);
            area[l] += 0.5 * (p.x() * q.y() - q.x() * p.y());
        }
    return area;
}

/// The surfaces to mesh: each outer loop, then the holes inside it (a hole goes to the
/// smallest outer loop that contains it).
std::vector<std::vector<std::size_t>> group_loops(const Frame& f, const std::vector<std::vector<Index>>& loops,
                                                  const std::vector<double>& area, const std::string& ctx) {
    auto inside = [&](const Eigen::Vector2d& x, const std::vector<Index>& loop) {
        bool in = false;
        for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
            const Eigen::Vector2d a = f.uv(loop[i]), b = f.uv(loop[j]);
            if ((a.y() > x.y()) != (b.y() > x.y()) &&
                x.x() < (b.x() - a.x()) * (x.y() - a.y()) / (b.y() - a.y()) + a.x())
                in = !in;
        }
        return in;
    };
    std::vector<std::vector<std::size_t>> surfaces;  // outer loop, then its holes
    for (std::size_t l = 0; l < loops.size(); ++l)
        if (area[l] > 0.0) surfaces.push_back({l});
    if (surfaces.empty())
        throw TopologyError(ctx +
                            ": the loops enclose no region (no loop runs counter-clockwise about the plane normal)");
    for (std::size_t l = 0; l < loops.size(); ++l) {
        if (area[l] > 0.0) continue;
        std::size_t best = surfaces.size();
        for (std::size_t s = 0; s < surfaces.size(); ++s)
            if (inside(f.uv(loops[l][0]), loops[surfaces[s][0]]) &&
                (best == surfaces.size() || area[surfaces[s][0]] < area[surfaces[best][0]]))
                best = s;
        if (best == surfaces.size())
            throw TopologyError(ctx + ": a hole of its boundary at " + format_point(f.points[loops[l][0]]) +
                                " lies outside every outer loop");
        surfaces[best].push_back(l);
    }
    return surfaces;
}

/// The loops must bound a region Gmsh can mesh: no two loop segments cross, touch or overlap
/// other than consecutive ones at their shared point, and no two loop points coincide. Gmsh's
/// 2D mesher throws from inside an OpenMP region on such input, which ends the process, so
/// it is refused here first, with the place. Exact (CGAL's sweep with exact constructions).
void check_simple_loops(const Frame& f, const std::vector<std::vector<Index>>& loops, const std::string& ctx) {
    using K = CGAL::Exact_predicates_exact_constructions_kernel;
    using Segment = CGAL::Arr_segment_traits_2<K>::Curve_2;
    std::vector<Segment> segments;
    std::vector<std::pair<std::array<double, 2>, Index>> at;  // uv position, point id
    for (const auto& loop : loops)
        for (std::size_t i = 0; i < loop.size(); ++i) {
            const Eigen::Vector2d a = f.uv(loop[i]), b = f.uv(loop[(i + 1) % loop.size()]);
            if (a == b)
                throw TopologyError(ctx + ": two consecutive points of its boundary coincide at " +
                                    format_point(f.at(loop[i])));
            segments.emplace_back(K::Point_2(a.x(), a.y()), K::Point_2(b.x(), b.y()));
            at.push_back({{a.x(), a.y()}, loop[i]});
        }
    std::sort(at.begin(), at.end());
    for (std::size_t i = 1; i < at.size(); ++i)
        if (at[i].first == at[i - 1].first)
            throw TopologyError(ctx + ": two points of its boundary coincide at " + format_point(f.at(at[i].second)) +
                                " (the boundary touches itself there); the region cannot be meshed");
    std::vector<K::Point_2> crossings;
    CGAL::compute_intersection_points(segments.begin(), segments.end(), std::back_inserter(crossings), false);
    if (crossings.empty()) return;
    const Vec3 x =
        f.origin + CGAL::to_double(crossings.front().x()) * f.u + CGAL::to_double(crossings.front().y()) * f.v;
    throw TopologyError(ctx + ": its boundary crosses or overlaps itself at " + format_point(x) + " (" +
                        std::to_string(crossings.size()) +
                        " point(s) in all), so it bounds no region; on an input surface this is usually a "
                        "T-junction or overlapping edges: repair the surface there");
}

/// The geo model in the current Gmsh session: one point per outer point (size: the mean of
/// its two loop edges), one line per loop edge (kept as it is: transfinite with 2 nodes), one
/// plane surface per group. Returns the surfaces' tags; \p point_tag receives the points'.
std::vector<int> add_geo_model(const Frame& f, const std::vector<std::vector<Index>>& loops,
                               const std::vector<std::vector<std::size_t>>& surfaces, const std::string& ctx,
                               std::map<Index, int>& point_tag) {
    const std::vector<Vec3>& points = f.points;
    std::vector<int> loop_tag(loops.size()), lines;
    for (std::size_t l = 0; l < loops.size(); ++l) {
        const auto& loop = loops[l];
        const std::size_t m = loop.size();
        for (std::size_t i = 0; i < m; ++i) {
            const Index p = loop[i];
            if (point_tag.count(p))
                throw TopologyError(ctx + ": its new boundary passes twice through " + format_point(points[p]));
            const Vec3& x = points[p];
            const double h =
                0.5 * ((x - points[loop[(i + 1) % m]]).norm() + (x - points[loop[(i + m - 1) % m]]).norm());
            const Eigen::Vector2d q = f.uv(p);
            point_tag[p] = gmsh::model::geo::addPoint(q.x(), q.y(), 0.0, h);
        }
        std::vector<int> ll;
        for (std::size_t i = 0; i < m; ++i) {
            ll.push_back(gmsh::model::geo::addLine(point_tag[loop[i]], point_tag[loop[(i + 1) % m]]));
            lines.push_back(ll.back());
        }
        loop_tag[l] = gmsh::model::geo::addCurveLoop(ll);
    }
    std::vector<int> surf_tags;
    for (const auto& s : surfaces) {
        std::vector<int> wires;
        for (std::size_t l : s) wires.push_back(loop_tag[l]);
        surf_tags.push_back(gmsh::model::geo::addPlaneSurface(wires));
    }
    gmsh::model::geo::synchronize();
    for (int line : lines) gmsh::model::mesh::setTransfiniteCurve(line, 2);
    return surf_tags;
}

/// The nodes Gmsh meshed: the boundary points keep their ids, the interior ones are appended to
/// out.new_points. Returns Gmsh node → point id.
std::unordered_map<std::size_t, Index> take_nodes(const Frame& f, PlaneMesh& out, const std::map<Index, int>& point_tag,
                                                  const std::vector<int>& surf_tags, const std::string& ctx) {
    std::unordered_map<std::size_t, Index> node;
    std::vector<std::size_t> tags;
    std::vector<double> xyz, par;
    for (const auto& [p, t] : point_tag) {
        gmsh::model::mesh::getNodes(tags, xyz, par, 0, t);
        if (tags.size() != 1) throw BackendError(ctx + ": Gmsh gave no node for a boundary point");
        node[tags[0]] = p;
    }
    gmsh::model::mesh::getNodes(tags, xyz, par, 1, -1, false, false);
    if (!tags.empty()) throw BackendError(ctx + ": Gmsh added nodes on the boundary it was to keep");
    for (int s : surf_tags) {
        gmsh::model::mesh::getNodes(tags, xyz, par, 2, s, false, false);
        for (std::size_t i = 0; i < tags.size(); ++i) {
            node[tags[i]] = static_cast<Index>(f.points.size() + out.new_points.size());
            out.new_points.push_back(f.origin + xyz[3 * i] * f.u + xyz[3 * i + 1] * f.v);
        }
    }
    return node;
}

/// Surface \p s's triangles appended to out.triangles, counter-clockwise about the normal.
/// Returns the area they cover; BackendError if one overlaps the others.
double take_triangles(const Frame& f, PlaneMesh& out, int s, const std::unordered_map<std::size_t, Index>& node,
                      const std::string& ctx) {
    std::vector<std::size_t> elems, enodes;
    gmsh::model::mesh::getElementsByType(2, elems, enodes, s);
    // Gmsh orients the triangles of one surface consistently: flip them all or none (by their
    // total signed area; triangles with three nearly collinear boundary points have a sign
    // that is round-off and must follow the others).
    const std::size_t first = out.triangles.size();
    double signed_area = 0.0;
    std::vector<double> area_of;
    for (std::size_t e = 0; e < elems.size(); ++e) {
        std::array<Index, 3> t{};
        for (std::size_t i = 0; i < 3; ++i) {
            const auto it = node.find(enodes[3 * e + i]);
            if (it == node.end()) throw BackendError(ctx + ": a triangle uses a node Gmsh did not report");
            t[i] = it->second;
        }
        const Eigen::Vector2d a = f.uv(t[0]), b = f.uv(t[1]), c = f.uv(t[2]);
        area_of.push_back(0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x()));
        signed_area += area_of.back();
        out.triangles.push_back(t);
    }
    const double sign = signed_area < 0.0 ? -1.0 : 1.0;
    double meshed = 0.0;
    for (std::size_t e = 0; e < elems.size(); ++e) {
        auto& t = out.triangles[first + e];
        if (sign < 0.0) std::swap(t[1], t[2]);  // counter-clockwise about the normal
        const double ar = sign * area_of[e];
        double longest = 0.0;
        for (std::size_t i = 0; i < 3; ++i) longest = std::max(longest, (f.uv(t[i]) - f.uv(t[(i + 1) % 3])).norm());
        if (ar < -1e-9 * longest * longest)
            throw BackendError(ctx + ": Gmsh's triangles overlap near " + format_point(f.at(t[0])));
        meshed += ar;
    }
    return meshed;
}

/// Conforming, edge by edge: every directed edge of the triangles once at most; its reverse
/// present too (an interior edge) unless it runs along a loop in the loop's direction (the
/// region lies left of its loops). A triangle folded over a nearly straight stretch of a loop
/// breaks this even when the areas add up.
void check_conforming(const Frame& f, const std::vector<std::vector<Index>>& loops, const std::string& ctx) {
    std::map<std::pair<Index, Index>, int> used;
    for (const auto& t : f.out.triangles)
        for (std::size_t i = 0; i < 3; ++i) ++used[{t[i], t[(i + 1) % 3]}];
    std::map<std::pair<Index, Index>, int> on_loop;
    for (const auto& loop : loops)
        for (std::size_t i = 0; i < loop.size(); ++i) on_loop[{loop[i], loop[(i + 1) % loop.size()]}] = 1;
    for (const auto& [e, count] : used) {
        const bool ok =
            count == 1 && (on_loop.count(e) ? !used.count({e.second, e.first}) : used.count({e.second, e.first}) == 1);
        if (!ok)
            throw BackendError(ctx + ": Gmsh's triangles of the plane do not join edge to edge near " +
                               format_point(f.at(e.first)) +
                               " (they fold over a nearly straight stretch of its boundary); a coarser or smoother "
                               "surface mesh there avoids it");
    }
    for (const auto& [e, one] : on_loop)
        if (!used.count(e))
            throw BackendError(ctx + ": a boundary segment at " + format_point(f.at(e.first)) +
                               " is not an edge of Gmsh's triangles");
}

}  // namespace

PlaneMesh mesh_plane_region(const std::vector<Vec3>& points, const std::vector<std::vector<Index>>& loops,
                            const Vec3& origin, const Vec3& normal, const std::string& ctx, double growth,
                            const std::vector<char>& grow_from) {
    PlaneMesh out;
    const Frame frame(points, out, origin, normal);
    // Outer loops run counter-clockwise about n, holes clockwise (the faces' orientation).
    const std::vector<double> area = loop_areas(frame, loops);
    check_simple_loops(frame, loops, ctx);
    const std::vector<std::vector<std::size_t>> surfaces = group_loops(frame, loops, area, ctx);

    GmshSession session("strata_plane");
    GmshOptionScope opts;
    gmsh_call(ctx, [&] {
        // Frontal-Delaunay (6) ignores a size callback and, between a fine hole and a coarse outer
        // loop, inserts no point at all (Gmsh 4.8: a ring of spacing 0.1 in a square of side 100
        // stays 67 nodes). Delaunay (5) follows the callback (9 triangles in 10 within 1.2 of the
        // size, a few up to 3.3; tests/hybrid/test_plane_mesh.cpp). MeshAdapt (1) stays within 1.5
        // but took 4.7 times as long on the hemisphere-cylinder and left its tetrahedra worse
        // (0.021 against 0.034).
        opts.set("Mesh.Algorithm", growth > 0.0 ? 5 : 6);
        opts.set("Mesh.RandomFactor", 1e-12);
        opts.set("Mesh.MeshSizeMin", 0.0);
        opts.set("Mesh.MeshSizeMax", 1e22);
        opts.set("Mesh.MeshSizeFactor", 1.0);
        opts.set("Mesh.MeshSizeFromPoints", 1);
        opts.set("Mesh.MeshSizeExtendFromBoundary", 1);
        opts.set("Mesh.MeshSizeFromCurvature", 0);
        opts.set("Mesh.RecombineAll", 0);
        opts.set("Mesh.ElementOrder", 1);
        std::map<Index, int> point_tag;  // outer point → geo point
        const std::vector<int> surf_tags = add_geo_model(frame, loops, surfaces, ctx, point_tag);
        std::unique_ptr<tetgen::SizeField> graded;
        if (growth > 0.0) {
            // The loop points it grows from with their spacing (as their geo points' sizes), graded
            // like the tetrahedra, up to the coarsest spacing of the loops.
            std::vector<Vec3> at;
            std::vector<double> size;
            double coarsest = 0.0;
            for (const auto& loop : loops)
                for (std::size_t i = 0, m = loop.size(); i < m; ++i) {
                    const Vec3& x = frame.at(loop[i]);
                    const double h =
                        0.5 * ((x - frame.at(loop[(i + 1) % m])).norm() + (x - frame.at(loop[(i + m - 1) % m])).norm());
                    coarsest = std::max(coarsest, h);
                    const auto k = static_cast<std::size_t>(loop[i]);
                    if (!grow_from.empty() && (k >= grow_from.size() || !grow_from[k])) continue;
                    at.push_back(x);
                    size.push_back(h);
                }
            graded = std::make_unique<tetgen::SizeField>(std::move(at), std::move(size), growth);
            gmsh::model::mesh::setSizeCallback([&frame, &graded, coarsest](int, int, double x, double y, double) {
                return std::min((*graded)(frame.origin + x * frame.u + y * frame.v), coarsest);
            });
        }
        struct RemoveCallback {
            bool on;
            ~RemoveCallback() {
                if (on) gmsh::model::mesh::removeSizeCallback();
            }
        } remove_callback{growth > 0.0};
        gmsh::model::mesh::generate(2);
        const auto node = take_nodes(frame, out, point_tag, surf_tags, ctx);
        double meshed = 0.0, expected = 0.0;
        for (double a : area) expected += a;
        for (int s : surf_tags) meshed += take_triangles(frame, out, s, node, ctx);
        if (std::abs(meshed - expected) > 1e-6 * expected)
            throw BackendError(ctx + ": the triangles cover an area of " + format_number(meshed) + " instead of " +
                               format_number(expected) + " (Gmsh's 2D mesher failed on the plane)");
    });
    check_conforming(frame, loops, ctx);
    return out;
}

}  // namespace strata
