// The option mapping shared by the front-ends (moved here from the strata program so that the
// Python package applies the same rules and messages).

#include <strata/frontend/options.h>

#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/geometry/cad.h>

#include <algorithm>
#include <cctype>

namespace strata {

std::string input_name(const std::vector<std::string>& inputs) {
    std::string name;
    for (const std::string& f : inputs) name += (name.empty() ? "" : " + ") + f;
    return name;
}

bool any_cad_input(const std::vector<std::string>& inputs) {
    return std::any_of(inputs.begin(), inputs.end(), [](const std::string& f) { return is_cad_file(f); });
}

std::vector<std::pair<std::string, PatchKind>> parse_patch_options(const std::vector<std::string>& items) {
    std::vector<std::pair<std::string, PatchKind>> out;
    for (const std::string& s : items) {
        const auto eq = s.rfind('=');
        if (eq == std::string::npos || eq == 0 || eq + 1 == s.size())
            throw InputError("--patch '" + s + "': expected NAME=KIND, e.g. --patch symmetry_plane=symmetry");
        out.emplace_back(s.substr(0, eq), parse_patch_kind(s.substr(eq + 1)));
    }
    return out;
}

PrepareParams prepare_params(const SurfaceOptions& c) {
    PrepareParams p = c.prepare;
    if (c.quads) p.cad.elements = SurfaceElements::Quads;
    if (!c.mixed.empty()) {
        p.cad.elements = SurfaceElements::Mixed;
        p.cad.quad_surfaces = c.mixed;
    }
    const CadParams none;
    p.fuse = p.cad.fuse;  // --fuse: CAD solids by OpenCASCADE, overlapping mesh components by CGAL
    p.remesh = c.remesh >= 0.0;
    if (p.remesh) {
        // The surface-meshing options apply to the new mesh as they do to CAD.
        RemeshParams& r = p.remeshing;
        r.size = c.remesh > 0.0 ? c.remesh : p.cad.size;
        r.size_min = p.cad.size_min;
        r.curvature_points = p.cad.curvature_points;
        r.quads = c.quads;
        if (!c.mixed.empty())
            throw InputError(
                "--mixed names CAD surface tags, which a remeshed surface no longer has; use "
                "--quads or leave --remesh out");
        if (c.remesh > 0.0 && p.cad.size != none.size && p.cad.size != c.remesh)
            throw InputError("--remesh " + format_number(c.remesh) + " and --size " + format_number(p.cad.size) +
                             " ask for two sizes; give one");
    } else if (p.remeshing.feature_angle_deg != RemeshParams{}.feature_angle_deg) {
        throw InputError("--feature-angle applies to --remesh only; add --remesh or remove it");
    }
    const bool cad_options = c.quads || !c.mixed.empty() || p.cad.size != none.size ||
                             p.cad.curvature_points != none.curvature_points || p.cad.size_min != none.size_min ||
                             !p.cad.units.empty();
    const bool any_cad = any_cad_input(c.inputs);
    if (!any_cad && !p.remesh && cad_options)
        throw InputError("'" + c.input +
                         "' is already a surface mesh: --size, --size-min, --curvature, --quads and --mixed "
                         "apply to CAD input or with --remesh only, --units to STEP and IGES; remove them "
                         "(--scale scales any input) or add --remesh");
    if (!any_cad && !p.cad.units.empty())
        throw InputError("'" + c.input +
                         "' is a surface mesh, which carries no unit: --units applies to STEP and IGES "
                         "only; use --scale to convert");
    p.patch_kinds = parse_patch_options(c.patches);
    return p;
}

LayerParams layer_params(const LayerOptions& o) {
    LayerParams p = o.params;
    p.distribution.kind = parse_distribution(o.distribution);
    p.normals = parse_normal_method(o.normals);
    p.proximity = parse_proximity_mode(o.proximity);
    p.control_functions = p.control_functions && !o.no_control;
    p.concave = p.concave && !o.no_concave;
    p.hold_back = p.hold_back && !o.no_hold_back;
    return p;
}

HybridParams hybrid_params(const LayerOptions& layers, const MeshOptions& mesh) {
    HybridParams hp = mesh.params;
    hp.layers = layer_params(layers);
    hp.threads = hp.layers.threads;
    hp.farfield.shape = parse_farfield_shape(mesh.farfield);
    return hp;
}

const std::vector<std::pair<std::string, std::string>>& flag_of_parameter() {
    static const std::vector<std::pair<std::string, std::string>> table = {
        {"PrepareParams::patch_kinds", "--patch"},
        {"CadParams::size", "--size"},
        {"CadParams::size_min", "--size-min"},
        {"CadParams::curvature_points", "--curvature"},
        {"CadParams::elements", "--quads/--mixed"},
        {"CadParams::quad_surfaces", "--mixed"},
        {"CadParams::fuse", "--fuse"},
        {"PrepareParams::internal_flow", "--internal"},
        {"PrepareParams::scale", "--scale"},
        {"CadParams::units", "--units"},
        {"DistributionParams::layers", "--layers"},
        {"DistributionParams::kind", "--distribution"},
        {"DistributionParams::first_height", "--first-height"},
        {"DistributionParams::growth", "--growth"},
        {"DistributionParams::thickness", "--thickness"},
        {"DistributionParams::yplus", "--yplus"},
        {"DistributionParams::reynolds", "--reynolds"},
        {"DistributionParams::reference_length", "--ref-length"},
        {"LayerParams::sweeps", "--sweeps"},
        {"LayerParams::max_sweeps", "--max-sweeps"},
        // The switches whose flag turns them off: their "= false" first, as the flag itself.
        {"LayerParams::control_functions = false", "--no-control"},
        {"LayerParams::concave = false", "--no-concave"},
        {"LayerParams::hold_back = false", "--no-hold-back"},
        {"LayerParams::control_functions", "--no-control"},
        {"LayerParams::concave", "--no-concave"},
        {"LayerParams::hold_back", "--no-hold-back"},
        {"LayerParams::normals", "--normals"},
        {"LayerParams::proximity", "--proximity"},
        {"LayerParams::min_quality", "--min-quality"},
        {"LayerParams::max_turn_deg", "--max-turn"},
        {"LayerParams::max_twist_deg", "--max-twist"},
        {"LayerParams::fan_angle_deg", "--fan-angle"},
        {"LayerParams::threads", "--threads"},
        {"HybridParams::threads", "--threads"},
        {"FarfieldParams::shape", "--farfield"},
        {"FarfieldParams::size", "--farfield-size"},
        {"PyramidParams::height", "--pyramid-height"},
        {"TetFillParams::radius_edge", "--radius-edge"},
        {"TetFillParams::min_dihedral", "--min-dihedral"},
        {"TetFillParams::max_dihedral", "--max-dihedral"},
        {"TetFillParams::growth", "--tet-growth"},
    };
    return table;
}

std::string translate_names(std::string message, const std::vector<std::pair<std::string, std::string>>& names) {
    auto continues = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'; };
    for (const auto& [name, replacement] : names) {
        for (std::size_t at = message.find(name); at != std::string::npos; at = message.find(name, at)) {
            const std::size_t end = at + name.size();
            if (end < message.size() && continues(message[end])) {
                at = end;
                continue;
            }
            message.replace(at, name.size(), replacement);
            at += replacement.size();
        }
    }
    return message;
}

}  // namespace strata
