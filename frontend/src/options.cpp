// The option mapping shared by the front-ends (moved here from the strata program so that the
// Python package applies the same rules and messages).

#include <strata/frontend/options.h>

#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/core/parallel.h>
#include <strata/surface/cad.h>

#include <algorithm>
#include <array>
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

namespace {

/// "NAME=KIND[:NEW]" as its three parts (NEW empty where not given).
std::array<std::string, 3> patch_option_parts(const std::string& s) {
    const auto eq = s.rfind('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == s.size())
        throw InputError("--patch '" + s +
                         "': expected NAME=KIND or NAME=KIND:NEWNAME, e.g. --patch symmetry_plane=symmetry or "
                         "--patch surface_3=wall:fuselage");
    const std::string rest = s.substr(eq + 1);
    const auto colon = rest.find(':');
    if (colon != std::string::npos && colon + 1 == rest.size())
        throw InputError("--patch '" + s + "': no new name after ':'; give NAME=KIND:NEWNAME");
    return {s.substr(0, eq), rest.substr(0, colon), colon == std::string::npos ? "" : rest.substr(colon + 1)};
}

}  // namespace

std::vector<std::pair<std::string, PatchKind>> parse_patch_options(const std::vector<std::string>& items) {
    std::vector<std::pair<std::string, PatchKind>> out;
    for (const std::string& s : items) {
        const auto [name, kind, rename] = patch_option_parts(s);
        out.emplace_back(name, parse_patch_kind(kind));
    }
    return out;
}

std::vector<std::pair<std::string, std::string>> parse_patch_renames(const std::vector<std::string>& items) {
    std::vector<std::pair<std::string, std::string>> out;
    for (const std::string& s : items) {
        const auto [name, kind, rename] = patch_option_parts(s);
        if (!rename.empty()) out.emplace_back(name, rename);
    }
    return out;
}

PrepareParams prepare_params(const SurfaceOptions& c, const LayerParams* layers) {
    PrepareParams p = c.prepare;
    if (c.quads) p.cad.elements = SurfaceElements::Quads;
    if (!c.mixed.empty()) {
        p.cad.elements = SurfaceElements::Mixed;
        p.cad.quad_surfaces = c.mixed;
    }
    const CadParams none;
    p.fuse = p.cad.fuse;  // --fuse: CAD solids by OpenCASCADE, overlapping mesh components by CGAL
    p.wrap = c.wrap >= 0.0;
    p.wrapping.alpha = std::max(c.wrap, 0.0);
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
    if (!any_cad && p.cad.narrow_face_ratio != none.narrow_face_ratio)
        throw InputError("'" + c.input +
                         "' is a surface mesh: --narrow-faces sizes the narrow faces of a CAD model; remove it");
    if (!any_cad && p.cad.sew_tolerance != none.sew_tolerance)
        throw InputError("'" + c.input +
                         "' is a surface mesh: --sew-tolerance sews the faces of a CAD model (STEP, IGES, BREP); "
                         "for a surface mesh whose faces miss each other, use --merge-tolerance");
    if (!any_cad && !p.cad.units.empty())
        throw InputError("'" + c.input +
                         "' is a surface mesh, which carries no unit: --units applies to STEP and IGES "
                         "only; use --scale to convert");
    p.patch_kinds = parse_patch_options(c.patches);
    p.patch_names = parse_patch_renames(c.patches);
    // Walls sized for the first layer: CAD in its own unit (before --scale), a remeshed surface
    // in the model's (after it).
    p.remeshing.max_aspect_ratio = p.cad.max_aspect_ratio;
    if (layers) p.cad.threads = p.wrapping.threads = layers->threads;
    if (layers && (any_cad || p.remesh) && !automatic_first_height(layers->distribution))
        size_walls_for_layers(p, *layers, resolve(layers->distribution).first_height);
    return p;
}

void size_walls_for_layers(PrepareParams& p, const LayerParams& layers, double first_height) {
    if (!(p.cad.max_aspect_ratio > 0.0)) return;
    const double fan = layers.min_quality > 0.0 ? layers.fan_angle_deg : 0.0;
    p.cad.first_height = first_height / p.scale;
    p.cad.fan_angle_deg = fan;
    p.remeshing.first_height = first_height;
    p.remeshing.fan_angle_deg = fan;
}

std::string sewing_hint(const SewReport& sew) {
    if (sew.cracks == 0) return "";
    return "; better for this CAD model: its faces were sewn with a tolerance of " + format_number(sew.tolerance, 3) +
           ", but " + std::to_string(sew.cracks) + " of their edges still miss another by up to " +
           format_number(sew.widest_gap, 3) + " (at " + format_point(sew.gap_at) + "): CadParams::sew_tolerance " +
           format_number(sew.suggested_tolerance, 2) + " sews them";
}

LayerParams layer_params(const LayerOptions& o) {
    LayerParams p = o.params;
    check_threads(p.threads, "LayerParams::threads");  // before any work: the stages check it again
    p.distribution.kind = parse_distribution(o.distribution);
    p.normals = parse_normal_method(o.normals);
    p.proximity = parse_proximity_mode(o.proximity);
    // Its errors before any input is read (an option should not cost a run), with a first height
    // chosen as run() would where none is asked: on walls of any length, the same checks.
    DistributionParams d = p.distribution;
    if (automatic_first_height(d)) d.first_height = automatic_first_height(d, 1.0);
    (void)resolve(d);
    return p;
}

HybridParams hybrid_params(const LayerOptions& layers, const MeshOptions& mesh) {
    HybridParams hp = mesh.params;
    hp.layers = layer_params(layers);
    hp.threads = hp.layers.threads;
    hp.farfield.shape = parse_farfield_shape(mesh.farfield);
    hp.tets.mesher = parse_tet_mesher(mesh.tets);
    return hp;
}

Options options_of(const HybridParams& mesh, const PrepareParams& prepare) {
    Options o;
    o.surface.prepare = prepare;
    o.layers.params = mesh.layers;
    o.layers.distribution = to_string(mesh.layers.distribution.kind);
    o.layers.normals = to_string(mesh.layers.normals);
    o.layers.proximity = to_string(mesh.layers.proximity);
    o.mesh.params = mesh;
    o.mesh.farfield = to_string(mesh.farfield.shape);
    o.mesh.tets = to_string(mesh.tets.mesher);
    return o;
}

namespace {

using Stage = OptionStage;

/// An option bound to the field \p f returns (a captureless lambda).
template <class F>
OptionSpec spec(std::string flag, std::string keyword, std::string param, Stage stage, F f, std::string help) {
    OptionSpec o;
    o.flag = std::move(flag);
    o.keyword = std::move(keyword);
    o.param = std::move(param);
    o.stage = stage;
    o.field = +f;
    o.help = std::move(help);
    return o;
}

OptionSpec no_default(OptionSpec o) {
    o.show_default = false;
    return o;
}

/// An optional size (OptionSpec::optional_size), Python's doc \p keyword_help.
OptionSpec optional_size(OptionSpec o, std::string keyword_help) {
    o.show_default = false;
    o.optional_size = true;
    o.keyword_help = std::move(keyword_help);
    return o;
}

/// A switch on by default that the CLI's flag turns off; \p keyword_help says what it does on.
OptionSpec turned_off(OptionSpec o, std::string keyword_help) {
    o.flag_sets_false = true;
    o.show_default = false;
    o.keyword_help = std::move(keyword_help);
    return o;
}

/// How the surface is made (CadParams, RemeshParams, PrepareParams; the switches quads, remesh).
void add_surface_options(std::vector<OptionSpec>& t) {
    t.push_back(spec(
        "--size", "size", "CadParams::size", Stage::Surface,
        [](Options& o) -> double& { return o.surface.prepare.cad.size; },
        "target surface element size, model units (CAD or --remesh; 0: CAD 1/20 of the bounding-box diagonal, "
        "--remesh the input's median edge)"));
    t.push_back(spec(
        "--size-min", "size_min", "CadParams::size_min", Stage::Surface,
        [](Options& o) -> double& { return o.surface.prepare.cad.size_min; },
        "smallest element size under curvature refinement (CAD or --remesh; 0: size/20)"));
    t.push_back(spec(
        "--curvature", "curvature_points", "CadParams::curvature_points", Stage::Surface,
        [](Options& o) -> int& { return o.surface.prepare.cad.curvature_points; },
        "refine by curvature: elements per 2*pi of radius (CAD or --remesh; 0: off)"));
    t.push_back(spec(
        "--narrow-faces", "narrow_face_ratio", "CadParams::narrow_face_ratio", Stage::Surface,
        [](Options& o) -> double& { return o.surface.prepare.cad.narrow_face_ratio; },
        "CAD faces narrower than the size over this get triangles this many times their width long, not slivers "
        "(0: off)"));
    t.push_back(spec(
        "", "algorithm", "CadParams::algorithm", Stage::Surface,
        [](Options& o) -> int& { return o.surface.prepare.cad.algorithm; },
        "Gmsh 2D algorithm for CAD: 1, 2, 5, 6 or 9"));
    t.push_back(no_default(spec(
        "--quads", "quads", "", Stage::Surface, [](Options& o) -> bool& { return o.surface.quads; },
        "recombine the surface mesh into quadrilaterals (CAD or --remesh)")));
    t.push_back(no_default(spec(
        "--mixed", "mixed", "CadParams::quad_surfaces", Stage::Surface,
        [](Options& o) -> std::vector<int>& { return o.surface.mixed; },
        "quadrilaterals on these CAD surface tags, triangles elsewhere (CAD only)")));
    t.push_back(no_default(spec(
        "--fuse", "fuse", "CadParams::fuse", Stage::Surface,
        [](Options& o) -> bool& { return o.surface.prepare.cad.fuse; },
        "fuse overlapping bodies into one: a CAD file's solids before meshing "
        "(OpenCASCADE), overlapping closed surface-mesh components after reading (exact "
        "corefinement, CGAL)")));
    t.push_back(optional_size(
        spec("--remesh", "remesh", "", Stage::Surface, [](Options& o) -> double& { return o.surface.remesh; },
             "--remesh [SIZE]: mesh the surface again with Gmsh (a dirty STL's needle faces, the cuts of --fuse): "
             "sharp edges (--feature-angle) and patches are kept; SIZE, or --size, is the element size (default: "
             "the input's median edge); --size-min, --curvature and --quads apply"),
        "None, or mesh the surface again with Gmsh (a dirty STL's needle faces, the cuts of fuse) with this element "
        "size (0: size, or the input's median edge): sharp edges (feature_angle_deg) and patches are kept"));
    t.push_back(optional_size(
        spec("--wrap", "wrap", "", Stage::Surface, [](Options& o) -> double& { return o.surface.wrap; },
             "--wrap [SIZE]: replace the walls by one watertight surface wrapped round them (CGAL's alpha wrap), "
             "for a surface nothing repairs in place (non-manifold edges, holes, parts through or against each "
             "other); SIZE is the narrowest gap or hole the wrap follows (default: a hundredth of the model's "
             "diagonal), the wrap lies SIZE/30 outside the input; with --remesh the wrap is meshed again"),
        "None, or replace the walls by one watertight surface wrapped round them (CGAL's alpha wrap) with this "
        "size, the narrowest gap it follows (0: a hundredth of the model's diagonal); with remesh, meshed again"));
    t.push_back(spec(
        "--feature-angle", "feature_angle_deg", "RemeshParams::feature_angle_deg", Stage::Surface,
        [](Options& o) -> double& { return o.surface.prepare.remeshing.feature_angle_deg; },
        "with --remesh: edges whose faces turn more than this, degrees, stay sharp"));
    t.push_back(no_default(spec(
        "--units", "units", "CadParams::units", Stage::Surface,
        [](Options& o) -> std::string& { return o.surface.prepare.cad.units; },
        "STEP and IGES only: read the model in this length unit (mm, cm, m, km, in, ft, "
        "...); default: the unit the file declares. Every length option is in the unit "
        "the summary states")));
    t.push_back(spec(
        "--sew-tolerance", "sew_tolerance", "CadParams::sew_tolerance", Stage::Surface,
        [](Options& o) -> double& { return o.surface.prepare.cad.sew_tolerance; },
        "STEP, IGES, BREP: faces that bound no solid (a surface model, whose faces each have their own edges) are "
        "sewn by OpenCASCADE with this tolerance, a share of the bounding-box diagonal (in [0, 0.001]; 0: not sewn)"));
    t.push_back(no_default(spec(
        "--trust-geo", "trust_geo", "CadParams::trust_geo", Stage::Surface,
        [](Options& o) -> bool& { return o.surface.prepare.cad.trust_geo; },
        "run a .geo script even where it runs shell commands or programs, talks to a server or writes files "
        "(SystemCall, OnelabRun, Save, Printf > file, ...), itself or through a script it reads: a .geo file is a "
        "program; give this only for a script whose author you trust")));
    t.push_back(spec(
        "--scale", "scale", "PrepareParams::scale", Stage::Surface,
        [](Options& o) -> double& { return o.surface.prepare.scale; },
        "multiply every coordinate by this after reading (any input; STL and MSH carry no unit)"));
    t.push_back(spec(
        "--collapse-edges", "collapse_ratio", "PrepareParams::collapse_ratio", Stage::Patches,
        [](Options& o) -> double& { return o.surface.prepare.collapse_ratio; },
        "collapse edges shorter than this share of the edges around them (a CAD model's small edges and sliver "
        "faces, whose needle faces cap the layer cells on them; in [0, 0.5], 0: off)"));
    t.push_back(spec(
        "--merge-tolerance", "merge_tolerance", "PrepareParams::merge_tolerance", Stage::Patches,
        [](Options& o) -> double& { return o.surface.prepare.merge_tolerance; },
        "nodes closer than this share of the bounding-box diagonal are one (in [0, 0.001]): a larger one welds "
        "the cracks a CAD export leaves between faces"));
    t.push_back(spec(
        "--fill-holes", "fill_holes", "PrepareParams::fill_holes", Stage::Patches,
        [](Options& o) -> int& { return o.surface.prepare.fill_holes; },
        "close the surface's open loops of at most this many edges with triangles (the few triangles an STL lost; 0: "
        "none, as a half model's cut is open on purpose)"));
    t.push_back(no_default(spec(
        "--caps", "caps", "PrepareParams::caps", Stage::Patches, [](Options& o) -> bool& { return o.surface.prepare.caps; },
        "with --fill-holes: close each open loop by a cap of its own (the inlet and outlets of a vessel cut open): "
        "patches cap_1, cap_2, ... of kind other, meshed inside, which the layers meet as an outflow plane; name "
        "them with --patch cap_1=other:inlet")));
    t.push_back(no_default(spec(
        "--internal", "internal_flow", "PrepareParams::internal_flow", Stage::Patches,
        [](Options& o) -> bool& { return o.surface.prepare.internal_flow; },
        "the fluid is inside the closed walls (a duct, a wind tunnel), not around them: "
        "layers grow inward from the outermost walls and outward from the bodies inside, "
        "and strata mesh fills the walls instead of adding a farfield")));
    OptionSpec patches = no_default(spec(
        "--patch", "patches", "PrepareParams::patch_kinds", Stage::Patches,
        [](Options& o) -> std::vector<std::string>& { return o.surface.patches; },
        "set a patch's kind, NAME=KIND with KIND wall|symmetry|farfield|other, and rename it with "
        "NAME=KIND:NEWNAME (patches given one name become one) (repeatable)"));
    patches.keyword_help =
        "None, or {patch name: 'wall' | 'symmetry' | 'farfield' | 'other', or 'KIND:NEWNAME' to rename it too}";
    t.push_back(std::move(patches));
}

/// The layers' heights (DistributionParams; enums as text) and the walls sized for them.
void add_distribution_options(std::vector<OptionSpec>& t) {
    t.push_back(spec(
        "--layers", "layers", "DistributionParams::layers", Stage::Layers,
        [](Options& o) -> int& { return o.layers.params.distribution.layers; }, "number of layers"));
    t.push_back(no_default(spec(
        "--first-height", "first_height", "DistributionParams::first_height", Stage::Layers,
        [](Options& o) -> double& { return o.layers.params.distribution.first_height; },
        "height of the first layer, model units (or --yplus); none (0): the one with which the layers reach 2 % "
        "of the walls' length (or the --thickness given), said in the summary")));
    t.push_back(spec(
        "--growth", "growth", "DistributionParams::growth", Stage::Layers,
        [](Options& o) -> double& { return o.layers.params.distribution.growth; },
        "growth ratio of geometric layers (0: 1.2)"));
    t.push_back(no_default(spec(
        "--thickness", "thickness", "DistributionParams::thickness", Stage::Layers,
        [](Options& o) -> double& { return o.layers.params.distribution.thickness; },
        "total thickness of the layers, model units")));
    t.push_back(no_default(spec(
        "--yplus", "yplus", "DistributionParams::yplus", Stage::Layers,
        [](Options& o) -> double& { return o.layers.params.distribution.yplus; },
        "first height from this target y+ (with --reynolds, --ref-length)")));
    t.push_back(no_default(spec(
        "--reynolds", "reynolds", "DistributionParams::reynolds", Stage::Layers,
        [](Options& o) -> double& { return o.layers.params.distribution.reynolds; },
        "Reynolds number for --yplus, and of the flow --foam-case writes")));
    t.push_back(spec(
        "--ref-length", "reference_length", "DistributionParams::reference_length", Stage::Layers,
        [](Options& o) -> double& { return o.layers.params.distribution.reference_length; },
        "reference length of the Reynolds number (--yplus, --foam-case), model units"));
    t.push_back(spec(
        "--distribution", "distribution", "DistributionParams::kind", Stage::Layers,
        [](Options& o) -> std::string& { return o.layers.distribution; },
        "auto (thickness if --thickness is given without --growth, else geometric), geometric (first "
        "height + growth), thickness (first height + thickness: growth solved) or tanh (the paper's; "
        "first height + thickness)"));
    t.push_back(spec(
        "--max-aspect-ratio", "max_aspect_ratio", "CadParams::max_aspect_ratio", Stage::Layers,
        [](Options& o) -> double& { return o.surface.prepare.cad.max_aspect_ratio; },
        "CAD input and --remesh: wall surfaces whose first-layer cells would have an OpenFOAM aspect ratio "
        "above this (fans' first cells too) are meshed again finer, up to about 200,000 faces, and where the mesh "
        "still has cells above it the walls are meshed again finer round them and the mesh made again, once "
        "(checkMesh fails above 1000; 0: keep the size)"));
    t.push_back(spec(
        "--step-quality", "step_quality", "CadParams::step_quality", Stage::Mesh,
        [](Options& o) -> double& { return o.surface.prepare.cad.step_quality; },
        "CAD input: where the layers step at a proximity limit (fewer layers beside more, in a narrow gap), the "
        "walls are meshed again finer so that the step's layer height is at least Q of the wall spacing there (the "
        "cells closing the step then reach a scaled Jacobian of about Q/2), with at most 3 times the faces; the "
        "finer walls are dropped if the layers would lose thickness on them (0: keep the walls)"));
}

/// How the layers are marched and where a column stops (LayerParams).
void add_marching_options(std::vector<OptionSpec>& t) {
    t.push_back(spec(
        "--sweeps", "sweeps", "LayerParams::sweeps", Stage::Layers,
        [](Options& o) -> int& { return o.layers.params.sweeps; }, "Poisson smoothing sweeps per layer"));
    t.push_back(spec(
        "--max-sweeps", "max_sweeps", "LayerParams::max_sweeps", Stage::Layers,
        [](Options& o) -> int& { return o.layers.params.max_sweeps; },
        "more sweeps allowed while the update stays large"));
    t.push_back(spec(
        "", "tolerance", "LayerParams::tolerance", Stage::Layers,
        [](Options& o) -> double& { return o.layers.params.tolerance; },
        "stop extra sweeps when the update is below this share of the layer height"));
    t.push_back(turned_off(spec(
                               "--no-control", "control_functions", "LayerParams::control_functions", Stage::Layers,
                               [](Options& o) -> bool& { return o.layers.params.control_functions; },
                               "no control functions (Phi, Psi from the wall; Theta from the distribution)"),
                           "control functions (Phi, Psi from the wall; Theta from the distribution)"));
    t.push_back(turned_off(
        spec(
            "--no-concave", "concave", "LayerParams::concave", Stage::Layers,
            [](Options& o) -> bool& { return o.layers.params.concave; }, "no extra smoothing in concave regions"),
        "extra smoothing in concave regions"));
    t.push_back(turned_off(spec(
                               "--no-hold-back", "hold_back", "LayerParams::hold_back", Stage::Layers,
                               [](Options& o) -> bool& { return o.layers.params.hold_back; },
                               "with --min-quality 0: where a layer's cells would invert, stop with an error "
                               "instead of holding the layer back there"),
                           "with min_quality 0: hold a layer back where its cells would invert instead of "
                           "stopping with an error"));
    t.push_back(spec(
        "--min-quality", "min_quality", "LayerParams::min_quality", Stage::Layers,
        [](Options& o) -> double& { return o.layers.params.min_quality; },
        "a column stops where a cell it would make has a scaled Jacobian below this share of what "
        "its wall face allows; 0: no local stopping (every column gets every layer, held back where "
        "it would fold; a fold that holding back cannot save is an error)"));
    t.push_back(spec(
        "--max-turn", "max_turn_deg", "LayerParams::max_turn_deg", Stage::Layers,
        [](Options& o) -> double& { return o.layers.params.max_turn_deg; },
        "a column stops where it would turn more than this, degrees"));
    t.push_back(spec(
        "--max-twist", "max_twist_deg", "LayerParams::max_twist_deg", Stage::Layers,
        [](Options& o) -> double& { return o.layers.params.max_twist_deg; },
        "a column stops where a cell it would make has its top turned more than this about its axis "
        "against its bottom, degrees"));
    t.push_back(spec(
        "--isotropy", "isotropy", "LayerParams::isotropy", Stage::Layers,
        [](Options& o) -> double& { return o.layers.params.isotropy; },
        "a column stops before a layer taller than this times the spacing of the layer front round it "
        "(cells taller than wide: the tetrahedra take over there, as AFLR3 stops its layers); every column "
        "keeps its first layer; 0: never"));
    t.push_back(spec(
        "--fan-angle", "fan_angle_deg", "LayerParams::fan_angle_deg", Stage::Layers,
        [](Options& o) -> double& { return o.layers.params.fan_angle_deg; },
        "a fan of columns (one per side, more between) at convex edges whose faces turn by this many "
        "degrees or more, and the convex edges that close their chains; 0: no fans"));
    t.push_back(spec(
        "--sharp-edge-stop", "sharp_edge_stop_deg", "LayerParams::sharp_edge_stop_deg", Stage::Layers,
        [](Options& o) -> double& { return o.layers.params.sharp_edge_stop_deg; },
        "columns stop at the wall on convex edges whose faces turn by this many degrees or more and "
        "that get no fan (one direction there leaves the cells on both sides skewed); 0: never"));
    t.push_back(spec(
        "--normals", "normals", "LayerParams::normals", Stage::Layers,
        [](Options& o) -> std::string& { return o.layers.normals; },
        "node normals: robust, area (the paper's), angle, max"));
    t.push_back(spec(
        "--proximity", "proximity", "LayerParams::proximity", Stage::Layers,
        [](Options& o) -> std::string& { return o.layers.proximity; },
        "where the domain is narrower than the layers need: stop (fewer layers there, the first "
        "height kept), scale (thinner layers there) or off"));
    t.push_back(spec(
        "--front-slope", "front_slope", "ProximityParams::front_slope", Stage::Mesh,
        [](Options& o) -> double& { return o.layers.params.proximity_limits.front_slope; },
        "where the layer top meets itself, the columns there are lowered and their neighbours follow within "
        "this thickness per unit of wall distance; halved where the same columns must be lowered again, and "
        "0.25 from the fifth round on (default 1: the lowering stays where the front met itself)"));
    t.push_back(spec(
        "--threads", "threads", "LayerParams::threads", Stage::Layers,
        [](Options& o) -> int& { return o.layers.params.threads; },
        "threads (0: all cores); the output is the same for any count"));
}

/// The rest of the hybrid mesh (FarfieldParams, PyramidParams, TetFillParams).
void add_mesh_options(std::vector<OptionSpec>& t) {
    t.push_back(spec(
        "--farfield", "farfield", "FarfieldParams::shape", Stage::Mesh,
        [](Options& o) -> std::string& { return o.mesh.farfield; },
        "generated outer boundary when the input has no farfield patch: sphere or box"));
    t.push_back(spec(
        "--farfield-size", "farfield_size", "FarfieldParams::size", Stage::Mesh,
        [](Options& o) -> double& { return o.mesh.params.farfield.size; },
        "farfield extent as a multiple of the body size"));
    t.push_back(spec(
        "", "farfield_divisions", "FarfieldParams::divisions", Stage::Mesh,
        [](Options& o) -> int& { return o.mesh.params.farfield.divisions; }, "resolution of the generated farfield"));
    t.push_back(spec(
        "--pyramid-height", "pyramid_height", "PyramidParams::height", Stage::Mesh,
        [](Options& o) -> double& { return o.mesh.params.pyramids.height; },
        "pyramid apex height relative to the quad size"));
    t.push_back(spec(
        "", "pyramid_min_height", "PyramidParams::min_height", Stage::Mesh,
        [](Options& o) -> double& { return o.mesh.params.pyramids.min_height; },
        "lowest pyramid apex, relative to the quad's shortest edge"));
    t.push_back(spec(
        "--tets", "tets", "TetFillParams::mesher", Stage::Mesh, [](Options& o) -> std::string& { return o.mesh.tets; },
        "tetrahedral mesher: tetgen (one thread, the same mesh for any thread count) or hxt (Gmsh's HXT on "
        "every thread, faster; the same mesh for the same thread count)"));
    t.push_back(spec(
        "--radius-edge", "radius_edge", "TetFillParams::radius_edge", Stage::Mesh,
        [](Options& o) -> double& { return o.mesh.params.tets.radius_edge; },
        "tetrahedron quality bound, radius/edge (TetGen -q)"));
    t.push_back(spec(
        "--min-dihedral", "min_dihedral", "TetFillParams::min_dihedral", Stage::Mesh,
        [](Options& o) -> double& { return o.mesh.params.tets.min_dihedral; },
        "smallest dihedral angle of the tetrahedra TetGen should aim for, degrees (TetGen -q R/D; 0: "
        "TetGen's own)"));
    t.push_back(spec(
        "--max-dihedral", "max_dihedral", "TetFillParams::max_dihedral", Stage::Mesh,
        [](Options& o) -> double& { return o.mesh.params.tets.max_dihedral; },
        "largest dihedral angle of the tetrahedra TetGen's optimisation works down to, degrees "
        "(TetGen -o/A; 0: TetGen's own, 165)"));
    t.push_back(spec(
        "--tet-improve", "tet_improve", "TetImproveParams::below", Stage::Mesh,
        [](Options& o) -> double& { return o.mesh.params.improve.below; },
        "after TetGen, improve the tetrahedra below this scaled Jacobian by flips and by moving the points "
        "TetGen added (0: off)"));
    t.push_back(spec(
        "", "refine", "TetFillParams::refine", Stage::Mesh,
        [](Options& o) -> bool& { return o.mesh.params.tets.refine; },
        "add interior Steiner points for quality and size"));
    t.push_back(spec(
        "", "max_volume", "TetFillParams::max_volume", Stage::Mesh,
        [](Options& o) -> double& { return o.mesh.params.tets.max_volume; }, "volume bound per tetrahedron (0: none)"));
    t.push_back(spec(
        "--tet-growth", "tet_growth", "TetFillParams::growth", Stage::Mesh,
        [](Options& o) -> double& { return o.mesh.params.tets.growth; },
        "growth of the tetrahedron size with distance from the body"));
    t.push_back(spec(
        "", "background_mesh", "TetFillParams::background_mesh", Stage::Mesh,
        [](Options& o) -> bool& { return o.mesh.params.tets.background_mesh; },
        "sample the size field on a background mesh"));
}

/// How a volume mesh is written (OutputOptions).
void add_output_options(std::vector<OptionSpec>& t) {
    t.push_back(no_default(spec(
        "--foam-case", "foam_case", "OutputOptions::foam_case", Stage::Output,
        [](Options& o) -> bool& { return o.output.foam_case; },
        "the output is an OpenFOAM case directory (-o CASE): CASE/constant/polyMesh and a simpleFoam start "
        "(k-omega SST; system/, constant/, 0.orig/ written where the case has none, 0/ a copy of 0.orig/), "
        "every patch given conditions from its kind; U 1 along x, Re from --reynolds (default 1e6) on --ref-length")));
}

std::vector<OptionSpec> make_table() {
    std::vector<OptionSpec> t;
    add_surface_options(t);
    add_distribution_options(t);
    add_marching_options(t);
    add_mesh_options(t);
    add_output_options(t);
    return t;
}

}  // namespace

const std::vector<OptionSpec>& option_table() {
    static const std::vector<OptionSpec> table = make_table();
    return table;
}

namespace {

/// Library names to the CLI's flags or (\p keywords) Python's: a switch's "= false" or "= true"
/// first (as what its flag, or its keyword so given, does), then the parameters, then for
/// Python the flags of the front-end's own messages.
std::vector<std::pair<std::string, std::string>> names_for(bool keywords) {
    std::vector<std::pair<std::string, std::string>> n;
    auto name = [keywords](const OptionSpec& o) -> const std::string& { return keywords ? o.keyword : o.flag; };
    for (const OptionSpec& o : option_table()) {
        if (name(o).empty() || o.param.empty() || !std::holds_alternative<bool& (*)(Options&)>(o.field)) continue;
        if (o.flag_sets_false)
            n.emplace_back(o.param + " = false", keywords ? o.keyword + "=False" : o.flag);
        else
            n.emplace_back(o.param + " = true", keywords ? o.keyword + "=True" : o.flag);
    }
    for (const OptionSpec& o : option_table())
        if (!name(o).empty() && !o.param.empty()) n.emplace_back(o.param, name(o));
    // Parameters several options set, or no option alone.
    n.emplace_back("CadParams::elements", keywords ? "quads/mixed" : "--quads/--mixed");
    n.emplace_back("HybridParams::threads", keywords ? "threads" : "--threads");
    n.emplace_back("PrepareParams::remesh", keywords ? "remesh" : "--remesh");
    n.emplace_back("PrepareParams::wrap", keywords ? "wrap" : "--wrap");
    n.emplace_back("PrepareParams::patch_names", keywords ? "patches" : "--patch");
    if (keywords)
        for (const OptionSpec& o : option_table())
            if (!o.keyword.empty() && !o.flag.empty()) n.emplace_back(o.flag, o.keyword);
    return n;
}

}  // namespace

const std::vector<std::pair<std::string, std::string>>& flag_of_parameter() {
    static const std::vector<std::pair<std::string, std::string>> names = names_for(false);
    return names;
}

const std::vector<std::pair<std::string, std::string>>& keyword_of_name() {
    static const std::vector<std::pair<std::string, std::string>> names = names_for(true);
    return names;
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
