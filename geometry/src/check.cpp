#include <strata/core/format.h>
#include <strata/core/mesh_check.h>
#include <strata/geometry/check.h>

#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/geometry/topology.h>

#include "model_span.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace strata {
namespace {

std::string patch_name(const SurfaceMesh& mesh, Index f) {
    const Index p = mesh.face_patch[f];
    return "'" + mesh.patches[p].name + "'";
}

/// "face 12 (patch 'wing', centroid (x, y, z))": enough to find the face in a viewer.
std::string face_text(const SurfaceMesh& mesh, Index f) {
    return "face " + std::to_string(f) + " (patch " + patch_name(mesh, f) + ", centroid " +
           format_point(face_centroid(mesh, mesh.points, f), 9) + ")";
}

}  // namespace

void check_surface(const SurfaceMesh& mesh, const std::string& source, bool small_faces_ok) {
    // The arrays first (one check for every stage): everything below indexes through them.
    require_sound(check_surface_arrays(mesh), source + ": ");
    // Before anything computes an area or a volume from the coordinates.
    const BoundingBox box = bounding_box(mesh.points);
    require_model_span(box, source + ": ");
    const Index nf = mesh.num_faces();

    for (Index f = 0; f < nf; ++f) {
        const Index* v = mesh.face_begin(f);
        const Index s = mesh.face_size(f);
        for (Index i = 0; i < s; ++i)
            for (Index j = i + 1; j < s; ++j)
                if (v[i] == v[j])
                    throw TopologyError(source + ": " + face_text(mesh, f) + " uses node " + std::to_string(v[i]) +
                                        " twice (a collapsed face, often from merging close nodes); remove "
                                        "the face or remesh that region");
    }

    // Relative to the model size, so the check means the same in millimetres and metres.
    const double diag = box.diagonal();
    const double min_area = small_faces_ok ? 0.0 : 1e-12 * diag * diag;
    for (Index f = 0; f < nf; ++f) {
        const double a = face_area_vector(mesh, f).norm();
        if (!(a > min_area))  // also catches a == 0 on a zero-size model
            throw TopologyError(source + ": " + face_text(mesh, f) + " has (near) zero area " + format_number(a, 3) +
                                " (its corners are collinear or coincident); remove the face or remesh "
                                "that region");
    }

    const EdgeTable edges = edge_table(mesh);
    Index bad = 0, first = kNone;
    for (Index e = 0; e < edges.faces.rows(); ++e)
        if (edges.faces.row_size(e) > 2) {
            if (first == kNone) first = e;
            ++bad;
        }
    if (first != kNone) {
        const Index a = edges.nodes[first][0], b = edges.nodes[first][1];
        std::string faces;
        for (const Index* f = edges.faces.row_begin(first); f != edges.faces.row_end(first); ++f)
            faces += (faces.empty() ? "" : ", ") + std::to_string(*f) + " (patch " + patch_name(mesh, *f) + ")";
        throw TopologyError(source + ": non-manifold edge between node " + std::to_string(a) + " " +
                            format_point(mesh.points[a], 9) + " and node " + std::to_string(b) + " " +
                            format_point(mesh.points[b], 9) + " is shared by " +
                            std::to_string(edges.faces.row_size(first)) + " faces: " + faces +
                            (bad > 1 ? " (" + std::to_string(bad - 1) + " more such edges)" : std::string()) +
                            "; an edge may bound at most two faces: fix the surface in the CAD tool or merge "
                            "the duplicate faces (meshed from CAD, a part thinner than the size gets its two "
                            "sides meshed through the same nodes: give a smaller CadParams::size)");
    }
}

NeedleReport needle_faces(const SurfaceMesh& mesh, double min_angle_deg, const std::vector<PatchKind>& kinds) {
    NeedleReport r;
    for (Index f = 0; f < mesh.num_faces(); ++f) {
        const PatchKind kind = mesh.patches[static_cast<std::size_t>(mesh.face_patch[f])].kind;
        if (!kinds.empty() && std::find(kinds.begin(), kinds.end(), kind) == kinds.end()) continue;
        ++r.faces;
        const Index n = mesh.face_size(f);
        double sharpest = 180.0;
        Index corner = 0;
        for (Index c = 0; c < n; ++c) {
            const Vec3& o = mesh.points[mesh.face_node(f, c)];
            const Vec3 a = mesh.points[mesh.face_node(f, (c + 1) % n)] - o;
            const Vec3 b = mesh.points[mesh.face_node(f, (c + n - 1) % n)] - o;
            if (a.squaredNorm() == 0.0 || b.squaredNorm() == 0.0) continue;
            const double angle = std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / std::numbers::pi;
            if (angle < sharpest) sharpest = angle, corner = c;
        }
        if (sharpest < min_angle_deg) ++r.needles;
        if (sharpest < r.sharpest_deg) {
            r.sharpest_deg = sharpest;
            r.worst_face = f;
            r.where = mesh.points[mesh.face_node(f, corner)];
        }
    }
    return r;
}

}  // namespace strata
