#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/geometry/cad.h>
#include <strata/geometry/check.h>
#include <strata/geometry/prepare.h>
#include <strata/geometry/topology.h>
#include <strata/io/files.h>
#include <strata/io/read_surface.h>

#include <algorithm>
#include <cctype>
#include <cmath>

namespace strata {
namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

/// The reader for \p path's extension: CAD through Gmsh (mesh_cad), STL and MSH through io/.
SurfaceMesh read_any(const std::string& path, const CadParams& cad, CadUnits* units) {
    check_input_file(path);
    if (is_cad_file(path)) return mesh_cad(path, cad, units);
    const std::string ext = lower_extension(path);
    if (ext == ".stl") return read_stl(path);
    if (ext == ".msh") return read_msh(path);
    throw InputError("'" + path + "': unknown file type '" + ext +
                     "'; Strata reads CAD (.step .stp .iges .igs .brep .brp .geo) and surface "
                     "meshes (.stl .msh)");
}

}  // namespace

void assign_patch_kinds(SurfaceMesh& mesh, const std::vector<std::pair<std::string, PatchKind>>& kinds,
                        const std::string& source) {
    for (Patch& p : mesh.patches) {
        const std::string n = lower(p.name);
        if (n.find("symmetry") != std::string::npos)
            p.kind = PatchKind::Symmetry;
        else if (n.find("farfield") != std::string::npos)
            p.kind = PatchKind::Farfield;
        else
            p.kind = PatchKind::Wall;
    }
    for (const auto& [name, kind] : kinds) {
        const Index i = find_patch(mesh, name);
        if (i == kNone) {
            std::string list;
            for (const Patch& p : mesh.patches) list += (list.empty() ? "" : ", ") + p.name;
            throw InputError(source + ": PrepareParams::patch_kinds " + name + "=" + std::string(to_string(kind)) +
                             ": no patch named '" + name + "'; the patches are: " + list);
        }
        mesh.patches[static_cast<std::size_t>(i)].kind = kind;
    }
}

SurfaceMesh prepare_mesh(SurfaceMesh raw, const PrepareParams& params, const std::string& source, PrepareReport* report,
                         Progress* progress) {
    strata::report(progress, "surface", 0.6);
    if (!(params.scale > 0.0) || !std::isfinite(params.scale))
        throw InputError(source + ": PrepareParams::scale = " + format_number(params.scale) +
                         ": need a positive, finite factor");
    if (params.scale != 1.0)
        for (Vec3& x : raw.points) x *= params.scale;
    assign_patch_kinds(raw, params.patch_kinds, source);
    // Check the raw mesh for NaN and emptiness before merging (merging NaN points is meaningless).
    if (raw.num_faces() == 0) throw InputError(source + ": no faces; it holds no surface mesh");
    SurfaceMesh merged = merge_coincident_nodes(raw, params.merge_tolerance);
    const Index merged_nodes = raw.num_points() - merged.num_points();
    raw = SurfaceMesh{};  // the input copy is no longer needed
    strata::report(progress, "surface", 0.7);
    check_surface(merged, source);
    strata::report(progress, "surface", 0.8);
    OrientReport orient;
    SurfaceMesh oriented = orient_surface(merged, &orient, params.internal_flow);
    if (report) {
        report->scale = params.scale;
        report->merged_nodes = merged_nodes;
        report->orient = orient;
    }
    strata::report(progress, "surface", 1.0);
    return oriented;
}

SurfaceMesh prepare_surface(const std::string& path, const PrepareParams& params, PrepareReport* report,
                            Progress* progress) {
    strata::report(progress, "surface", 0.0);
    CadUnits units;
    SurfaceMesh raw = read_any(path, params.cad, &units);
    SurfaceMesh out = prepare_mesh(std::move(raw), params, path, report, progress);
    if (report) report->units = units;
    return out;
}

}  // namespace strata
