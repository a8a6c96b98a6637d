// The `strata` command line: a thin front-end over the pipeline stages. Every failure is one
// line on stderr and a non-zero exit; outputs are written atomically by the stages' writers.

#include <strata/core/error.h>
#include <strata/geometry/prepare.h>
#include <strata/geometry/topology.h>
#include <strata/io/write_surface.h>
#include <strata/io/cobalt.h>
#include <strata/hybrid/hybrid_mesh.h>
#include <strata/module/layers.h>
#include <strata/core/validate.h>
#include <strata/io/write_volume.h>
#include <strata/core/progress.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

using strata::PatchKind;

/// Parse repeated `--patch NAME=KIND` values.
std::vector<std::pair<std::string, PatchKind>> parse_patch_options(const std::vector<std::string>& items) {
    std::vector<std::pair<std::string, PatchKind>> out;
    for (const std::string& s : items) {
        const auto eq = s.rfind('=');
        if (eq == std::string::npos || eq == 0 || eq + 1 == s.size())
            throw strata::InputError("--patch '" + s + "': expected NAME=KIND, e.g. --patch symmetry_plane=symmetry");
        out.emplace_back(s.substr(0, eq), strata::parse_patch_kind(s.substr(eq + 1)));
    }
    return out;
}

struct SurfaceOptions {
    std::string input;
    std::string output;
    double size = 0.0;
    double size_min = 0.0;
    int curvature = 0;
    bool quads = false;
    std::vector<int> mixed;
    bool fuse = false;
    std::vector<std::string> patches;
    std::string msh_version = "4.1";
    bool quiet = false;
};

void add_surface_input_options(CLI::App& cmd, SurfaceOptions& o) {
    cmd.add_option("INPUT", o.input, "CAD (.step .stp .iges .igs .brep .brp .geo) or surface mesh (.stl .msh)")
        ->required();
    cmd.add_option("--size", o.size,
                   "target surface element size, model units (CAD only; default: 1/20 of the bounding-box diagonal)")
        ->check(CLI::NonNegativeNumber);
    cmd.add_option("--size-min", o.size_min,
                   "smallest element size under curvature refinement (CAD only; default: size/20)")
        ->check(CLI::NonNegativeNumber);
    cmd.add_option("--curvature", o.curvature, "refine by curvature: elements per 2*pi of radius (CAD only; 0 = off)")
        ->check(CLI::NonNegativeNumber);
    auto* q = cmd.add_flag("--quads", o.quads, "recombine the surface mesh into quadrilaterals (CAD only)");
    auto* m =
        cmd.add_option("--mixed", o.mixed, "quadrilaterals on these CAD surface tags, triangles elsewhere (CAD only)")
            ->delimiter(',')
            ->expected(1, -1);
    q->excludes(m);
    cmd.add_flag("--fuse", o.fuse, "fuse all solids into one body before meshing (CAD only)");
    cmd.add_option("--patch", o.patches,
                   "set a patch's kind, NAME=KIND with KIND wall|symmetry|farfield|other (repeatable)");
}

strata::PrepareParams prepare_params(const SurfaceOptions& o) {
    strata::PrepareParams p;
    p.cad.size = o.size;
    p.cad.size_min = o.size_min;
    p.cad.curvature_points = o.curvature;
    p.cad.fuse = o.fuse;
    if (o.quads) p.cad.elements = strata::SurfaceElements::Quads;
    if (!o.mixed.empty()) {
        p.cad.elements = strata::SurfaceElements::Mixed;
        p.cad.quad_surfaces = o.mixed;
    }
    const bool cad = strata::is_cad_file(o.input);
    if (!cad && (o.quads || !o.mixed.empty() || o.fuse || o.size > 0 || o.curvature > 0 || o.size_min > 0))
        throw strata::InputError("'" + o.input +
                                 "' is already a surface mesh: --size, --size-min, --curvature, --quads, --mixed and "
                                 "--fuse apply to CAD input only; remove them");
    p.patch_kinds = parse_patch_options(o.patches);
    return p;
}

void print_surface_summary(const strata::SurfaceMesh& mesh, const strata::PrepareReport& rep) {
    const strata::Csr loops = strata::boundary_loops(mesh);
    std::printf("surface: %d nodes, %d triangles, %d quadrilaterals, %d patches\n", static_cast<int>(mesh.num_points()),
                static_cast<int>(mesh.num_triangles()), static_cast<int>(mesh.num_quads()),
                static_cast<int>(mesh.patches.size()));
    std::vector<int> count(mesh.patches.size(), 0);
    for (strata::Index p : mesh.face_patch) ++count[static_cast<std::size_t>(p)];
    for (std::size_t i = 0; i < mesh.patches.size(); ++i)
        std::printf("  patch %zu %-24s %-9s %d faces\n", i + 1, mesh.patches[i].name.c_str(),
                    std::string(strata::to_string(mesh.patches[i].kind)).c_str(), count[i]);
    std::printf(
        "topology: %d connected components (%d closed), %d open boundary loops, %d merged nodes, %d faces "
        "re-oriented\n",
        static_cast<int>(rep.orient.components), static_cast<int>(rep.orient.closed_components),
        static_cast<int>(loops.rows()), static_cast<int>(rep.merged_nodes), static_cast<int>(rep.orient.flipped_faces));
}

/// Where layers were held back to stay valid (LayerParams::hold_back), so the user knows they are thinner there.
void print_held_back(const std::vector<strata::LayerStats>& stats) {
    int layers = 0, most = 0, first = 0;
    for (std::size_t k = 0; k < stats.size(); ++k) {
        if (stats[k].held_nodes == 0) continue;
        if (layers++ == 0) first = static_cast<int>(k) + 1;
        most = std::max(most, static_cast<int>(stats[k].held_nodes));
    }
    if (layers > 0)
        std::printf(
            "note: from layer %d on, %d layers were held back (lowered, unsmoothed) at up to %d nodes where their "
            "cells would have inverted; the layers are thinner there\n",
            first, layers, most);
}

int run_surface(const SurfaceOptions& o) {
    const auto t0 = std::chrono::steady_clock::now();
    const strata::PrepareParams params = prepare_params(o);
    double version = 4.1;
    if (o.msh_version == "2.2")
        version = 2.2;
    else if (o.msh_version != "4.1")
        throw strata::InputError("--msh-version " + o.msh_version + ": use 4.1 or 2.2");
    strata::PrepareReport rep;
    const strata::SurfaceMesh mesh = strata::prepare_surface(o.input, params, &rep);
    strata::write_surface(mesh, o.output, version);
    if (!o.quiet) {
        print_surface_summary(mesh, rep);
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::printf("wrote %s (%.2f s)\n", o.output.c_str(), s);
    }
    return 0;
}

struct LayerOptions {
    SurfaceOptions surface;
    int layers = 0;
    double first_height = 0.0;
    double growth = 0.0;
    double thickness = 0.0;
    double yplus = 0.0;
    double reynolds = 0.0;
    double ref_length = 1.0;
    std::string distribution;
    int sweeps = 10;
    int max_sweeps = 50;
    bool no_control = false;
    bool no_concave = false;
    bool no_hold_back = false;
    std::string normals = "robust";
    int threads = 0;
};

void add_layer_options(CLI::App& cmd, LayerOptions& o) {
    cmd.add_option("--layers", o.layers, "number of layers")->required()->check(CLI::PositiveNumber);
    cmd.add_option("--first-height", o.first_height, "height of the first layer, model units")
        ->check(CLI::PositiveNumber);
    cmd.add_option("--growth", o.growth, "growth ratio of geometric layers (default 1.2)")
        ->check(CLI::Range(1.0, 10.0));
    cmd.add_option("--thickness", o.thickness, "total thickness of the layers, model units")
        ->check(CLI::PositiveNumber);
    cmd.add_option("--yplus", o.yplus, "first height from this target y+ (with --reynolds, --ref-length)")
        ->check(CLI::PositiveNumber);
    cmd.add_option("--reynolds", o.reynolds, "Reynolds number for --yplus")->check(CLI::PositiveNumber);
    cmd.add_option("--ref-length", o.ref_length, "reference length of the Reynolds number, model units (default 1)")
        ->check(CLI::PositiveNumber);
    cmd.add_option("--distribution", o.distribution,
                   "geometric (first height + growth), thickness (first height + thickness: growth solved) or tanh "
                   "(the paper's; first height + thickness); default from the options given")
        ->check(CLI::IsMember({"geometric", "thickness", "tanh"}));
    cmd.add_option("--sweeps", o.sweeps, "Poisson smoothing sweeps per layer (default 10)")
        ->check(CLI::NonNegativeNumber);
    cmd.add_option("--max-sweeps", o.max_sweeps, "more sweeps allowed while the update stays large (default 50)")
        ->check(CLI::NonNegativeNumber);
    cmd.add_flag("--no-control", o.no_control,
                 "no control functions (Phi, Psi from the wall; Theta from the distribution)");
    cmd.add_flag("--no-concave", o.no_concave, "no extra smoothing in concave regions");
    cmd.add_flag("--no-hold-back", o.no_hold_back,
                 "where a layer's cells would invert, stop with an error instead of holding the layer back there");
    cmd.add_option("--normals", o.normals, "node normals: robust (default), area (the paper's), angle, max")
        ->check(CLI::IsMember({"robust", "area", "angle", "max"}));
    cmd.add_option("--threads", o.threads, "threads for smoothing (default: all cores)")->check(CLI::NonNegativeNumber);
}

strata::LayerParams layer_params(const LayerOptions& o) {
    strata::LayerParams p;
    strata::DistributionParams& d = p.distribution;
    d.layers = o.layers;
    d.first_height = o.first_height;
    d.thickness = o.thickness;
    d.yplus = o.yplus;
    d.reynolds = o.reynolds;
    d.reference_length = o.ref_length;
    if (o.first_height > 0.0 && o.yplus > 0.0)
        throw strata::InputError("--first-height and --yplus both set the first layer height: give one of them");
    if (!(o.first_height > 0.0) && !(o.yplus > 0.0))
        throw strata::InputError("the first layer height is missing: give --first-height H or --yplus Y --reynolds RE");
    if (o.distribution == "tanh")
        d.kind = strata::Distribution::Tanh;
    else if (o.distribution == "thickness" || (o.distribution.empty() && o.thickness > 0.0 && o.growth == 0.0))
        d.kind = strata::Distribution::Thickness;
    else
        d.kind = strata::Distribution::Geometric;
    if (d.kind == strata::Distribution::Geometric) {
        if (o.thickness > 0.0)
            throw strata::InputError(
                "--thickness with --growth over-determines the layers: give two of first height, growth "
                "and thickness");
        d.growth = o.growth > 0.0 ? o.growth : 1.2;
    } else if (!(o.thickness > 0.0)) {
        throw strata::InputError("--distribution " + std::string(strata::to_string(d.kind)) + " needs --thickness");
    }
    p.sweeps = o.sweeps;
    p.max_sweeps = std::max(o.max_sweeps, o.sweeps);
    p.control_functions = !o.no_control;
    p.concave = !o.no_concave;
    p.hold_back = !o.no_hold_back;
    p.normals = strata::parse_normal_method(o.normals);
    p.threads = o.threads;
    return p;
}

/// One-line progress bar on stderr when it is a terminal.
class BarProgress : public strata::Progress {
public:
    void report(std::string_view stage, double fraction) override {
        if (!isatty(2)) return;
        const int w = 30, n = static_cast<int>(fraction * w + 0.5);
        std::fprintf(stderr, "\r%-8.*s [%-*s] %3d%%", static_cast<int>(stage.size()), stage.data(), w,
                     std::string(static_cast<std::size_t>(n), '#').c_str(), static_cast<int>(fraction * 100 + 0.5));
        if (fraction >= 1.0) std::fprintf(stderr, "\n");
    }
};

int run_layers(const LayerOptions& o) {
    const auto t0 = std::chrono::steady_clock::now();
    const strata::PrepareParams pp = prepare_params(o.surface);
    const strata::LayerParams lp = layer_params(o);
    double version = 4.1;
    if (o.surface.msh_version == "2.2")
        version = 2.2;
    else if (o.surface.msh_version != "4.1")
        throw strata::InputError("--msh-version " + o.surface.msh_version + ": use 4.1 or 2.2");
    strata::PrepareReport rep;
    const strata::SurfaceMesh wall = strata::prepare_surface(o.surface.input, pp, &rep);
    const auto t1 = std::chrono::steady_clock::now();
    BarProgress bar;
    const strata::LayerMesh lm = strata::extrude_layers(wall, lp, o.surface.quiet ? nullptr : &bar);
    const auto t2 = std::chrono::steady_clock::now();
    const strata::ValidationReport v = strata::require_valid_mesh(lm.mesh, o.surface.input);
    strata::write_volume(lm.mesh, o.surface.output, version);
    const auto t3 = std::chrono::steady_clock::now();
    if (o.surface.quiet) return 0;
    print_surface_summary(wall, rep);
    std::printf("layer  height       min SJ  mean SJ  max orth  mean orth  sweeps\n");
    for (std::size_t k = 0; k < lm.stats.size(); ++k) {
        const strata::LayerStats& s = lm.stats[k];
        std::printf("%5zu  %-11.4g  %6.3f  %7.3f  %7.1f°  %8.2f°  %6d\n", k + 1, s.height, s.min_scaled_jacobian,
                    s.mean_scaled_jacobian, s.max_orthogonality_deg, s.mean_orthogonality_deg, s.sweeps);
    }
    if (lm.unsmoothed_nodes > 0)
        std::printf(
            "note: %d nodes (sharp convex edges, corners of open edges, ends of needle triangles) were extruded along "
            "their normal without smoothing\n",
            static_cast<int>(lm.unsmoothed_nodes));
    print_held_back(lm.stats);
    auto secs = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
    std::printf("cells: %zu hexahedra, %zu prisms; min scaled Jacobian %.3f; volume %.6g\n", lm.mesh.hexes.size(),
                lm.mesh.prisms.size(), v.min_scaled_jacobian, v.cell_volume);
    std::printf("time: surface %.2f s, layers %.2f s, check and write %.2f s\n", secs(t0, t1), secs(t1, t2),
                secs(t2, t3));
    std::printf("wrote %s\n", o.surface.output.c_str());
    return 0;
}

struct MeshOptions {
    LayerOptions layer;
    std::string farfield = "sphere";
    double farfield_size = 20.0;
    double pyramid_height = 0.5;
    double radius_edge = 1.5;
    double min_dihedral = 0.0;
    double tet_growth = 0.3;
};

bool is_cobalt(const std::string& path) {
    const auto dot = path.rfind('.');
    const std::string ext = dot == std::string::npos ? "" : path.substr(dot);
    return ext == ".cgr" || ext == ".cog" || ext == ".grd";
}

int run_mesh(const MeshOptions& o) {
    const auto t0 = std::chrono::steady_clock::now();
    const SurfaceOptions& so = o.layer.surface;
    const strata::PrepareParams pp = prepare_params(so);
    strata::HybridParams hp;
    hp.layers = layer_params(o.layer);
    hp.farfield.shape = strata::parse_farfield_shape(o.farfield);
    hp.farfield.size = o.farfield_size;
    hp.pyramids.height = o.pyramid_height;
    hp.tets.radius_edge = o.radius_edge;
    hp.tets.min_dihedral = o.min_dihedral;
    hp.tets.growth = o.tet_growth;
    double version = 4.1;
    if (so.msh_version == "2.2")
        version = 2.2;
    else if (so.msh_version != "4.1")
        throw strata::InputError("--msh-version " + so.msh_version + ": use 4.1 or 2.2");
    strata::PrepareReport rep;
    const strata::SurfaceMesh surface = strata::prepare_surface(so.input, pp, &rep);
    const double t_surface = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    BarProgress bar;
    strata::HybridReport hr;
    const strata::VolumeMesh mesh = strata::build_hybrid_mesh(surface, hp, so.quiet ? nullptr : &bar, &hr);
    const auto t1 = std::chrono::steady_clock::now();
    if (is_cobalt(so.output))
        strata::write_cobalt(mesh, so.output);
    else
        strata::write_volume(mesh, so.output, version);
    const double t_write = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    if (so.quiet) return 0;
    print_surface_summary(surface, rep);
    double jmin = 1.0;
    for (const strata::LayerStats& s : hr.layer_stats) jmin = std::min(jmin, s.min_scaled_jacobian);
    std::printf("layers: %zu, min scaled Jacobian %.3f\n", hr.layer_stats.size(), jmin);
    print_held_back(hr.layer_stats);
    if (!hr.remeshed_patches.empty()) {
        std::string names;
        for (strata::Index p : hr.remeshed_patches)
            names += (names.empty() ? "" : ", ") + mesh.boundary.patches[static_cast<std::size_t>(p)].name;
        std::printf("planes re-meshed around the layers' sides: %s\n", names.c_str());
    }
    std::printf("cells: %zu hexahedra, %zu prisms, %zu pyramids, %zu tetrahedra (%d in all), %zu nodes\n",
                mesh.hexes.size(), mesh.prisms.size(), mesh.pyramids.size(), mesh.tets.size(),
                static_cast<int>(mesh.num_cells()), mesh.points.size());
    std::printf("valid: min scaled Jacobian %.3f (%s), volume %.6g (boundary %.6g)\n",
                hr.validation.min_scaled_jacobian, hr.validation.worst_cell.c_str(), hr.validation.cell_volume,
                hr.validation.boundary_volume);
    std::printf(
        "time: surface %.2f s, layers %.2f s, pyramids %.2f s, tetrahedra %.2f s, validation %.2f s, write %.2f s\n",
        t_surface, hr.seconds_layers, hr.seconds_pyramids, hr.seconds_tets, hr.seconds_validate, t_write);
    std::printf("wrote %s%s\n", so.output.c_str(), is_cobalt(so.output) ? (" and " + so.output + ".bc").c_str() : "");
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "Strata: near-body hybrid meshes for viscous CFD.\n"
        "Boundary-layer prisms and hexahedra marched from the wall, tetrahedra beyond.",
        "strata"};
    app.set_version_flag("--version", std::string("strata ") + STRATA_VERSION);
    app.require_subcommand(1);

    SurfaceOptions so;
    CLI::App* surface = app.add_subcommand(
        "surface", "read CAD or a surface mesh; write the checked, oriented surface mesh with patches");
    add_surface_input_options(*surface, so);
    surface->add_option("-o,--output", so.output, "output surface mesh (.msh; .vtk, .stl, ... by extension)")
        ->required();
    surface->add_option("--msh-version", so.msh_version, "MSH file version for .msh output: 4.1 (default) or 2.2");
    surface->add_flag("-q,--quiet", so.quiet, "print nothing but errors");

    LayerOptions lo;
    CLI::App* layers =
        app.add_subcommand("layers", "extrude boundary-layer prisms and hexahedra from the walls; write the layers");
    add_surface_input_options(*layers, lo.surface);
    layers->add_option("-o,--output", lo.surface.output, "output volume mesh (.msh; .vtk, .su2, ... by extension)")
        ->required();
    layers->add_option("--msh-version", lo.surface.msh_version,
                       "MSH file version for .msh output: 4.1 (default) or 2.2");
    layers->add_flag("-q,--quiet", lo.surface.quiet, "print nothing but errors");
    add_layer_options(*layers, lo);

    MeshOptions mo;
    CLI::App* meshcmd = app.add_subcommand("mesh",
                                           "the whole pipeline: surface, boundary layers, pyramids, tetrahedra; "
                                           "write one validated hybrid mesh");
    add_surface_input_options(*meshcmd, mo.layer.surface);
    meshcmd
        ->add_option("-o,--output", mo.layer.surface.output,
                     "output: .cgr/.cog/.grd (Cobalt60, with a .bc patch map), .msh, .vtk, .su2, ...")
        ->required();
    meshcmd->add_option("--msh-version", mo.layer.surface.msh_version,
                        "MSH file version for .msh output: 4.1 (default) or 2.2");
    meshcmd->add_flag("-q,--quiet", mo.layer.surface.quiet, "print nothing but errors");
    add_layer_options(*meshcmd, mo.layer);
    meshcmd
        ->add_option("--farfield", mo.farfield,
                     "generated outer boundary when the input has no farfield patch: sphere "
                     "(default) or box")
        ->check(CLI::IsMember({"sphere", "box"}));
    meshcmd
        ->add_option("--farfield-size", mo.farfield_size, "farfield extent as a multiple of the body size (default 20)")
        ->check(CLI::Range(1.5, 1e4));
    meshcmd
        ->add_option("--pyramid-height", mo.pyramid_height,
                     "pyramid apex height relative to the quad size (default 0.5)")
        ->check(CLI::Range(0.1, 2.0));
    meshcmd
        ->add_option("--radius-edge", mo.radius_edge, "tetrahedron quality bound, radius/edge (TetGen -q; default 1.5)")
        ->check(CLI::Range(1.1, 10.0));
    meshcmd
        ->add_option("--min-dihedral", mo.min_dihedral,
                     "smallest dihedral angle of the tetrahedra TetGen should aim for, degrees (TetGen -q R/D; 0 = "
                     "TetGen's own)")
        ->check(CLI::Range(0.0, 30.0));
    meshcmd
        ->add_option("--tet-growth", mo.tet_growth,
                     "growth of the tetrahedron size with distance from the body (default 0.3)")
        ->check(CLI::NonNegativeNumber);

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::string msg = e.what();
        std::cerr << "strata: error: " << msg << " (see strata --help)\n";
        return 2;
    }

    try {
        if (*surface) return run_surface(so);
        if (*layers) return run_layers(lo);
        if (*meshcmd) return run_mesh(mo);
    } catch (const strata::Cancelled& e) {
        std::cerr << "strata: " << e.what() << "\n";
        return 130;
    } catch (const std::exception& e) {
        std::string msg = e.what();
        for (char& c : msg)
            if (c == '\n') c = ' ';  // one line, whatever a backend said
        std::cerr << "strata: error: " << msg << "\n";
        return 1;
    }
    return 0;
}
