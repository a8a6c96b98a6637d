// Planar regions meshed with Gmsh's 2D mesher: plane_mesh.h.

#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/io/gmsh_session.h>
#include <strata/hybrid/plane_mesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <unordered_map>

namespace strata {

PlaneMesh mesh_plane_region(const std::vector<Vec3>& points, const std::vector<std::vector<Index>>& loops,
                            const Vec3& origin, const Vec3& normal, const std::string& ctx) {
    PlaneMesh out;
    const Vec3 n = normal.normalized();
    const Vec3 u = (std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
    const Vec3 v = n.cross(u);
    // A point's coordinates in the plane (new points: the ones Gmsh gave).
    auto uv = [&](Index p) {
        const Vec3 d = (static_cast<std::size_t>(p) < points.size()
                            ? points[static_cast<std::size_t>(p)]
                            : out.new_points[static_cast<std::size_t>(p) - points.size()]) -
                       origin;
        return Eigen::Vector2d(d.dot(u), d.dot(v));
    };
    // Outer loops run counter-clockwise about n, holes clockwise (the faces' orientation).
    std::vector<double> area(loops.size(), 0.0);
    for (std::size_t l = 0; l < loops.size(); ++l)
        for (std::size_t i = 0; i < loops[l].size(); ++i) {
            const Eigen::Vector2d p = uv(loops[l][i]), q = uv(loops[l][(i + 1) % loops[l].size()]);
            area[l] += 0.5 * (p.x() * q.y() - q.x() * p.y());
        }
    auto inside = [&](const Eigen::Vector2d& x, const std::vector<Index>& loop) {
        bool in = false;
        for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
            const Eigen::Vector2d a = uv(loop[i]), b = uv(loop[j]);
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
            if (inside(uv(loops[l][0]), loops[surfaces[s][0]]) &&
                (best == surfaces.size() || area[surfaces[s][0]] < area[surfaces[best][0]]))
                best = s;
        if (best == surfaces.size())
            throw TopologyError(ctx + ": a hole of its boundary at " + format_point(points[loops[l][0]]) +
                                " lies outside every outer loop");
        surfaces[best].push_back(l);
    }

    GmshSession session("strata_plane");
    GmshOptionScope opts;
    gmsh_call(ctx, [&] {
        opts.set("Mesh.Algorithm", 6);
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
                const Eigen::Vector2d q = uv(p);
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
        gmsh::model::mesh::generate(2);

        std::unordered_map<std::size_t, Index> node;  // Gmsh node → outer point
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
                node[tags[i]] = static_cast<Index>(points.size() + out.new_points.size());
                out.new_points.push_back(origin + xyz[3 * i] * u + xyz[3 * i + 1] * v);
            }
        }
        double meshed = 0.0, expected = 0.0;
        for (double a : area) expected += a;
        for (int s : surf_tags) {
            std::vector<std::size_t> elems, enodes;
            gmsh::model::mesh::getElementsByType(2, elems, enodes, s);
            // Gmsh orients the triangles of one surface consistently: flip them all or none
            // (by their total signed area; triangles with three nearly collinear boundary points
            // have a sign that is round-off and must follow the others).
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
                const Eigen::Vector2d a = uv(t[0]), b = uv(t[1]), c = uv(t[2]);
                area_of.push_back(0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x()));
                signed_area += area_of.back();
                out.triangles.push_back(t);
            }
            const double sign = signed_area < 0.0 ? -1.0 : 1.0;
            for (std::size_t e = 0; e < elems.size(); ++e) {
                auto& t = out.triangles[first + e];
                if (sign < 0.0) std::swap(t[1], t[2]);  // counter-clockwise about the normal
                const double ar = sign * area_of[e];
                double longest = 0.0;
                for (int i = 0; i < 3; ++i)
                    longest = std::max(
                        longest,
                        (uv(t[static_cast<std::size_t>(i)]) - uv(t[static_cast<std::size_t>((i + 1) % 3)])).norm());
                if (ar < -1e-9 * longest * longest)
                    throw BackendError(
                        ctx + ": Gmsh's triangles overlap near " +
                        format_point(points.size() > static_cast<std::size_t>(t[0])
                                         ? points[static_cast<std::size_t>(t[0])]
                                         : out.new_points[static_cast<std::size_t>(t[0]) - points.size()]));
                meshed += ar;
            }
        }
        if (std::abs(meshed - expected) > 1e-6 * expected)
            throw BackendError(ctx + ": the triangles cover an area of " + std::to_string(meshed) + " instead of " +
                               std::to_string(expected) + " (Gmsh's 2D mesher failed on the plane)");
    });
    // Conforming, edge by edge: every directed edge of the triangles once at most; its reverse
    // present too (an interior edge) unless it runs along a loop in the loop's direction (the
    // region lies left of its loops). A triangle folded over a nearly straight stretch of a
    // loop breaks this even when the areas add up.
    std::map<std::pair<Index, Index>, int> used;
    for (const auto& t : out.triangles)
        for (std::size_t i = 0; i < 3; ++i) ++used[{t[i], t[(i + 1) % 3]}];
    std::map<std::pair<Index, Index>, int> on_loop;
    for (const auto& loop : loops)
        for (std::size_t i = 0; i < loop.size(); ++i) on_loop[{loop[i], loop[(i + 1) % loop.size()]}] = 1;
    for (const auto& [e, count] : used) {
        const bool ok =
            count == 1 && (on_loop.count(e) ? !used.count({e.second, e.first}) : used.count({e.second, e.first}) == 1);
        if (!ok) {
            const Index a = e.first;
            const Vec3 x = static_cast<std::size_t>(a) < points.size()
                               ? points[static_cast<std::size_t>(a)]
                               : out.new_points[static_cast<std::size_t>(a) - points.size()];
            throw BackendError(ctx + ": Gmsh's triangles of the plane do not join edge to edge near " +
                               format_point(x) +
                               " (they fold over a nearly straight stretch of its boundary); a coarser or smoother "
                               "surface mesh there avoids it");
        }
    }
    for (const auto& [e, one] : on_loop)
        if (!used.count(e))
            throw BackendError(ctx + ": a boundary segment at " +
                               format_point(points[static_cast<std::size_t>(e.first)]) +
                               " is not an edge of Gmsh's triangles");
    return out;
}

}  // namespace strata
