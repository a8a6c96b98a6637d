#include <strata/core/enum_names.h>
#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/format.h>
#include <strata/geometry/primitives.h>
#include <strata/geometry/topology.h>
#include <strata/hybrid/farfield.h>
#include <strata/hybrid/plane_mesh.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <string>

namespace strata {

constexpr EnumNames<FarfieldShape, 2> kShapeNames{{"box", "sphere"}};
std::string_view to_string(FarfieldShape shape) {
    return kShapeNames.name(shape);
}

FarfieldShape parse_farfield_shape(std::string_view text) {
    return kShapeNames.parse(text, "FarfieldParams::shape");
}

namespace {

/// Box c + h [−1, 1]³ in the right-handed frame \p e, each side an n × n grid of squares
/// split into triangles, outward. \p half: only its part with e[2] coordinate ≥ 0 (n even),
/// open on the plane through c normal to e[2].
SurfaceMesh box(const Vec3& c, const std::array<Vec3, 3>& e, double h, int n, bool half) {
    SurfaceMesh m;
    m.patches.push_back({"farfield", PatchKind::Farfield});
    std::map<std::array<int, 3>, Index> ids;  // lattice coordinates → node (shared edges)
    auto node = [&](int i, int j, int k) {
        const std::array<int, 3> key{i, j, k};
        auto it = ids.find(key);
        if (it != ids.end()) return it->second;
        const Index id = m.num_points();
        m.points.push_back(c +
                           h * ((2.0 * i / n - 1.0) * e[0] + (2.0 * j / n - 1.0) * e[1] + (2.0 * k / n - 1.0) * e[2]));
        ids.emplace(key, id);
        return id;
    };
    const auto lo = [&](int axis) { return half && axis == 2 ? n / 2 : 0; };  // first lattice index per axis
    // For each axis and side, (u, v) span the face so that u × v points outward.
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            if (half && axis == 2 && side == 0) continue;  // the open side, on the plane
            const int a = (axis + 1) % 3, b = (axis + 2) % 3;
            for (int i = lo(a); i < n; ++i)
                for (int j = lo(b); j < n; ++j) {
                    auto at = [&](int u, int v) {
                        std::array<int, 3> p{};
                        p[axis] = side * n;
                        p[a] = u;
                        p[b] = v;
                        return node(p[0], p[1], p[2]);
                    };
                    Index q[4] = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
                    if (side == 0) std::swap(q[1], q[3]);  // e_a × e_b = +e_axis: reverse on the low side
                    // Alternate the diagonal for a symmetric triangulation.
                    if ((i + j) % 2 == 0) {
                        m.add_face({q[0], q[1], q[2]}, 0);
                        m.add_face({q[0], q[2], q[3]}, 0);
                    } else {
                        m.add_face({q[0], q[1], q[3]}, 0);
                        m.add_face({q[1], q[2], q[3]}, 0);
                    }
                }
        }
    return m;
}

/// Icosphere of radius r around c, subdivided until edges are about 2r/n (the icosahedron's
/// edge is about 1.05 r, each level halves it).
SurfaceMesh sphere(const Vec3& c, double r, int n) {
    int levels = 0;
    for (double edge = 1.05; edge > 2.0 / n; edge *= 0.5) ++levels;
    return icosphere(c, r, levels, {"farfield", PatchKind::Farfield});
}

}  // namespace

namespace {

void check_params(const FarfieldParams& params) {
    if (!(params.size > 1.0))
        throw InputError(
            "FarfieldParams::size = " + format_number(params.size) +
            ": the farfield must be larger than the body (a multiple of its size > 1, typically 10 to 50)");
    if (params.divisions < 2)
        throw InputError("FarfieldParams::divisions = " + std::to_string(params.divisions) + ": need at least 2");
}

}  // namespace

SurfaceMesh make_farfield(const std::vector<Vec3>& body_points, const FarfieldParams& params) {
    check_params(params);
    const BoundingBox bb = bounding_box(body_points);
    const Vec3 c = 0.5 * (bb.min + bb.max);
    const double half = 0.5 * params.size * bb.diagonal();
    return params.shape == FarfieldShape::Box
               ? box(c, {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()}, half, params.divisions, false)
               : sphere(c, half, params.divisions);
}

SurfaceMesh make_half_farfield(const std::vector<Vec3>& body_points, const Vec3& plane_point, const Vec3& plane_normal,
                               const FarfieldParams& params) {
    check_params(params);
    const Vec3 w = plane_normal.normalized();
    const Vec3 u = (std::abs(w.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(w).normalized();
    const Vec3 v = w.cross(u);
    // The body and its mirror image: their bounding box in the frame (u, v, w), centred on the plane.
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec3& p : body_points) {
        const Vec3 d = p - plane_point;
        const Vec3 q(d.dot(u), d.dot(v), std::abs(d.dot(w)));
        lo = lo.cwiseMin(q);
        hi = hi.cwiseMax(q);
    }
    const double du = hi.x() - lo.x(), dv = hi.y() - lo.y(), dw = 2.0 * hi.z();
    const double half = 0.5 * params.size * std::sqrt(du * du + dv * dv + dw * dw);
    const Vec3 c = plane_point + 0.5 * (lo.x() + hi.x()) * u + 0.5 * (lo.y() + hi.y()) * v;
    const int n = params.divisions + params.divisions % 2;
    SurfaceMesh m = box(c, {u, v, w}, half, n, true);
    if (params.shape == FarfieldShape::Sphere)  // the half cube projected onto the hemisphere
        for (Vec3& p : m.points) p = c + half * (p - c).normalized();
    return m;
}

namespace {

/// The open boundary loops of \p walls for a message: how many, and the largest three by their
/// edges, each with the centre of its nodes ("2 open boundary loops: 3 edges around (x, y, z),
/// ...").
std::string describe_loops(const SurfaceMesh& walls, const Csr& open) {
    std::vector<Index> order(static_cast<std::size_t>(open.rows()));
    for (Index l = 0; l < open.rows(); ++l) order[static_cast<std::size_t>(l)] = l;
    std::stable_sort(order.begin(), order.end(), [&](Index a, Index b) { return open.row_size(a) > open.row_size(b); });
    std::string s = std::to_string(open.rows()) + " open boundary loop" + (open.rows() == 1 ? "" : "s") + ": ";
    for (std::size_t k = 0; k < order.size() && k < 3; ++k) {
        const Index l = order[k];
        Vec3 c = Vec3::Zero();
        for (const Index* v = open.row_begin(l); v != open.row_end(l); ++v)
            c += walls.points[static_cast<std::size_t>(*v)];
        c /= static_cast<double>(open.row_size(l));
        s += (k ? ", " : "") + std::to_string(open.row_size(l)) + " edges around " + format_point(c);
    }
    if (order.size() > 3) s += ", ...";
    // A crack: two open edges' nodes nearly meet (an export whose faces miss each other by a
    // tolerance). Not for long loops (a half model's cut): the search is quadratic.
    // Nodes next to each other along a loop are an open edge apart, not a crack: skipped.
    struct At {
        Index node, loop, pos;
    };
    std::vector<At> nodes;
    for (Index l = 0; l < open.rows(); ++l)
        for (Index p = 0; p < open.row_size(l); ++p) nodes.push_back({open.row_begin(l)[p], l, p});
    const double diag = bounding_box(walls.points).diagonal();
    double gap = std::numeric_limits<double>::infinity();
    Vec3 where = Vec3::Zero();
    if (nodes.size() <= 5000)
        for (std::size_t i = 0; i < nodes.size(); ++i)
            for (std::size_t j = i + 1; j < nodes.size(); ++j) {
                const At &x = nodes[i], &y = nodes[j];
                if (x.node == y.node) continue;
                if (x.loop == y.loop) {
                    const Index apart = std::abs(x.pos - y.pos), size = open.row_size(x.loop);
                    if (apart <= 1 || apart == size - 1) continue;
                }
                const Vec3 &a = walls.points[static_cast<std::size_t>(x.node)],
                           &b = walls.points[static_cast<std::size_t>(y.node)];
                const double d = (a - b).norm();
                if (d < gap) gap = d, where = 0.5 * (a + b);
            }
    if (gap < 1e-4 * diag)
        s += "; two of their nodes are " + format_number(gap, 3) + " apart at " + format_point(where) +
             ", a crack: PrepareParams::merge_tolerance " + format_number(std::min(1e-3, 2.0 * gap / diag), 2) +
             " (a share of the model's size) welds nodes that close";
    return s;
}

/// The --fill-holes that would close the loops that are holes: the largest loop's edges, or the
/// second largest's where the largest lies in one plane (a half model's cut, with holes too).
std::string fill_hint(const SurfaceMesh& walls, const Csr& open) {
    std::vector<Index> sizes;
    Index largest = 0;
    for (Index l = 0; l < open.rows(); ++l) {
        sizes.push_back(open.row_size(l));
        if (open.row_size(l) > open.row_size(largest)) largest = l;
    }
    if (sizes.empty()) return "";
    std::sort(sizes.rbegin(), sizes.rend());
    Index k = sizes[0];
    if (sizes.size() > 1) {
        std::vector<Vec3> cut;
        for (const Index* v = open.row_begin(largest); v != open.row_end(largest); ++v)
            cut.push_back(walls.points[static_cast<std::size_t>(*v)]);
        if (fit_plane(cut).deviation <= 1e-6 * bounding_box(walls.points).diagonal()) k = sizes[1];
    }
    return "; if they are holes (faces missing from the file), PrepareParams::fill_holes " + std::to_string(k) +
           " closes every open loop of up to " + std::to_string(k) + " edges";
}

}  // namespace

SurfaceMesh close_half_model(const SurfaceMesh& walls, const FarfieldParams& params) {
    const Csr open = boundary_loops(walls);
    std::vector<Vec3> on_plane;
    for (Index v : open.values) on_plane.push_back(walls.points[v]);
    const PatchPlane pl = fit_plane(on_plane);
    const double diag = bounding_box(walls.points).diagonal();
    if (open.rows() == 0 || !(pl.deviation <= 1e-6 * diag))
        throw InputError(
            "the surface is open (" + describe_loops(walls, open) + "), but its open edges do not lie in one plane " +
            "(they are " + format_number(pl.deviation) + " off their best plane, the body's size is " +
            format_number(diag) +
            "): only a half model cut by one symmetry plane is closed automatically; close the holes in the CAD tool "
            "(or the fluid domain yourself: walls plus symmetry and farfield patches) or mesh the full body" +
            fill_hint(walls, open));
    // The plane's normal towards the body.
    double below = 0.0, above = 0.0;
    for (const Vec3& p : walls.points) {
        const double w = (p - pl.point).dot(pl.normal);
        below = std::min(below, w);
        above = std::max(above, w);
    }
    const Vec3 n = above >= -below ? pl.normal : Vec3(-pl.normal);
    // A symmetric body meets its symmetry plane square (its faces along the cut stand across the
    // plane); the faces round a missing face of a convex body lie along the hole's plane, and
    // every node of the body lies on one side of it, as for a half model. So: the faces on the
    // open edges, weighted by the edges' lengths, must stand at more than 60 degrees to the plane
    // on average (|cos| under 0.5).
    // Nor does any of those faces lie in the plane: the symmetry plane would cover it (a
    // cube's corner triangle missing from its top: two of the hole's edges are the cube's,
    // square to the top, but the third borders the top's other triangle).
    double along = 0.0, length = 0.0;
    bool in_plane = false;
    {
        const EdgeTable et = edge_table(walls);
        for (std::size_t e = 0; e < et.nodes.size(); ++e) {
            if (et.faces.row_size(static_cast<Index>(e)) != 1) continue;
            const double l = (walls.points[static_cast<std::size_t>(et.nodes[e][0])] -
                              walls.points[static_cast<std::size_t>(et.nodes[e][1])])
                                 .norm();
            const Index f = et.faces.row_begin(static_cast<Index>(e))[0];
            const Vec3 a = face_area_vector(walls, f);
            if (!(a.norm() > 0.0)) continue;
            along += l * std::abs(a.normalized().dot(pl.normal));
            length += l;
            bool on = true;
            for (Index c = 0; c < walls.face_size(f); ++c)
                on = on &&
                     std::abs(
                         (walls.points[static_cast<std::size_t>(walls.face_node(f, c))] - pl.point).dot(pl.normal)) <=
                         1e-6 * diag;
            in_plane = in_plane || on;
        }
    }
    if (std::min(above, -below) > 1e-6 * diag || (length > 0.0 && along / length > 0.5) || in_plane)
        throw InputError(
            "the surface is open (" + describe_loops(walls, open) + ") and its open edges lie in one plane, but " +
            (std::min(above, -below) > 1e-6 * diag
                 ? "the body lies on both sides of it (" + format_number(std::max(above, -below)) + " and " +
                       format_number(std::min(above, -below)) + " away)"
             : in_plane ? std::string("a face along them lies in it (a body cut by its symmetry plane has no "
                                      "face in the plane)")
                        : "the faces along them lie along it (at " +
                              format_number(std::acos(std::min(1.0, along / length)) * 180.0 / 3.141592653589793, 2) +
                              " degrees on average; a body cut by its symmetry plane meets it square)") +
            ", so it is not a half model cut by a symmetry plane: a hole or a crack in the surface "
            "(a missing face, or faces whose nodes do not meet); close it in the CAD tool or export it "
            "again" +
            fill_hint(walls, open));

    SurfaceMesh dom;
    dom.patches = walls.patches;
    const Index sym = static_cast<Index>(dom.patches.size()), far = sym + 1;
    dom.patches.push_back({"symmetry", PatchKind::Symmetry});
    dom.patches.push_back({"farfield", PatchKind::Farfield});
    dom.points = walls.points;
    for (Index f = 0; f < walls.num_faces(); ++f)
        dom.add_face(walls.face_begin(f), walls.face_size(f), walls.face_patch[f]);
    const SurfaceMesh ff = make_half_farfield(walls.points, pl.point, n, params);
    const Index base = dom.num_points();
    dom.points.insert(dom.points.end(), ff.points.begin(), ff.points.end());
    for (Index f = 0; f < ff.num_faces(); ++f)  // outward → into the fluid
        dom.add_face({base + ff.face_node(f, 0), base + ff.face_node(f, 2), base + ff.face_node(f, 1)}, far);

    // The symmetry plane: inside the farfield's open edge, outside the walls' open edges.
    std::vector<std::vector<Index>> loops;
    auto add_loop = [&](const Index* b, const Index* e, Index offset, bool outer) {
        std::vector<Index> loop;
        for (const Index* v = b; v != e; ++v) loop.push_back(offset + *v);
        const Vec3 c = dom.points[loop[0]];
        Vec3 area = Vec3::Zero();
        for (std::size_t i = 0; i < loop.size(); ++i)
            area += (dom.points[loop[i]] - c).cross(dom.points[loop[(i + 1) % loop.size()]] - c);
        if ((area.dot(n) > 0.0) != outer) std::reverse(loop.begin(), loop.end());
        loops.push_back(std::move(loop));
    };
    const Csr ff_open = boundary_loops(ff);
    for (Index l = 0; l < ff_open.rows(); ++l) add_loop(ff_open.row_begin(l), ff_open.row_end(l), base, true);
    for (Index l = 0; l < open.rows(); ++l) add_loop(open.row_begin(l), open.row_end(l), 0, false);
    const PlaneMesh pm =
        mesh_plane_region(dom.points, loops, pl.point, n, "meshing the symmetry plane of the half model");
    dom.points.insert(dom.points.end(), pm.new_points.begin(), pm.new_points.end());
    for (const auto& t : pm.triangles) dom.add_face({t[0], t[1], t[2]}, sym);
    if (boundary_loops(dom).rows() != 0)
        throw TopologyError(
            "closing the half model: the symmetry plane does not join the walls and the farfield edge to edge");
    return dom;
}

}  // namespace strata
