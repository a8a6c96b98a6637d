// The alpha wrap of a triangle soup, its patches and its distance from the input: wrap.h.

#include <strata/geometry/cgal_kernel.h>

#include "cgal_mesh.h"

#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/format.h>
#include <strata/core/parallel.h>
#include <strata/geometry/intersections.h>
#include <strata/geometry/wrap.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/alpha_wrap_3.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <vector>

namespace strata {
namespace {

using Triangles = std::vector<cgal::Triangle>;
using Tree = CGAL::AABB_tree<
    CGAL::AABB_traits<cgal::Kernel, CGAL::AABB_triangle_primitive<cgal::Kernel, Triangles::const_iterator>>>;

/// The triangles of \p mesh (quads split along their first diagonal) and the face of each.
struct Soup {
    Triangles triangles;
    std::vector<Index> face;
};

Soup soup_of(const SurfaceMesh& mesh) {
    Soup s;
    for (const SurfaceTriangle& t : surface_triangles(mesh)) {
        s.triangles.emplace_back(cgal::point(mesh.points[t.v[0]]), cgal::point(mesh.points[t.v[1]]),
                                 cgal::point(mesh.points[t.v[2]]));
        s.face.push_back(t.face);
    }
    return s;
}

/// Where the distance of one mesh from another is measured: its nodes, the midpoints of its
/// faces' edges and its faces' centres.
std::vector<Vec3> samples(const SurfaceMesh& mesh) {
    std::vector<Vec3> at = mesh.points;
    for (Index f = 0; f < mesh.num_faces(); ++f) {
        const Index n = mesh.face_size(f);
        const Index* v = mesh.face_begin(f);
        for (Index i = 0; i < n; ++i) at.push_back(0.5 * (mesh.points[v[i]] + mesh.points[v[(i + 1) % n]]));
        at.push_back(face_centroid(mesh, mesh.points, f));
    }
    return at;
}

/// The farthest of \p at from \p tree's triangles (the first where several tie) and its distance.
std::pair<double, Vec3> farthest(const std::vector<Vec3>& at, const Tree& tree, int threads) {
    const auto n = static_cast<std::int64_t>(at.size());
    std::vector<double> d(at.size(), 0.0);
#pragma omp parallel for num_threads(thread_count(threads, n)) schedule(static)
    for (std::int64_t i = 0; i < n; ++i)
        d[static_cast<std::size_t>(i)] = std::sqrt(tree.squared_distance(cgal::point(at[static_cast<std::size_t>(i)])));
    std::size_t worst = 0;
    for (std::size_t i = 1; i < d.size(); ++i)
        if (d[i] > d[worst]) worst = i;
    return {d.empty() ? 0.0 : d[worst], at.empty() ? Vec3::Zero() : at[worst]};
}

void check_wrap_input(const SurfaceMesh& soup, const WrapParams& p) {
    if (soup.num_faces() == 0) throw InputError("wrap_surface: the surface has no faces; nothing to wrap");
    for (const Vec3& x : soup.points)
        if (!x.allFinite())
            throw InputError("wrap_surface: a node at " + format_point(x) +
                             " has a coordinate that is not a finite number; repair the file");
    if (!(p.alpha >= 0.0) || !std::isfinite(p.alpha))
        throw InputError("wrap_surface: WrapParams::alpha = " + format_number(p.alpha) +
                         ": give a size >= 0 (0: a hundredth of the model's diagonal)");
    if (!(p.offset >= 0.0) || !std::isfinite(p.offset))
        throw InputError("wrap_surface: WrapParams::offset = " + format_number(p.offset) +
                         ": give a distance >= 0 (0: alpha / 30)");
    check_threads(p.threads, "WrapParams::threads");
}

}  // namespace

SurfaceMesh wrap_surface(const SurfaceMesh& soup, const WrapParams& params, WrapReport* report) {
    check_wrap_input(soup, params);
    const auto start = std::chrono::steady_clock::now();
    Vec3 lo = soup.points.front(), hi = lo;
    for (const Vec3& x : soup.points) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
    const double alpha = params.alpha > 0.0 ? params.alpha : (hi - lo).norm() / 100.0;
    const double offset = params.offset > 0.0 ? params.offset : alpha / 30.0;

    std::vector<cgal::Point> points;
    points.reserve(soup.points.size());
    for (const Vec3& x : soup.points) points.push_back(cgal::point(x));
    std::vector<std::array<std::size_t, 3>> triangles;
    for (const SurfaceTriangle& t : surface_triangles(soup))
        triangles.push_back({static_cast<std::size_t>(t.v[0]), static_cast<std::size_t>(t.v[1]),
                             static_cast<std::size_t>(t.v[2])});
    cgal::TriangleMesh wrapped;
    CGAL::alpha_wrap_3(points, triangles, alpha, offset, wrapped);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (wrapped.number_of_faces() == 0)
        throw TopologyError("wrap_surface: CGAL's alpha wrap of the " + std::to_string(soup.num_faces()) +
                            " faces (alpha " + format_number(alpha) + ") is empty; give a smaller alpha");
    SurfaceMesh out;
    out.patches = soup.patches;
    std::vector<Index> node;
    cgal::append_triangles(wrapped, node, out, 0);  // each face's patch below

    // Each face's patch: the nearest input face's.
    const Soup in = soup_of(soup);
    Tree input(in.triangles.cbegin(), in.triangles.cend());
    input.build();
    input.accelerate_distance_queries();
    for (Index f = 0; f < out.num_faces(); ++f) {
        const auto hit = input.closest_point_and_primitive(cgal::point(face_centroid(out, out.points, f)));
        const Index from = in.face[static_cast<std::size_t>(hit.second - in.triangles.cbegin())];
        out.face_patch[static_cast<std::size_t>(f)] = soup.face_patch[static_cast<std::size_t>(from)];
    }
    if (report) {
        const Soup w = soup_of(out);
        Tree wrap_tree(w.triangles.cbegin(), w.triangles.cend());
        wrap_tree.build();
        wrap_tree.accelerate_distance_queries();
        WrapReport& r = *report;
        r = WrapReport{};
        r.alpha = alpha, r.offset = offset, r.seconds = seconds;
        r.input_faces = soup.num_faces(), r.faces = out.num_faces();
        std::tie(r.wrap_to_input, r.wrap_to_input_at) = farthest(samples(out), input, params.threads);
        std::tie(r.input_to_wrap, r.input_to_wrap_at) = farthest(samples(soup), wrap_tree, params.threads);
    }
    return out;
}

}  // namespace strata
