// Poisson marching extrusion (Thompson, Chalasani & Soni), as ALGORITHM.md restates it.
// Per layer: a three-level locally orthogonal reference mesh (Eqs. 11–12), point-Jacobi
// smoothing of the middle level with the Poisson equation (Eq. 3) in Knupp's local logical
// space, level 2 regenerated after every sweep; then the middle level becomes the next wall.

#include <strata/core/cell_quality.h>
#include <strata/core/enum_names.h>
#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/face_match.h>
#include <strata/core/format.h>
#include <strata/core/parallel.h>
#include <strata/core/solver_checks.h>
#include <strata/geometry/check.h>
#include <strata/geometry/normals.h>
#include <strata/geometry/topology.h>
#include <strata/module/layers.h>
#include <strata/module/proximity.h>
#include <strata/module/stencil.h>

#include "columns.h"
#include "fans.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <memory>
#include <cmath>
#include <numbers>
#include <numeric>
#include <optional>
#include <string>

namespace strata {
namespace {

/// The extruded part of the input: faces on Wall patches, nodes renumbered compactly.
struct Wall {
    SurfaceMesh mesh;
    std::vector<Index> input_node;  ///< wall node → input node
    std::vector<Index> input_face;  ///< wall face → input face
    Csr loops;                      ///< boundary loops of the wall (its open edges)
};

}  // namespace

void require_wall_faces(const SurfaceMesh& surface) {
    for (const Index p : surface.face_patch)
        if (surface.patches[static_cast<std::size_t>(p)].kind == PatchKind::Wall) return;
    throw InputError(
        "no wall faces to extrude: every patch is symmetry, farfield or other; mark the body as a wall "
        "(PrepareParams::patch_kinds NAME=wall)");
}

namespace {

Wall extract_wall(const SurfaceMesh& in) {
    Wall w;
    w.mesh.patches = in.patches;
    auto is_wall = [&](Index f) {
        return in.patches[static_cast<std::size_t>(in.face_patch[f])].kind == PatchKind::Wall;
    };
    // Wall nodes keep the input's order (identity when every face is a wall).
    std::vector<Index> map(static_cast<std::size_t>(in.num_points()), kNone);
    for (Index f = 0; f < in.num_faces(); ++f)
        if (is_wall(f))
            for (const Index* v = in.face_begin(f); v != in.face_end(f); ++v) map[static_cast<std::size_t>(*v)] = 0;
    for (Index i = 0; i < in.num_points(); ++i)
        if (map[static_cast<std::size_t>(i)] == 0) {
            map[static_cast<std::size_t>(i)] = static_cast<Index>(w.input_node.size());
            w.input_node.push_back(i);
            w.mesh.points.push_back(in.points[i]);
        }
    for (Index f = 0; f < in.num_faces(); ++f) {
        if (!is_wall(f)) continue;
        Index v[4];
        const Index n = in.face_size(f);
        for (Index i = 0; i < n; ++i) v[i] = map[static_cast<std::size_t>(in.face_node(f, i))];
        w.mesh.add_face(v, n, in.face_patch[f]);
        w.input_face.push_back(f);
    }
    if (w.mesh.num_faces() == 0) require_wall_faces(in);
    w.loops = boundary_loops(w.mesh);
    return w;
}

/// Planes the nodes of the wall's open boundaries stay in (and across which their rings are
/// mirrored). A boundary loop lying in one plane that the wall crosses (the wall's normals
/// lie in it, as on a symmetry or outflow plane) gives that plane to all its nodes. Otherwise
/// each node gets the local plane spanned by the loop's tangent and the wall normal, so open
/// edges still slide consistently; nodes where the loop turns sharply (corners) get none and
/// are extruded along their normal.
/// Nodes already constrained by patch_constraints (\p fixed) keep their constraint.
void boundary_planes(const SurfaceMesh& wall, const Csr& loops, const std::vector<Vec3>& normals,
                     const std::vector<char>& fixed, std::vector<MirrorPlane>& planes, std::vector<Index>& node_plane) {
    const double diag = bounding_box(wall.points).diagonal();
    for (Index l = 0; l < loops.rows(); ++l) {
        const Index* lv = loops.row_begin(l);
        const Index m = loops.row_size(l);
        const bool any_fixed =
            std::any_of(lv, lv + m, [&](Index v) { return fixed[static_cast<std::size_t>(v)] != 0; });
        Vec3 c = Vec3::Zero();
        for (Index i = 0; i < m; ++i) c += wall.points[lv[i]];
        c /= static_cast<double>(m);
        Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
        for (Index i = 0; i < m; ++i) {
            const Vec3 d = wall.points[lv[i]] - c;
            cov += d * d.transpose();
        }
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
        const Vec3 normal = es.eigenvectors().col(0).normalized();
        double dev = 0.0, cross = 0.0;
        for (Index i = 0; i < m; ++i) {
            dev = std::max(dev, std::abs((wall.points[lv[i]] - c).dot(normal)));
            cross = std::max(cross, std::abs(normals[lv[i]].dot(normal)));
        }
        if (!any_fixed && m >= 3 && dev <= 1e-6 * diag && cross < 0.5) {
            for (Index i = 0; i < m; ++i)
                node_plane[static_cast<std::size_t>(lv[i])] = static_cast<Index>(planes.size());
            planes.push_back({c, normal});
            continue;
        }
        for (Index i = 0; i < m; ++i) {
            if (fixed[static_cast<std::size_t>(lv[i])]) continue;
            const Vec3& p = wall.points[lv[i]];
            const Vec3 d0 = p - wall.points[lv[(i + m - 1) % m]], d1 = wall.points[lv[(i + 1) % m]] - p;
            if (d0 == Vec3::Zero() || d1 == Vec3::Zero()) continue;  // a fan's column
            const Vec3 t0 = d0.normalized(), t1 = d1.normalized();
            if (t0.dot(t1) < std::cos(30.0 * std::numbers::pi / 180.0)) continue;  // a corner of the loop
            const Vec3 pn = (t0 + t1).cross(normals[lv[i]]);
            if (pn.norm() < 1e-12) continue;
            node_plane[static_cast<std::size_t>(lv[i])] = static_cast<Index>(planes.size());
            planes.push_back({p, pn.normalized()});
        }
    }
}

/// Open-boundary nodes of the wall that lie on planar non-wall patches of the input (a
/// symmetry or outflow plane, the side of a box): on one such patch the node marches in its
/// plane (the mirror plane of its ring), on two it marches along their line of intersection
/// (\p node_line, unit, pointing into the flow) without smoothing, so the layers' side faces
/// lie exactly in the planes and the planes can be re-meshed around them. Marks the nodes it
/// constrains in \p fixed, and in \p one_patch (if given) those on a single non-wall patch.
void patch_constraints(const SurfaceMesh& surface, const Wall& w, const Csr& loops, const std::vector<Vec3>& normals,
                       std::vector<MirrorPlane>& planes, std::vector<Index>& node_plane, std::vector<Vec3>& node_line,
                       std::vector<char>& fixed, std::vector<char>* one_patch = nullptr) {
    const Csr in_vf = vertex_faces(surface);
    std::vector<Index> plane_of_patch(surface.patches.size(), -2);  // -2: not fitted yet
    auto plane_of = [&](Index patch) {
        Index& p = plane_of_patch[static_cast<std::size_t>(patch)];
        if (p == -2) {
            const PatchPlane pp = patch_plane(surface, patch);
            p = kNone;
            if (pp.planar()) {
                p = static_cast<Index>(planes.size());
                planes.push_back({pp.point, pp.normal});
            }
        }
        return p;
    };
    for (Index l = 0; l < loops.rows(); ++l)
        for (const Index* v = loops.row_begin(l); v != loops.row_end(l); ++v) {
            const Index in = w.input_node[static_cast<std::size_t>(*v)];
            std::vector<Index> on;  // planes of the non-wall patches at the node
            Index first_patch = kNone;
            bool one = true;
            for (const Index* f = in_vf.row_begin(in); f != in_vf.row_end(in); ++f) {
                const Index patch = surface.face_patch[*f];
                if (surface.patches[static_cast<std::size_t>(patch)].kind == PatchKind::Wall) continue;
                one &= first_patch == kNone || first_patch == patch;
                first_patch = patch;
                const Index p = plane_of(patch);
                if (p == kNone || std::find(on.begin(), on.end(), p) != on.end()) continue;
                // Planes within ~6° of one another hold the node as one plane.
                if (std::any_of(on.begin(), on.end(),
                                [&](Index q) { return planes[q].normal.cross(planes[p].normal).norm() < 0.1; }))
                    continue;
                on.push_back(p);
            }
            if (on.empty()) continue;
            fixed[static_cast<std::size_t>(*v)] = 1;
            if (one_patch) (*one_patch)[static_cast<std::size_t>(*v)] = one;
            if (on.size() == 1) {
                node_plane[static_cast<std::size_t>(*v)] = on[0];
                continue;
            }
            Vec3 d = planes[on[0]].normal.cross(planes[on[1]].normal).normalized();
            if (d.dot(normals[*v]) < 0.0) d = -d;
            node_line[static_cast<std::size_t>(*v)] = d;
        }
}

/// Nodes on sharp convex edges and corners (a wing's sharp trailing edge, a box corner seen
/// from outside): some incident face is more than 60° off the node's max-min normal and the
/// node is convex there. The Poisson terms pull such a node across the edge and fold the
/// thin cells on its sides within a few layers, so it is extruded along its normal without
/// smoothing (ALGORITHM.md section 9 leaves sharp convex edges open; this is our decision).
void freeze_sharp_convex_nodes(const SurfaceMesh& wall, const Csr& vf, Stencils& st, int threads) {
    static const double kSharp = std::cos(60.0 * std::numbers::pi / 180.0);
    const std::vector<Vec3> n = node_normals(wall, wall.points, vf, NormalMethod::MaxMinDot, threads);
    for (Index o = 0; o < wall.num_points(); ++o) {
        if (!st.valid[o]) continue;
        double worst = 1.0;
        for (const Index* f = vf.row_begin(o); f != vf.row_end(o); ++f) {
            const Vec3 a = face_area_vector(wall, *f);
            if (a.norm() > 0.0) worst = std::min(worst, n[o].dot(a.normalized()));
        }
        if (worst >= kSharp) continue;
        // Convex all round: every neighbour lies below the tangent plane. A node where a sharp
        // edge meets a concave junction (a fin's trailing edge on a body) keeps its smoothing,
        // which the concave term needs there.
        double highest = -1.0;
        for (Index j = st.offsets[o]; j < st.offsets[o + 1]; ++j) {
            const Vec3 e = wall.points[st.points[j].node] - wall.points[o];
            if (st.points[j].mirror == kNone && e.norm() > 0.0) highest = std::max(highest, n[o].dot(e) / e.norm());
        }
        if (highest < 0.05) st.valid[o] = 0;
    }
}

/// f(α) of Eq. 18: full weight for neighbours leaning towards the normal, none beyond 90°.
double concave_ramp(double alpha) {
    constexpr double q = std::numbers::pi / 4.0, h = std::numbers::pi / 2.0;
    if (alpha <= q) return 1.0;
    if (alpha >= h) return 0.0;
    return 0.5 * (1.0 - std::cos(4.0 * alpha));
}

/// concave_ramp(acos(\p cosine)) without the arc cosine where the cosine is clearly on one
/// side of 45° or 90° (the margin far above acos's rounding, so the answer is the same bits).
double concave_ramp_of_cosine(double cosine) {
    constexpr double margin = 1e-9;
    if (cosine >= std::numbers::sqrt2 / 2.0 + margin) return 1.0;
    if (cosine <= -margin) return 0.0;
    return concave_ramp(std::acos(cosine));
}

/// First and second ξ, η derivatives of the level-1 positions at node o.
struct Derivs {
    Vec3 d[5];
};

/// Everything the sweeps need, fixed for the whole extrusion.
struct Marcher {
    const SurfaceMesh& wall;
    const LayerParams& params;
    int threads;  ///< thread_count(params.threads)
    Csr vf;
    Stencils st;
    std::vector<MirrorPlane> planes;
    std::vector<Index> node_plane;
    std::vector<Vec3> node_line;   ///< zero, or the line a node marches along (two planes meet there)
    std::vector<double> phi, psi;  ///< control functions, per node, from the wall
    /// Per node, the share of every layer height it marches (below 1 where the proximity
    /// limit leaves less room than the layers ask; LayerParams::proximity).
    std::vector<double> height_scale;
    /// Per node, the tallest a layer of its column may be (infinity: none; height_cap): finite
    /// where a front round's bound leaves less room than the layers ask, so that the column
    /// keeps its first height and every layer, its layers growing as asked up to the cap. Such
    /// a column marches as if it had none (CappedPaths).
    std::vector<double> cap;

    bool capped(std::size_t i) const { return cap[i] != std::numeric_limits<double>::infinity(); }
    /// Per node, empty or a fixed marching direction (the columns of a fan, fans.h); zero: none.
    std::vector<Vec3> fixed;
    /// Per face, empty or 1 for a face of a fan (zero area on the wall; its cells are built to shape).
    std::vector<char> fan_face;

    Vec3 at(const std::vector<Vec3>& r, const StencilPoint& p) const {
        return p.mirror == kNone ? r[p.node] : planes[p.mirror].reflect(r[p.node]);
    }

    Derivs derivatives(const std::vector<Vec3>& r, Index o) const {
        Derivs out;
        for (int d = 0; d < 5; ++d) out.d[d] = st.centre[o][d] * r[o];
        for (Index j = st.offsets[o]; j < st.offsets[o + 1]; ++j) {
            const Vec3 p = at(r, st.points[j]);
            for (int d = 0; d < 5; ++d) out.d[d] += st.weights[j][d] * p;
        }
        return out;
    }

    /// Per node, the nodes whose smoothing update reads its position (its stencil's centre
    /// and the nodes whose faces its normal is made of): the transpose of what each reads.
    Csr readers;

    std::vector<Vec3> normals(const std::vector<Vec3>& r) const {
        std::vector<Vec3> n = node_normals(wall, r, vf, params.normals, threads);
        for (std::size_t i = 0; i < n.size(); ++i) constrain_normal(static_cast<Index>(i), n[i]);
        return n;
    }

    /// normals(r) at \p nodes only, into \p n (other entries left as they are).
    void normals_at(const std::vector<Vec3>& r, const std::vector<Index>& nodes, NormalScratch& scratch,
                    std::vector<Vec3>& n) const {
        node_normals_at(wall, r, vf, params.normals, nodes, scratch, n, threads);
        for (Index i : nodes) constrain_normal(i, n[static_cast<std::size_t>(i)]);
    }

    /// A fan's columns march along their fixed directions (in the plane, at a plane node);
    /// other nodes on a plane march in it: their normal is the mirror-symmetric one.
    void constrain_normal(Index node, Vec3& n) const {
        const auto i = static_cast<std::size_t>(node);
        if (!fixed.empty() && fixed[i] != Vec3::Zero()) {
            n = fixed[i];
        } else if (node_plane[i] != kNone) {
            const Vec3& pn = planes[node_plane[i]].normal;
            const Vec3 t = n - n.dot(pn) * pn;
            if (t.norm() > 1e-12) n = t.normalized();
        } else if (node_line[i] != Vec3::Zero()) {
            n = node_line[i];
        }
    }

    /// Φ, Ψ (Eq. 14 in the form of ALGORITHM.md section 4) from the initial surface.
    void control_functions() {
        const Index n = wall.num_points();
        phi.assign(static_cast<std::size_t>(n), 0.0);
        psi.assign(static_cast<std::size_t>(n), 0.0);
        if (!params.control_functions) return;
        for (Index o = 0; o < n; ++o) {
            if (!st.valid[o]) continue;
            const Derivs g = derivatives(wall.points, o);
            const Vec3 &rx = g.d[Stencils::Xi], &ry = g.d[Stencils::Eta];
            const double g11 = rx.dot(rx), g12 = rx.dot(ry), g22 = ry.dot(ry);
            const Vec3 R = g22 * g.d[Stencils::XiXi] - 2.0 * g12 * g.d[Stencils::XiEta] + g11 * g.d[Stencils::EtaEta];
            // [g11 g22, g11 g12; g12 g22, g11 g22] (Φ, Ψ) = −(R·r_ξ, R·r_η)
            const double a = g11 * g22, b = g11 * g12, c = g12 * g22, d = g11 * g22;
            const double det = a * d - b * c;
            if (!(std::abs(det) > 1e-12 * a * d)) continue;
            const double ra = -R.dot(rx), rb = -R.dot(ry);
            phi[o] = (d * ra - b * rb) / det;
            psi[o] = (a * rb - c * ra) / det;
        }
    }
};

/// sin² of the smallest angle between r_ξ and r_η below which a node's local logical space is
/// taken as degenerate. The mixed M6's tip-edge nodes, whose rings join 0.03 mm cap edges to
/// one 25 mm needle, measure 3e-5 to 6e-3; the other example walls 0.05 and more.
constexpr double kDegenerateLogical = 0.01;

/// Nodes whose local logical space is degenerate on the wall: r_ξ and r_η of their stencil are
/// within ~6° of parallel, which happens when one edge neighbour is hundreds of times farther
/// than the others (the apex of a fan of needle triangles). Knupp's space puts every neighbour
/// on the unit circle, so that neighbour alone makes both derivatives, g11 g22 − g12² nearly
/// vanishes and the point-Jacobi update loses the diagonal dominance it needs: on the mixed M6
/// it swings to and fro along the needle, 0.4 layer heights at sweep 5, 100 at sweep 8. Such
/// nodes are extruded along their normal, like the sharp convex ones.
void freeze_degenerate_nodes(Marcher& mc) {
    for (Index o = 0; o < mc.wall.num_points(); ++o) {
        if (!mc.st.valid[o]) continue;
        const Derivs g = mc.derivatives(mc.wall.points, o);
        const Vec3 &rx = g.d[Stencils::Xi], &ry = g.d[Stencils::Eta];
        const double g11 = rx.dot(rx), g12 = rx.dot(ry), g22 = ry.dot(ry);
        if (!(g11 * g22 - g12 * g12 > kDegenerateLogical * g11 * g22)) mc.st.valid[o] = 0;
    }
}

/// Scaled Jacobian of the cell over wall face f between levels \p a and \p b, corner by corner
/// as cell_quality.h measures prisms and hexahedra.
double cell_jacobian(const SurfaceMesh& wall, Index f, const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    const Index* v = wall.face_begin(f);
    const Index n = wall.face_size(f);
    double j = 1.0;
    for (Index i = 0; i < n; ++i) {
        const Index next = v[(i + 1) % n], prev = v[(i + n - 1) % n];
        j = std::min(j, corner_scaled_jacobian(a[v[i]], a[next], a[prev], b[v[i]]));
        j = std::min(j, corner_scaled_jacobian(b[v[i]], b[prev], b[next], a[v[i]]));
    }
    return j;
}

/// The column direction at node i of level \p r that maximises the smallest wall-side corner
/// Jacobian of its cells: the max-min direction of the unit corner normals (e_next × e_prev at
/// i), not of the face normals, as a warped quadrilateral's corner can face away from its area
/// vector. In the plane of a plane node. \p min_dot: its smallest dot product with them.
Vec3 corner_direction(const Marcher& mc, const std::vector<Vec3>& r, Index i, double& min_dot) {
    std::vector<Vec3> corners;
    for (const Index* f = mc.vf.row_begin(i); f != mc.vf.row_end(i); ++f) {
        const Index* v = mc.wall.face_begin(*f);
        const Index n = mc.wall.face_size(*f);
        for (Index c = 0; c < n; ++c) {
            if (v[c] != i) continue;
            const Vec3 x = (r[v[(c + 1) % n]] - r[i]).cross(r[v[(c + n - 1) % n]] - r[i]);
            corners.push_back(x.norm() > 0.0 ? Vec3(x.normalized()) : Vec3::Zero());
        }
    }
    Vec3 d = max_min_dot_direction(corners, &min_dot);
    if (mc.node_plane[i] != kNone) {
        const Vec3& pn = mc.planes[mc.node_plane[i]].normal;
        d -= d.dot(pn) * pn;
        if (!(d.norm() > 1e-12)) return min_dot = -1.0, Vec3::Zero();
        d.normalize();
        min_dot = 1.0;
        for (const Vec3& c : corners)
            if (c.squaredNorm() != 0.0) min_dot = std::min(min_dot, d.dot(c));
    }
    return d;
}

/// Stops the layer locally where its cells would invert after smoothing (ALGORITHM.md
/// section 6 asks for "a validity check that stops layers locally"). The nodes of such cells
/// are held back: their smoothing is dropped, they go along corner_direction, and their height
/// is cut by kHoldShrink per round until the cells around them are valid and keep at least
/// half of what their columns allow at vanishing height (so that the cells next to a held
/// node do not end just above zero either). This is what keeps the layer where the Poisson
/// smoothing cannot: on the mixed M6 the wing-tip cap next to the sharp trailing edge is
/// 0.03–0.1 mm across and meshed with a few faces round it, while ten layers make 0.52 mm,
/// so the cap's curvature times the layer height is near 1 (the control functions assume it
/// small), and even plain extrusion crosses columns there by layer 5. Returns the number of
/// nodes held back: 0, with \p r1 untouched, when no cell inverted. A node whose corners span
/// a hemisphere has no valid direction and is left as it is (the validity check reports it).
Index hold_back_folds(const Marcher& mc, const std::vector<Vec3>& r0, double dk, std::vector<Vec3>& r1,
                      std::vector<char>& ever_held) {
    constexpr double kHoldShrink = 0.8;  // height factor per round (0.5 lost twice the thickness on the M6)
    constexpr int kHoldRounds = 100;     // 0.8^100 ≈ 2e-10 of the layer height
    const SurfaceMesh& wall = mc.wall;
    const Index nw = wall.num_points(), nf = wall.num_faces();
    std::vector<Index> check;  // faces to (re)check this round
    // A fan's faces have no area on the wall: their cells are shaped by construction.
    auto fan = [&](Index f) { return !mc.fan_face.empty() && mc.fan_face[static_cast<std::size_t>(f)] != 0; };
    for (Index f = 0; f < nf; ++f)
        if (!fan(f) && cell_jacobian(wall, f, r0, r1) <= 0.0) check.push_back(f);
    if (check.empty()) return 0;
    check.clear();
    for (Index f = 0; f < nf; ++f)
        if (!fan(f)) check.push_back(f);

    std::vector<char> held(static_cast<std::size_t>(nw), 0);
    std::vector<double> scale(static_cast<std::size_t>(nw), 1.0);
    std::vector<Vec3> dir(static_cast<std::size_t>(nw), Vec3::Zero());
    std::vector<int> node_round(static_cast<std::size_t>(nw), -1), face_round(static_cast<std::size_t>(nf), -1);
    std::vector<Index> moved;
    // What the cell over f tends to as its columns shrink: the smallest wall-side corner
    // Jacobian, sin(corner angle) times the cosine between corner normal and column.
    auto limit = [&](Index f) {
        const Index* v = wall.face_begin(f);
        const Index n = wall.face_size(f);
        double q = 1.0;
        for (Index c = 0; c < n; ++c) {
            const Index i = v[c];
            const Vec3 col = held[i] ? dir[i] : Vec3(r1[i] - r0[i]);
            const Vec3 e1 = r0[v[(c + 1) % n]] - r0[i], e2 = r0[v[(c + n - 1) % n]] - r0[i];
            const double l = e1.norm() * e2.norm() * col.norm();
            q = std::min(q, l > 0.0 ? e1.cross(e2).dot(col) / l : 0.0);
        }
        return q;
    };
    Index count = 0;
    for (int round = 0; round < kHoldRounds && !check.empty(); ++round) {
        // Nodes of the cells that fail: held back, or lowered further if they already are.
        moved.clear();
        for (const Index f : check) {
            bool near_held = false;
            for (const Index* v = wall.face_begin(f); v != wall.face_end(f); ++v) near_held |= held[*v] != 0;
            const double need = near_held ? std::max(0.0, 0.5 * limit(f)) : 0.0;
            if (cell_jacobian(wall, f, r0, r1) > need) continue;
            for (const Index* v = wall.face_begin(f); v != wall.face_end(f); ++v)
                if (node_round[static_cast<std::size_t>(*v)] != round) {
                    node_round[static_cast<std::size_t>(*v)] = round;
                    moved.push_back(*v);
                }
        }
        for (const Index i : moved) {
            if (!held[i]) {
                double min_dot = -1.0;
                dir[i] = corner_direction(mc, r0, i, min_dot);
                if (!(min_dot > 0.0)) continue;
                held[i] = 1;
                ever_held[static_cast<std::size_t>(i)] = 1;
                ++count;
            } else {
                scale[i] *= kHoldShrink;
            }
            r1[i] = r0[i] + scale[i] * (dk * mc.height_scale[i]) * dir[i];
        }
        // Only the cells of the nodes that moved can change.
        check.clear();
        for (const Index i : moved)
            for (const Index* f = mc.vf.row_begin(i); f != mc.vf.row_end(i); ++f)
                if (!fan(*f) && face_round[static_cast<std::size_t>(*f)] != round) {
                    face_round[static_cast<std::size_t>(*f)] = round;
                    check.push_back(*f);
                }
    }
    return count;
}

}  // namespace

namespace {

/// Everything fixed for the whole extrusion: the planes and lines open-boundary nodes keep to,
/// the stencils, the nodes extruded without smoothing, the control functions.
constexpr EnumNames<ProximityMode, 3> kProximityModeNames{{"off", "scale", "stop"}};

/// Lower \p levels until the ends of every wall edge differ by at most one (a breadth-first
/// sweep from the lowest), the lowered nodes taking the reason of the node that lowered them.
void levels_differ_by_one(const SurfaceMesh& wall, std::vector<int>& levels, std::vector<Shortfall>& reason) {
    const EdgeTable edges = edge_table(wall);
    std::vector<std::vector<Index>> adjacent(levels.size());
    for (const auto& e : edges.nodes) {
        adjacent[static_cast<std::size_t>(e[0])].push_back(e[1]);
        adjacent[static_cast<std::size_t>(e[1])].push_back(e[0]);
    }
    // Levels are small integers: buckets by level give a Dijkstra sweep in linear time.
    std::vector<std::vector<Index>> bucket(static_cast<std::size_t>(*std::max_element(levels.begin(), levels.end())) +
                                           2);
    for (std::size_t i = 0; i < levels.size(); ++i)
        bucket[static_cast<std::size_t>(levels[i])].push_back(static_cast<Index>(i));
    for (std::size_t l = 0; l < bucket.size(); ++l)
        for (std::size_t q = 0; q < bucket[l].size(); ++q) {
            const Index i = bucket[l][q];
            if (static_cast<std::size_t>(levels[static_cast<std::size_t>(i)]) != l) continue;  // stale
            for (const Index j : adjacent[static_cast<std::size_t>(i)]) {
                int& lj = levels[static_cast<std::size_t>(j)];
                if (lj <= static_cast<int>(l) + 1) continue;
                lj = static_cast<int>(l) + 1;
                reason[static_cast<std::size_t>(j)] = reason[static_cast<std::size_t>(i)];
                bucket[l + 1].push_back(j);
            }
        }
}

/// The front rounds' bounds \p extra (per wall node) spread along the wall, each from its node
/// at that node's slope (LayerConstraints::node_front_slope, else ProximityParams::front_slope):
/// one envelope per slope, the lowest holding.
std::vector<double> front_limits(const Wall& w, const ProximityParams& given, const LayerConstraints& constraints,
                                 const std::vector<double>& extra) {
    const std::size_t nw = extra.size();
    const std::vector<double>& by_input = constraints.node_front_slope;
    if (!by_input.empty() && by_input.size() != constraints.node_thickness_limit.size())
        throw InputError("LayerConstraints::node_front_slope has " + std::to_string(by_input.size()) +
                         " values for " + std::to_string(constraints.node_thickness_limit.size()) + " nodes");
    std::vector<double> slope(nw, given.front_slope);
    if (!by_input.empty())
        for (std::size_t i = 0; i < nw; ++i) slope[i] = by_input[static_cast<std::size_t>(w.input_node[i])];
    std::vector<double> slopes;
    for (std::size_t i = 0; i < nw; ++i) {
        if (!(slope[i] > 0.0 && std::isfinite(slope[i])))
            throw InputError("LayerConstraints::node_front_slope = " + format_number(slope[i]) +
                             ": need a thickness per unit of wall distance above 0");
        if (std::isfinite(extra[i])) slopes.push_back(slope[i]);
    }
    std::sort(slopes.begin(), slopes.end());
    slopes.erase(std::unique(slopes.begin(), slopes.end()), slopes.end());
    std::vector<double> limit(nw, std::numeric_limits<double>::infinity());
    for (const double s : slopes) {
        ProximityParams front = given;
        front.slope = s;
        std::vector<double> from(nw, std::numeric_limits<double>::infinity());
        for (std::size_t i = 0; i < nw; ++i)
            if (slope[i] == s) from[i] = extra[i];
        const std::vector<double> by_front = thickness_limits(w.mesh, std::vector<ProximityHit>(nw), front, from);
        for (std::size_t i = 0; i < nw; ++i) limit[i] = std::min(limit[i], by_front[i]);
    }
    return limit;
}

/// How steeply a bound set where a column stopped (LayerConstraints::node_stop_limit) rises
/// along the wall: thickness per unit of wall distance. The steps a stop leaves were closed by
/// cells up to five times as steep (kMaxStepSlope); capped, the columns beside a stop are
/// prisms whose levels slope with the bound; a lower slope lowers more of them (the trade-off
/// measured: ALGORITHM.md, "Capped columns").
constexpr double kStopSlope = 2.0;

/// How many times extrude_layers marches again with the columns that stopped capped where they
/// did (capped_at_stops): the columns the second march stops (beside those capped, at the
/// last layers) are capped by the third.
constexpr int kStopMarches = 2;

/// The thickness of the first k layers of \p delta, k = 0, ..., \p layers, each no taller than
/// \p cap (infinity: as asked).
std::vector<double> capped_reach(const std::vector<double>& delta, int layers, double cap) {
    std::vector<double> reach{0.0};
    for (int k = 0; k < layers; ++k) reach.push_back(reach.back() + std::min(delta[static_cast<std::size_t>(k)], cap));
    return reach;
}

/// The tallest a layer may be for the first \p n of \p delta, each as asked up to that height
/// (the first height and the growth kept where the layers are thinner), to add up to \p limit:
/// infinity where they fit as asked, 0 where even \p n layers as thin as the thinnest do not.
double height_cap(const std::vector<double>& delta, int n, double limit) {
    const auto end = delta.begin() + n;
    auto sum = [&](double h) {
        return std::accumulate(delta.begin(), end, 0.0, [h](double s, double d) { return s + std::min(d, h); });
    };
    if (n <= 0 || sum(std::numeric_limits<double>::infinity()) <= limit) return std::numeric_limits<double>::infinity();
    double lo = *std::min_element(delta.begin(), end), hi = *std::max_element(delta.begin(), end);
    if (sum(lo) > limit) return 0.0;
    for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        (sum(mid) > limit ? hi : lo) = mid;
    }
    return lo;
}

/// Per node, the share of the layer heights that fits the proximity limit (1: the full
/// \p thickness fits), or in Stop mode 1 and (\p max_levels) the layers that fit it, with why.
/// In Stop mode a front round's bound below the proximity limit keeps the column's layers and
/// first height, its layers no taller than a cap (\p cap, height_cap), and takes layers off
/// only where even layers as thin as the first do not fit. Directions: the level-0 marching directions.
std::vector<double> proximity_scale(const SurfaceMesh& surface, const Wall& w, const Marcher& mc,
                                    const LayerConstraints& constraints, const std::vector<double>& delta,
                                    std::vector<Shortfall>& reason, std::vector<int>& max_levels,
                                    std::vector<double>& cap) {
    const std::vector<double>& by_input = constraints.node_thickness_limit;
    const auto nw = static_cast<std::size_t>(w.mesh.num_points());
    const int layers = mc.params.distribution.layers;
    double thickness = 0.0;
    for (int k = 0; k < layers; ++k) thickness += delta[static_cast<std::size_t>(k)];
    std::vector<double> scale(nw, 1.0);
    reason.assign(nw, Shortfall::None);
    max_levels.assign(nw, layers);
    cap.assign(nw, std::numeric_limits<double>::infinity());
    if ((mc.params.proximity == ProximityMode::Off && by_input.empty()) || !(thickness > 0.0)) return scale;
    if (!by_input.empty() && by_input.size() != surface.points.size())
        throw InputError("LayerConstraints::node_thickness_limit has " + std::to_string(by_input.size()) +
                         " values for a surface of " + std::to_string(surface.points.size()) + " nodes");
    if (!constraints.node_stop_limit.empty() && (constraints.node_stop_limit.size() != surface.points.size() ||
                                                 constraints.node_stop_reason.size() != surface.points.size()))
        throw InputError("LayerConstraints::node_stop_limit and node_stop_reason need one value per node of a "
                         "surface of " + std::to_string(surface.points.size()) + " nodes");
    std::vector<ProximityHit> hits(nw);
    if (mc.params.proximity != ProximityMode::Off)
        hits = cast_proximity_rays(surface, w.input_node, w.mesh.points, mc.normals(w.mesh.points), mc.threads);
    std::vector<double> extra;
    if (!by_input.empty())
        for (std::size_t i = 0; i < nw; ++i) extra.push_back(by_input[static_cast<std::size_t>(w.input_node[i])]);
    // Which bound holds: the proximity limit alone, or the extra (front) bound below it, each
    // through its own envelope (the same as one envelope of the two where the slopes agree).
    const std::vector<double> by_proximity = thickness_limits(w.mesh, hits, mc.params.proximity_limits);
    std::vector<double> limit = by_proximity;
    if (!extra.empty()) {
        const std::vector<double> by_front = front_limits(w, mc.params.proximity_limits, constraints, extra);
        for (std::size_t i = 0; i < nw; ++i) limit[i] = std::min(limit[i], by_front[i]);
    }
    auto fitting = [&](double l) {  // the layers whose heights add up to l at most
        int n = 0;
        for (double sum = delta[0]; n < layers && sum <= l; sum += delta[static_cast<std::size_t>(++n)]) {
        }
        return n;
    };
    for (std::size_t i = 0; i < nw; ++i) {
        if (!(limit[i] < thickness)) continue;
        reason[i] = limit[i] < by_proximity[i] ? Shortfall::Front : Shortfall::Proximity;
        if (mc.params.proximity != ProximityMode::Stop) {
            scale[i] = limit[i] / thickness;
            continue;
        }
        max_levels[i] = fitting(by_proximity[i]);
    }
    if (mc.params.proximity == ProximityMode::Stop) {
        // Neighbouring columns within one layer where proximity limits them (a gap, a facing
        // wall); a front round's limits (lowered where the front met itself) only lower their
        // own columns and those the envelope reaches: spread by whole layers per edge they
        // would take every column of a coarse wall with them (the wing-fuselage's 355 nodes all
        // fell to 1 % of the thickness after one round).
        std::vector<Shortfall> prox_reason(nw, Shortfall::Proximity);
        levels_differ_by_one(w.mesh, max_levels, prox_reason);
        // Where columns stopped in an earlier march (capped_at_stops), their bounds spread at
        // kStopSlope, and the columns they lower follow for their neighbours.
        std::vector<double> own_stop, by_stop;
        if (!constraints.node_stop_limit.empty()) {
            for (std::size_t i = 0; i < nw; ++i)
                own_stop.push_back(constraints.node_stop_limit[static_cast<std::size_t>(w.input_node[i])]);
            ProximityParams spread = mc.params.proximity_limits;
            spread.front_slope = kStopSlope;
            by_stop = front_limits(w, spread, LayerConstraints{}, own_stop);
        }
        for (std::size_t i = 0; i < nw; ++i) {
            if (reason[i] == Shortfall::None && max_levels[i] < layers) reason[i] = Shortfall::Proximity;
            double bound = limit[i] < by_proximity[i] ? limit[i] : std::numeric_limits<double>::infinity();
            Shortfall why = Shortfall::Front;
            if (!by_stop.empty() && by_stop[i] < bound) {
                bound = by_stop[i];
                why = by_stop[i] < own_stop[i] ? Shortfall::Neighbours
                                               : constraints.node_stop_reason[static_cast<std::size_t>(w.input_node[i])];
            }
            if (bound < by_proximity[i]) {
                // As thick as the layers that fit the bound would be: a bound a little below
                // the thickness asked (the envelope round a lowered column) takes off what a
                // layer does, so the front moves away from where it met itself.
                const int n = fitting(bound);
                const double fit = std::accumulate(delta.begin(), delta.begin() + n, 0.0);
                if (n < max_levels[i]) cap[i] = height_cap(delta, max_levels[i], fit);
                if (cap[i] == 0.0) {
                    cap[i] = std::numeric_limits<double>::infinity();
                    max_levels[i] = n, reason[i] = why;
                } else if (max_levels[i] == layers && mc.capped(i)) {
                    reason[i] = why;
                    continue;
                }
            }
            if (max_levels[i] == layers) reason[i] = Shortfall::None;
        }
    }
    return scale;
}

/// Fans at sharp convex edges, and the stops at sharp edges without one (fans.h), come with
/// local stopping, where smoothing runs.
bool fans_on(const LayerParams& params) {
    return params.min_quality > 0.0 && !params.keep_invalid && params.smoothing;
}

/// A column to march again capped (march_capped): its node of the input surface, the levels it
/// keeps the thickness of, and why.
struct CapAt {
    Index node = kNone;
    int level = 0;
    Shortfall why = Shortfall::None;
};

/// Where \p lm's cells have an interior face OpenFOAM's checkMesh would fail as skewed (above
/// kFoamSkewness).
struct SkewedLayers {
    /// The nodes of the input surface (ascending) whose fan's columns have a node on such a
    /// face: a fan through a coarsely faceted wall, whose chain doubles back on itself, makes
    /// wedges whose shared faces stand far off the line between their centres.
    std::vector<Index> fan_nodes;
    /// The other columns with a node on such a face, to cap below it (the lowest level of the
    /// face's nodes, at least 1; reason quality): a column bent at a concave junction (a fin's
    /// trailing edge on a body) whose layers stretch beside its neighbours'.
    std::vector<CapAt> columns;
};
/// With \p fans_only, only the cells with a node on a fan's column are looked at (a face with
/// such a node has such cells on both sides), and only fan_nodes is filled.
SkewedLayers skewed_layers(const LayerMesh& lm, int threads, bool fans_only) {
    std::vector<Index> column(lm.mesh.points.size(), kNone);  // the column each node is on
    std::vector<int> level(lm.mesh.points.size(), 0);
    const auto on_fan = [&](Index i) {
        return i != kNone && !lm.fan_column.empty() && lm.fan_column[static_cast<std::size_t>(i)] != 0;
    };
    for (Index i = 0; i < lm.wall_nodes(); ++i)
        if (!fans_only || on_fan(i))
            for (int k = 0; k <= lm.node_layers(i); ++k) {
                const auto v = static_cast<std::size_t>(lm.level_node(k, i));
                if (column[v] == kNone) column[v] = i, level[v] = k;  // a fan's shared wall node: its first column
            }
    VolumeMesh subset;
    if (fans_only) {
        subset.points = lm.mesh.points;
        auto take = [&](const auto& cells, auto& into) {
            for (const auto& c : cells)
                if (std::any_of(c.begin(), c.end(), [&](Index v) { return column[static_cast<std::size_t>(v)] != kNone; }))
                    into.push_back(c);
        };
        take(lm.mesh.tets, subset.tets);
        take(lm.mesh.pyramids, subset.pyramids);
        take(lm.mesh.prisms, subset.prisms);
        take(lm.mesh.hexes, subset.hexes);
    }
    const VolumeMesh& cells = fans_only ? subset : lm.mesh;
    std::vector<std::uint64_t> skewed;
    const FaceMatch match = match_faces(cells, threads);
    solver_checks(cells, match, threads, &skewed);
    SkewedLayers out;
    for (const std::uint64_t s : skewed) {
        if (match.across[s] < 0) continue;  // not a face between two cells
        Index v[4];
        const int n = match.slots.nodes(s, v);
        const bool fan = std::any_of(v, v + n, [&](Index x) { return on_fan(column[static_cast<std::size_t>(x)]); });
        int lowest = std::numeric_limits<int>::max();
        for (int c = 0; c < n; ++c) lowest = std::min(lowest, level[static_cast<std::size_t>(v[c])]);
        for (int c = 0; c < n; ++c) {
            const Index i = column[static_cast<std::size_t>(v[c])];
            if (i == kNone) continue;
            const Index input = lm.input_node[static_cast<std::size_t>(i)];
            if (fan && on_fan(i))
                out.fan_nodes.push_back(input);
            else if (!fan && lowest >= 1)
                out.columns.push_back({input, lowest, Shortfall::Quality});
        }
    }
    std::sort(out.fan_nodes.begin(), out.fan_nodes.end());
    out.fan_nodes.erase(std::unique(out.fan_nodes.begin(), out.fan_nodes.end()), out.fan_nodes.end());
    return out;
}

/// Each column of \p caps bounded in \p constraints to the thickness \p reach gives its level
/// (LayerConstraints::node_stop_limit, for its reason; sized to \p nodes first if empty); whether
/// any bound was lowered.
bool lower_stop_limits(const std::vector<CapAt>& caps, const std::vector<double>& reach, std::size_t nodes,
                       LayerConstraints& constraints) {
    if (constraints.node_stop_limit.empty()) {
        constraints.node_stop_limit.assign(nodes, std::numeric_limits<double>::infinity());
        constraints.node_stop_reason.assign(nodes, Shortfall::None);
    }
    bool any = false;
    for (const CapAt& c : caps) {
        const auto v = static_cast<std::size_t>(c.node);
        const double bound = reach[static_cast<std::size_t>(c.level)];
        if (!(bound < constraints.node_stop_limit[v])) continue;
        constraints.node_stop_limit[v] = bound, constraints.node_stop_reason[v] = c.why;
        any = true;
    }
    return any;
}

/// The layers marched again with each column of \p caps bounded to the thickness of the levels
/// it keeps (LayerConstraints::node_stop_limit, with its reason): marching as before, it keeps
/// every layer up to there, its tallest layers capped (CappedPaths). Up to kStopMarches times;
/// nothing after those, where proximity limits scale, or where no bound is lowered.
std::optional<LayerMesh> march_capped(const SurfaceMesh& surface, const LayerParams& params,
                                      const LayerConstraints& constraints, const std::vector<CapAt>& caps,
                                      const std::vector<double>& delta, Progress* progress) {
    if (caps.empty() || params.proximity != ProximityMode::Stop || constraints.stop_marches >= kStopMarches)
        return std::nullopt;
    const std::vector<double> reach =
        capped_reach(delta, params.distribution.layers, std::numeric_limits<double>::infinity());
    LayerConstraints again = constraints;
    ++again.stop_marches;
    if (!lower_stop_limits(caps, reach, surface.points.size(), again)) return std::nullopt;
    return extrude_layers(surface, params, again, progress);
}

/// The layers marched again with no fan at \p nodes (of the input surface) either, those of them
/// that had one listed in \p list of the result (ascending); nothing if none had one.
std::optional<LayerMesh> without_fans(const SurfaceMesh& surface, const LayerParams& params,
                                      const LayerConstraints& constraints, const std::vector<Index>& nodes,
                                      std::vector<Index> LayerMesh::*list, Progress* progress) {
    LayerConstraints again = constraints;
    std::vector<Index> dropped;
    for (const Index v : nodes)
        if (again.bar_fan(v, surface.points.size())) dropped.push_back(v);
    if (dropped.empty()) return std::nullopt;
    LayerMesh retry = extrude_layers(surface, params, again, progress);
    std::vector<Index>& into = retry.*list;
    into.insert(into.end(), dropped.begin(), dropped.end());
    std::sort(into.begin(), into.end());
    return retry;
}

/// Per wall node, the normal of the plane a chain of fans may end in (fans.h): that of the one
/// non-wall patch the node is on, if it is planar (a symmetry plane); zero elsewhere. A plane
/// node on two patches would need its fan's columns shared between their re-meshings. Empty
/// for a closed wall.
std::vector<Vec3> fan_planes(const SurfaceMesh& surface, const Wall& w, const LayerParams& params) {
    std::vector<Vec3> plane_normal;
    if (w.loops.rows() == 0) return plane_normal;
    const auto nn = static_cast<std::size_t>(w.mesh.num_points());
    const std::vector<Vec3> n =
        node_normals(w.mesh, w.mesh.points, vertex_faces(w.mesh), params.normals, thread_count(params.threads));
    std::vector<MirrorPlane> planes;
    std::vector<Index> node_plane(nn, kNone);
    std::vector<Vec3> node_line(nn, Vec3::Zero());
    std::vector<char> fixed(nn, 0), one_patch(nn, 0);
    patch_constraints(surface, w, w.loops, n, planes, node_plane, node_line, fixed, &one_patch);
    plane_normal.assign(nn, Vec3::Zero());
    for (std::size_t i = 0; i < nn; ++i)
        if (node_plane[i] != kNone && one_patch[i])
            plane_normal[i] = planes[static_cast<std::size_t>(node_plane[i])].normal;
    return plane_normal;
}

/// The fans (fans_on). \p w gets the fans' columns and strip faces; the result keeps
/// their directions and bases (its mesh moved into \p w).
FanWall add_fans(const SurfaceMesh& surface, const LayerParams& params, const std::vector<char>& no_fan_nodes,
                 Wall& w) {
    const Index nwall = w.mesh.num_points();
    FanWall fans;
    if (fans_on(params)) {
        std::vector<char> excluded;
        if (!no_fan_nodes.empty()) {
            if (no_fan_nodes.size() != surface.points.size())
                throw InputError("LayerConstraints::no_fan_nodes has " + std::to_string(no_fan_nodes.size()) +
                                 " values for a surface of " + std::to_string(surface.points.size()) + " nodes");
            for (const Index i : w.input_node) excluded.push_back(no_fan_nodes[static_cast<std::size_t>(i)]);
        }
        const std::vector<Vec3> plane_normal = fan_planes(surface, w, params);
        const std::vector<double> heights = layer_heights(params.distribution);  // and the next layer's
        const double thickness = std::accumulate(heights.begin(), heights.begin() + params.distribution.layers, 0.0);
        fans = build_fans(w.mesh, w.loops, plane_normal, 2.0 * thickness, params.fan_angle_deg, excluded);
    }
    if (!fans.empty()) {
        for (Index i = nwall; i < fans.mesh.num_points(); ++i)
            w.input_node.push_back(w.input_node[static_cast<std::size_t>(fans.base[static_cast<std::size_t>(i)])]);
        w.input_face.resize(static_cast<std::size_t>(fans.mesh.num_faces()), kNone);
        w.mesh = std::move(fans.mesh);
        // Through a plane node's columns, where one has a fan.
        std::vector<char> open(static_cast<std::size_t>(nwall), 0);
        for (const Index v : w.loops.values) open[static_cast<std::size_t>(v)] = 1;
        for (Index i = nwall; i < w.mesh.num_points(); ++i)
            if (open[static_cast<std::size_t>(fans.base[static_cast<std::size_t>(i)])]) {
                w.loops = boundary_loops(w.mesh);
                break;
            }
    }
    return fans;
}

/// Per node of \p mc, the share of the \p thickness asked (the sum of the first layers of
/// \p delta) its layers are asked to reach, capped and scaled.
std::vector<double> thickness_shares(const Marcher& mc, const std::vector<double>& delta, double thickness) {
    std::vector<double> share = mc.height_scale;
    const int layers = mc.params.distribution.layers;
    for (std::size_t i = 0; i < share.size(); ++i)
        if (mc.capped(i)) share[i] *= capped_reach(delta, layers, mc.cap[i]).back() / thickness;
    return share;
}

/// Marcher::readers: for each node o, what its smoothing update reads (o, its stencil points'
/// nodes, the corners of the faces round it, which make its normal), transposed; each row
/// ascending, each reader once.
Csr smoothing_readers(const SurfaceMesh& wall, const Csr& vf, const Stencils& st) {
    const Index n = wall.num_points();
    std::vector<std::pair<Index, Index>> reads;  // (node read, reader)
    std::vector<Index> row;
    for (Index o = 0; o < n; ++o) {
        row.assign(1, o);
        for (Index j = st.offsets[o]; j < st.offsets[o + 1]; ++j) row.push_back(st.points[j].node);
        for (const Index* f = vf.row_begin(o); f != vf.row_end(o); ++f)
            row.insert(row.end(), wall.face_begin(*f), wall.face_end(*f));
        std::sort(row.begin(), row.end());
        row.erase(std::unique(row.begin(), row.end()), row.end());
        for (Index a : row) reads.emplace_back(a, o);
    }
    std::sort(reads.begin(), reads.end());
    Csr out;
    out.offsets.assign(static_cast<std::size_t>(n) + 1, 0);
    out.values.reserve(reads.size());
    for (const auto& [a, o] : reads) {
        ++out.offsets[static_cast<std::size_t>(a) + 1];
        out.values.push_back(o);
    }
    for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) out.offsets[i + 1] += out.offsets[i];
    return out;
}

/// \p plan_only: the directions and the proximity levels only (proximity_plan), no stencils
/// or control functions.
Marcher make_marcher(const SurfaceMesh& surface, const Wall& w, const FanWall& fans, const LayerParams& params,
                     const LayerConstraints& constraints, const std::vector<double>& delta,
                     std::vector<Shortfall>& scale_reason, std::vector<int>& max_levels, bool plan_only = false) {
    Marcher mc{w.mesh, params, thread_count(params.threads), vertex_faces(w.mesh), {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}};
    if (!fans.empty()) mc.fixed = fans.direction, mc.fan_face = fans.fan_face;
    {
        const std::vector<Vec3> n = node_normals(w.mesh, w.mesh.points, mc.vf, params.normals, mc.threads);
        const std::size_t nn = static_cast<std::size_t>(w.mesh.num_points());
        mc.node_plane.assign(nn, kNone);
        mc.node_line.assign(nn, Vec3::Zero());
        std::vector<char> fixed(nn, 0);
        patch_constraints(surface, w, w.loops, n, mc.planes, mc.node_plane, mc.node_line, fixed);
        boundary_planes(w.mesh, w.loops, n, fixed, mc.planes, mc.node_plane);
    }
    if (!plan_only) {
        mc.st = build_stencils(w.mesh, node_rings(w.mesh), mc.node_plane, mc.planes);
        freeze_sharp_convex_nodes(w.mesh, mc.vf, mc.st, mc.threads);
        freeze_degenerate_nodes(mc);
        // A fan's columns march along their fixed directions, unsmoothed.
        for (std::size_t i = 0; i < mc.fixed.size(); ++i)
            if (mc.fixed[i] != Vec3::Zero()) mc.st.valid[i] = 0;
        mc.control_functions();
        mc.readers = smoothing_readers(w.mesh, mc.vf, mc.st);
    }
    mc.height_scale = proximity_scale(surface, w, mc, constraints, delta, scale_reason, max_levels, mc.cap);
    return mc;
}

/// Step 1 of a layer (Eq. 11): level 1 of the locally orthogonal reference mesh, \p r0 moved by
/// the layer height \p dk along its normals. Returns those normals.
std::vector<Vec3> reference_level(const Marcher& mc, const std::vector<Vec3>& r0, double dk, std::vector<Vec3>& r1) {
    std::vector<Vec3> n0 = mc.normals(r0);
    for (std::size_t i = 0; i < r0.size(); ++i) r1[i] = r0[i] + (dk * mc.height_scale[i]) * n0[i];
    return n0;
}

/// The three levels of the reference mesh the smoothing works on: the wall of the layer, its
/// middle level (being smoothed) and level 2 (Eq. 12, regenerated after every sweep).
struct Levels {
    const std::vector<Vec3>& r0;
    const std::vector<Vec3>& r1;
    const std::vector<Vec3>& r2;
};

/// The concave-region terms (Eqs. 15–18) added to node o's L and K, in the rotation-invariant
/// form: Σ ν_m times the second derivative along neighbour m's direction, scaled by the metric
/// across it (for M = 4 exactly g22 g33 (ν_E + ν_W) r_ξξ + g11 g33 (ν_N + ν_S) r_ηη).
void add_concave_terms(const Marcher& mc, const Levels& lv, Index o, const Derivs& g, const Vec3& metric, double g33,
                       Vec3& L, double& K) {
    const double g11 = metric[0], g12 = metric[1], g22 = metric[2];
    const auto& c = mc.st.centre[o];
    const Vec3 nrm = (lv.r2[o] - lv.r1[o]).normalized();
    for (Index j = mc.st.offsets[o]; j < mc.st.offsets[o + 1]; ++j) {
        const auto& dir = mc.st.direction[j];
        if (dir[0] == 0.0 && dir[1] == 0.0) continue;
        const Vec3 e = mc.at(lv.r1, mc.st.points[j]) - lv.r1[o];
        const double gm = e.squaredNorm();
        if (gm <= g33) continue;
        const double ramp = concave_ramp_of_cosine(std::clamp(e.dot(nrm) / std::sqrt(gm), -1.0, 1.0));
        // Literal reading g_m/g33 − 1, capped (ALGORITHM.md section 6); the bounded reading
        // 1 − g33/g_m when the cap is 0.
        const double cap = mc.params.concave_cap;
        const double nu = (cap > 0.0 ? std::min(gm / g33 - 1.0, cap) : 1.0 - g33 / gm) * ramp;
        if (nu <= 0.0) continue;
        const double cs = dir[0], sn = dir[1];
        const double gperp = sn * sn * g11 - 2.0 * sn * cs * g12 + cs * cs * g22;
        const double wt = g33 * nu * gperp;
        L += wt *
             (cs * cs * g.d[Stencils::XiXi] + 2.0 * cs * sn * g.d[Stencils::XiEta] + sn * sn * g.d[Stencils::EtaEta]);
        K += wt * (cs * cs * c[Stencils::XiXi] + 2.0 * cs * sn * c[Stencils::XiEta] + sn * sn * c[Stencils::EtaEta]);
    }
}

/// How far the iterate's spacing across the layer may exceed the spacing asked there before the
/// concave terms stop following it (see jacobi_update).
constexpr double kConcaveSpacingBand = 1.5;

/// The point-Jacobi update of node o's middle-level position: Eq. 3 with the control functions
/// Φ, Ψ, Θ (\p theta) and the concave terms, written as K r_o + (L − K r_o) = 0 (r_ζζ = r2 − 2 r1 +
/// r0 carries −2 r_o), projected into the node's plane. Unchanged where the node is extruded
/// without smoothing or its metrics are degenerate (K ≥ 0).
///
/// The concave terms take the iterate's g33 only up to (kConcaveSpacingBand × \p spacing)², the
/// spacing asked of the layer at this node (½ (δ_k + δ_{k+1}) × its proximity scale): their
/// weight grows with g33 (ν_m is capped), so from the iterate alone a node they raised was
/// pulled up harder at the next sweep. At a concave junction that fed on itself: a node of the
/// sphere with a fin through it (10 layers from 1e-3) rose 1.3 layer heights a sweep until held
/// at kMaxSmoothingMove, its first cell 11 times as tall as asked and its layers alternately
/// about 5 times taller and shorter than the one below. Within the band nothing changes. The
/// Poisson terms keep the iterate's metrics.
Vec3 jacobi_update(const Marcher& mc, const Levels& lv, Index o, double theta, double spacing) {
    if (!mc.st.valid[o]) return lv.r1[o];
    const Derivs g = mc.derivatives(lv.r1, o);
    const Vec3 &rx = g.d[Stencils::Xi], &ry = g.d[Stencils::Eta];
    const Vec3 rz = 0.5 * (lv.r2[o] - lv.r0[o]);
    const double g11 = rx.dot(rx), g12 = rx.dot(ry), g22 = ry.dot(ry), g33 = rz.dot(rz);
    const double A = g22 * g33, B = -2.0 * g12 * g33, C = g11 * g33, D = g11 * g22 - g12 * g12;
    const auto& c = mc.st.centre[o];
    Vec3 L = A * (g.d[Stencils::XiXi] + mc.phi[o] * rx) + B * g.d[Stencils::XiEta] +
             C * (g.d[Stencils::EtaEta] + mc.psi[o] * ry) + D * (lv.r2[o] - 2.0 * lv.r1[o] + lv.r0[o] + theta * rz);
    double K = A * (c[Stencils::XiXi] + mc.phi[o] * c[Stencils::Xi]) + B * c[Stencils::XiEta] +
               C * (c[Stencils::EtaEta] + mc.psi[o] * c[Stencils::Eta]) - 2.0 * D;
    if (mc.params.concave) {
        const double band = kConcaveSpacingBand * spacing;
        add_concave_terms(mc, lv, o, g, Vec3(g11, g12, g22), std::min(g33, band * band), L, K);
    }
    if (!(K < 0.0)) return lv.r1[o];  // degenerate metrics: leave the reference position
    Vec3 p = lv.r1[o] - L / K;
    if (!p.allFinite()) return lv.r1[o];  // K so small (needle stencils) that L / K overflows
    if (mc.node_plane[o] != kNone) p = mc.planes[mc.node_plane[o]].project(p);
    return p;
}

/// How far the smoothing may move a node from where plain extrusion put it, in layer heights
/// (of that node: scaled heights count scaled). The Poisson corrections that keep layers smooth
/// and orthogonal move nodes a fraction of a layer height, those of concave corners a few; a
/// node carried further is a divergent update, and its cells would stop its column or fold
/// the front. Measured: at 2 the wing-fuselage's layer top intersected itself, from 10 to 40
/// every case gives the same worst cells.
constexpr double kMaxSmoothingMove = 10.0;

/// A node whose smoothing update reads only nodes that moved at most this share of the
/// tolerance (LayerParams::tolerance × δ_k) in the last sweep is not updated in the next one:
/// the layer's own test of convergence (every node moving at most the tolerance), node by
/// node, ten times stricter (ALGORITHM.md, "Speed").
constexpr double kSettledMove = 0.1;

/// The most a column may lean off the normal of the front it grows from, degrees, once smoothed
/// (limit_lean).
constexpr double kMaxLeanDeg = 30.0;

/// Each of the \p nw wall nodes of the smoothed level \p r1 moved back towards its extruded
/// position \p ref (\p r0 plus its layer height along its normal) until its column leans at most
/// kMaxLeanDeg off that normal; its progress along the normal is kept. Where the layers grow
/// taller than the front's spacing the Poisson terms within the layer outweigh the marching one
/// by (height / spacing)², and once the front's faces have stretched one way (round a leading
/// edge) Knupp's logical space mixes their two directions: the smoothing then pulls a leading
/// edge's columns round towards its tip layer after layer, where plain normals stay put, and
/// their cells shear until the columns stop (ALGORITHM.md, "How far a column may lean").
void limit_lean(Index nw, const std::vector<Vec3>& r0, const std::vector<Vec3>& ref, std::vector<Vec3>& r1) {
    const double tan_lean = std::tan(kMaxLeanDeg * std::numbers::pi / 180.0);
    for (std::size_t o = 0; o < static_cast<std::size_t>(nw); ++o) {
        const Vec3 up = ref[o] - r0[o];
        const double h = up.norm();
        if (!(h > 0.0)) continue;
        const Vec3 n = up / h;
        const Vec3 d = r1[o] - ref[o];
        const double along = d.dot(n);
        const Vec3 side = d - along * n;
        const double most = tan_lean * std::max(h + along, 0.0), now = side.norm();
        if (now > most) r1[o] = ref[o] + along * n + (most / now) * side;
    }
}

/// The nodes to update in the next sweep, ascending, into \p todo: those reading a node in
/// \p moved (Marcher::readers). Where many moved, every node: updating a node whose reads did
/// not change gives the position it has. \p queued: per node, 0 (and 0 again on return).
void next_todo(const Csr& readers, const std::vector<Index>& moved, std::vector<char>& queued,
               std::vector<Index>& todo) {
    const Index n = readers.rows();
    todo.clear();
    if (moved.size() * 8 >= static_cast<std::size_t>(n)) {
        todo.resize(static_cast<std::size_t>(n));
        std::iota(todo.begin(), todo.end(), Index{0});
        return;
    }
    for (Index a : moved)
        for (const Index* o = readers.row_begin(a); o != readers.row_end(a); ++o) queued[static_cast<std::size_t>(*o)] = 1;
    for (Index o = 0; o < n; ++o)
        if (queued[static_cast<std::size_t>(o)]) queued[static_cast<std::size_t>(o)] = 0, todo.push_back(o);
}

/// Node \p o's point-Jacobi update held within kMaxSmoothingMove layer heights of its extruded
/// position \p ref: a node the sweeps carry away (a concave junction node whose update
/// diverges: 60 layer heights in one layer on the body-fin box, 250 beside the
/// wing-fuselage's junction) stays there.
Vec3 smoothed_position(const Marcher& mc, const Levels& lv, Index o, double theta, double dk, double dk1,
                       const Vec3& ref) {
    Vec3 next = jacobi_update(mc, lv, o, theta, 0.5 * (dk + dk1) * mc.height_scale[o]);
    const double reach = kMaxSmoothingMove * dk * mc.height_scale[o];
    const Vec3 d = next - ref;
    if (d.squaredNorm() > reach * reach) next = ref + (reach / d.norm()) * d;
    return next;
}

/// Step 2 of a layer: point-Jacobi sweeps of the Poisson system over the middle level \p r1
/// (each node's update reads only the previous iterate, so the result does not depend on the
/// thread count), level 2 regenerated from it before every sweep (Eq. 12). At least
/// LayerParams::sweeps sweeps, more (up to max_sweeps) while the largest update exceeds
/// tolerance × δ_k; each update held within kMaxSmoothingMove layer heights of \p r1 as it came
/// in (the extruded level), and the result's columns leaning at most kMaxLeanDeg (limit_lean).
/// After the first sweep only the nodes whose reads moved more than kSettledMove of the
/// tolerance are updated (next_todo). Returns the sweeps done.
int smooth_level(const Marcher& mc, const std::vector<Vec3>& r0, double dk, double dk1, std::vector<Vec3>& r1) {
    const LayerParams& p = mc.params;
    const double theta = p.control_functions ? -2.0 * (dk1 - dk) / (dk + dk1) : 0.0;
    const int max_sweeps = p.smoothing ? std::max(p.max_sweeps, p.sweeps) : 0;
    const Index nw = mc.wall.num_points();
    std::vector<Vec3> r2(r1.size()), n1(r1.size()), next;
    const std::vector<Vec3> ref = r1;  // the extruded level the smoothing corrects
    // The nodes to update this sweep: at first all; then those whose update reads a node that
    // moved more than kSettledMove of the tolerance in the last sweep (the others have
    // converged: they would compute about where they are).
    std::vector<Index> todo(static_cast<std::size_t>(nw)), moved;
    std::iota(todo.begin(), todo.end(), Index{0});
    std::vector<char> queued(static_cast<std::size_t>(nw), 0);
    std::vector<double> move;
    NormalScratch scratch;
    const double settled = kSettledMove * p.tolerance * dk;
    int sweep = 0;
    for (; sweep < max_sweeps; ++sweep) {
        mc.normals_at(r1, todo, scratch, n1);
        const auto nt = static_cast<Index>(todo.size());
        next.resize(todo.size());
        move.resize(todo.size());
        double max_move = 0.0;
#pragma omp parallel for num_threads(thread_count(mc.threads, nt)) schedule(static) reduction(max : max_move)
        for (Index t = 0; t < nt; ++t) {
            const Index o = todo[static_cast<std::size_t>(t)];
            r2[o] = r1[o] + (dk1 * mc.height_scale[o]) * n1[o];  // Eq. 12
            next[t] = smoothed_position(mc, Levels{r0, r1, r2}, o, theta, dk, dk1, ref[o]);
            move[t] = (next[t] - r1[o]).norm();
            max_move = std::max(max_move, move[t]);
        }
        moved.clear();
        for (Index t = 0; t < nt; ++t) {
            const Index o = todo[static_cast<std::size_t>(t)];
            r1[o] = next[t];
            if (move[t] > settled) moved.push_back(o);
        }
        if (sweep + 1 >= p.sweeps && max_move <= p.tolerance * dk) {
            ++sweep;
            break;
        }
        next_todo(mc.readers, moved, queued, todo);
    }
    if (sweep > 0) limit_lean(nw, r0, ref, r1);
    return sweep;
}

/// What a level's smoothing (reference_level, smooth_level) reads besides the positions it
/// starts from: the walls with their fans, the marcher's per-node data built from them, the
/// heights and the settings. Two marches with equal keys smooth a level from equal positions
/// to equal bytes.
struct SmoothingKey {
    std::vector<Vec3> wall, fixed, node_line;
    std::vector<Index> face_offsets, face_nodes, node_plane, stencil_offsets;
    std::vector<std::array<double, 5>> stencil_weights, stencil_centre;
    std::vector<char> valid;
    std::vector<double> phi, psi, height_scale, delta;
    std::array<double, 2> numbers{};
    std::array<int, 6> flags{};
    bool operator==(const SmoothingKey&) const = default;
};

SmoothingKey smoothing_key(const Marcher& mc, const std::vector<double>& delta) {
    const LayerParams& p = mc.params;
    return {mc.wall.points,
            mc.fixed,
            mc.node_line,
            mc.wall.face_offsets,
            mc.wall.face_nodes,
            mc.node_plane,
            mc.st.offsets,
            mc.st.weights,
            mc.st.centre,
            mc.st.valid,
            mc.phi,
            mc.psi,
            mc.height_scale,
            delta,
            {p.tolerance, p.concave_cap},
            {p.sweeps, p.max_sweeps, p.smoothing, p.control_functions, p.concave, static_cast<int>(p.normals)}};
}

}  // namespace

/// Per level of the last march: the positions it started from and the level as smoothed.
struct SmoothedLevels {
    SmoothingKey key;
    std::vector<std::vector<Vec3>> from, to;
    std::vector<int> sweeps;

    /// A march with \p k starts: what was kept for another key goes.
    void begin(SmoothingKey k) {
        if (k == key) return;
        key = std::move(k);
        from.clear(), to.clear(), sweeps.clear();
    }

    /// smooth_level of level \p level from \p r0 (\p r1 as reference_level left it), or what
    /// the last march smoothed from the same \p r0; the levels kept above it go when it is
    /// smoothed anew (they started from its result).
    int smooth(int level, const Marcher& mc, const std::vector<Vec3>& r0, double dk, double dk1,
               std::vector<Vec3>& r1) {
        const auto u = static_cast<std::size_t>(level);
        if (u < from.size() && from[u] == r0) {
            r1 = to[u];
            return sweeps[u];
        }
        const int done = smooth_level(mc, r0, dk, dk1, r1);
        from.resize(u), to.resize(u), sweeps.resize(u);
        from.push_back(r0), to.push_back(r1), sweeps.push_back(done);
        return done;
    }
};

std::shared_ptr<SmoothedLevels> make_smoothed_levels() { return std::make_shared<SmoothedLevels>(); }

namespace {

/// With stopping off (LayerParams::min_quality 0): the first cell of layer \p k whose columns all
/// go on and that would invert, or whose quality cannot be computed (NaN: coordinates out of
/// range), stops the extrusion with a TopologyError naming it, unless LayerParams::keep_invalid.
void check_folds(const Wall& w, const LayerParams& params, int k, const Columns& col, const std::vector<Vec3>& r1) {
    if (params.keep_invalid) return;
    double jmin = 1.0;
    Index f = kNone;
    for (Index g = 0; g < col.faces.count(); ++g) {
        const auto& v = col.faces.nodes[static_cast<std::size_t>(g)];
        bool all = true;
        for (int c = 0; c < col.faces.size[static_cast<std::size_t>(g)]; ++c)
            all &= col.active[static_cast<std::size_t>(v[static_cast<std::size_t>(c)])] != 0;
        if (!all) continue;
        const double j = column_cell_jacobian(col, g, r1);
        if (std::isnan(j) || (!std::isnan(jmin) && j < jmin)) jmin = j, f = g;
        if (std::isnan(j)) break;  // sticky: a NaN is the worst
    }
    if (jmin > 0.0) return;
    const Index wf = f < w.mesh.num_faces() ? f : kNone;  // split halves: name the layer only
    const std::string what = std::isnan(jmin)
                                 ? " has a quality that cannot be computed (a non-finite coordinate: the "
                                   "model's coordinates or the layer heights are out of range)"
                                 : " would invert (min scaled Jacobian " + format_number(jmin) +
                                       "); the layers fold there: keep LayerParams::min_quality above 0 "
                                       "so the columns stop there, or use fewer layers or a smaller total "
                                       "thickness" +
                                       (params.concave ? std::string()
                                                       : std::string(", or let the concave-region smoothing "
                                                                     "act (drop LayerParams::concave = false)"));
    const auto& v = col.faces.nodes[static_cast<std::size_t>(f)];
    const int n = col.faces.size[static_cast<std::size_t>(f)];
    Vec3 centre = Vec3::Zero();
    for (int c = 0; c < n; ++c) centre += col.top[static_cast<std::size_t>(v[static_cast<std::size_t>(c)])];
    centre /= n;
    const std::string message =
        "layer " + std::to_string(k + 1) + " of " + std::to_string(params.distribution.layers) + ": the " +
        (n == 3 ? "prism" : "hexahedron") + " over wall face " +
        (wf != kNone ? std::to_string(w.input_face[static_cast<std::size_t>(wf)]) : std::string("(part of a quad)")) +
        " (patch '" + w.mesh.patches[static_cast<std::size_t>(col.faces.patch[static_cast<std::size_t>(f)])].name +
        "') at " + format_point(centre) + what;
    if (std::isnan(jmin)) throw TopologyError(message);
    std::vector<Index> nodes;  // the folding cell's wall nodes, as nodes of the input surface
    double reached = std::numeric_limits<double>::infinity();  // the layers below it, at its lowest corner
    for (int c = 0; c < n; ++c) {
        const auto i = static_cast<std::size_t>(v[static_cast<std::size_t>(c)]);
        nodes.push_back(w.input_node[i]);
        reached = std::min(reached, (col.top[i] - w.mesh.points[i]).norm());
    }
    throw LocalTopologyError(message, std::move(nodes), std::isfinite(reached) ? reached : 0.0);
}

/// Orthogonality of layer \p k's columns that go on: the angle between each one's segment and the
/// normal it started along.
void layer_orthogonality(const Columns& col, int k, const std::vector<Vec3>& r0, const std::vector<Vec3>& r1,
                         const std::vector<Vec3>& n0, LayerStats& stats) {
    double omax = 0.0, osum = 0.0;
    Index count = 0;
    for (std::size_t i = 0; i < r0.size(); ++i) {
        if (col.levels[i] != k + 1) continue;
        const Vec3 e = r1[i] - r0[i];
        const double ang = std::acos(std::clamp(e.normalized().dot(n0[i]), -1.0, 1.0)) * 180.0 / std::numbers::pi;
        omax = std::max(omax, ang);
        osum += ang;
        ++count;
    }
    stats.max_orthogonality_deg = omax;
    stats.mean_orthogonality_deg = count > 0 ? osum / static_cast<double>(count) : 0.0;
    stats.columns = count;
}

/// Not one column got a layer: a TopologyError with why, by how many nodes, and where the first is.
[[noreturn]] void throw_no_layers(const Wall& w, const Columns& col) {
    std::array<Index, kShortfalls> count{};
    std::array<Index, kShortfalls> first{};
    first.fill(kNone);
    for (std::size_t i = 0; i < col.reason.size(); ++i) {
        const auto r = static_cast<std::size_t>(col.reason[i]);
        if (count[r]++ == 0) first[r] = static_cast<Index>(i);
    }
    std::string why;
    for (std::size_t r = 0; r < kShortfalls; ++r)
        if (count[r] > 0)
            why += (why.empty() ? "" : ", ") + std::to_string(count[r]) + " " +
                   std::string(to_string(static_cast<Shortfall>(r))) + " (the first at " +
                   format_point(w.mesh.points[static_cast<std::size_t>(first[r])]) + ")";
    // The sharpest wall corner: needle triangles make cells no marching can keep usable.
    const NeedleReport needle = needle_faces(w.mesh, kNeedleCornerDeg);
    const std::string needles = needle.needles > 0
                                    ? "; the wall has needle faces (a corner of " +
                                          format_number(needle.sharpest_deg, 3) + " degrees at " +
                                          format_point(needle.where) + "): remesh the surface into well-shaped faces"
                                    : "";
    throw TopologyError(
        "no wall node could grow a single layer; the columns stopped for: " + why + needles +
        ". Quality: the first layer's cells would be poor (a smaller first height, a finer surface, "
        "or a lower LayerParams::min_quality); proximity: the gaps are narrower than the first layer; sharp edge: "
        "convex edges too sharp for one direction that got no fan (a lower "
        "LayerParams::fan_angle_deg gives them fans, sharp_edge_stop_deg 0 keeps one direction)");
}

/// Per edge of the wall's open boundary loops, in order, the patch of the input face across it
/// if that face is not a wall (a symmetry plane of a half model), else kNone ("layer_side").
std::vector<Index> side_patches(const SurfaceMesh& surface, const Wall& w) {
    const EdgeTable in_edges = edge_table(surface);
    std::vector<Index> out;
    for (Index l = 0; l < w.loops.rows(); ++l) {
        const Index m = w.loops.row_size(l);
        for (Index i = 0; i < m; ++i) {
            const Index a = w.loops.row_begin(l)[i], b = w.loops.row_begin(l)[(i + 1) % m];
            Index patch = kNone;
            const Index ia = w.input_node[static_cast<std::size_t>(a)], ib = w.input_node[static_cast<std::size_t>(b)];
            if (const Index e = find_edge(in_edges, ia, ib); e != kNone) {
                for (const Index* f = in_edges.faces.row_begin(e); f != in_edges.faces.row_end(e); ++f)
                    if (surface.patches[static_cast<std::size_t>(surface.face_patch[*f])].kind != PatchKind::Wall)
                        patch = surface.face_patch[*f];
            }
            out.push_back(patch);
        }
        // An edge between two columns of a plane node's fan (one input node) lies in the plane
        // of the loop's edges on either side: the next edge's patch.
        const std::size_t first = out.size() - static_cast<std::size_t>(m);
        const Index* lv = w.loops.row_begin(l);
        for (Index i = m; i-- > 0;) {
            const Index ia = w.input_node[static_cast<std::size_t>(lv[i])];
            if (ia == w.input_node[static_cast<std::size_t>(lv[(i + 1) % m])])
                out[first + static_cast<std::size_t>(i)] = out[first + static_cast<std::size_t>((i + 1) % m)];
        }
    }
    return out;
}

/// The settings extrude_layers checks before any work: an InputError naming the first out of range.
void check_layer_params(const LayerParams& params) {
    check_threads(params.threads, "LayerParams::threads");
    if (params.sweeps < 0)
        throw InputError("LayerParams::sweeps = " + std::to_string(params.sweeps) +
                         ": need 0 or more sweeps per layer");
    if (!(params.min_quality >= 0.0 && params.min_quality < 1.0))
        throw InputError("LayerParams::min_quality = " + format_number(params.min_quality) +
                         ": need a scaled Jacobian in [0, 1) (0: no local stopping)");
    if (!(params.max_turn_deg > 0.0))
        throw InputError("LayerParams::max_turn_deg = " + format_number(params.max_turn_deg) +
                         ": need an angle above 0 degrees");
    if (!(params.max_twist_deg > 0.0 && params.max_twist_deg <= 180.0))
        throw InputError("LayerParams::max_twist_deg = " + format_number(params.max_twist_deg) +
                         ": need an angle above 0 and at most 180 degrees");
    if (!(params.sharp_edge_stop_deg >= 0.0 && params.sharp_edge_stop_deg <= 180.0))
        throw InputError("LayerParams::sharp_edge_stop_deg = " + format_number(params.sharp_edge_stop_deg) +
                         ": need an angle in [0, 180] degrees (0: never stop there)");
    if (!(params.proximity_limits.front_slope > 0.0 && std::isfinite(params.proximity_limits.front_slope)))
        throw InputError("ProximityParams::front_slope = " + format_number(params.proximity_limits.front_slope) +
                         ": need a thickness per unit of wall distance above 0");
    if (!(params.isotropy >= 0.0 && std::isfinite(params.isotropy)))
        throw InputError("LayerParams::isotropy = " + format_number(params.isotropy) +
                         ": need a ratio of layer height to front spacing of 0 or more (0: never stop for it)");
    if (!(params.fan_angle_deg >= 0.0 && params.fan_angle_deg <= 180.0))
        throw InputError("LayerParams::fan_angle_deg = " + format_number(params.fan_angle_deg) +
                         ": need an angle in [0, 180] degrees (0: no fans)");
}

/// The columns whose layers are capped (Marcher::cap) march as if they were not, so that the
/// front and the smoothing round them are what they would be had each stopped where its capped
/// layers end (a front round's bound is what that many layers add up to); their nodes are
/// placed along that path, level k where the heights of the capped layers below it add up to,
/// at the same place on the path as the asked heights put it.
class CappedPaths {
public:
    CappedPaths(const Marcher& mc, const std::vector<double>& delta) {
        const int layers = mc.params.distribution.layers;
        reach_ = capped_reach(delta, layers, std::numeric_limits<double>::infinity());
        for (std::size_t i = 0; i < mc.cap.size(); ++i) {
            if (!mc.capped(i)) continue;
            nodes_.push_back(static_cast<Index>(i));
            path_.push_back({mc.wall.points[i]});
            at_.push_back(capped_reach(delta, layers, mc.cap[i]));
        }
    }

    /// Level \p k + 1 as marched (\p r1), with the capped columns' nodes where they are placed.
    const std::vector<Vec3>& place(int k, const std::vector<Vec3>& r1) {
        if (nodes_.empty()) return r1;
        placed_ = r1;
        for (std::size_t c = 0; c < nodes_.size(); ++c) {
            const auto i = static_cast<std::size_t>(nodes_[c]);
            std::vector<Vec3>& path = path_[c];
            path.push_back(r1[i]);
            const double s = at_[c][static_cast<std::size_t>(k) + 1];
            std::size_t j = 0;
            while (j + 2 < path.size() && reach_[j + 1] <= s) ++j;
            const double t = std::clamp((s - reach_[j]) / (reach_[j + 1] - reach_[j]), 0.0, 1.0);
            placed_[i] = path[j] + t * (path[j + 1] - path[j]);
        }
        return placed_;
    }

private:
    std::vector<double> reach_;               ///< the sums of the heights asked, k = 0, ..., layers
    std::vector<Index> nodes_;                ///< the capped wall nodes
    std::vector<std::vector<Vec3>> path_;     ///< per capped node, its positions as marched, level by level
    std::vector<std::vector<double>> at_;     ///< per capped node, the sums of its capped heights
    std::vector<Vec3> placed_;
};


/// Steps 1 to 4 of every layer over the columns \p col (extrude_layers): each level's moving
/// nodes appended to \p out's points, its stats, and the nodes held back. Where a fan's first
/// cells would be unusable, the layers marched again without it instead.
std::optional<LayerMesh> march_levels(const SurfaceMesh& surface, const Wall& w, const Marcher& mc,
                                      const LayerConstraints& constraints, const std::vector<double>& delta,
                                      const StopRules& rules, Columns& col, LayerMesh& out, Progress* progress) {
    const LayerParams& params = mc.params;
    const int layers = params.distribution.layers;
    const Index nw = w.mesh.num_points();
    const bool holds =
        params.hold_back && params.smoothing && std::max(params.max_sweeps, params.sweeps) > 0 && !params.keep_invalid;
    std::vector<Vec3> r0 = w.mesh.points, r1(r0.size());
    std::vector<char> held(static_cast<std::size_t>(nw));
    out.stats.assign(static_cast<std::size_t>(layers), LayerStats{});
    CappedPaths capped(mc, delta);
    SmoothedLevels* smoothed = constraints.smoothed.get();
    if (smoothed) smoothed->begin(smoothing_key(mc, delta));
    for (int k = 0; k < layers; ++k) {
        const double dk = delta[static_cast<std::size_t>(k)], dk1 = delta[static_cast<std::size_t>(k) + 1];
        LayerStats& stats = out.stats[static_cast<std::size_t>(k)];
        stats.height = dk;
        if (std::none_of(col.active.begin(), col.active.end(), [](char a) { return a != 0; })) continue;
        // 1. The locally orthogonal reference mesh: level 1 along the normals (level 2 in step 2).
        const std::vector<Vec3> n0 = reference_level(mc, r0, dk, r1);
        // 2. Poisson smoothing of level 1 over every node (stopped ones as ghosts); where its
        // cells would still invert, hold it back.
        stats.sweeps = smoothed ? smoothed->smooth(k, mc, r0, dk, dk1, r1) : smooth_level(mc, r0, dk, dk1, r1);
        std::fill(held.begin(), held.end(), 0);
        // 3. The columns whose cells are usable go on to level k + 1, the others stop. Stopping
        // off: every column goes on (but for limits), held back where it would fold.
        if (!rules.quality) {
            if (holds) hold_back_folds(mc, r0, dk, r1, held);
            check_folds(w, params, k, col, r1);
        }
        const std::vector<Vec3>& placed = capped.place(k, r1);
        stats.stopped_nodes = stop_columns(col, rules, k, placed);
        if (k == 0 && std::find(col.pinned.begin(), col.pinned.end(), 2) != col.pinned.end()) {
            // A fan whose first cells would be unusable (a needle face beside it, a gap
            // narrower than the first layer): no fan at those wall nodes, and march again.
            std::vector<Index> unusable;
            for (Index i = 0; i < nw; ++i)
                if (col.pinned[static_cast<std::size_t>(i)] == 2)
                    unusable.push_back(w.input_node[static_cast<std::size_t>(i)]);
            if (auto retry = without_fans(surface, params, constraints, unusable, &LayerMesh::fans_dropped, progress))
                return retry;
        }
        col.pinned.clear();
        for (Index i = 0; i < nw; ++i) {
            const auto u = static_cast<std::size_t>(i);
            if (col.levels[u] != k + 1) continue;
            out.mesh.points.push_back(placed[u]);
            if (held[u]) out.held_back[u] = 1, ++stats.held_nodes;
        }
        if (rules.quality && holds) {
            // The stopped columns' ghosts are held back where they would fold, so the level the
            // next layer starts from stays sound; the moving ones keep what was judged.
            const std::vector<Vec3> judged = r1;
            hold_back_folds(mc, r0, dk, r1, held);
            for (Index i = 0; i < nw; ++i)
                if (col.levels[static_cast<std::size_t>(i)] == k + 1)
                    r1[static_cast<std::size_t>(i)] = judged[static_cast<std::size_t>(i)];
        }
        layer_orthogonality(col, k, r0, r1, n0, stats);
        // 4. Level 1 becomes the wall of the next layer (for every node: the ghosts march on).
        std::swap(r0, r1);
        report(progress, "layers", static_cast<double>(k + 1) / layers);
    }
    return std::nullopt;
}

/// The layers marched again with each column that stopped for its own cells or a neighbour's
/// step (quality, turning, twist, neighbours) bounded to the thickness of the layers it reached
/// (LayerConstraints::node_stop_limit): marching as before, it keeps every layer up to where it
/// stopped, its tallest layers capped (CappedPaths), where that many layers fit at least at the
/// first height (height_cap). Up to kStopMarches times; empty after those, where proximity
/// limits scale or where no column stopped lower than its bound.
std::optional<LayerMesh> capped_at_stops(const SurfaceMesh& surface, const LayerParams& params,
                                         const LayerConstraints& constraints, const Wall& w, const Columns& col,
                                         const std::vector<double>& delta, Progress* progress) {
    const int layers = params.distribution.layers;
    const std::vector<double> reach = capped_reach(delta, layers, std::numeric_limits<double>::infinity());
    std::vector<CapAt> caps;
    for (std::size_t i = 0; i < col.levels.size(); ++i) {
        const int m = col.levels[i];
        const Shortfall why = col.reason[i];
        const bool own = why == Shortfall::Quality || why == Shortfall::Turning || why == Shortfall::Twist ||
                         why == Shortfall::Neighbours;
        if (!own || m <= 0 || m >= layers || height_cap(delta, layers, reach[static_cast<std::size_t>(m)]) == 0.0)
            continue;
        caps.push_back({w.input_node[i], m, why});
    }
    return march_capped(surface, params, constraints, caps, delta, progress);
}

/// The normal of the symmetry or outflow plane each of \p mc's columns is held in (zero: none).
std::vector<Vec3> held_plane_normals(const Marcher& mc) {
    std::vector<Vec3> normal(mc.node_plane.size(), Vec3::Zero());
    for (std::size_t i = 0; i < normal.size(); ++i)
        if (mc.node_plane[i] != kNone) normal[i] = mc.planes[mc.node_plane[i]].normal;
    return normal;
}

/// The columns of \p w that stop at the wall (1): on a sharp edge without a fan
/// (LayerParams::sharp_edge_stop_deg, ALGORITHM.md) and at a fan's end at a junction (fans.h).
std::vector<char> wall_stops(const Wall& w, const FanWall& fans, const LayerParams& params,
                             const std::vector<Vec3>& plane_normal) {
    std::vector<char> stops(static_cast<std::size_t>(w.mesh.num_points()), 0);
    if (fans_on(params) && params.sharp_edge_stop_deg > 0.0)
        stops = sharp_single_nodes(w.mesh, plane_normal, params.sharp_edge_stop_deg);
    for (const Index t : fans.terminals) stops[static_cast<std::size_t>(t)] = 1;
    return stops;
}

}  // namespace

bool LayerConstraints::bar_fan(Index v, std::size_t nodes) {
    if (no_fan_nodes.empty()) no_fan_nodes.assign(nodes, 0);
    char& no = no_fan_nodes[static_cast<std::size_t>(v)];
    const bool was = no != 0;
    no = 1;
    return !was;
}

std::string_view to_string(ProximityMode mode) {
    return kProximityModeNames.name(mode);
}

ProximityMode parse_proximity_mode(std::string_view text) {
    return kProximityModeNames.parse(text, "LayerParams::proximity");
}

ProximityPlan proximity_plan(const SurfaceMesh& surface, const LayerParams& params,
                             const LayerConstraints& constraints) {
    check_threads(params.threads, "LayerParams::threads");
    const std::vector<double> delta = layer_heights(params.distribution);
    Wall w = extract_wall(surface);
    const FanWall fans = add_fans(surface, params, constraints.no_fan_nodes, w);
    std::vector<Shortfall> reason;
    std::vector<int> max_levels(static_cast<std::size_t>(w.mesh.num_points()), params.distribution.layers);
    make_marcher(surface, w, fans, params, constraints, delta, reason, max_levels, true);
    ProximityPlan plan;
    plan.levels.assign(surface.points.size(), params.distribution.layers);
    plan.proximity.assign(surface.points.size(), 0);
    for (std::size_t i = 0; i < max_levels.size(); ++i) {  // a fan's columns: their wall node's lowest
        const auto v = static_cast<std::size_t>(w.input_node[i]);
        plan.levels[v] = std::min(plan.levels[v], max_levels[i]);
        if (max_levels[i] < params.distribution.layers && reason[i] == Shortfall::Proximity) plan.proximity[v] = 1;
    }
    // A strip quad of a fan is (b's column, a's column, a's next column, b's next column)
    // (fans.cpp); a corner's polygon has one wall node and no wedge along an edge.
    for (Index f = 0; f < w.mesh.num_faces(); ++f) {
        if (fans.fan_face.empty() || !fans.fan_face[static_cast<std::size_t>(f)] || w.mesh.face_size(f) != 4) continue;
        const Index* c = w.mesh.face_begin(f);
        const auto base = [&](int k) { return fans.base[static_cast<std::size_t>(c[k])]; };
        if (base(0) == base(1) || base(1) != base(2) || base(0) != base(3)) continue;
        plan.fan_wedges.push_back(
            {w.input_node[static_cast<std::size_t>(base(1))], w.input_node[static_cast<std::size_t>(base(0))],
             fans.direction[static_cast<std::size_t>(c[1])], fans.direction[static_cast<std::size_t>(c[2])]});
    }
    return plan;
}

LayerMesh extrude_layers(const SurfaceMesh& surface, const LayerParams& params, const LayerConstraints& constraints,
                         Progress* progress) {
    if (!constraints.smoothed) {  // one store for this call's stop marches
        LayerConstraints shared = constraints;
        shared.smoothed = make_smoothed_levels();
        return extrude_layers(surface, params, shared, progress);
    }
    const std::vector<double> delta = layer_heights(params.distribution);
    check_layer_params(params);
    Wall w = extract_wall(surface);
    const Index nwall = w.mesh.num_points();
    FanWall fans = add_fans(surface, params, constraints.no_fan_nodes, w);
    const int layers = params.distribution.layers;
    double thickness = 0.0;
    for (int k = 0; k < layers; ++k) thickness += delta[static_cast<std::size_t>(k)];
    std::vector<Shortfall> scale_reason;
    const Index nw = w.mesh.num_points();
    LayerMesh out(nw, layers);
    std::vector<int> max_levels(static_cast<std::size_t>(nw), layers);
    const Marcher mc = make_marcher(surface, w, fans, params, constraints, delta, scale_reason, max_levels);
    // Columns held in a symmetry or outflow plane are judged by what a direction in it allows.
    const std::vector<Vec3> plane_normal = held_plane_normals(mc);
    Columns col(w.mesh, layers, out.mesh.points, plane_normal, mc.node_line);
    col.max_levels = std::move(max_levels);
    if (params.isotropy > 0.0) col.find_edges(w.mesh);
    if (!fans.empty()) {
        // A fan's columns start at their wall node, and each gets its first layer.
        for (Index i = nwall; i < nw; ++i)
            col.point[static_cast<std::size_t>(i)] = fans.base[static_cast<std::size_t>(i)];
        col.pinned.assign(static_cast<std::size_t>(nw), 0);
        for (Index i = 0; i < nw; ++i)
            col.pinned[static_cast<std::size_t>(i)] = fans.direction[static_cast<std::size_t>(i)] != Vec3::Zero();
        out.fan_edges = fans.fan_edges, out.fan_nodes = fans.fan_nodes, out.fan_corners = fans.corners;
        out.fan_plane_nodes = fans.plane_nodes;
        out.fan_column = col.pinned;
    }
    for (const auto& [i, why] : fans.unfanned)
        out.fans_unclosed.push_back(
            {w.input_node[static_cast<std::size_t>(i)], w.mesh.points[static_cast<std::size_t>(i)], why});
    out.input_node = w.input_node;
    for (Index i = 0; i < nw; ++i) out.unsmoothed_nodes += mc.st.valid[i] ? 0 : 1;
    out.asked_thickness = thickness;
    out.held_back.assign(static_cast<std::size_t>(nw), 0);
    out.height_scale = thickness_shares(mc, delta, thickness);
    for (Index i = 0; i < nw; ++i) {
        const auto u = static_cast<std::size_t>(i);
        if (col.max_levels[u] < layers) col.limit[u] = scale_reason[u];  // Stop mode: the levels say it
        if (col.max_levels[u] < layers) scale_reason[u] = Shortfall::None;
        const double share = out.height_scale[u];
        if (share < 1.0) ++out.thinned_nodes;
        out.min_thickness_share = std::min(out.min_thickness_share, share);
    }
    const std::vector<char> stops = wall_stops(w, fans, params, plane_normal);
    for (std::size_t u = 0; u < stops.size(); ++u)
        if (stops[u]) {
            col.max_levels[u] = 0;
            col.limit[u] = Shortfall::SharpEdge;
            scale_reason[u] = Shortfall::None;
        }
    out.scale_reason = std::move(scale_reason);
    out.mesh.points.reserve(static_cast<std::size_t>(nw) * static_cast<std::size_t>(layers + 1));
    out.mesh.points.insert(out.mesh.points.end(), w.mesh.points.begin(), w.mesh.points.begin() + nwall);
    report(progress, "layers", 0.0);

    // Stopping: on unless turned off (min_quality 0) or for diagnostics (keep_invalid).
    const StopRules rules{params.min_quality,
                          params.max_turn_deg,
                          params.max_twist_deg,
                          params.isotropy,
                          params.min_quality > 0.0 && !params.keep_invalid,
                          mc.threads};
    if (auto retry = march_levels(surface, w, mc, constraints, delta, rules, col, out, progress))
        return std::move(*retry);
    if (std::all_of(col.levels.begin(), col.levels.end(), [](int l) { return l == 0; })) throw_no_layers(w, col);
    if (rules.quality)
        if (auto again = capped_at_stops(surface, params, constraints, w, col, delta, progress)) return std::move(*again);
    out.set_columns(col.levels, fans.empty() ? std::vector<Index>{} : fans.base);
    out.stop_reason.assign(static_cast<std::size_t>(nw), Shortfall::None);
    for (Index i = 0; i < nw; ++i)
        if (col.levels[static_cast<std::size_t>(i)] < layers)
            out.stop_reason[static_cast<std::size_t>(i)] = col.reason[static_cast<std::size_t>(i)];
    build_layer_cells(col, w.mesh, w.loops, side_patches(surface, w), out);
    out.mesh.cell_layers = layer_of_cells(out);
    if (!fans.empty() && rules.quality) {
        // Fans whose cells have faces checkMesh would fail as skewed: no fan at those wall
        // nodes, and march again (each round marks new nodes, so this ends). Other columns
        // under such faces: cap_skewed_columns, where the whole mesh has them.
        if (auto retry = without_fans(surface, params, constraints, skewed_layers(out, mc.threads, true).fan_nodes,
                                      &LayerMesh::fans_skewed, progress))
            return std::move(*retry);
    }
    out.stop_limit = constraints.node_stop_limit, out.stop_limit_reason = constraints.node_stop_reason;
    out.stop_marches = constraints.stop_marches;
    return out;
}

std::vector<std::int32_t> layer_of_cells(const LayerMesh& lm) {
    std::vector<std::int32_t> layers;
    layers.reserve(static_cast<std::size_t>(lm.mesh.num_cells()));
    for (const CellType t : kCellTypes)
        for (std::size_t i = 0; i < lm.mesh.num_cells(t); ++i) {
            const Index* c = lm.mesh.cell(t, i);
            int level = 0;
            for (int k = 0; k < cell_corners(t); ++k) level = std::max(level, lm.level_of(c[k]));
            layers.push_back(level);
        }
    return layers;
}

LayerMesh extrude_layers(const SurfaceMesh& surface, const LayerParams& params, Progress* progress) {
    return extrude_layers(surface, params, LayerConstraints{}, progress);
}

bool cap_skewed_columns(const LayerMesh& lm, const LayerParams& params, std::size_t nodes,
                        LayerConstraints& constraints, int threads) {
    if (params.proximity != ProximityMode::Stop) return false;
    const std::vector<CapAt> caps = skewed_layers(lm, threads, false).columns;
    const std::vector<double> reach = capped_reach(layer_heights(params.distribution), params.distribution.layers,
                                                   std::numeric_limits<double>::infinity());
    return lower_stop_limits(caps, reach, nodes, constraints);
}

LayerReport layer_report(const LayerMesh& lm) {
    LayerReport r;
    r.layers = lm.layers();
    r.first_height = lm.stats.empty() ? 0.0 : lm.stats.front().height;
    r.thickness = lm.asked_thickness;
    const Index nw = lm.wall_nodes();
    // Thickness reached: the length of each column; why it fell short: it stopped, else it
    // was held back, else it was thinned. A wall node with a fan (several columns) counts once,
    // as its shortest column.
    std::vector<double> share(static_cast<std::size_t>(nw), 1.0);
    std::vector<int> levels(static_cast<std::size_t>(nw), lm.layers());
    std::vector<Shortfall> why(static_cast<std::size_t>(nw), Shortfall::None);
    std::vector<char> proximity(static_cast<std::size_t>(nw), 0);  // a column of it stopped or thinned for that
    auto base = [&](Index i) { return lm.level_node(0, i); };      // the wall node a column starts at
    for (Index i = 0; i < nw; ++i) {
        double length = 0.0;
        for (int k = 0; k < lm.node_layers(i); ++k)
            length += (lm.mesh.points[lm.level_node(k + 1, i)] - lm.mesh.points[lm.level_node(k, i)]).norm();
        const auto u = static_cast<std::size_t>(i);
        Shortfall w = Shortfall::None;
        if (u < lm.stop_reason.size() && lm.stop_reason[u] != Shortfall::None)
            w = lm.stop_reason[u];
        else if (u < lm.held_back.size() && lm.held_back[u])
            w = Shortfall::HeldBack;
        else if (u < lm.scale_reason.size())
            w = lm.scale_reason[u];
        const auto b = static_cast<std::size_t>(base(i));
        if (w == Shortfall::Proximity || (u < lm.scale_reason.size() && lm.scale_reason[u] == Shortfall::Proximity))
            proximity[b] = 1;
        const double s = r.thickness > 0.0 ? length / r.thickness : 1.0;
        if (b == u || lm.node_layers(i) < levels[b] || (lm.node_layers(i) == levels[b] && s < share[b])) {
            levels[b] = lm.node_layers(i);
            share[b] = s;
            if (w != Shortfall::None || b == u) why[b] = w;
        }
    }
    for (Index i = 0; i < nw; ++i) {
        const auto u = static_cast<std::size_t>(i);
        if (base(i) != i || why[u] == Shortfall::None) continue;
        r.short_nodes.push_back(
            {lm.input_node.empty() ? i : lm.input_node[u], lm.mesh.points[base(i)], share[u], levels[u], why[u]});
    }
    for (const auto& [dropped, reason] :
         {std::pair{&lm.fans_dropped, NoFan::Unusable}, std::pair{&lm.fans_skewed, NoFan::Skewed}}) {
        if (dropped->empty()) continue;
        std::vector<Index> wall_of(dropped->size(), kNone);  // a wall node of each
        for (Index i = 0; i < nw; ++i) {
            const Index v = lm.input_node.empty() ? i : lm.input_node[static_cast<std::size_t>(i)];
            const auto it = std::lower_bound(dropped->begin(), dropped->end(), v);
            if (it != dropped->end() && *it == v) wall_of[static_cast<std::size_t>(it - dropped->begin())] = i;
        }
        for (std::size_t j = 0; j < wall_of.size(); ++j)
            if (wall_of[j] != kNone) r.no_fan.push_back({(*dropped)[j], lm.mesh.points[base(wall_of[j])], reason});
    }
    r.no_fan.insert(r.no_fan.end(), lm.fans_unclosed.begin(), lm.fans_unclosed.end());
    std::stable_sort(r.no_fan.begin(), r.no_fan.end(),
                     [](const NoFanNode& a, const NoFanNode& b) { return a.node < b.node; });
    // Per patch of the wall: its faces, and its nodes once each.
    const SurfaceMesh& wall = lm.top;
    r.patches.resize(wall.patches.size());
    for (std::size_t p = 0; p < wall.patches.size(); ++p) r.patches[p].name = wall.patches[p].name;
    std::vector<std::pair<Index, Index>> patch_node;  // (patch, node), then sorted and unique
    for (Index f = 0; f < wall.num_faces(); ++f) {
        // A face of a fan has its nodes' columns start at one wall node: no face of the wall.
        bool fan = false;
        for (const Index* v = wall.face_begin(f); v != wall.face_end(f); ++v)
            fan |= base(*v) == base(*(v + 1 == wall.face_end(f) ? wall.face_begin(f) : v + 1));
        if (!fan) ++r.patches[static_cast<std::size_t>(wall.face_patch[f])].faces;
        for (const Index* v = wall.face_begin(f); v != wall.face_end(f); ++v)
            patch_node.emplace_back(wall.face_patch[f], base(*v));
    }
    std::sort(patch_node.begin(), patch_node.end());
    patch_node.erase(std::unique(patch_node.begin(), patch_node.end()), patch_node.end());
    const auto node = [&](Index i) {
        const auto u = static_cast<std::size_t>(i);
        return NodeCoverage{share[u], levels[u], why[u], proximity[u] != 0};
    };
    std::vector<std::vector<NodeCoverage>> patch_nodes(wall.patches.size());
    std::vector<char> on_wall(static_cast<std::size_t>(nw), 0);
    for (const auto& [patch, i] : patch_node) {
        patch_nodes[static_cast<std::size_t>(patch)].push_back(node(i));
        on_wall[static_cast<std::size_t>(i)] = 1;
    }
    std::vector<NodeCoverage> wall_nodes;
    for (Index i = 0; i < nw; ++i)
        if (on_wall[static_cast<std::size_t>(i)]) wall_nodes.push_back(node(i));
    Index faces = 0;
    for (std::size_t p = 0; p < r.patches.size(); ++p) {
        r.patches[p] = coverage_of(r.patches[p].name, r.patches[p].faces, patch_nodes[p], lm.layers());
        faces += r.patches[p].faces;
    }
    r.wall = coverage_of("wall", faces, wall_nodes, lm.layers());
    // Patches without wall faces (the wall's own table lists them all) are left out.
    r.patches.erase(
        std::remove_if(r.patches.begin(), r.patches.end(), [](const PatchCoverage& c) { return c.faces == 0; }),
        r.patches.end());
    return r;
}

}  // namespace strata
