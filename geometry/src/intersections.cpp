// Self-intersections of a surface mesh: intersections.h.
//
// Broad phase: CGAL's box_self_intersection_d over the triangles' bounding boxes. Narrow
// phase, by the node ids two triangles share (the classification of CGAL's
// Polygon_mesh_processing::self_intersections, which needs a halfedge mesh; this works on
// our face arrays, non-manifold nodes included):
//   none   the triangles intersect at all (CGAL::do_intersect);
//   a node the edge opposite it in either triangle meets the other triangle (the common part
//          of two triangles is convex and contains the node, so any further point of it
//          lies on such an edge, or is reached along an edge through the shared node, which
//          then leaves the other triangle through its opposite edge);
//   an edge the two opposite corners lie on the same side of it in one plane (folded flat);
//   three  a repeated triangle.
// All predicates exact (Epick), so a touching pair counts and a gap of one ulp does not.

#include <strata/geometry/cgal_kernel.h>

#include <strata/core/format.h>
#include <strata/core/parallel.h>
#include <strata/geometry/intersections.h>

#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>

namespace strata {
namespace {

using cgal::point;
using cgal::Point;
using cgal::Segment;
using cgal::Triangle;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t>;

using Tri = SurfaceTriangle;

/// Below this many boxes the broad phase compares them all (CGAL's streaming cutoff, default
/// 10): on an 82k-triangle sphere 1000 takes 0.056 s where 10 took 0.124 s (100: 0.081, 4000:
/// 0.062), on 2 threads.
constexpr std::ptrdiff_t kBoxCutoff = 1000;

bool intersect(const Tri& s, const Tri& t, const std::vector<Point>& p) {
    std::array<int, 3> in_t{-1, -1, -1};  // for each corner of s, its position in t or -1
    int shared = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (s.v[i] == t.v[j]) in_t[i] = j, ++shared;
    const Triangle ts(p[s.v[0]], p[s.v[1]], p[s.v[2]]), tt(p[t.v[0]], p[t.v[1]], p[t.v[2]]);
    switch (shared) {
        case 0:
            return CGAL::do_intersect(ts, tt);
        case 1: {
            const int i =
                static_cast<int>(std::find_if(in_t.begin(), in_t.end(), [](int j) { return j >= 0; }) - in_t.begin());
            const int j = in_t[i];
            const Segment os(p[s.v[(i + 1) % 3]], p[s.v[(i + 2) % 3]]);
            const Segment ot(p[t.v[(j + 1) % 3]], p[t.v[(j + 2) % 3]]);
            return CGAL::do_intersect(os, tt) || CGAL::do_intersect(ot, ts);
        }
        case 2: {
            int r = 0;  // the corner of s not in t
            while (in_t[r] >= 0) ++r;
            int o = 0;  // the corner of t not in s
            while (t.v[o] == s.v[(r + 1) % 3] || t.v[o] == s.v[(r + 2) % 3]) ++o;
            const Point &a = p[s.v[(r + 1) % 3]], &b = p[s.v[(r + 2) % 3]];
            return CGAL::coplanar(a, b, p[s.v[r]], p[t.v[o]]) &&
                   CGAL::coplanar_orientation(a, b, p[s.v[r]], p[t.v[o]]) == CGAL::POSITIVE;
        }
        default:
            return true;  // the same three nodes
    }
}

}  // namespace

std::vector<FacePair> self_intersections(const SurfaceMesh& mesh, std::size_t max_pairs, int threads) {
    std::vector<Point> p;
    p.reserve(mesh.points.size());
    for (const Vec3& x : mesh.points) p.push_back(point(x));
    const std::vector<Tri> tris = surface_triangles(mesh);
    std::vector<Box> boxes;
    boxes.reserve(tris.size());
    for (std::size_t i = 0; i < tris.size(); ++i) {
        const auto& v = tris[i].v;
        boxes.emplace_back(p[v[0]].bbox() + p[v[1]].bbox() + p[v[2]].bbox(), i);
    }
    // Candidates from the broad phase, then the exact tests in parallel (each pair alone; the
    // result is sorted, so it does not depend on the thread count).
    std::vector<std::pair<std::size_t, std::size_t>> candidates;
    CGAL::box_self_intersection_d(
        boxes.begin(), boxes.end(),
        [&](const Box& x, const Box& y) {
            if (tris[x.info()].face != tris[y.info()].face) candidates.emplace_back(x.info(), y.info());
        },
        kBoxCutoff);
    std::vector<char> hit(candidates.size(), 0);
    const auto n = static_cast<std::ptrdiff_t>(candidates.size());
#pragma omp parallel for schedule(static) num_threads(thread_count(threads, n))
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        const auto& [a, b] = candidates[static_cast<std::size_t>(i)];
        hit[static_cast<std::size_t>(i)] = intersect(tris[a], tris[b], p) ? 1 : 0;
    }
    std::vector<FacePair> pairs;
    for (std::size_t i = 0; i < candidates.size(); ++i)
        if (hit[i]) {
            const Index fa = tris[candidates[i].first].face, fb = tris[candidates[i].second].face;
            pairs.push_back({std::min(fa, fb), std::max(fa, fb)});
        }
    std::sort(pairs.begin(), pairs.end(),
              [](const FacePair& x, const FacePair& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    if (max_pairs > 0 && pairs.size() > max_pairs) pairs.resize(max_pairs);
    return pairs;
}

std::vector<SurfaceTriangle> surface_triangles(const SurfaceMesh& mesh) {
    std::vector<SurfaceTriangle> tris;
    tris.reserve(static_cast<std::size_t>(mesh.num_faces()) * 2);
    for (Index f = 0; f < mesh.num_faces(); ++f) {
        const Index* v = mesh.face_begin(f);
        for (Index k = 1; k + 1 < mesh.face_size(f); ++k) {
            const SurfaceTriangle t{{v[0], v[k], v[k + 1]}, f};
            if (!CGAL::collinear(point(mesh.points[t.v[0]]), point(mesh.points[t.v[1]]), point(mesh.points[t.v[2]])))
                tris.push_back(t);
        }
    }
    return tris;
}

std::string describe_face(const SurfaceMesh& mesh, Index f) {
    std::string s = "face " + std::to_string(f);
    const Index patch = mesh.face_patch[f];
    if (patch >= 0 && patch < static_cast<Index>(mesh.patches.size()))
        s += " (patch '" + mesh.patches[static_cast<std::size_t>(patch)].name + "')";
    Vec3 c = Vec3::Zero();
    for (const Index* v = mesh.face_begin(f); v != mesh.face_end(f); ++v) c += mesh.points[*v];
    return s + " at " + format_point(c / static_cast<double>(mesh.face_size(f)));
}

std::string describe_pair(const SurfaceMesh& mesh, const FacePair& pair) {
    return describe_face(mesh, pair.a) + " meets " + describe_face(mesh, pair.b);
}

}  // namespace strata
