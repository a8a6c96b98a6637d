// OpenFOAM checkMesh's figures: solver_checks.h. The formulas follow OpenFOAM v1912
// (primitiveMeshFaceCentresAndAreas, primitiveMeshCellCentresAndVols, primitiveMeshTools::
// faceOrthogonality, faceSkewness, boundaryFaceSkewness, cellClosedness, facePyramidVolume).

#include <strata/core/cell_faces.h>
#include <strata/core/format.h>
#include <strata/core/parallel.h>
#include <strata/core/solver_checks.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

namespace strata {
namespace {

constexpr double kRootVSmall = 1e-150;  // OpenFOAM's ROOTVSMALL (double)
constexpr std::int64_t kChunk = 1 << 14;

struct FaceGeometry {
    Vec3 centre = Vec3::Zero();
    Vec3 area = Vec3::Zero();  ///< area vector, the node order's right-hand normal
};

/// A face's centre and area vector as OpenFOAM computes them: triangles from each edge to the
/// mean of the corners, the centre their area-weighted centroid.
FaceGeometry face_geometry(const Vec3* p, const Index* v, int n) {
    Vec3 mean = Vec3::Zero();
    for (int i = 0; i < n; ++i) mean += p[static_cast<std::size_t>(v[i])];
    mean /= static_cast<double>(n);
    Vec3 sum_n = Vec3::Zero(), sum_ac = Vec3::Zero();
    double sum_a = 0.0;
    for (int i = 0; i < n; ++i) {
        const Vec3& a = p[static_cast<std::size_t>(v[i])];
        const Vec3& b = p[static_cast<std::size_t>(v[(i + 1) % n])];
        const Vec3 nn = (b - a).cross(mean - a);
        const double m = nn.norm();
        sum_n += nn;
        sum_a += m;
        sum_ac += m * (a + b + mean);
    }
    if (sum_a < kRootVSmall) return {mean, Vec3::Zero()};
    return {sum_ac / (3.0 * sum_a), 0.5 * sum_n};
}

/// A cell's centre as OpenFOAM computes it from its \p count faces \p fg (outward): the
/// volume-weighted centroid of the pyramids from each face to the mean of the face centres;
/// \p mag the summed absolute area components, \p vol3 three times the volume.
Vec3 cell_centre(const std::array<FaceGeometry, 6>& fg, int count, Vec3& mag, double& vol3) {
    Vec3 est = Vec3::Zero();
    for (int i = 0; i < count; ++i) est += fg[static_cast<std::size_t>(i)].centre;
    est /= static_cast<double>(count);
    Vec3 sum_c = Vec3::Zero();
    mag = Vec3::Zero();
    vol3 = 0.0;
    for (int i = 0; i < count; ++i) {
        const FaceGeometry& f = fg[static_cast<std::size_t>(i)];
        const double pyr3 = f.area.dot(f.centre - est);
        sum_c += pyr3 * (0.75 * f.centre + 0.25 * est);
        vol3 += pyr3;
        mag += f.area.cwiseAbs();
    }
    return std::abs(vol3) > kRootVSmall ? Vec3(sum_c / vol3) : est;
}

/// checkMesh's skewness of face \p f (corners \p v of \p p) between the cells centred at \p co
/// and \p cn (faceSkewness), or of a boundary face of the cell at \p co (\p cn null:
/// boundaryFaceSkewness, the neighbour's centre taken as the owner's mirror in the face).
double skewness_of(const Vec3* p, const Index* v, int n, const FaceGeometry& f, const Vec3& co, const Vec3* cn) {
    auto extent = [&](const Vec3& dir) {
        double e = 0.0;
        for (int i = 0; i < n; ++i) e = std::max(e, std::abs(dir.dot(p[static_cast<std::size_t>(v[i])] - f.centre)));
        return e;
    };
    const Vec3 cpf = f.centre - co;
    Vec3 d;
    double near;  // the distance under which the centres count as close: checkMesh's 0.2 |d|, 0.4 |d| at the boundary
    if (cn) {
        d = *cn - co;
        near = 0.2 * d.norm();
    } else {
        const Vec3 nrm = f.area / (f.area.norm() + kRootVSmall);
        d = nrm * nrm.dot(cpf);
        near = 0.4 * d.norm();
    }
    const Vec3 sv = cpf - (f.area.dot(cpf) / (f.area.dot(d) + kRootVSmall)) * d;
    const double m = sv.norm();
    return m / std::max(near + kRootVSmall, extent(sv / (m + kRootVSmall)));
}

/// The pyramid from a face (outward area \p area, centre \p fc) to a cell centre \p cc is
/// inverted: below checkMesh's -1e-15.
bool inverted_pyramid(const Vec3& area, const Vec3& fc, const Vec3& cc) {
    return area.dot(fc - cc) / 3.0 < -1e-15;
}

std::string cell_name(const FaceSlots& slots, std::uint64_t slot) {
    const FaceSlots::Slot s = slots.locate(slot);
    return std::string(to_string(s.type)) + " " + std::to_string(s.index);
}

/// Per chunk of face slots: the largest values (the first face that has each) and the sums.
struct Partial {
    double min_cos = 2.0, max_skew = -1.0, sum_cos = 0.0;
    std::uint64_t worst_ortho = 0, worst_skew = 0, first_pyramid = 0;
    bool has_ortho = false, has_skew = false, has_pyramid = false;
    Index faces = 0, severe = 0, errors = 0, skew = 0, pyramids = 0;
    std::vector<std::uint64_t> skewed;  ///< the slots of the faces above kFoamSkewness, if asked
};

}  // namespace

std::vector<std::string> SolverChecks::failures() const {
    std::vector<std::string> out;
    if (skew_faces > 0)
        out.push_back(std::to_string(skew_faces) + " faces with a skewness above " + format_number(kFoamSkewness) +
                      ", the worst " + format_number(max_skewness, 3) + " (" + worst_skew + ")");
    if (high_aspect_cells > 0)
        out.push_back(std::to_string(high_aspect_cells) + " cells with an aspect ratio above " +
                      format_number(kFoamAspectRatio) + ", the worst " + format_number(max_aspect_ratio, 4) + " (" +
                      worst_aspect + ")" +
                      (worst_aspect_type == CellType::Tet
                           ? std::string()
                           : ": layer cells lower than a thousandth of their wall face; a finer surface or a "
                             "thicker first layer lowers it"));
    if (non_orthogonality_errors > 0)
        out.push_back(std::to_string(non_orthogonality_errors) + " faces at 90 degrees or more of non-orthogonality (" +
                      worst_non_orthogonal + ")");
    if (negative_pyramids > 0)
        out.push_back(std::to_string(negative_pyramids) + " faces whose pyramid to a cell centre is inverted (" +
                      worst_pyramid + ")");
    if (unused_points > 0)
        out.push_back(std::to_string(unused_points) + " points used by no cell (the first " + first_unused + ")");
    return out;
}

namespace {

/// checkMesh's aspect ratio from a cell's summed absolute face-area components and its volume
/// (primitiveMeshTools::cellClosedness).
double aspect_ratio_of(const Vec3& mag, double volume) {
    const double v = std::max(kRootVSmall, volume);
    return std::max(mag.maxCoeff() / (mag.minCoeff() + kRootVSmall), mag.sum() / 6.0 / std::pow(v, 2.0 / 3.0));
}

}  // namespace

double fan_wedge_aspect_ratio(const Vec3& a, const Vec3& b, const Vec3& d1, const Vec3& d2, double h) {
    const Vec3 e = b - a, p1 = h * d1, p2 = h * d2;
    const Vec3 end = 0.5 * p1.cross(p2);  // each end triangle's area vector
    // The ends, the two sides along the directions and the outer side.
    const Vec3 mag =
        2.0 * end.cwiseAbs() + e.cross(p1).cwiseAbs() + e.cross(p2).cwiseAbs() + e.cross(p2 - p1).cwiseAbs();
    const double volume = std::abs(end.dot(e));
    if (!(volume > 0.0)) return std::numeric_limits<double>::infinity();
    return aspect_ratio_of(mag, volume);
}

double right_prism_aspect_ratio(const Vec3* corners, int n, double h) {
    Vec3 c = Vec3::Zero();
    for (int i = 0; i < n; ++i) c += corners[i];
    c /= static_cast<double>(n);
    Vec3 area = Vec3::Zero();
    for (int i = 0; i < n; ++i) area += 0.5 * (corners[i] - c).cross(corners[(i + 1) % n] - c);
    const double a = area.norm();
    if (!(a > 0.0) || !(h > 0.0)) return std::numeric_limits<double>::infinity();
    const Vec3 normal = area / a;
    // The same sums as a cell's in solver_checks: the bottom and top faces, then the sides.
    Vec3 mag = 2.0 * area.cwiseAbs();
    for (int i = 0; i < n; ++i) mag += (h * (corners[(i + 1) % n] - corners[i]).cross(normal)).cwiseAbs();
    return aspect_ratio_of(mag, a * h);
}

double leaning_prism_aspect_ratio(const Vec3* corners, const Vec3* directions, int n, double h) {
    if (n < 3 || n > 4 || !(h > 0.0)) return std::numeric_limits<double>::infinity();
    std::array<Vec3, 4> top;
    for (int i = 0; i < n; ++i) top[static_cast<std::size_t>(i)] = corners[i] + h * directions[i];
    // Each face's area vector (a polygon's from its centroid; a quad's is half its diagonals'
    // cross product either way) and centroid, oriented out of the cell: the volume by the
    // divergence theorem, checkMesh's sums of their components.
    auto polygon = [n](const Vec3* x, Vec3& centre) {
        centre = Vec3::Zero();
        for (int i = 0; i < n; ++i) centre += x[i];
        centre /= static_cast<double>(n);
        Vec3 a = Vec3::Zero();
        for (int i = 0; i < n; ++i) a += 0.5 * (x[i] - centre).cross(x[(i + 1) % n] - centre);
        return a;
    };
    Vec3 cb, ct;
    const Vec3 bottom = polygon(corners, cb), up = polygon(top.data(), ct);
    Vec3 mag = bottom.cwiseAbs() + up.cwiseAbs();
    // s = 1 when the corners run counter-clockwise seen from the top (the bottom's area vector
    // points into the cell); the outward area vectors are then -bottom, up and the sides'.
    const double s = bottom.dot(ct - cb) > 0.0 ? 1.0 : -1.0;
    double three_volume = s * (up.dot(ct) - bottom.dot(cb));
    for (int i = 0; i < n; ++i) {
        const Vec3 &a = corners[i], &b = corners[(i + 1) % n];
        const Vec3 &c = top[static_cast<std::size_t>((i + 1) % n)], &d = top[static_cast<std::size_t>(i)];
        const Vec3 side = 0.5 * (c - a).cross(d - b);  // of a-b-c-d, outward when s = 1
        mag += side.cwiseAbs();
        three_volume += s * side.dot(0.25 * (a + b + c + d));
    }
    const double volume = three_volume / 3.0;
    if (!(volume > 0.0)) return std::numeric_limits<double>::infinity();
    return aspect_ratio_of(mag, volume);
}

namespace {

/// The faces' geometry (into \p fg) of a cell with the corners \p corners and the faces \p t,
/// and its centre as OpenFOAM computes it.
Vec3 faces_and_centre(const Vec3* corners, const CellFaceTable& t, std::array<FaceGeometry, 6>& fg) {
    for (int f = 0; f < t.count; ++f) {
        Index v[4];
        for (int c = 0; c < t.size[static_cast<std::size_t>(f)]; ++c)
            v[c] = static_cast<Index>(t.node[static_cast<std::size_t>(f)][static_cast<std::size_t>(c)]);
        fg[static_cast<std::size_t>(f)] = face_geometry(corners, v, t.size[static_cast<std::size_t>(f)]);
    }
    Vec3 mag;
    double vol3 = 0.0;
    return cell_centre(fg, t.count, mag, vol3);
}

}  // namespace

bool face_pyramids_inverted(const Vec3* corners, CellType type) {
    const CellFaceTable& t = cell_faces(type);
    std::array<FaceGeometry, 6> fg;
    const Vec3 cc = faces_and_centre(corners, t, fg);
    for (int f = 0; f < t.count; ++f)
        if (inverted_pyramid(fg[static_cast<std::size_t>(f)].area, fg[static_cast<std::size_t>(f)].centre, cc))
            return true;
    return false;
}

Vec3 foam_cell_centre(const Vec3* corners, CellType type) {
    std::array<FaceGeometry, 6> fg;
    return faces_and_centre(corners, cell_faces(type), fg);
}

double face_skewness(const Vec3* p, const Index* v, int n, const Vec3& owner, const Vec3* neighbour) {
    return skewness_of(p, v, n, face_geometry(p, v, n), owner, neighbour);
}

namespace {

/// Each cell's centre (as OpenFOAM computes it) and checkMesh aspect ratio, from its own faces.
void cell_centres_and_aspects(const FaceSlots& slots, const std::vector<Vec3>& p, int threads,
                              std::vector<Vec3>& centre, std::vector<double>& aspect) {
    const CellNumbering& cells = slots.cells();
    const std::int64_t nc = cells.count();
    centre.assign(static_cast<std::size_t>(nc), Vec3::Zero());
    aspect.assign(static_cast<std::size_t>(nc), 0.0);
#pragma omp parallel for schedule(static) num_threads(thread_count(threads))
    for (std::int64_t g = 0; g < nc; ++g) {
        // A cell's faces are consecutive slots (face_match.h).
        const CellNumbering::Cell c = cells.locate(g);
        const auto count = static_cast<std::uint64_t>(cell_faces(c.type).count);
        const std::uint64_t s0 = slots.start(c.type) + static_cast<std::uint64_t>(c.index) * count, s1 = s0 + count;
        std::array<FaceGeometry, 6> fg;
        for (std::uint64_t s = s0; s < s1; ++s) {
            Index v[4];
            const int n = slots.nodes(s, v);
            fg[s - s0] = face_geometry(p.data(), v, n);
        }
        Vec3 mag = Vec3::Zero();
        double vol3 = 0.0;
        centre[static_cast<std::size_t>(g)] = cell_centre(fg, static_cast<int>(s1 - s0), mag, vol3);
        aspect[static_cast<std::size_t>(g)] = aspect_ratio_of(mag, vol3 / 3.0);
    }
}

/// The longest edge of cell \p index of type \p type of \p mesh.
double longest_edge(const VolumeMesh& mesh, CellType type, Index index) {
    double longest = 0.0;
    mesh.with_cells(type, [&](const auto& cells) {
        const auto& c = cells[static_cast<std::size_t>(index)];
        for (std::size_t i = 0; i < c.size(); ++i)
            for (std::size_t j = i + 1; j < c.size(); ++j)
                longest = std::max(longest, (mesh.points[static_cast<std::size_t>(c[i])] -
                                             mesh.points[static_cast<std::size_t>(c[j])]).norm());
    });
    return longest;
}

/// The cells above checkMesh's aspect ratio counted and listed into \p r (centres \p centre),
/// and the worst named.
void count_high_aspect(const VolumeMesh& mesh, const CellNumbering& cells, const std::vector<Vec3>& centre,
                       const std::vector<double>& aspect, SolverChecks& r) {
    for (std::int64_t g = 0; g < cells.count(); ++g) {
        const double a = aspect[static_cast<std::size_t>(g)];
        if (a > kFoamAspectRatio) {
            ++r.high_aspect_cells;
            const CellNumbering::Cell c = cells.locate(g);
            const double edge = longest_edge(mesh, c.type, static_cast<Index>(c.index));
            r.high_aspect.push_back({centre[static_cast<std::size_t>(g)], a, edge});
        }
        if (a > r.max_aspect_ratio) {
            r.max_aspect_ratio = a;
            const CellNumbering::Cell c = cells.locate(g);
            r.worst_aspect = describe_cell(mesh, c.type, c.index);
            r.worst_aspect_type = c.type;
        }
    }
}

/// The points no cell of \p mesh uses counted into \p r, and the first named: checkMesh fails
/// a polyMesh with any ("Unused points found in the mesh").
void count_unused_points(const VolumeMesh& mesh, SolverChecks& r) {
    std::vector<char> used(mesh.points.size(), 0);
    for (const CellType t : {CellType::Tet, CellType::Pyramid, CellType::Prism, CellType::Hex})
        mesh.with_cells(t, [&](const auto& cells) {
            for (const auto& c : cells)
                for (const Index v : c)
                    if (v >= 0 && static_cast<std::size_t>(v) < used.size()) used[static_cast<std::size_t>(v)] = 1;
        });
    for (std::size_t v = 0; v < used.size(); ++v) {
        if (used[v]) continue;
        if (r.unused_points++ == 0) r.first_unused = "node " + std::to_string(v) + " at " + format_point(mesh.points[v]);
    }
}

/// The figures of the face in slot \p s (outward from its cell, the owner) that checkMesh
/// judges, \p centre the cells' centres: its geometry, the cosine of its non-orthogonality (an
/// interior face) and its skewness.
struct FaceFigures {
    FaceGeometry f;
    const Vec3* owner = nullptr;      ///< the centre of the slot's cell
    const Vec3* neighbour = nullptr;  ///< the centre of the cell across; null at the boundary
    double cos = 1.0;                 ///< between the centres' line and the area vector (interior)
    double skew = 0.0;
};

FaceFigures face_figures(const FaceMatch& match, const std::vector<Vec3>& p, const std::vector<Vec3>& centre,
                         std::uint64_t s) {
    const FaceSlots& slots = match.slots;
    const std::int64_t other = match.across[s];
    Index v[4];
    const int n = slots.nodes(s, v);
    FaceFigures r;
    r.f = face_geometry(p.data(), v, n);
    r.owner = &centre[static_cast<std::size_t>(slots.cell(s))];
    if (other >= 0) {
        r.neighbour = &centre[static_cast<std::size_t>(slots.cell(static_cast<std::uint64_t>(other)))];
        const Vec3 d = *r.neighbour - *r.owner;
        r.cos = d.dot(r.f.area) / (d.norm() * r.f.area.norm() + kRootVSmall);
    }
    r.skew = skewness_of(p.data(), v, n, r.f, *r.owner, r.neighbour);
    return r;
}

/// The angle of cosine \p c in degrees.
double degrees(double c) {
    return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

/// The faces of the slots [\p begin, \p end) checked into \p q: each interior face once (from
/// its lower slot), each boundary face from its cell; \p centre the cells' centres.
void check_faces(const FaceMatch& match, const std::vector<Vec3>& p, const std::vector<Vec3>& centre,
                 std::uint64_t begin, std::uint64_t end, bool keep_skewed, Partial& q) {
    const double severe_cos = std::cos(kFoamNonOrthogonalDeg * std::numbers::pi / 180.0);
    auto pyramid = [&q](const Vec3& area, const Vec3& fc, const Vec3& cc, std::uint64_t s) {
        if (!inverted_pyramid(area, fc, cc)) return;
        ++q.pyramids;
        if (!q.has_pyramid) q.first_pyramid = s, q.has_pyramid = true;
    };
    for (auto s = begin; s < end; ++s) {
        const std::int64_t other = match.across[s];
        if (other == FaceMatch::kUnmatched) continue;
        if (other >= 0 && static_cast<std::uint64_t>(other) < s) continue;
        const FaceFigures ff = face_figures(match, p, centre, s);
        if (ff.neighbour) {
            ++q.faces;
            q.sum_cos += ff.cos;
            if (ff.cos < severe_cos) ++(ff.cos > 1e-15 ? q.severe : q.errors);
            if (ff.cos < q.min_cos) q.min_cos = ff.cos, q.worst_ortho = s, q.has_ortho = true;
            pyramid(-ff.f.area, ff.f.centre, *ff.neighbour, s);  // the neighbour's: its outward area is -area
        }
        if (ff.skew > kFoamSkewness) {
            ++q.skew;
            if (keep_skewed) q.skewed.push_back(s);
        }
        if (ff.skew > q.max_skew) q.max_skew = ff.skew, q.worst_skew = s, q.has_skew = true;
        pyramid(ff.f.area, ff.f.centre, *ff.owner, s);
    }
}

/// The chunks' partials merged in chunk order (the first face with the extreme value wins ties);
/// the counts into \p r, the skewed faces' slots appended to \p skewed if given.
Partial merge_partials(const std::vector<Partial>& part, SolverChecks& r, std::vector<std::uint64_t>* skewed) {
    Partial all;
    for (const Partial& q : part) {
        all.faces += q.faces;
        all.sum_cos += q.sum_cos;
        r.severely_non_orthogonal += q.severe;
        r.non_orthogonality_errors += q.errors;
        r.skew_faces += q.skew;
        if (skewed) skewed->insert(skewed->end(), q.skewed.begin(), q.skewed.end());
        r.negative_pyramids += q.pyramids;
        if (q.has_ortho && q.min_cos < all.min_cos)
            all.min_cos = q.min_cos, all.worst_ortho = q.worst_ortho, all.has_ortho = true;
        if (q.has_skew && q.max_skew > all.max_skew)
            all.max_skew = q.max_skew, all.worst_skew = q.worst_skew, all.has_skew = true;
        if (q.has_pyramid && !all.has_pyramid) all.first_pyramid = q.first_pyramid, all.has_pyramid = true;
    }
    return all;
}

/// The worst faces of \p all into \p r: their figures and names.
void name_worst_faces(const FaceMatch& match, const std::vector<Vec3>& p, const Partial& all, SolverChecks& r) {
    const FaceSlots& slots = match.slots;
    auto face_name = [&](std::uint64_t s) {
        Index v[4];
        const int n = slots.nodes(s, v);
        const FaceGeometry f = face_geometry(p.data(), v, n);
        const std::int64_t other = match.across[s];
        std::string who = cell_name(slots, s);
        if (other >= 0) who += " and " + cell_name(slots, static_cast<std::uint64_t>(other));
        return "the face at " + format_point(f.centre) + " of " + who;
    };
    if (all.has_ortho) {
        r.max_non_orthogonality_deg = degrees(all.min_cos);
        r.mean_non_orthogonality_deg = degrees(all.sum_cos / static_cast<double>(all.faces));
        r.worst_non_orthogonal = face_name(all.worst_ortho);
    }
    if (all.has_skew) {
        r.max_skewness = all.max_skew;
        r.worst_skew = face_name(all.worst_skew);
    }
    if (all.has_pyramid) r.worst_pyramid = face_name(all.first_pyramid);
}

}  // namespace

SolverChecks solver_checks(const VolumeMesh& mesh, const FaceMatch& match, int threads,
                           std::vector<std::uint64_t>* skewed) {
    SolverChecks r;
    if (skewed) skewed->clear();
    const FaceSlots& slots = match.slots;
    if (slots.cells().count() == 0) return r;
    std::vector<Vec3> centre;
    std::vector<double> aspect;
    cell_centres_and_aspects(slots, mesh.points, threads, centre, aspect);
    count_high_aspect(mesh, slots.cells(), centre, aspect, r);
    count_unused_points(mesh, r);
    const std::uint64_t ns = slots.count();
    const auto chunks = static_cast<std::int64_t>((ns + kChunk - 1) / kChunk);
    std::vector<Partial> part(static_cast<std::size_t>(chunks));
#pragma omp parallel for schedule(dynamic, 1) num_threads(thread_count(threads))
    for (std::int64_t k = 0; k < chunks; ++k) {
        const auto end = std::min<std::uint64_t>(ns, static_cast<std::uint64_t>(k + 1) * kChunk);
        check_faces(match, mesh.points, centre, static_cast<std::uint64_t>(k) * kChunk, end, skewed != nullptr,
                    part[static_cast<std::size_t>(k)]);
    }
    const Partial all = merge_partials(part, r, skewed);
    name_worst_faces(match, mesh.points, all, r);
    return r;
}

CellSolverFigures cell_solver_figures(const VolumeMesh& mesh, const FaceMatch& match, int threads) {
    CellSolverFigures r;
    const FaceSlots& slots = match.slots;
    const CellNumbering& cells = slots.cells();
    std::vector<Vec3> centre;
    cell_centres_and_aspects(slots, mesh.points, threads, centre, r.aspect_ratio);
    const auto nc = static_cast<std::size_t>(cells.count());
    r.non_orthogonality_deg.assign(nc, 0.0);
    r.skewness.assign(nc, 0.0);
#pragma omp parallel for schedule(static) num_threads(thread_count(threads))
    for (std::int64_t g = 0; g < cells.count(); ++g) {
        const CellNumbering::Cell c = cells.locate(g);
        const auto count = static_cast<std::uint64_t>(cell_faces(c.type).count);
        const std::uint64_t s0 = slots.start(c.type) + static_cast<std::uint64_t>(c.index) * count;
        double& ortho = r.non_orthogonality_deg[static_cast<std::size_t>(g)];
        double& skew = r.skewness[static_cast<std::size_t>(g)];
        for (std::uint64_t s = s0; s < s0 + count; ++s) {
            const std::int64_t other = match.across[s];
            if (other == FaceMatch::kUnmatched) continue;
            // From the lower slot, as solver_checks takes each interior face: the same figures.
            const bool lower = other < 0 || static_cast<std::uint64_t>(other) > s;
            const FaceFigures ff = face_figures(match, mesh.points, centre, lower ? s : static_cast<std::uint64_t>(other));
            if (ff.neighbour) ortho = std::max(ortho, degrees(ff.cos));
            skew = std::max(skew, ff.skew);
        }
    }
    return r;
}

}  // namespace strata
