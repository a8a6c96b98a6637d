// The `strata` command line: a thin front-end over the pipeline stages. Every failure is one
// line on stderr and a non-zero exit; outputs are written atomically by the stages' writers.

#include <strata/error.h>
#include <strata/geometry/prepare.h>
#include <strata/geometry/topology.h>
#include <strata/geometry/write_surface.h>
#include <strata/progress.h>

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

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
    cmd.add_option("--size", o.size, "target surface element size, model units (CAD only; default: 1/20 of the bounding-box diagonal)")
        ->check(CLI::NonNegativeNumber);
    cmd.add_option("--size-min", o.size_min, "smallest element size under curvature refinement (CAD only; default: size/20)")
        ->check(CLI::NonNegativeNumber);
    cmd.add_option("--curvature", o.curvature, "refine by curvature: elements per 2*pi of radius (CAD only; 0 = off)")
        ->check(CLI::NonNegativeNumber);
    auto* q = cmd.add_flag("--quads", o.quads, "recombine the surface mesh into quadrilaterals (CAD only)");
    auto* m = cmd.add_option("--mixed", o.mixed, "quadrilaterals on these CAD surface tags, triangles elsewhere (CAD only)")
                  ->delimiter(',')
                  ->expected(1, -1);
    q->excludes(m);
    cmd.add_flag("--fuse", o.fuse, "fuse all solids into one body before meshing (CAD only)");
    cmd.add_option("--patch", o.patches, "set a patch's kind, NAME=KIND with KIND wall|symmetry|farfield|other (repeatable)");
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
    std::printf("topology: %d connected components (%d closed), %d open boundary loops, %d merged nodes, %d faces re-oriented\n",
                static_cast<int>(rep.orient.components), static_cast<int>(rep.orient.closed_components),
                static_cast<int>(loops.rows()), static_cast<int>(rep.merged_nodes),
                static_cast<int>(rep.orient.flipped_faces));
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

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Strata: near-body hybrid meshes for viscous CFD.\n"
                 "Boundary-layer prisms and hexahedra marched from the wall, tetrahedra beyond.",
                 "strata"};
    app.set_version_flag("--version", std::string("strata ") + STRATA_VERSION);
    app.require_subcommand(1);

    SurfaceOptions so;
    CLI::App* surface = app.add_subcommand("surface", "read CAD or a surface mesh; write the checked, oriented surface mesh with patches");
    add_surface_input_options(*surface, so);
    surface->add_option("-o,--output", so.output, "output surface mesh (.msh; .vtk, .stl, ... by extension)")->required();
    surface->add_option("--msh-version", so.msh_version, "MSH file version for .msh output: 4.1 (default) or 2.2");
    surface->add_flag("-q,--quiet", so.quiet, "print nothing but errors");

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
