// The size field of the tetrahedral fill and the switches that hand it to TetGen.
//
// Sizing (params.growth > 0). TetFillParams::growth documents the field
//     h(x) = min(h_wall + growth · d(x), h_far),
// d the distance to the non-farfield ("wall", the layer top) part of the boundary. Here:
//   * h_wall is the mean length of the boundary edges at the nearest wall node, d the
//     distance to that node (the nearest node instead of the nearest triangle: off by less
//     than one wall edge, i.e. by growth × edge ≪ edge in h);
//   * h_far is the mean edge length of the farfield triangles (no farfield patch: no cap
//     beyond the bounding-box diagonal), lowered to the edge of the regular tet of volume
//     max_volume if that is set (TetGen's -m sizes also act as spacings: a point closer to a
//     vertex than the vertex's size is rejected, which would otherwise keep -a from being
//     met); boundary nodes keep their own mean edge length, capped the same way;
//   * TetGen's -m size is a bound on the circumradius of the tets at a vertex (checktet4split
//     splits a tet whose circumradius exceeds the size at one of its corners), so the size
//     given is kRadiusPerEdge × h.
// Sizes given only at the boundary points would be interpolated linearly by TetGen across
// the first, huge tets between body and farfield, i.e. the growth rate would be whatever the
// distance to the farfield makes it, not params.growth. So h is sampled on a background mesh
// (TetGen's bgmesh, tetrahedralize's last argument): a quality-only refinement (q2, no size)
// of the same PLC, whose node density already follows the local feature size (fine at the
// wall, coarse far out), which resolves the piecewise-linear h well and costs a fraction of
// the final run. h is evaluated at its nodes, TetGen interpolates linearly inside its tets.
//
// kRadiusPerEdge = 0.75 is calibrated: under the bound r, TetGen's q1.5 tets have a mean edge
// of about 1.33 r (1.63 r for a regular tet), so 0.75 h gives a mean edge within ~5% of h up
// to the farfield's influence (checked with growth 0.1-0.3 on the cube in a box of
// tests/hybrid/test_tetgen_fill.cpp).
//
// Nearest wall node: nanoflann's k-d tree (Debian's libnanoflann-dev, header-only), with the
// distance computed as Eigen's squaredNorm of the difference. Of equally near nodes (exact
// ties are common on symmetric inputs: 38 of the sphere case's queries) the one of the
// smallest size counts, then the lowest-numbered: h is a function of the geometry, never of
// the tree's layout. (The hand-written tree this replaced took whichever tie its traversal
// met first.)

#include "tetgen_sizing.h"

#include <strata/core/face_geometry.h>
#include <strata/core/format.h>
#include <strata/geometry/kd_cloud.h>

#include <nanoflann.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <vector>

namespace strata::tetgen {
namespace {

/// nanoflann result set keeping the nearest point; of equally near ones the one of the
/// smallest \p size, then the lowest index. worstDist is just above the best distance so that
/// equally near points are still offered.
class NearestSmallest {
public:
    explicit NearestSmallest(const std::vector<double>& size) : size_(size) {}
    bool full() const { return true; }
    bool addPoint(double d2, std::size_t i) {
        const bool tie = d2 == best_ && index_ < size_.size();
        const bool better =
            d2 < best_ || (tie && (size_[i] < size_[index_] || (size_[i] == size_[index_] && i < index_)));
        if (better) best_ = d2, index_ = i;
        return true;
    }
    double worstDist() const { return std::nextafter(best_, std::numeric_limits<double>::infinity()); }
    std::size_t index() const { return index_; }

private:
    const std::vector<double>& size_;
    double best_ = std::numeric_limits<double>::infinity();
    std::size_t index_ = std::numeric_limits<std::size_t>::max();
};

}  // namespace

struct SizeField::Tree {
    using KdTree = nanoflann::KDTreeSingleIndexAdaptor<KdSquaredDistance<Vec3>, KdCloud<Vec3>, 3, std::size_t>;
    KdCloud<Vec3> cloud;
    const std::vector<double>& size;
    KdTree index;
    Tree(const std::vector<Vec3>& points, const std::vector<double>& sizes)
        : cloud{points}, size(sizes), index(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {
        index.buildIndex();
    }
    std::size_t nearest(const Vec3& x) const {
        NearestSmallest result(size);
        const double q[3] = {x[0], x[1], x[2]};
        index.findNeighbors(result, q, nanoflann::SearchParams());
        return result.index();
    }
};

std::string switches(const TetFillParams& p, bool sizing, bool background, double tolerance) {
    // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
    std::string s = "pYzQ";
    if (tolerance > 0.0) {
        s += 'T';
        s += format_number(tolerance, 3);
    }
    if (background) {
        s += 'c';  // keep the convex hull: every walk towards a point stays inside the mesh
        s += 'q';
        s += format_number(kBackgroundRatio, 17);
        return s;
    }
    if (!p.refine) return s;
    s += 'q';
    s += format_number(p.radius_edge, 17);
    if (p.min_dihedral > 0.0) {
        s += '/';
        s += format_number(p.min_dihedral, 17);
    }
    if (p.max_volume > 0.0) {
        s += 'a';
        s += format_number(p.max_volume, 17);
    }
    if (sizing) s += 'm';
    if (p.max_dihedral > 0.0) {
        s += "o/";
        s += format_number(p.max_dihedral, 17);
    }
    return s;
}

double tolerance_keeping_points(const std::vector<Vec3>& points) {
    if (points.size() < 2) return 0.0;
    const BoundingBox box = bounding_box(points);
    const double diagonal = (box.max - box.min).norm();
    const double near = 10.0 * kTetGenEpsilon * diagonal;
    // Closest pair below `near`: sweep along x, each point against those within `near` after it.
    std::vector<Index> order(points.size());
    std::iota(order.begin(), order.end(), Index{0});
    std::sort(order.begin(), order.end(), [&](Index a, Index b) {
        return points[static_cast<std::size_t>(a)].x() < points[static_cast<std::size_t>(b)].x() ||
               (points[static_cast<std::size_t>(a)].x() == points[static_cast<std::size_t>(b)].x() && a < b);
    });
    double closest = near;
    for (std::size_t i = 0; i < order.size(); ++i) {
        const Vec3& p = points[static_cast<std::size_t>(order[i])];
        for (std::size_t j = i + 1; j < order.size(); ++j) {
            const Vec3& q = points[static_cast<std::size_t>(order[j])];
            if (q.x() - p.x() >= closest) break;
            const double d = (q - p).norm();
            if (d > 0.0) closest = std::min(closest, d);  // equal points are the caller's error
        }
    }
    return closest < near ? 0.01 * closest / diagonal : 0.0;
}

// ---------------------------------------------------------------------------------------

SizeField::SizeField(const SurfaceMesh& b, double growth, double max_volume)
    : growth_(growth), volume_edge_(std::numeric_limits<double>::infinity()) {
    // Mean incident edge length per node (interior edges counted from both faces, which
    // leaves the mean unchanged on a closed surface).
    node_size_.assign(b.points.size(), 0.0);
    std::vector<int> count(b.points.size(), 0);
    std::vector<char> wall(b.points.size(), 0);
    double far_sum = 0.0;
    long far_edges = 0;
    for (Index f = 0; f < b.num_faces(); ++f) {
        const bool is_far = b.patches[b.face_patch[f]].kind == PatchKind::Farfield;
        for (int i = 0; i < 3; ++i) {
            const Index u = b.face_node(f, i), v = b.face_node(f, (i + 1) % 3);
            const double l = (b.points[u] - b.points[v]).norm();
            node_size_[u] += l, node_size_[v] += l;
            ++count[u], ++count[v];
            if (is_far) far_sum += l, ++far_edges;
            if (!is_far) wall[u] = wall[v] = 1;
        }
    }
    for (std::size_t i = 0; i < node_size_.size(); ++i)
        if (count[i] > 0) node_size_[i] /= count[i];
    cap_ = far_edges > 0 ? far_sum / static_cast<double>(far_edges) : bounding_box(b.points).diagonal();
    if (max_volume > 0.0) volume_edge_ = std::cbrt(6.0 * std::sqrt(2.0) * max_volume);
    cap_ = std::min(cap_, volume_edge_);
    for (std::size_t i = 0; i < b.points.size(); ++i)
        if (wall[i]) wall_points_.push_back(b.points[i]), wall_size_.push_back(node_size_[i]);
    if (!wall_points_.empty()) tree_ = std::make_unique<Tree>(wall_points_, wall_size_);
}

SizeField::SizeField(std::vector<Vec3> points, std::vector<double> sizes, double growth)
    : growth_(growth),
      cap_(std::numeric_limits<double>::infinity()),
      volume_edge_(std::numeric_limits<double>::infinity()),
      node_size_(sizes),
      wall_points_(std::move(points)),
      wall_size_(std::move(sizes)) {
    if (!wall_points_.empty()) tree_ = std::make_unique<Tree>(wall_points_, wall_size_);
}

SizeField::~SizeField() = default;

double SizeField::boundary_size(Index i) const {
    return std::min(node_size_[i], volume_edge_);
}

double SizeField::operator()(const Vec3& x) const {
    if (!tree_) return cap_;
    const std::size_t w = tree_->nearest(x);
    return std::min(wall_size_[w] + growth_ * (x - wall_points_[w]).norm(), cap_);
}

void set_sizes(tetgenio& io, Index num_boundary, const SizeField& h) {
    delete[] io.pointmtrlist;
    io.pointmtrlist = new REAL[static_cast<std::size_t>(io.numberofpoints)];
    io.numberofpointmtrs = 1;
    for (int i = 0; i < io.numberofpoints; ++i) {
        const Vec3 x(io.pointlist[3 * i], io.pointlist[3 * i + 1], io.pointlist[3 * i + 2]);
        const double edge = i < num_boundary ? h.boundary_size(i) : h(x);
        io.pointmtrlist[i] = kRadiusPerEdge * edge;
    }
}

// TetGen locates every point of the final mesh in the background mesh by walking, and a walk
// that leaves the mesh falls back to a search of every tet (TetGen 1.5's scoutpoint: a sweep
// of the whole background mesh per point inserted). The background mesh is therefore the whole
// convex hull (switch c, no holes: the cavities are meshed too), and that hull lies just
// outside every point of the final mesh: a separate farfield is pushed out by 1 %; where there
// is none (internal flow: the walls are the outer boundary) or it shares points with another
// patch (a symmetry plane, a wall ending on it), the 8 corners of a box 5 % larger than the
// boundary's bounding box are added as loose points, so the hull is that box (as faces, which
// TetGen's refinement has to keep, they made the background mesh take minutes). Without them
// walks towards points near the walls left the hull and swept the mesh: the sphere over a
// floor (internal, 40 layers, 1.1 M tetrahedra) spent 498 s in TetGen instead of 41.
SurfaceMesh background_boundary(const SurfaceMesh& b) {
    std::vector<char> far(static_cast<std::size_t>(b.num_points()), 0), other(far.size(), 0);
    for (Index f = 0; f < b.num_faces(); ++f) {
        const bool ff = b.patches[static_cast<std::size_t>(b.face_patch[f])].kind == PatchKind::Farfield;
        for (const Index* v = b.face_begin(f); v != b.face_end(f); ++v)
            (ff ? far : other)[static_cast<std::size_t>(*v)] = 1;
    }
    Vec3 c = Vec3::Zero();
    Index n = 0;
    bool shared = false;
    for (Index i = 0; i < b.num_points() && !shared; ++i) {
        shared = far[static_cast<std::size_t>(i)] && other[static_cast<std::size_t>(i)];
        if (far[static_cast<std::size_t>(i)]) c += b.points[i], ++n;
    }
    SurfaceMesh out = b;
    if (n > 0 && !shared) {
        c /= static_cast<double>(n);
        for (Index i = 0; i < b.num_points(); ++i)
            if (far[static_cast<std::size_t>(i)]) out.points[i] = c + 1.01 * (b.points[i] - c);
        return out;
    }
    const BoundingBox box = bounding_box(b.points);
    const Vec3 margin = Vec3::Constant(0.05 * box.diagonal());
    const Vec3 lo = box.min - margin, hi = box.max + margin;
    for (int k = 0; k < 8; ++k)
        out.points.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
    return out;
}

}  // namespace strata::tetgen
