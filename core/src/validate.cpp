// The volume-mesh validator. Independent checks:
//  0. the arrays are sound (check_volume_arrays); with an id out of range nothing else runs;
//  1. every cell has a positive scaled Jacobian at every corner (cell_quality.h) and a
//     positive volume;
//  2. face conformity: every cell face, oriented out of its cell, is matched by node set
//     (match_faces): two cell faces with one node set = an interior face (opposite
//     orientations), one cell face = a boundary face (listed in mesh.boundary with the same
//     orientation), anything else is a problem;
//  3. the cell volumes sum to the volume the boundary encloses (divergence theorem, the
//     same face formula for both so a conforming mesh agrees to rounding).
// Work is cut into fixed chunks whose results are merged in chunk order, so the report
// (problems, sums) does not depend on the number of threads.

#include <strata/core/cell_faces.h>
#include <strata/core/cell_quality.h>
#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/face_match.h>
#include <strata/core/format.h>
#include <strata/core/mesh_check.h>
#include <strata/core/parallel.h>
#include <strata/core/validate.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace strata {
namespace {

/// (1/3) (c − r)·A of one face, A its area vector (quads: ½ d1×d2), c the mean of its
/// corners: the face's share of the enclosed volume. Shared by cells and the boundary.
/// \p magnitude, if given, receives the term's size before cancellation (|Σx| |area| over 9 or
/// 12): what its rounding error is relative to.
double face_volume_term(const Vec3* x, int n, double* magnitude = nullptr) {
    if (n == 3) {
        const Vec3 a = 0.5 * (x[1] - x[0]).cross(x[2] - x[0]);
        const Vec3 s = x[0] + x[1] + x[2];
        if (magnitude) *magnitude = s.norm() * a.norm() / 9.0;
        return s.dot(a) / 9.0;
    }
    const Vec3 a = 0.5 * (x[2] - x[0]).cross(x[3] - x[1]);
    const Vec3 s = x[0] + x[1] + x[2] + x[3];
    if (magnitude) *magnitude = s.norm() * a.norm() / 12.0;
    return s.dot(a) / 12.0;
}

// ---------------------------------------------------------------------------------------
// Problems: at most kMaxPerKind lines per kind, then a count.

enum Kind : int {
    kBadInput,
    kJacobian,
    kOverlap,
    kNonConforming,
    kQuadTriangles,
    kHole,
    kBoundaryUnmatched,
    kBoundaryInterior,
    kBoundaryOrientation,
    kBoundaryDuplicate,
    kVolume,
    kNumKinds
};

constexpr std::size_t kMaxPerKind = 5;

constexpr std::array<const char*, kNumKinds> kKindNoun{"input problems",
                                                       "inverted or degenerate cells",
                                                       "misoriented interior faces",
                                                       "faces shared by three or more cells",
                                                       "quad faces against two triangles",
                                                       "unmatched cell faces (holes)",
                                                       "boundary faces that are no cell face",
                                                       "boundary faces on interior faces",
                                                       "misoriented boundary faces",
                                                       "duplicated boundary faces",
                                                       "volume mismatches"};

/// The kind of problem each FaceIssue is, in FaceIssue order.
constexpr std::array<Kind, 9> kKindOfIssue{
    kNonConforming,       kOverlap,       kOverlap, kBoundaryInterior, kBoundaryDuplicate,
    kBoundaryOrientation, kQuadTriangles, kHole,    kBoundaryUnmatched};
Kind kind_of(FaceIssue issue) {
    return kKindOfIssue[static_cast<std::size_t>(issue)];
}

struct Problems {
    std::array<std::vector<std::string>, kNumKinds> lines;
    std::array<std::size_t, kNumKinds> count{};

    /// \p make builds the message only when it will be kept (millions of problems are cheap).
    template <class F>
    void add(Kind k, F&& make) {
        if (count[k]++ < kMaxPerKind) lines[k].push_back(make());
    }
    void merge(Problems&& o) {
        for (int k = 0; k < kNumKinds; ++k) {
            for (std::string& s : o.lines[k])
                if (lines[k].size() < kMaxPerKind) lines[k].push_back(std::move(s));
            count[k] += o.count[k];
        }
    }
    std::size_t total() const {
        std::size_t t = 0;
        for (std::size_t c : count) t += c;
        return t;
    }
    std::vector<std::string> flatten() const {
        std::vector<std::string> out;
        for (int k = 0; k < kNumKinds; ++k) {
            out.insert(out.end(), lines[k].begin(), lines[k].end());
            if (count[k] > lines[k].size())
                out.push_back("... and " + std::to_string(count[k] - lines[k].size()) + " more " + kKindNoun[k]);
        }
        return out;
    }
};

// ---------------------------------------------------------------------------------------
// Check 1: scaled Jacobians and cell volumes, in fixed chunks of cells.

constexpr std::int64_t kCellChunk = 1 << 15;

struct CellResult {
    double min_jacobian = 1.0;
    std::int64_t worst = -1;                             ///< the first cell with min_jacobian (global cell number)
    std::array<double, 4> type_min{1.0, 1.0, 1.0, 1.0};  ///< the same per cell type
    std::array<std::int64_t, 4> type_worst{-1, -1, -1, -1};
    std::array<std::array<Index, kQualityBins>, 4> histogram{};  ///< per cell type, quality_bin
    double volume = 0.0;
    Problems problems;
};

void sticky_min(double& m, double v) {  // NaN wins, so a NaN anywhere shows in the report
    if (std::isnan(v) || v < m) m = v;
}

CellResult check_cells(const VolumeMesh& mesh, const CellNumbering& cells, int threads) {
    const std::int64_t n = cells.count();
    const std::int64_t chunks = (n + kCellChunk - 1) / kCellChunk;
    std::vector<CellResult> results(static_cast<std::size_t>(chunks));
#pragma omp parallel for schedule(dynamic, 1) num_threads(thread_count(threads))
    for (std::int64_t c = 0; c < chunks; ++c) {
        CellResult& r = results[static_cast<std::size_t>(c)];
        const std::int64_t end = std::min(n, (c + 1) * kCellChunk);
        for (std::int64_t g = c * kCellChunk; g < end; ++g) {
            const auto [t, i] = cells.locate(g);
            const Index* v = mesh.cell(t, static_cast<std::size_t>(i));
            const double j = min_scaled_jacobian(mesh.points, v, t);
            const double vol = cell_volume(mesh.points, v, t);
            if (r.worst < 0 || j < r.min_jacobian) r.worst = g;
            sticky_min(r.min_jacobian, j);
            const auto k = static_cast<std::size_t>(t);
            if (r.type_worst[k] < 0 || j < r.type_min[k]) r.type_worst[k] = g;
            sticky_min(r.type_min[k], j);
            ++r.histogram[k][static_cast<std::size_t>(quality_bin(j))];
            r.volume += vol;
            if (!(j > 0.0))
                r.problems.add(kJacobian, [&, t = t, i = i] {
                    return describe_cell(mesh, t, i) + " has min scaled Jacobian " + format_number(j, 3) +
                           " (inverted or degenerate: corners must be in Gmsh order, the bottom face "
                           "seen from inside the cell ordered as in Gmsh's reference element)";
                });
            else if (!(vol > 0.0))
                r.problems.add(kJacobian, [&, t = t, i = i] {
                    return describe_cell(mesh, t, i) + " has volume " + format_number(vol) +
                           " though its corners are positive (a strongly warped cell)";
                });
        }
    }
    CellResult out;
    for (CellResult& r : results) {  // chunk order: independent of the thread count
        if (out.worst < 0 || r.min_jacobian < out.min_jacobian) out.worst = r.worst;
        sticky_min(out.min_jacobian, r.min_jacobian);
        for (std::size_t k = 0; k < 4; ++k) {
            for (std::size_t b = 0; b < kQualityBins; ++b) out.histogram[k][b] += r.histogram[k][b];
            if (r.type_worst[k] < 0) continue;
            if (out.type_worst[k] < 0 || r.type_min[k] < out.type_min[k]) out.type_worst[k] = r.type_worst[k];
            sticky_min(out.type_min[k], r.type_min[k]);
        }
        out.volume += r.volume;
        out.problems.merge(std::move(r.problems));
    }
    return out;
}

// ---------------------------------------------------------------------------------------
// Check 3: the volume the boundary encloses, relative to the bounding-box centre.

struct BoundaryVolume {
    double volume = 0.0;
    /// The rounding error the sum may carry: its terms cancel (a thin shell of layers far from
    /// the centre encloses little against its faces' terms), so the error is relative to their
    /// sizes, not to the volume: eps (16 + 4 sqrt(faces)) Σ|term|.
    double rounding = 0.0;
};

BoundaryVolume boundary_volume(const VolumeMesh& mesh) {
    const SurfaceMesh& b = mesh.boundary;
    const BoundingBox box = bounding_box(mesh.points);
    const Vec3 r = 0.5 * (box.min + box.max);
    double sum = 0.0, magnitude = 0.0;
    Vec3 x[4];
    for (Index f = 0; f < b.num_faces(); ++f) {
        const int n = static_cast<int>(b.face_size(f));
        for (int k = 0; k < n; ++k) x[k] = mesh.points[b.face_node(f, k)] - r;
        double m = 0.0;
        sum += face_volume_term(x, n, &m);
        magnitude += m;
    }
    const double eps = std::numeric_limits<double>::epsilon();
    return {sum, eps * (16.0 + 4.0 * std::sqrt(static_cast<double>(b.num_faces()))) * magnitude};
}

ValidationReport validate(const VolumeMesh& mesh, const ValidateParams& params, std::size_t& total) {
    check_threads(params.threads, "ValidateParams::threads");
    ValidationReport report;
    strata::report(params.progress, "validation", 0.0);
    const CellNumbering cells(mesh);
    report.cells = static_cast<Index>(cells.count());
    Problems problems;
    const MeshProblems arrays = check_volume_arrays(mesh);
    for (const std::string& line : arrays.lines) problems.add(kBadInput, [&] { return line; });
    problems.count[kBadInput] = arrays.count;
    if (!arrays.indexable) {  // an id out of range: stop before using it
        total = problems.total();
        report.problems = problems.flatten();
        return report;
    }

    CellResult cr = check_cells(mesh, cells, params.threads);
    report.min_scaled_jacobian = cr.min_jacobian;
    if (cr.worst >= 0) {
        const auto [t, i] = cells.locate(cr.worst);
        report.worst_cell = describe_cell(mesh, t, i);
    }
    for (std::size_t k = 0; k < 4; ++k) {
        report.by_type[k].min_scaled_jacobian = cr.type_min[k];
        report.by_type[k].histogram = cr.histogram[k];
        if (cr.type_worst[k] < 0) continue;
        const auto [t, i] = cells.locate(cr.type_worst[k]);
        report.by_type[k].worst_cell = describe_cell(mesh, t, i);
    }
    report.cell_volume = cr.volume;
    problems.merge(std::move(cr.problems));
    strata::report(params.progress, "validation", 0.4);

    const FaceMatch match = match_faces(mesh, params.threads);
    report.interior_faces = static_cast<Index>(match.interior);
    report.boundary_faces = static_cast<Index>(match.boundary);
    for (const FaceMatch::Problem& p : match.problems)
        problems.add(kind_of(p.issue), [&] { return describe(match, p); });
    strata::report(params.progress, "validation", 0.6);
    report.solver = solver_checks(mesh, match, params.threads);

    strata::report(params.progress, "validation", 0.9);
    const BoundaryVolume bv = boundary_volume(mesh);
    report.boundary_volume = bv.volume;
    const double diff = std::abs(report.cell_volume - report.boundary_volume);
    if (!(diff <= params.volume_tolerance * std::abs(report.boundary_volume) + bv.rounding))
        problems.add(kVolume, [&] {
            return "the cells' volumes sum to " + format_number(report.cell_volume, 12) +
                   " but the boundary encloses " + format_number(report.boundary_volume, 12) +
                   " (relative difference " + format_number(diff / std::abs(report.boundary_volume), 3) +
                   " > tolerance " + format_number(params.volume_tolerance, 3) +
                   "): cells are missing or overlap, or the boundary is incomplete or misoriented";
        });

    total = problems.total();
    report.problems = problems.flatten();
    strata::report(params.progress, "validation", 1.0);
    return report;
}

}  // namespace

double cell_volume(const std::vector<Vec3>& p, const Index* cell, CellType type) {
    // Coordinates relative to the cell's centroid: the face terms are then of the cell's own
    // size, not of its distance from the origin (Σ area vectors = 0, so the result does not
    // depend on the reference point in exact arithmetic).
    const int n = cell_corners(type);
    Vec3 r = Vec3::Zero();
    for (int k = 0; k < n; ++k) r += p[cell[k]];
    r /= static_cast<double>(n);
    std::array<Vec3, 8> x;
    for (int k = 0; k < n; ++k) x[static_cast<std::size_t>(k)] = p[cell[k]] - r;
    const CellFaceTable& table = cell_faces(type);
    double sum = 0.0;
    Vec3 f[4];
    for (std::size_t i = 0; i < static_cast<std::size_t>(table.count); ++i) {
        for (std::size_t k = 0; k < static_cast<std::size_t>(table.size[i]); ++k)
            f[k] = x[static_cast<std::size_t>(table.node[i][k])];
        sum += face_volume_term(f, table.size[i]);
    }
    return sum;
}

ValidationReport validate_mesh(const VolumeMesh& mesh, const ValidateParams& params) {
    std::size_t total = 0;
    return validate(mesh, params, total);
}

ValidationReport require_valid_mesh(const VolumeMesh& mesh, const std::string& what, const ValidateParams& params) {
    std::size_t total = 0;
    ValidationReport report = validate(mesh, params, total);
    if (report.ok()) return report;
    std::string first;
    for (std::size_t i = 0; i < std::min<std::size_t>(3, report.problems.size()); ++i)
        first += (i ? "; " : "") + report.problems[i];
    throw TopologyError(what + ": invalid mesh: " + std::to_string(total) +
                        (total == 1 ? " problem: " : " problems: ") + first);
}

}  // namespace strata
