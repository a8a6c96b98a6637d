// CAD input and surface meshing through Gmsh. This file is the Gmsh adapter for CAD: Gmsh's
// 1-based size_t node tags and int entity tags stay in here; the caller gets a SurfaceMesh.
#include <strata/surface/cad.h>

#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/core/parallel.h>
#include <strata/core/union_find.h>
#include <strata/geometry/intersections.h>
#include <strata/geometry/topology.h>
#include <strata/io/cad_content.h>
#include <strata/io/cad_units.h>
#include <strata/io/files.h>
#include <strata/io/geo_script.h>
#include <strata/io/gmsh_model.h>
#include <strata/io/gmsh_session.h>
#include <strata/io/input_file.h>
#include <strata/surface/prepare.h>

#include "narrow_faces.h"
#include "wall_size.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <new>
#include <numeric>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

namespace strata {
namespace {

enum class CadFormat { Step, Iges, Brep, Geo };

std::optional<CadFormat> format_of(const std::string& path) {
    const std::string ext = lower_extension(path);
    if (ext == ".step" || ext == ".stp") return CadFormat::Step;
    if (ext == ".iges" || ext == ".igs") return CadFormat::Iges;
    if (ext == ".brep" || ext == ".brp") return CadFormat::Brep;
    if (ext == ".geo") return CadFormat::Geo;
    return std::nullopt;
}

const char* format_name(CadFormat f) {
    switch (f) {
        case CadFormat::Step:
            return "STEP";
        case CadFormat::Iges:
            return "IGES";
        case CadFormat::Brep:
            return "BREP";
        case CadFormat::Geo:
            return "Gmsh .geo";
    }
    return "CAD";
}

// "1-11, 14, 20-22": the valid tags of a model with many surfaces stay one readable line.
std::string format_tags(std::vector<int> tags) {
    std::sort(tags.begin(), tags.end());
    std::string out;
    for (std::size_t i = 0; i < tags.size();) {
        std::size_t j = i;
        while (j + 1 < tags.size() && tags[j + 1] == tags[j] + 1) ++j;
        if (!out.empty()) out += ", ";
        out += std::to_string(tags[i]);
        if (j > i) out += "-" + std::to_string(tags[j]);
        i = j + 1;
    }
    return out;
}

void validate(const CadParams& p) {
    if (!(p.size_point_growth > 0.0) || !std::isfinite(p.size_point_growth))
        throw InputError("CadParams::size_point_growth = " + format_number(p.size_point_growth) +
                         ": need a positive, finite rise of the size per unit of distance");
    for (const SizePoint& q : p.size_points)
        if (!(q.size > 0.0) || !std::isfinite(q.size) || !q.at.allFinite())
            throw InputError("CadParams::size_points: the size " + format_number(q.size) + " at (" +
                             format_number(q.at.x()) + ", " + format_number(q.at.y()) + ", " + format_number(q.at.z()) +
                             "): need a positive, finite size at a finite point");
    if (!(p.size >= 0.0) || !std::isfinite(p.size))
        throw InputError("CAD meshing: size must be a finite number >= 0 (0 = automatic), got " +
                         format_number(p.size));
    if (!(p.size_min >= 0.0) || !std::isfinite(p.size_min))
        throw InputError("CAD meshing: size_min must be a finite number >= 0 (0 = automatic), got " +
                         format_number(p.size_min));
    if (p.size > 0.0 && p.size_min > p.size)
        throw InputError("CAD meshing: size_min (" + format_number(p.size_min) + ") is larger than size (" +
                         format_number(p.size) + "); give a smaller size_min");
    if (!p.units.empty() && !parse_length_unit(p.units))
        throw InputError("CadParams::units = '" + p.units + "': unknown length unit; use one of " +
                         std::string(length_unit_names()));
    if (!(p.first_height >= 0.0) || !std::isfinite(p.first_height))
        throw InputError("CAD meshing: first_height must be a finite number >= 0 (0 = no aspect-ratio limit), got " +
                         format_number(p.first_height));
    if (!(p.max_aspect_ratio == 0.0 || p.max_aspect_ratio >= 10.0) || !std::isfinite(p.max_aspect_ratio))
        throw InputError("CadParams::max_aspect_ratio = " + format_number(p.max_aspect_ratio) +
                         ": give 0 (no limit) or a ratio of at least 10 (OpenFOAM's checkMesh fails above 1000)");
    if (!(p.sew_tolerance >= 0.0 && p.sew_tolerance <= 1e-3))
        throw InputError("CadParams::sew_tolerance = " + format_number(p.sew_tolerance) +
                         ": give a share of the model's size in [0, 0.001] (0: faces are not sewn)");
    if (!(p.narrow_face_ratio == 0.0 || p.narrow_face_ratio >= 1.0) || !std::isfinite(p.narrow_face_ratio))
        throw InputError("CadParams::narrow_face_ratio = " + format_number(p.narrow_face_ratio) +
                         ": give 0 (off) or a ratio of at least 1 (triangles that many times as long as a narrow face "
                         "is wide)");
    if (!(p.wall_faces_budget > 0.0))
        throw InputError("CAD meshing: wall_faces_budget must be positive, got " + format_number(p.wall_faces_budget));
    check_threads(p.threads, "CadParams::threads");
    if (p.curvature_points < 0)
        throw InputError("CAD meshing: curvature_points must be >= 0 (0 = off), got " +
                         std::to_string(p.curvature_points));
    // Gmsh 4.8's 2D algorithms. Left out: 3 ("initial mesh only") leaves an unrefined mesh;
    // 7 (BAMG) aborts the whole process (an uncaught std::string, std::terminate) on curved
    // surfaces, seen on a sphere; 8 (Frontal-Delaunay for quads) segfaults on every surface in
    // Debian's Gmsh 4.8.4, a plane square included, through the API and the gmsh CLI alike.
    // Unknown values would silently fall back to Gmsh's default.
    static constexpr std::array<int, 5> kAlgorithms{1, 2, 5, 6, 9};
    if (std::find(kAlgorithms.begin(), kAlgorithms.end(), p.algorithm) == kAlgorithms.end()) {
        const std::string why = p.algorithm == 7   ? " (BAMG aborts the process on curved surfaces in Gmsh 4.8)"
                                : p.algorithm == 8 ? " (Frontal-Delaunay for quads crashes Gmsh 4.8.4; for quads use "
                                                     "algorithm 6 with quad elements, which recombines)"
                                                   : "";
        throw InputError("CAD meshing: Gmsh 2D algorithm " + std::to_string(p.algorithm) + " is not supported" + why +
                         "; use 1 (MeshAdapt), 2 (Automatic), 5 (Delaunay), 6 (Frontal-Delaunay) "
                         "or 9 (packing of parallelograms)");
    }
}

// Gmsh's options are process-wide. One mesh_cad call must not leave its sizes (or whatever a
// .geo script set) to the next call, nor to a user who initialised Gmsh for their own work:
// the options this file sets, and those scripts commonly set, are saved and put back.
const std::vector<std::string> kSavedOptions = {
    "Mesh.MeshSizeMax",
    "Mesh.MeshSizeMin",
    "Mesh.MeshSizeFromCurvature",
    "Mesh.MeshSizeExtendFromBoundary",
    "Mesh.MeshSizeFromPoints",
    "Mesh.MeshSizeFactor",
    "Mesh.Algorithm",
    "Mesh.Algorithm3D",
    "Mesh.RecombineAll",
    "Mesh.RecombinationAlgorithm",
    "Mesh.ElementOrder",
    "Mesh.SubdivisionAlgorithm",
    "Mesh.Smoothing",
    "Mesh.MinimumCirclePoints",
    "Mesh.MinimumCurvePoints",
    "Mesh.Optimize",
    "Mesh.SaveAll",
    "Geometry.Tolerance",
    "Geometry.ToleranceBoolean",
    "Geometry.OCCFixDegenerated",
    "Geometry.OCCFixSmallEdges",
    "Geometry.OCCFixSmallFaces",
    "Geometry.OCCSewFaces",
    "Geometry.OCCMakeSolids",
    "Geometry.OCCScaling",
    "General.Terminal",
    "General.Verbosity",
    "General.NumThreads",
    "Geometry.OCCParallel",
};

double get_number(const std::string& name) {
    double v = 0.0;
    gmsh_call("reading Gmsh option " + name, [&] { gmsh::option::getNumber(name, v); });
    return v;
}

void set_number(const std::string& name, double v) {
    gmsh_call("setting Gmsh option " + name, [&] { gmsh::option::setNumber(name, v); });
}

/// Standard output sent to /dev/null while it lives: OpenCASCADE's IGES reader prints its
/// statistics ("Total number of loaded entities 125.", in colour) on std::cout whatever Gmsh's
/// verbosity, into the summary a user or a design loop reads.
class QuietStdout {
public:
    QuietStdout() {
        std::cout.flush();
        std::fflush(stdout);
        const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
        saved_ = null < 0 ? -1 : ::fcntl(1, F_DUPFD_CLOEXEC, 0);
        if (saved_ >= 0 && ::dup2(null, 1) < 0) {
            ::close(saved_);
            saved_ = -1;
        }
        if (null >= 0) ::close(null);
    }
    ~QuietStdout() {
        if (saved_ < 0) return;
        std::cout.flush();
        std::fflush(stdout);
        ::dup2(saved_, 1);
        ::close(saved_);
    }
    QuietStdout(const QuietStdout&) = delete;
    QuietStdout& operator=(const QuietStdout&) = delete;

private:
    int saved_ = -1;
};

/// InputError unless \p path can be given to Gmsh: a file (Gmsh reads it by name, more than once:
/// its unit, the import, sewing's reload), holding what its extension says (OpenCASCADE takes a
/// PNG for a model with no surfaces).
void check_input(const std::string& path, CadFormat format) {
    require_regular_input(path, "Gmsh");
    if (format == CadFormat::Geo) return;
    check_cad_content(path, format == CadFormat::Step   ? CadContent::Step
                            : format == CadFormat::Iges ? CadContent::Iges
                                                        : CadContent::Brep);
}

/// The file into the current model (load without its error translation).
void import_file(const std::string& path, CadFormat format, bool trust_geo) {
    if (format == CadFormat::Geo) {
        // merge, not open: gmsh::open renames the current model after the file (or
        // adds a new one), and the current model belongs to our GmshSession.
        // Refused unless trusted where it reaches outside the model (a shell command, a file
        // written); its Macros renamed if Gmsh holds them already.
        merge_geo_script(path, trust_geo);
        // A script may have used either kernel; both must be visible to the model.
        gmsh::model::geo::synchronize();
        gmsh::model::occ::synchronize();
    } else {
        // The format is given explicitly: Gmsh guesses from the extension and knows
        // neither ".brp" nor upper-case extensions.
        const char* kind = format == CadFormat::Step ? "step" : format == CadFormat::Iges ? "iges" : "brep";
        // Every shape, not only the highest dimension's: with highestDimOnly a file
        // holding a solid and loose faces (a fuselage solid and a wing written as
        // surfaces) lost the faces without a word. Free curves and points (a STEP's
        // construction geometry) bound nothing Strata meshes and go.
        gmsh::vectorpair imported;
        {
            const std::optional<QuietStdout> quiet =
                format == CadFormat::Iges ? std::make_optional<QuietStdout>() : std::nullopt;
            gmsh::model::occ::importShapes(path, imported, false, kind);
        }
        gmsh::model::occ::synchronize();
        for (const int dim : {1, 0}) {
            gmsh::vectorpair entities, loose;
            gmsh::model::getEntities(entities, dim);
            for (const auto& e : entities) {
                std::vector<int> up, down;
                gmsh::model::getAdjacencies(e.first, e.second, up, down);
                if (up.empty()) loose.push_back(e);
            }
            if (loose.empty()) continue;
            gmsh::model::occ::remove(loose, true);
            gmsh::model::occ::synchronize();
        }
    }
}

void load(const std::string& path, CadFormat format, bool trust_geo) {
    const std::string context = path + ": Gmsh could not read this " + std::string(format_name(format)) + " file";
    try {
        gmsh_call(context, [&] {
            try {
                import_file(path, format, trust_geo);
            } catch (const std::bad_alloc&) {
                throw out_of_memory(path);
            }
        });
    } catch (const BackendError& e) {
        const std::string hint = format == CadFormat::Geo
                                     ? "; fix the script (open it in Gmsh to see the error in context)"
                                     : "; check that it is a valid " + std::string(format_name(format)) +
                                           " file (export it again from the CAD tool)";
        throw InputError(std::string(e.what()) + hint);
    }
}

std::vector<int> entity_tags(int dim) {
    gmsh::vectorpair dim_tags;
    gmsh::model::getEntities(dim_tags, dim);
    std::vector<int> tags;
    tags.reserve(dim_tags.size());
    for (const auto& [d, t] : dim_tags) tags.push_back(t);
    // Tag order, so the same file always gives the same node and face numbering.
    std::sort(tags.begin(), tags.end());
    return tags;
}

void fuse_volumes(const std::string& path) {
    const std::vector<int> volumes = entity_tags(3);
    if (volumes.size() < 2) return;
    gmsh::vectorpair occ_volumes;
    gmsh_call(path + ": listing the solids", [&] { gmsh::model::occ::getEntities(occ_volumes, 3); });
    if (occ_volumes.size() != volumes.size())
        throw InputError(path + ": cannot fuse the " + std::to_string(volumes.size()) +
                         " solids: they are not OpenCASCADE entities (a built-in kernel .geo "
                         "script); add SetFactory(\"OpenCASCADE\") to the script, or do the "
                         "Boolean union in it and mesh without fuse");
    gmsh::vectorpair object{{3, volumes.front()}};
    gmsh::vectorpair tools;
    for (std::size_t i = 1; i < volumes.size(); ++i) tools.emplace_back(3, volumes[i]);
    gmsh_call(path + ": fusing the " + std::to_string(volumes.size()) +
                  " solids into one (Boolean union) failed; repair the CAD or mesh without fuse",
              [&] {
                  gmsh::vectorpair out;
                  std::vector<gmsh::vectorpair> out_map;
                  gmsh::model::occ::fuse(object, tools, out, out_map);
                  gmsh::model::occ::synchronize();
              });
}

/// The curves bounding exactly one of \p surfaces once (a seam, which bounds its surface twice, is
/// not one, nor a degenerate edge, of length \p min_length or less: a sphere's poles): the free edges of a model
/// whose faces are not sewn.
std::vector<int> free_curves(const std::vector<int>& surfaces, double min_length) {
    std::map<int, int> uses;
    for (const int s : surfaces) {
        gmsh::vectorpair boundary;
        gmsh::model::getBoundary({{2, s}}, boundary, false, false, false);
        for (const auto& [dim, c] : boundary) ++uses[std::abs(c)];
    }
    std::vector<int> out;
    for (const auto& [c, n] : uses) {
        if (n != 1) continue;
        std::vector<int> up, down;
        gmsh::model::getAdjacencies(1, c, up, down);
        if (up.size() != 1) continue;
        double length = 0.0;
        try {
            gmsh::model::occ::getMass(1, c, length);
        } catch (...) {  // no length OpenCASCADE can measure: degenerate
            continue;
        }
        if (length > min_length) out.push_back(c);
    }
    return out;
}

/// A surface's bounding box, which sewing moves by at most its tolerance (its area and centre
/// of mass can change more, where healing fixes a degenerate edge).
struct SurfaceMark {
    int tag = 0;
    std::array<double, 6> box{};
};

SurfaceMark mark(int s) {
    SurfaceMark m;
    m.tag = s;
    auto& b = m.box;
    gmsh::model::getBoundingBox(2, s, b[0], b[1], b[2], b[3], b[4], b[5]);
    return m;
}

double box_distance(const SurfaceMark& a, const SurfaceMark& b) {
    double d = 0.0;
    for (std::size_t k = 0; k < 6; ++k) d += (a.box[k] - b.box[k]) * (a.box[k] - b.box[k]);
    return std::sqrt(d);
}

/// Gaps between free curves: how many lie within a reach of another along their whole length
/// (a crack rather than an open edge), the widest such gap and where.
struct Gaps {
    Index cracks = 0;
    double widest = 0.0;
    Vec3 at = Vec3::Zero();
};

/// The gaps between \p curves: each sampled at 5 points, a point's gap its distance to the
/// nearest other of them (candidates by bounding boxes within \p reach, swept along x), a
/// curve's the largest of its points'; a curve whose gap is within \p reach is a crack.
Gaps measure_gaps(const std::vector<int>& curves, double reach) {
    struct Box {
        Vec3 lo, hi;
    };
    const std::size_t n = curves.size();
    std::vector<Box> box(n);
    for (std::size_t i = 0; i < n; ++i)
        gmsh::model::getBoundingBox(1, curves[i], box[i].lo.x(), box[i].lo.y(), box[i].lo.z(), box[i].hi.x(),
                                    box[i].hi.y(), box[i].hi.z());
    std::vector<std::size_t> by_x(n);
    std::iota(by_x.begin(), by_x.end(), std::size_t{0});
    std::sort(by_x.begin(), by_x.end(), [&](std::size_t a, std::size_t b) {
        return box[a].lo.x() < box[b].lo.x() || (box[a].lo.x() == box[b].lo.x() && a < b);
    });
    std::vector<std::vector<int>> near(n);
    for (std::size_t p = 0; p < n; ++p) {
        const std::size_t i = by_x[p];
        for (std::size_t q = p + 1; q < n && box[by_x[q]].lo.x() <= box[i].hi.x() + reach; ++q) {
            const std::size_t j = by_x[q];
            if ((box[i].lo.array() - reach <= box[j].hi.array()).all() &&
                (box[j].lo.array() - reach <= box[i].hi.array()).all()) {
                near[i].push_back(curves[j]);
                near[j].push_back(curves[i]);
            }
        }
    }
    Gaps g;
    for (std::size_t i = 0; i < n; ++i) {
        if (near[i].empty()) continue;
        std::vector<double> lo, hi;
        gmsh::model::getParametrizationBounds(1, curves[i], lo, hi);
        if (lo.empty() || hi.empty()) continue;
        double gap = 0.0;
        Vec3 at = Vec3::Zero();
        for (int k = 0; k <= 4; ++k) {
            std::vector<double> xyz, closest, t;
            try {
                gmsh::model::getValue(1, curves[i], {lo[0] + (hi[0] - lo[0]) * k / 4.0}, xyz);
            } catch (...) {  // a curve OpenCASCADE cannot evaluate is not measured
                continue;
            }
            if (xyz.size() < 3) continue;
            double best = std::numeric_limits<double>::infinity();
            for (const int c : near[i]) {
                try {
                    gmsh::model::getClosestPoint(1, c, xyz, closest, t);
                } catch (...) {  // "curve is null in projection": an edge without a 3D curve
                    continue;
                }
                if (closest.size() >= 3)
                    best = std::min(best, std::hypot(closest[0] - xyz[0], closest[1] - xyz[1], closest[2] - xyz[2]));
            }
            if (best > gap) gap = best, at = Vec3(xyz[0], xyz[1], xyz[2]);
        }
        if (!(gap <= reach)) continue;  // an open edge (or no partner): a hole, not a crack
        ++g.cracks;
        if (gap > g.widest) g.widest = gap, g.at = at;
    }
    return g;
}

/// The largest sewing tolerance chosen unasked (a share of the diagonal): features narrower than
/// the tolerance are sewn shut, and small edges and faces under it removed.
constexpr double kSewShareMax = 1e-5;
/// The most a face may move in the healing (its bounding box, a share of the diagonal) for the
/// sewn model to be kept; beyond, the file is meshed unsewn.
constexpr double kSewMoveMax = 1e-4;

/// Loose faces written twice (a CAD exporter's slip): the same bounding box, area and normal as
/// a lower-tagged one. Two bodies' copies of the face they touch along face opposite ways and
/// stay (--fuse removes both). Removed from the model; their tags returned.
std::vector<int> remove_written_twice(const std::vector<int>& loose, double diagonal) {
    struct Face {
        int tag;
        SurfaceMark box;
        double area = 0.0;
        Vec3 normal = Vec3::Zero();
    };
    std::vector<Face> faces;
    for (const int s : loose) {
        Face f{s, mark(s)};
        try {
            gmsh::model::occ::getMass(2, s, f.area);
            std::vector<double> c(3), closest, uv, n;
            gmsh::model::occ::getCenterOfMass(2, s, c[0], c[1], c[2]);
            gmsh::model::getClosestPoint(2, s, c, closest, uv);
            gmsh::model::getNormal(s, uv, n);
            if (n.size() >= 3) f.normal = Vec3(n[0], n[1], n[2]);
        } catch (...) {  // a face OpenCASCADE cannot measure is compared with none
            continue;
        }
        faces.push_back(f);
    }
    std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) {
        return a.box.box[0] < b.box.box[0] || (a.box.box[0] == b.box.box[0] && a.tag < b.tag);
    });
    const double eps = 1e-7 * diagonal;
    std::set<int> twice;
    for (std::size_t i = 0; i < faces.size(); ++i)
        for (std::size_t j = i + 1; j < faces.size() && faces[j].box.box[0] <= faces[i].box.box[0] + eps; ++j) {
            const Face &a = faces[i], &b = faces[j];
            if (twice.count(a.tag) || twice.count(b.tag)) continue;
            if (box_distance(a.box, b.box) > eps || std::abs(a.area - b.area) > 1e-7 * std::max(a.area, b.area) ||
                !(a.normal.dot(b.normal) > 0.99))
                continue;
            twice.insert(std::max(a.tag, b.tag));
        }
    if (twice.empty()) return {};
    gmsh::vectorpair gone;
    for (const int s : twice) gone.emplace_back(2, s);
    gmsh::model::occ::remove(gone, true);
    gmsh::model::occ::synchronize();
    return {twice.begin(), twice.end()};
}

/// Of \p surfaces, those that bound no solid.
std::vector<int> loose_surfaces(const std::vector<int>& surfaces) {
    std::vector<int> loose;
    for (const int s : surfaces) {
        std::vector<int> up, down;
        gmsh::model::getAdjacencies(2, s, up, down);
        if (up.empty()) loose.push_back(s);
    }
    return loose;
}

/// OpenCASCADE's sewing of the faces \p loose at \p tolerance, with degenerate edges, edges and
/// faces smaller than it fixed (sewn alone, a degenerate edge at a spherical nose's pole can
/// leave the shell open and the nose's 1D mesh not closing, and Gmsh then aborts the process).
/// With no solid in the model (\p only_faces) the whole model is healed (Gmsh then replaces it);
/// else the loose faces, whose originals are removed after. Returns what the healing made.
gmsh::vectorpair heal_loose(const std::vector<int>& loose, bool only_faces, double tolerance) {
    gmsh::vectorpair healed, input;
    for (const int s : loose) input.emplace_back(2, s);
    gmsh::model::occ::healShapes(healed, only_faces ? gmsh::vectorpair{} : input, tolerance, true, true, true, true,
                                 true);
    if (!only_faces) {
        std::set<int> kept;
        for (const auto& [dim, tag] : healed)
            if (dim == 2) kept.insert(tag);
        gmsh::vectorpair gone;
        for (const int s : loose)
            if (!kept.count(s)) gone.emplace_back(2, s);
        gmsh::model::occ::remove(gone, true);
    }
    gmsh::model::occ::synchronize();
    return healed;
}

/// The free edges left after sewing the surfaces \p now into \p r (free_after, cracks,
/// widest_gap, gap_at, suggested_tolerance).
void measure_left_gaps(const std::vector<int>& now, double diagonal, SewReport& r) {
    const std::vector<int> open = free_curves(now, 1e-9 * diagonal);
    r.free_after = static_cast<Index>(open.size());
    if (open.empty()) return;
    const Gaps left = measure_gaps(open, 1e-3 * diagonal);
    // Edges that lie on another (no gap) and stayed apart are not a matter of tolerance.
    if (left.widest > 0.0) r.cracks = left.cracks, r.widest_gap = left.widest, r.gap_at = left.at;
    if (r.cracks > 0) {
        // Twice the widest gap, two significant digits up, as a share of the diagonal.
        const double want = std::min(1e-3, 2.0 * r.widest_gap / diagonal);
        const double e = std::pow(10.0, std::floor(std::log10(want)) - 1.0);
        r.suggested_tolerance = std::min(1e-3, std::ceil(want / e - 1e-9) * e);
    }
}

/// Each surface \p now against the one \p before with the nearest bounding box: how far the
/// healing moved a face (into r.moved: trimmed faces whose small edges were "fixed" can lose
/// much of their area), and the file's tags back, one to one (new tag → old), where \p matched.
std::map<int, int> match_surfaces(const std::vector<int>& now, const std::vector<SurfaceMark>& before, double diagonal,
                                  SewReport& r, bool& matched) {
    std::map<int, int> old_of;
    matched = now.size() == before.size();
    std::set<int> taken;
    for (std::size_t i = 0; i < now.size(); ++i) {
        const SurfaceMark m = mark(now[i]);
        // The nearest, and the nearest not matched yet (two bodies' copies of the face they touch
        // along have the same box).
        int best = -1;
        double nearest = std::numeric_limits<double>::infinity(), best_d = nearest;
        for (const SurfaceMark& b : before) {
            const double d = box_distance(b, m);
            nearest = std::min(nearest, d);
            if (d < best_d && !taken.count(b.tag)) best_d = d, best = b.tag;
        }
        r.moved = std::max(r.moved, nearest);
        matched = matched && best >= 0 && best_d <= nearest + 1e-9 * diagonal;
        if (matched) taken.insert(best), old_of[now[i]] = best;
    }
    return old_of;
}

/// The sewn surfaces given their file's tags \p old_of (new tag → old) back as physical groups
/// "surface_<tag>", unless the model has groups of its own (then r.renumbered). Returns the new
/// tag of each of the file's surface tags (empty: unchanged).
std::map<int, int> name_by_file_tags(const std::map<int, int>& old_of, SewReport& r) {
    std::map<int, int> renamed;
    bool same = true;
    for (const auto& [n, o] : old_of) same = same && n == o;
    if (same) return renamed;
    gmsh::vectorpair groups;
    gmsh::model::getPhysicalGroups(groups, 2);
    if (!groups.empty()) {
        r.renumbered = true;  // a model with its own groups is named by them
        return renamed;
    }
    for (const auto& [n, o] : old_of) {
        gmsh::model::addPhysicalGroup(2, {n}, o);
        gmsh::model::setPhysicalName(2, o, "surface_" + std::to_string(o));
        renamed[o] = n;
    }
    return renamed;
}

/// CadParams::sew_tolerance: the faces that bound no solid sewn (and closed shells made solids),
/// the sewn faces given the file's tags back as physical groups "surface_<tag>" where sewing
/// renumbered them. Returns the new tag of each of the file's surface tags (empty: unchanged).
std::map<int, int> sew_faces(double share, SewReport& r) {
    std::vector<int> all = entity_tags(2);
    std::vector<int> loose = loose_surfaces(all);
    if (loose.empty() || !(share > 0.0)) return {};
    double xmin = 0, ymin = 0, zmin = 0, xmax = 0, ymax = 0, zmax = 0;
    gmsh::model::getBoundingBox(-1, -1, xmin, ymin, zmin, xmax, ymax, zmax);
    const double diagonal = std::hypot(xmax - xmin, ymax - ymin, zmax - zmin);
    // Faces written twice go first: sewn, both copies would be meshed on the same edges but
    // with their own interiors (three faces on each edge round them).
    const std::vector<int> twice = remove_written_twice(loose, diagonal);
    if (!twice.empty()) {
        auto drop = [&](std::vector<int>& v) {
            v.erase(std::remove_if(v.begin(), v.end(),
                                   [&](int s) { return std::binary_search(twice.begin(), twice.end(), s); }),
                    v.end());
        };
        drop(all);
        drop(loose);
    }
    const auto written_twice = static_cast<Index>(twice.size());
    // The tolerance: at least the share asked, raised (up to kSewShareMax) to twice the widest
    // gap measured between the loose faces' edges.
    const std::vector<int> loose_edges = free_curves(loose, 1e-9 * diagonal);
    r.written_twice = written_twice;
    if (loose_edges.empty()) return {};  // closed faces (a sphere's): nothing to sew
    r.faces = static_cast<Index>(loose.size());
    r.free_before = static_cast<Index>(loose_edges.size());
    const Gaps gaps = measure_gaps(loose_edges, 1e-3 * diagonal);
    if (gaps.cracks == 0) {  // no edge runs along another (a lone sheet): nothing to sew
        r = SewReport{};
        r.written_twice = written_twice;
        return {};
    }
    r.gap_before = gaps.widest;
    r.tolerance = std::max(share * diagonal, std::min(2.0 * gaps.widest, kSewShareMax * diagonal));
    std::vector<SurfaceMark> before;
    for (const int s : all) before.push_back(mark(s));
    const gmsh::vectorpair healed = heal_loose(loose, entity_tags(3).empty(), r.tolerance);
    const std::vector<int> now = entity_tags(2);
    for (const auto& [dim, tag] : healed)
        if (dim == 3) ++r.solids;
    measure_left_gaps(now, diagonal, r);
    bool matched = false;
    const std::map<int, int> old_of = match_surfaces(now, before, diagonal, r, matched);
    if (r.moved > kSewMoveMax * diagonal + 10.0 * r.tolerance) {
        r.rejected = true;  // the caller reads the file again, unsewn
        return {};
    }
    if (!matched) {
        r.renumbered = true;
        return {};
    }
    return name_by_file_tags(old_of, r);
}

// A script that meshed itself ("Mesh 2;") would keep its curve mesh: generate(2) meshes the
// surfaces again but not the curves, so the caller's sizes would apply only half. Clear it,
// except when the model has discrete entities, whose mesh may be their only geometry (an STL
// merged and classified by the script); Gmsh then re-meshes what it can.
void clear_script_mesh(const std::string& path) {
    gmsh_call(path + ": clearing the mesh the script made", [] {
        std::vector<int> types;
        std::vector<std::vector<std::size_t>> tags, nodes;
        gmsh::model::mesh::getElements(types, tags, nodes, -1, -1);
        if (types.empty()) return;
        gmsh::vectorpair entities;
        gmsh::model::getEntities(entities, -1);
        for (const auto& [dim, tag] : entities) {
            std::string type;
            gmsh::model::getType(dim, tag, type);
            if (type.find("Discrete") != std::string::npos) return;
        }
        gmsh::model::mesh::clear();
    });
}

/// The meshed surfaces as one SurfaceMesh, by the one conversion of the Gmsh adapter (patches
/// from the physical groups, gmsh_model.h), nodes numbered as the faces use them. Every surface
/// must have got elements: one without would leave a hole.
SurfaceMesh extract(const std::string& path, const std::vector<int>& surfaces, std::vector<int>& face_surface) {
    SurfaceMesh mesh = surface_from_gmsh_model(path, NodeOrder::FirstUse, &face_surface);
    std::vector<int> with_faces = face_surface;
    std::sort(with_faces.begin(), with_faces.end());
    for (int s : surfaces)
        if (!std::binary_search(with_faces.begin(), with_faces.end(), s))
            throw BackendError(path + ": surface " + std::to_string(s) +
                               " got no elements from Gmsh, which would leave a hole; the "
                               "surface may be degenerate or too small for the element size: "
                               "try a smaller size or another algorithm, or repair the CAD");
    return mesh;
}

/// Gmsh's generate(2) for mesh_cad, each time the same way: run in a child whose mesh is
/// brought back (generate_surfaces_in_child), so that Gmsh's abort or crash is an error and not
/// the end of this process, and \p progress (the program's --timeout, a host's cancel) stops
/// Gmsh's meshing at once; with quads, where Blossom fails, by the simple recombination, the
/// fallback recorded in \p report.
struct SurfaceGenerator {
    bool quads = false;
    GmshOptionScope& options;
    const Progress* progress = nullptr;
    RecombinationReport& report;

    void operator()(const std::string& context, const std::function<void()>& generate) const {
        const std::string failure =
            gmsh_call(context, [&] { return generate_surfaces_in_child(context, quads, options, generate, progress); });
        if (!failure.empty()) report.blossom_failure = failure;
    }
};

/// The edges of \p mesh that bound more than two faces: where Gmsh meshed two sides of a part
/// thinner than the size through the same nodes (or the model is not manifold there).
Index shared_chords(const SurfaceMesh& mesh) {
    const EdgeTable et = edge_table(mesh);
    Index n = 0;
    for (Index e = 0; e < et.faces.rows(); ++e) n += et.faces.row_size(e) > 2 ? 1 : 0;
    return n;
}

/// The default size (a twentieth of the model's bounding-box diagonal) on the walls of a model
/// that is mostly something else: an air domain's farfield, symmetry and outflow faces round a
/// body give it the domain's diagonal, and the body a handful of faces (a hemisphere-cylinder in
/// its box: 50 wall nodes). Its wall surfaces then get the same share of their own diagonal.
struct WallDefaultSizes {
    std::vector<int> walls;  ///< wall surfaces, or none: the default serves them
    double share = 1.0;      ///< their size over Mesh.MeshSizeMax
    /// The walls' sizes at the current Mesh.MeshSizeMax (halved with it by mend_default_size),
    /// on their curves and points too.
    EntitySizes sizes() const {
        EntitySizes s;
        const double size = share * get_number("Mesh.MeshSizeMax");
        for (const int w : walls) s.cap_surface(w, size);
        return s;
    }
};

/// The walls' default sizes of a model of diagonal \p diagonal meshed at the default size:
/// none unless it has faces other than walls and the walls' bounding box (CAD boxes, which may be
/// a little loose) spans less than half its diagonal.
WallDefaultSizes wall_default_sizes(const CadParams& params, const std::vector<int>& surfaces, bool default_size,
                                    double diagonal) {
    WallDefaultSizes d;
    if (!default_size) return d;
    std::vector<int> walls;
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const auto& [s, name] : surface_patch_names(surfaces)) {
        if (patch_kind_of(name, params.wall_patch_kinds) != PatchKind::Wall) continue;
        walls.push_back(s);
        double x0 = 0, y0 = 0, z0 = 0, x1 = 0, y1 = 0, z1 = 0;
        gmsh::model::getBoundingBox(2, s, x0, y0, z0, x1, y1, z1);
        lo = lo.cwiseMin(Vec3(x0, y0, z0)), hi = hi.cwiseMax(Vec3(x1, y1, z1));
    }
    if (walls.empty() || walls.size() == surfaces.size()) return d;
    const double share = (hi - lo).norm() / diagonal;
    if (!(share < 0.5)) return d;
    d.walls = std::move(walls);
    d.share = share;
    return d;
}

/// CadParams::max_aspect_ratio on the mesh just made (refine_walls): its wall surfaces by the
/// patch each will belong to, each round the whole model meshed again (so the curves the walls
/// share with the other surfaces stay conforming).
SurfaceMesh limit_wall_aspect(const std::string& path, const CadParams& params, const std::vector<int>& surfaces,
                              const std::vector<const PointSizes*>& points, const WallDefaultSizes& defaults,
                              SurfaceMesh mesh,
                              std::vector<int>& face_surface,
                              WallSizeReport& r, const SurfaceGenerator& generate_surfaces) {
    std::set<int> walls;
    for (const auto& [s, name] : surface_patch_names(surfaces))
        if (patch_kind_of(name, params.wall_patch_kinds) == PatchKind::Wall) walls.insert(s);
    const WallLimits limits{params.first_height, params.max_aspect_ratio, params.fan_angle_deg,
                            params.wall_faces_budget};
    const std::string measuring = path + ": measuring the first layer's aspect ratio over the walls";
    WallAspect first;
    gmsh_call(measuring, [&] { first = wall_aspect(mesh, face_surface, walls, limits); });
    // Gmsh multiplies every size by Mesh.MeshSizeFactor, the callback's too.
    const double factor = get_number("Mesh.MeshSizeFactor");
    refine_walls(limits, std::move(first), r, [&](const WallCaps& caps, WallAspect& measured) {
        {
            const std::string context = path +
                                        ": meshing the walls again finer for the first layer's aspect ratio "
                                        "(max_aspect_ratio " +
                                        format_number(params.max_aspect_ratio) + ")";
            const auto generate = [&] {
                std::optional<SizeCallback> callback;
                gmsh::model::mesh::clear();
                EntitySizes sizes = defaults.sizes();
                const EntitySizes capped = entity_sizes(caps);
                for (const auto& [entity, size] : capped.sizes()) sizes.cap(entity.first, entity.second, size);
                callback.emplace(sizes, factor, points);
                gmsh::model::mesh::generate(2);
            };
            generate_surfaces(context, generate);
        }
        face_surface.clear();
        mesh = extract(path, surfaces, face_surface);
        gmsh_call(measuring, [&] { measured = wall_aspect(mesh, face_surface, walls, limits); });
        return true;
    });
    return mesh;
}

/// Units: OpenCASCADE converts STEP and IGES to millimetres; scaled back on import to the unit
/// the file declares, or the one asked. Sets Gmsh's import options for it; returns the units.
CadUnits set_import_units(const std::string& path, CadFormat format, const CadParams& params) {
    CadUnits read_in;
    const bool has_unit = format == CadFormat::Step || format == CadFormat::Iges;
    if (!has_unit && !params.units.empty())
        throw InputError(path + ": a " + std::string(format_name(format)) +
                         " file declares no length unit, so CadParams::units (" + params.units +
                         ") cannot convert it; its numbers are kept as they are (scale them with "
                         "PrepareParams::scale)");
    double scaling = 1.0;
    if (has_unit) {
        const std::optional<LengthUnit> declared = declared_length_unit(path);
        const LengthUnit target =
            params.units.empty() ? declared.value_or(LengthUnit{"mm", 1.0}) : *parse_length_unit(params.units);
        read_in = {target.name, declared ? declared->name : ""};
        scaling = 1.0 / target.millimetres;
    }
    gmsh_call("setting Gmsh option Geometry.OCCTargetUnit",
              [] { gmsh::option::setString("Geometry.OCCTargetUnit", ""); });
    set_number("Geometry.OCCScaling", scaling);
    return read_in;
}

/// The loaded model's faces that bound no solid sewn (sew_faces), once more from the file at
/// a higher tolerance where gaps were left that it sews, or back as the file has them where the
/// healing changed the geometry. Returns the new tag of each of the file's surface tags where
/// they differ; \p sewn says what was done.
std::map<int, int> sew_model(const std::string& path, CadFormat format, const CadParams& params, SewReport& sewn) {
    std::map<int, int> renamed;
    gmsh_call(path +
                  ": sewing the faces that bound no solid (OpenCASCADE) failed; sew them in the CAD tool, or "
                  "give CadParams::sew_tolerance 0 to mesh them as they are",
              [&] {
                  auto reload = [&] {
                      gmsh::vectorpair everything;
                      gmsh::model::getEntities(everything, -1);
                      gmsh::model::removePhysicalGroups();
                      gmsh::model::occ::remove(everything, true);
                      gmsh::model::occ::synchronize();
                      load(path, format, params.trust_geo);
                  };
                  renamed = sew_faces(params.sew_tolerance, sewn);
                  if (!sewn.rejected && sewn.cracks > 0 && sewn.suggested_tolerance <= kSewShareMax) {
                      // Edges still apart by a gap the measure before sewing missed (a
                      // face's edge that healing changed): once more from the file, at the
                      // tolerance that sews them.
                      reload();
                      SewReport again;
                      renamed = sew_faces(std::max(params.sew_tolerance, sewn.suggested_tolerance), again);
                      again.first_tolerance = sewn.tolerance;
                      sewn = again;
                  }
                  if (sewn.rejected) {
                      // The healing changed the geometry: the faces as the file has them.
                      reload();
                      renamed.clear();
                  }
              });
    return renamed;
}

/// In a model with solids, the faces that bound none and whose group of loose faces (joined by
/// shared curves) still has a free edge: removed from the model, counted in \p r (ignored,
/// ignored_surface, ignored_at). A closed group of loose faces (a box of faces round the
/// solids) stays, and so does every loose face where a free edge runs along another (a crack
/// sewing left: the open surface's error says which tolerance sews it).
void ignore_open_loose_faces(double diagonal, SewReport& r) {
    if (entity_tags(3).empty()) return;
    const std::vector<int> loose = loose_surfaces(entity_tags(2));
    if (loose.empty()) return;
    const std::vector<int> free = free_curves(loose, 1e-9 * diagonal);
    if (free.empty() || measure_gaps(free, 1e-3 * diagonal).cracks > 0) return;
    // Groups of loose faces by the curves they share; each group with a free curve goes.
    std::map<int, std::vector<std::size_t>> faces_of_curve;
    std::vector<std::vector<int>> curves(loose.size());
    for (std::size_t i = 0; i < loose.size(); ++i) {
        gmsh::vectorpair boundary;
        gmsh::model::getBoundary({{2, loose[i]}}, boundary, false, false, false);
        for (const auto& [dim, c] : boundary) {
            curves[i].push_back(std::abs(c));
            faces_of_curve[std::abs(c)].push_back(i);
        }
    }
    UnionFind groups(loose.size());
    for (const auto& [c, faces] : faces_of_curve)
        for (std::size_t k = 1; k < faces.size(); ++k)
            groups.unite(static_cast<Index>(faces[0]), static_cast<Index>(faces[k]));
    std::set<Index> open;
    for (const int c : free) open.insert(groups.find(static_cast<Index>(faces_of_curve[c].front())));
    gmsh::vectorpair gone;
    for (std::size_t i = 0; i < loose.size(); ++i) {
        if (!open.count(groups.find(static_cast<Index>(i)))) continue;
        if (r.ignored++ == 0) {
            r.ignored_surface = loose[i];
            double x = 0, y = 0, z = 0;
            gmsh::model::occ::getCenterOfMass(2, loose[i], x, y, z);
            r.ignored_at = Vec3(x, y, z);
        }
        gone.emplace_back(2, loose[i]);
    }
    gmsh::model::occ::remove(gone, true);
    gmsh::model::occ::synchronize();
}

/// Up to 5 x 5 points inside surface \p s, evaluated from a grid over its parameters (those
/// Gmsh says lie on the trimmed face); empty where Gmsh cannot tell.
std::vector<Vec3> points_inside(int s) {
    std::vector<double> lo, hi;
    gmsh::model::getParametrizationBounds(2, s, lo, hi);
    std::vector<Vec3> out;
    if (lo.size() < 2 || hi.size() < 2) return out;
    for (int i = 1; i <= 5; ++i)
        for (int j = 1; j <= 5; ++j) {
            const std::vector<double> uv{lo[0] + (hi[0] - lo[0]) * i / 6.0, lo[1] + (hi[1] - lo[1]) * j / 6.0};
            if (gmsh::model::isInside(2, s, uv) != 1) continue;
            std::vector<double> xyz;
            gmsh::model::getValue(2, s, uv, xyz);
            if (xyz.size() >= 3) out.emplace_back(xyz[0], xyz[1], xyz[2]);
        }
    return out;
}

/// The largest distance from \p points to surface \p s (infinity where it cannot be measured).
double farthest_from(const std::vector<Vec3>& points, int s) {
    if (points.empty()) return std::numeric_limits<double>::infinity();
    double far = 0.0;
    for (const Vec3& p : points) {
        std::vector<double> closest, uv;
        gmsh::model::getClosestPoint(2, s, {p.x(), p.y(), p.z()}, closest, uv);
        if (closest.size() < 3) return std::numeric_limits<double>::infinity();
        far = std::max(far, (Vec3(closest[0], closest[1], closest[2]) - p).norm());
    }
    return far;
}

/// Surface \p s's unit normal at the point of it nearest \p p (zero where Gmsh has none).
Vec3 normal_near(int s, const Vec3& p) {
    std::vector<double> closest, uv, n;
    gmsh::model::getClosestPoint(2, s, {p.x(), p.y(), p.z()}, closest, uv);
    gmsh::model::getNormal(s, uv, n);
    return n.size() >= 3 ? Vec3(n[0], n[1], n[2]) : Vec3::Zero();
}

/// Of two surfaces \p a < \p b bounded by the same curves and lying on each other, the one the
/// model holds twice (0: both stay). Faces of two different solids are where those touch (two
/// bodies' copies of their common face: --fuse removes both); two loose faces facing opposite
/// ways likewise. Else the loose one goes, or the higher tag.
int copy_of_pair(int a, int b, const Vec3& at) {
    std::vector<int> up_a, up_b, down;
    gmsh::model::getAdjacencies(2, a, up_a, down);
    gmsh::model::getAdjacencies(2, b, up_b, down);
    if (!up_a.empty() && !up_b.empty()) {
        std::sort(up_a.begin(), up_a.end());
        std::sort(up_b.begin(), up_b.end());
        return up_a == up_b ? b : 0;
    }
    if (up_a.empty() && up_b.empty()) return normal_near(a, at).dot(normal_near(b, at)) > 0.99 ? b : 0;
    return up_a.empty() ? a : b;
}

/// Faces the model holds twice with different geometry (a shell listing a face and a copy
/// remade on the same edges): surfaces bounded by exactly the same curves that lie on each
/// other, each within 1e-6 of the model's size (\p diagonal) of the other at up to 25 points.
/// Meshed both, each on those edges with its own interior, three faces on each edge round
/// them. The copy (copy_of_pair) is removed (a solid it bounds is removed first, its other faces
/// kept), counted in \p r (coincident, coincident_surface, coincident_with, coincident_at,
/// coincident_distance).
void remove_coincident_faces(double diagonal, SewReport& r) {
    std::map<std::vector<int>, std::vector<int>> by_curves;
    for (const int s : entity_tags(2)) {
        gmsh::vectorpair boundary;
        gmsh::model::getBoundary({{2, s}}, boundary, false, false, false);
        std::vector<int> curves;
        for (const auto& [dim, c] : boundary) curves.push_back(std::abs(c));
        std::sort(curves.begin(), curves.end());
        curves.erase(std::unique(curves.begin(), curves.end()), curves.end());
        if (!curves.empty()) by_curves[curves].push_back(s);
    }
    const double tolerance = 1e-6 * diagonal;
    std::set<int> gone;
    for (const auto& [curves, group] : by_curves)
        for (std::size_t i = 0; i < group.size(); ++i)
            for (std::size_t j = i + 1; j < group.size(); ++j) {
                const int a = group[i], b = group[j];
                if (gone.count(a) || gone.count(b)) continue;
                const std::vector<Vec3> on_a = points_inside(a), on_b = points_inside(b);
                const double d = std::max(farthest_from(on_a, b), farthest_from(on_b, a));
                if (!(d <= tolerance)) continue;
                const int copy = copy_of_pair(a, b, on_a.front());
                if (copy == 0) continue;
                if (r.coincident++ == 0) {
                    r.coincident_surface = copy;
                    r.coincident_with = copy == a ? b : a;
                    r.coincident_at = (copy == a ? on_a : on_b).front();
                }
                r.coincident_distance = std::max(r.coincident_distance, d);
                gone.insert(copy);
            }
    for (const int s : gone) {
        std::vector<int> up, down;
        gmsh::model::getAdjacencies(2, s, up, down);
        gmsh::vectorpair solids;
        for (const int v : up) solids.emplace_back(3, v);
        if (!solids.empty()) gmsh::model::occ::remove(solids, false);
        gmsh::model::occ::remove({{2, s}}, true);
    }
    if (!gone.empty()) gmsh::model::occ::synchronize();
}

/// The name the file gives the one solid surface \p s bounds (the last part of Gmsh's label
/// path "Shapes/model/Fuselage/Fuselage"); empty where it bounds none, several or a name-less one.
std::string body_of(int s) {
    std::vector<int> up, down;
    gmsh::model::getAdjacencies(2, s, up, down);
    if (up.size() != 1) return {};
    std::string name;
    gmsh::model::getEntityName(3, up.front(), name);
    name = name.substr(name.find_last_of('/') + 1);
    const auto first = name.find_first_not_of(' ');
    return first == std::string::npos ? std::string{} : name.substr(first, name.find_last_not_of(' ') - first + 1);
}

/// Each patch of \p mesh given the body its surfaces (\p face_surface) all bound (Patch::body).
void name_bodies(SurfaceMesh& mesh, const std::vector<int>& face_surface) {
    std::map<int, std::string> body;
    std::vector<std::optional<std::string>> of_patch(mesh.patches.size());
    for (Index f = 0; f < mesh.num_faces(); ++f) {
        const int s = face_surface[static_cast<std::size_t>(f)];
        auto it = body.find(s);
        if (it == body.end()) it = body.emplace(s, body_of(s)).first;
        auto& p = of_patch[static_cast<std::size_t>(mesh.face_patch[f])];
        if (!p) p = it->second;
        else if (*p != it->second) p = std::string{};
    }
    for (std::size_t i = 0; i < mesh.patches.size(); ++i) mesh.patches[i].body = of_patch[i].value_or("");
}

/// The diagonal of the model's bounding box (InputError where it has no extent).
double model_diagonal(const std::string& path) {
    double xmin = 0, ymin = 0, zmin = 0, xmax = 0, ymax = 0, zmax = 0;
    gmsh_call(path + ": computing the bounding box",
              [&] { gmsh::model::getBoundingBox(-1, -1, xmin, ymin, zmin, xmax, ymax, zmax); });
    const double diagonal =
        std::sqrt((xmax - xmin) * (xmax - xmin) + (ymax - ymin) * (ymax - ymin) + (zmax - zmin) * (zmax - zmin));
    if (!(diagonal > 0.0) || !std::isfinite(diagonal))
        throw InputError(path + ": the model has no extent (bounding-box diagonal " + format_number(diagonal) +
                         "); check the file's geometry");
    return diagonal;
}

/// Whether a .geo script set a Gmsh option itself: a script's own mesh settings stand unless
/// the caller asked for something explicitly (a CadParams field away from its default);
/// everything else gets Strata's defaults, set explicitly so that no earlier Gmsh user's
/// settings leak in.
struct ScriptSet {
    bool script = false;
    const GmshOptionScope& options;
    bool operator()(const char* name) const { return script && options.changed(name); }
};

/// The element sizes mesh_cad asked of Gmsh.
struct CadSizes {
    bool default_size = false;      ///< the size is mesh_cad's default (no CadParams::size, none from a script)
    double size = 0.0;              ///< Mesh.MeshSizeMax
    bool curvature = false;         ///< sizes from the curvature
    bool default_size_min = false;  ///< likewise for the smallest size
};

/// Gmsh's size options from \p params (a script's where \p script_set, else Strata's defaults
/// for a model of bounding-box diagonal \p diagonal), and the linear elements Strata needs.
CadSizes set_sizes(const CadParams& params, const ScriptSet& script_set, double diagonal) {
    CadSizes s;
    s.default_size = !(params.size > 0.0) && !script_set("Mesh.MeshSizeMax");  // before it is set
    if (params.size > 0.0)
        set_number("Mesh.MeshSizeMax", params.size);
    else if (!script_set("Mesh.MeshSizeMax"))
        set_number("Mesh.MeshSizeMax", diagonal / 20.0);
    s.size = get_number("Mesh.MeshSizeMax");

    if (params.curvature_points > 0)
        set_number("Mesh.MeshSizeFromCurvature", params.curvature_points);
    else if (!script_set("Mesh.MeshSizeFromCurvature"))
        set_number("Mesh.MeshSizeFromCurvature", 0);
    s.curvature = get_number("Mesh.MeshSizeFromCurvature") > 0;

    s.default_size_min = !(params.size_min > 0.0) && !script_set("Mesh.MeshSizeMin");
    if (params.size_min > 0.0)
        set_number("Mesh.MeshSizeMin", params.size_min);
    else if (!script_set("Mesh.MeshSizeMin"))
        // The floor matters only for curvature refinement, which would otherwise resolve a
        // sharp edge's tiny radius with needle-small elements. Without it, no floor: a
        // script's point sizes are then never clamped.
        set_number("Mesh.MeshSizeMin", s.curvature ? s.size / 20.0 : 0.0);

    // Gmsh's default, explicit: sizes on curves (curvature-refined edges, a script's point
    // sizes) spread into the surfaces they bound instead of jumping to the maximum size.
    if (!script_set("Mesh.MeshSizeExtendFromBoundary")) set_number("Mesh.MeshSizeExtendFromBoundary", 1);
    if (!script_set("Mesh.MeshSizeFactor")) set_number("Mesh.MeshSizeFactor", 1);
    // Strata needs linear faces, whatever a script asks for.
    set_number("Mesh.ElementOrder", 1);
    if (!script_set("Mesh.SubdivisionAlgorithm")) set_number("Mesh.SubdivisionAlgorithm", 0);
    return s;
}

/// Gmsh's 2D algorithm and recombination from \p params (or a script's, where \p script_set).
void set_algorithm(const CadParams& params, const ScriptSet& script_set) {
    const int kDefaultAlgorithm = CadParams{}.algorithm;  // not constexpr: clang rejects the std::string members
    if (params.algorithm != kDefaultAlgorithm || !script_set("Mesh.Algorithm"))
        set_number("Mesh.Algorithm", params.algorithm);
    // A script's 7 or 8 would kill the process (see validate); 6 with the script's
    // recombination settings still gives it quads.
    if (const double a = get_number("Mesh.Algorithm"); a == 7 || a == 8)
        set_number("Mesh.Algorithm", kDefaultAlgorithm);
    if (params.simple_recombination)
        set_number("Mesh.RecombinationAlgorithm", 0);
    else if (!script_set("Mesh.RecombinationAlgorithm"))
        set_number("Mesh.RecombinationAlgorithm", 1);  // Blossom
}

/// Triangles, quads or quads on CadParams::quad_surfaces only (given by the file's tags, \p
/// renamed by sewing; \p surfaces the model's).
void set_elements(const std::string& path, const CadParams& params, const std::map<int, int>& renamed,
                  const std::vector<int>& surfaces, const ScriptSet& script_set) {
    switch (params.elements) {
        case SurfaceElements::Triangles:
            if (!script_set("Mesh.RecombineAll")) set_number("Mesh.RecombineAll", 0);
            break;
        case SurfaceElements::Quads:
            set_number("Mesh.RecombineAll", 1);
            break;
        case SurfaceElements::Mixed: {
            set_number("Mesh.RecombineAll", 0);
            for (int asked : params.quad_surfaces) {
                // The file's tag (sewing may have renumbered the surfaces; fuse's tags stand).
                const auto it = params.fuse ? renamed.end() : renamed.find(asked);
                const int tag = it == renamed.end() ? asked : it->second;
                if (!std::binary_search(surfaces.begin(), surfaces.end(), tag))
                    throw InputError(path + ": quad surface " + std::to_string(asked) +
                                     " is not a surface of the model" +
                                     (params.fuse ? " (after fusing the solids)" : "") + "; its surfaces are " +
                                     format_tags(surfaces));
                gmsh_call(path + ": asking for quads on surface " + std::to_string(tag),
                          [&] { gmsh::model::mesh::setRecombine(2, tag); });
            }
            break;
        }
    }
}

/// Where the default size is too coarse for the model: the edges where a thin part's two sides
/// were meshed through the same nodes (shared_chords), then the pairs of faces that cross where
/// two parts meet closer than the size (a nacelle on its pylon); compared in that order.
std::pair<Index, Index> coarse_defects(const SurfaceMesh& mesh) {
    return {shared_chords(mesh), static_cast<Index>(self_intersections(mesh).size())};
}

/// A part thinner than the default size can get its two sides meshed through the same nodes (a
/// blade's tip, one chord across), and two parts closer than it faces that cross: halve the
/// size, up to three times, while that leaves fewer such defects (coarse_defects, chords
/// first). Where it does not (a model whose surfaces meet three to an edge, which no size
/// mends), the size and mesh before stay: no finer mesh for nothing. \p generate meshes the
/// model once; the sizes used go into \p r.
SurfaceMesh mend_default_size(const std::string& path, const std::vector<int>& surfaces, const CadSizes& sizes,
                              const SurfaceGenerator& generate_surfaces, const std::function<void()>& generate,
                              SurfaceMesh mesh, std::vector<int>& face_surface, WallSizeReport& r) {
    std::pair<Index, Index> defects = coarse_defects(mesh);
    for (int round = 0; round < 3 && defects != std::pair<Index, Index>{0, 0}; ++round) {
        const double before = get_number("Mesh.MeshSizeMax"), smaller = before / 2.0;
        const std::string finer_context = path + ": Gmsh failed to mesh the surfaces again finer (maximum size " +
                                          format_number(smaller) +
                                          ") where the default size left a thin part's two sides on one chord or "
                                          "faces crossing; give a smaller size";
        auto remesh_at = [&](double at) {
            set_number("Mesh.MeshSizeMax", at);
            if (sizes.curvature && sizes.default_size_min) set_number("Mesh.MeshSizeMin", at / 20.0);
            generate_surfaces(finer_context, [&] {
                gmsh::model::mesh::clear();
                generate();
            });
            face_surface.clear();
            return extract(path, surfaces, face_surface);
        };
        SurfaceMesh finer = remesh_at(smaller);
        const std::pair<Index, Index> left = coarse_defects(finer);
        if (left >= defects) {
            mesh = remesh_at(before);  // the Gmsh model back to the mesh kept
            break;
        }
        mesh = std::move(finer);
        defects = left;
        r.thin_size = smaller;
        r.default_size = sizes.size;
    }
    return mesh;
}

}  // namespace

bool is_cad_file(const std::string& path) {
    return format_of(path).has_value();
}

SurfaceMesh mesh_cad(const std::string& path, const CadParams& params, CadUnits* units, WallSizeReport* walls,
                     SewReport* sew, RecombinationReport* recombination, const Progress* progress) {
    const std::optional<CadFormat> format = format_of(path);
    if (!format)
        throw InputError(path +
                         ": not a CAD file Strata reads; use .step/.stp, .iges/.igs, "
                         ".brep/.brp or a Gmsh .geo script");
    validate(params);
    check_input(path, *format);
    const bool script = *format == CadFormat::Geo;

    GmshSession session("strata_cad");
    GmshOptionScope options;  // declared after the session: restored while Gmsh is still locked
    options.save(kSavedOptions);
    options.save_string("Geometry.OCCTargetUnit");
    const CadUnits read_in = set_import_units(path, *format, params);
    if (units) *units = read_in;
    set_number("Geometry.OCCParallel", thread_count(params.threads) > 1 ? 1.0 : 0.0);

    load(path, *format, params.trust_geo);

    const std::vector<int> loaded_surfaces = entity_tags(2);
    if (loaded_surfaces.empty())
        throw InputError(path +
                         ": no surfaces in the model; the file holds only points or "
                         "curves (or nothing): export the surfaces or solids from the "
                         "CAD tool");
    SewReport sewn;
    // The file's surface tag → its tag after sewing, where they differ.
    const std::map<int, int> renamed = script ? std::map<int, int>{} : sew_model(path, *format, params, sewn);
    if (!script) {
        gmsh_call(path + ": removing the faces the model holds twice",
                  [&] { remove_coincident_faces(model_diagonal(path), sewn); });
        gmsh_call(path + ": setting aside the faces that bound no solid",
                  [&] { ignore_open_loose_faces(model_diagonal(path), sewn); });
    }
    if (sew) *sew = sewn;
    if (params.fuse) fuse_volumes(path);
    const std::vector<int> surfaces = entity_tags(2);

    const ScriptSet script_set{script, options};
    const CadSizes sizes = set_sizes(params, script_set, model_diagonal(path));
    set_algorithm(params, script_set);
    set_elements(path, params, renamed, surfaces, script_set);
    if (script) clear_script_mesh(path);

    // CadParams::size_points, in the model's coordinates as the result's (scaled on import),
    // and the narrow faces' (CadParams::narrow_face_ratio).
    WallSizeReport wall_report;
    const PointSizes asked(params.size_points, params.size_point_growth);
    WallDefaultSizes defaults;
    gmsh_call(path + ": measuring the walls for the default size",
              [&] { defaults = wall_default_sizes(params, surfaces, sizes.default_size, model_diagonal(path)); });
    const double face_size = defaults.share * sizes.size;  // the walls', narrow faces are measured against
    if (!defaults.walls.empty()) wall_report.walls_default_size = face_size, wall_report.default_size = sizes.size;
    std::vector<SizePoint> narrow_points;
    gmsh_call(path + ": measuring the CAD faces' widths", [&] {
        narrow_points =
            narrow_face_points(surfaces, params, face_size, std::max(face_size / 8.0, params.size_min), wall_report);
    });
    const PointSizes narrow(std::move(narrow_points), kNarrowFaceGrowth);
    const std::vector<const PointSizes*> points{&asked, &narrow};
    const double size_factor = get_number("Mesh.MeshSizeFactor");
    const std::string context = path + ": Gmsh failed to mesh the surfaces (maximum size " + format_number(sizes.size) +
                                "); try a smaller size, another algorithm, or repair the CAD";
    const std::function<void()> generate = [&] {
        std::optional<SizeCallback> callback;
        if (!asked.empty() || !narrow.empty() || !defaults.walls.empty())
            callback.emplace(defaults.sizes(), size_factor, points);
        gmsh::model::mesh::generate(2);
    };
    const bool quads = get_number("Mesh.RecombineAll") > 0.0 || params.elements == SurfaceElements::Mixed;
    RecombinationReport recombined;
    const SurfaceGenerator generate_surfaces{quads, options, progress, recombined};
    generate_surfaces(context, generate);

    std::vector<int> face_surface;
    SurfaceMesh mesh = extract(path, surfaces, face_surface);
    if (sizes.default_size)
        mesh = mend_default_size(path, surfaces, sizes, generate_surfaces, generate, std::move(mesh), face_surface,
                                 wall_report);
    if (!defaults.walls.empty()) wall_report.walls_default_size = defaults.share * get_number("Mesh.MeshSizeMax");
    if (params.first_height > 0.0 && params.max_aspect_ratio > 0.0)
        mesh = limit_wall_aspect(path, params, surfaces, points, defaults, std::move(mesh), face_surface,
                                 wall_report, generate_surfaces);
    if (walls) *walls = wall_report;
    if (recombination) *recombination = recombined;
    gmsh_call(path + ": reading the bodies' names", [&] { name_bodies(mesh, face_surface); });
    return mesh;
}

}  // namespace strata
