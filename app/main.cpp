// The `strata` command line: a thin front-end over the pipeline stages. Options are bound to
// the library's Params structs, so every default and every inference is the library's own (the
// Gmsh-API entry point and the Python package get the same mesh for the same values); library
// messages name parameters ("LayerParams::sweeps") and are shown here with the flag instead.
// Every failure is one line on stderr and a non-zero exit; outputs are written atomically by
// the writers; Ctrl-C cancels at the next check of the running stage (exit 130, nothing
// written), a second Ctrl-C ends the program at once.

#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/core/progress.h>
#include <strata/core/solver_checks.h>
#include <strata/core/validate.h>
#include <strata/frontend/options.h>
#include <strata/frontend/pipeline.h>
#include <strata/frontend/prepare_layers.h>
#include <strata/frontend/report.h>
#include <strata/geometry/check.h>
#include <strata/geometry/intersections.h>
#include <strata/geometry/topology.h>
#include <strata/hybrid/hybrid_mesh.h>
#include <strata/io/files.h>
#include <strata/io/formats.h>
#include <strata/io/write_report.h>
#include <strata/io/write_surface.h>
#include <strata/io/write_volume.h>
#include <strata/module/distribution.h>
#include <strata/module/layers.h>
#include <strata/surface/prepare.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <iostream>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace {

// ---------------------------------------------------------------------------------------
// Ctrl-C, and SIGTERM and SIGHUP (what `timeout`, Slurm and a closed terminal send): the
// handler only sets a flag (all a signal handler may do); the stages poll it through
// Progress::cancelled(), every temporary output goes as the stack unwinds, and the program
// exits 128 + the signal. A second signal while a stage that cannot poll (Gmsh's or TetGen's
// meshing, a writer) runs ends the program at once, after removing the temporary outputs.

std::atomic<bool> g_interrupted{false};
std::atomic<int> g_signal{0};  // the signal that stopped the run; 0: none (--timeout or none)
static_assert(std::atomic<bool>::is_always_lock_free, "the stop flag must be lock-free to be set in a handler");
static_assert(std::atomic<int>::is_always_lock_free, "the signal number must be lock-free to be set in a handler");

extern "C" void on_stop_signal(int sig) {
    if (g_interrupted.exchange(true) && g_signal.load() != 0) {
        strata::remove_temporaries();
        std::signal(sig, SIG_DFL);
        ::raise(sig);
        return;
    }
    g_signal.store(sig);
}

void install_stop_handlers() {
    struct sigaction sa {};
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    for (const int sig : {SIGINT, SIGTERM, SIGHUP}) sigaction(sig, &sa, nullptr);
    // Past the file size limit (ulimit -f) a write fails with EFBIG, which the writers report,
    // instead of the process being killed with the temporary output left behind.
    std::signal(SIGXFSZ, SIG_IGN);
}

/// The name of a stop signal, for the message.
const char* signal_name(int sig) {
    return sig == SIGTERM ? "SIGTERM" : sig == SIGHUP ? "SIGHUP" : "Ctrl-C (SIGINT)";
}

/// What a message on stderr starts with where a progress bar may be drawn on the line (a
/// terminal): a line break; nothing otherwise, so a redirected stderr holds one line.
const char* after_bar() {
    return isatty(2) ? "\n" : "";
}

/// A library that throws through code that cannot pass the exception on ends the process
/// through std::terminate: Gmsh 4.8's surface mesher throws its error text (a std::string) out
/// of an OpenMP region when it cannot mesh a CAD face ("The 1D mesh seems not to be forming a
/// closed loop", "Impossible to mesh periodic surface"). Instead of "terminate called after
/// throwing an instance of std::string" and SIGABRT: one line naming what failed and what to
/// do, exit 1. Nothing is left: outputs are written under a temporary name and renamed, and
/// this happens before writing.
[[noreturn]] void on_terminate() {
    const std::string what = strata::current_exception_text();
    std::fprintf(stderr,
                 "%sstrata: error: a library aborted the run (%s): Gmsh does so on a CAD face it cannot mesh; "
                 "repair or simplify that face in the CAD tool or export the model again (a STEP of solids rather "
                 "than loose faces), or try another --size or --algorithm; nothing was written\n",
                 after_bar(), what.c_str());
    std::fflush(stderr);
    strata::remove_temporaries();
    std::_Exit(1);
}

// ---------------------------------------------------------------------------------------
// --timeout: a watchdog thread. At the deadline it asks the running stage to stop, as Ctrl-C
// does (exit 124, nothing written; TetGen and Gmsh's surface meshing, run in child processes,
// are killed then). A stage that cannot poll (Gmsh reading a CAD file, OpenCASCADE's union)
// gets kTimeoutGrace seconds more; then the
// program ends there, unless the writers have started (they finish, so no file is left half
// written under a temporary name).

std::atomic<bool> g_timed_out{false};
std::atomic<bool> g_writing{false};
constexpr double kTimeoutGrace = 5.0;

class Watchdog {
public:
    explicit Watchdog(double seconds) : seconds_(seconds) {
        if (seconds > 0.0) thread_ = std::thread([this] { watch(); });
    }
    ~Watchdog() {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            done_ = true;
        }
        wake_.notify_all();
        if (thread_.joinable()) thread_.join();
    }
    Watchdog(const Watchdog&) = delete;
    Watchdog& operator=(const Watchdog&) = delete;

private:
    void watch() {
        using Seconds = std::chrono::duration<double>;
        std::unique_lock<std::mutex> lock(mutex_);
        if (wake_.wait_for(lock, Seconds(seconds_), [this] { return done_; })) return;
        g_timed_out.store(true);
        g_interrupted.store(true);  // the running stage stops at its next check
        if (wake_.wait_for(lock, Seconds(kTimeoutGrace), [this] { return done_; })) return;
        if (g_writing.load()) return;
        std::fprintf(stderr,
                     "%sstrata: error: stopped by --timeout %g s: the running stage (Gmsh's own "
                     "meshing, which cannot be asked to stop) went on %g s beyond it; nothing was written\n",
                     after_bar(), seconds_, kTimeoutGrace);
        std::fflush(stderr);
        strata::remove_temporaries();
        std::_Exit(124);
    }
    double seconds_;
    std::mutex mutex_;
    std::condition_variable wake_;
    bool done_ = false;
    std::thread thread_;
};

/// Before the first output file is opened: stop if cancelled (Ctrl-C, --timeout), and from here
/// on let the writers finish.
void begin_writing() {
    if (g_interrupted.load()) throw strata::Cancelled();
    g_writing.store(true);
}

// ---------------------------------------------------------------------------------------
// A crash (SIGSEGV, SIGBUS, SIGFPE, SIGILL) ends the program with one line naming the stage it
// was in, instead of the shell's bare "Segmentation fault": Gmsh's surface mesher has crashed
// on some CAD faces and sizes (MeshAdapt, in this process: a trial in a child as for TetGen
// would double every surface's meshing time; only quads with Blossom, which aborts the process
// on some surfaces, are tried in a child first, io/gmsh_session.h). The handler does only what a signal handler
// may: write() a message built from a stage name kept in a fixed buffer, then _exit(1).
// Outputs are written under a temporary name and renamed; the handler removes the temporaries
// (remove_temporaries: unlink and rmdir only), so nothing is left.

char g_stage[24] = "reading";  // the stage last reported (Terminal::report), NUL-terminated
char g_input[512] = "";        // the input's name (the Terminal's), NUL-terminated

template <std::size_t N>
void keep(char (&buffer)[N], std::string_view text) {
    const std::size_t n = std::min(text.size(), N - 1);
    for (std::size_t i = 0; i < n; ++i) buffer[i] = text[i];
    buffer[n] = '\0';
}

void set_stage(std::string_view stage) {
    keep(g_stage, stage);
}

void write_text(const char* text) {
    std::size_t n = 0;
    while (text[n] != '\0') ++n;
    while (n > 0) {
        const ssize_t w = ::write(2, text, n);
        if (w <= 0) return;
        text += w, n -= static_cast<std::size_t>(w);
    }
}

extern "C" void on_crash(int sig) {
    strata::remove_temporaries();
    const char* name = sig == SIGSEGV ? "SIGSEGV" : sig == SIGBUS ? "SIGBUS" : sig == SIGFPE ? "SIGFPE" : "SIGILL";
    write_text(isatty(2) ? "\nstrata: error: the program crashed (" : "strata: error: the program crashed (");
    write_text(name);
    write_text(") in its ");
    write_text(g_stage);
    write_text(" stage");
    if (g_input[0] != '\0') {
        write_text(" on ");
        write_text(g_input);
    }
    const bool surface = std::strcmp(g_stage, "surface") == 0;
    write_text(surface ? " (Gmsh meshing the surface, or reading it: it crashes on some CAD faces and sizes, and on "
                         "some damaged .msh files; try another --size, --size-min or --curvature, or export the "
                         "model or the mesh again)"
                       : " (a fault in Strata or a library it calls: please report it with the input and the "
                         "command)");
    write_text(g_writing.load() ? "; it was writing: its temporary files were removed and the previous "
                                  "output is as it was\n"
                                : "; nothing was written\n");
    ::_exit(1);
}

void install_crash_handler() {
    struct sigaction sa {};
    sa.sa_handler = on_crash;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESETHAND;  // a fault inside the handler ends the program the default way
    for (const int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL}) sigaction(sig, &sa, nullptr);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// One-line progress bar on stderr when it is a terminal; cancelled once Ctrl-C was pressed.
class Terminal : public strata::Progress {
public:
    /// \p input: the input's name, for the line a crash prints (on_crash).
    Terminal(bool quiet, std::string_view input) : draw_(!quiet && isatty(2)) { keep(g_input, input); }
    void report(std::string_view stage, double fraction) override {
        set_stage(stage);
        if (stage != stage_) stage_ = stage, started_ = std::chrono::steady_clock::now();
        if (!draw_) return;
        const int w = 30, n = static_cast<int>(fraction * w + 0.5);
        std::fprintf(stderr, "\r%-10.*s [%-*s] %3d%% %6.1f s", static_cast<int>(stage.size()), stage.data(), w,
                     std::string(static_cast<std::size_t>(n), '#').c_str(), static_cast<int>(fraction * 100 + 0.5),
                     seconds_since(started_));
        if (fraction >= 1.0) std::fprintf(stderr, "\n");
    }
    bool cancelled() const override { return g_interrupted.load(); }

private:
    bool draw_;
    std::string stage_;  ///< the stage reported last, and when it was first reported
    std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
};

// ---------------------------------------------------------------------------------------
// Library messages name parameters; the user of this program knows the flags.

std::string in_flags(const std::string& message) {
    return strata::translate_names(message, strata::flag_of_parameter());
}

// ---------------------------------------------------------------------------------------
// Options, bound to the Params structs (their defaults are the library's).

/// What a subcommand takes: the input, the output, and the front-ends' options (bound to the
/// Params structs: their defaults are the library's).
struct Common {
    strata::Options o;
    std::string output, msh_version = "4.1";
    bool binary = false;  ///< .msh in binary
    bool quiet = false;
    double timeout = 0.0;  ///< seconds, 0: none (Watchdog)
};

/// The flags of the front-ends' option table (frontend/options.h) for \p stage, bound to \p o.
void add_table_options(CLI::App& cmd, strata::Options& o, std::initializer_list<strata::OptionStage> stages) {
    for (const strata::OptionSpec& spec : strata::option_table()) {
        if (spec.flag.empty() || std::find(stages.begin(), stages.end(), spec.stage) == stages.end()) continue;
        CLI::Option* opt = std::visit(
            [&](auto field) -> CLI::Option* {
                auto& value = field(o);
                using T = std::decay_t<decltype(value)>;
                if constexpr (std::is_same_v<T, bool>) {
                    if (spec.flag_sets_false)
                        return cmd.add_flag_callback(
                            spec.flag, [&value] { value = false; }, spec.help);
                    return cmd.add_flag(spec.flag, value, spec.help);
                } else if constexpr (std::is_same_v<T, std::vector<int>>) {
                    return cmd.add_option(spec.flag, value, spec.help)->delimiter(',')->expected(1, -1);
                } else {
                    return cmd.add_option(spec.flag, value, spec.help);
                }
            },
            spec.field);
        if (spec.show_default && !std::holds_alternative<bool& (*)(strata::Options&)>(spec.field))
            opt->capture_default_str();
        if (spec.optional_size)
            opt->check(CLI::Validator(
                [](std::string& text) -> std::string {
                    char* end = nullptr;
                    const double v = std::strtod(text.c_str(), &end);
                    if (end && *end == '\0' && v >= 0.0) return "";
                    return "'" + text + "' is not a size: give a number >= 0 after the flag, or the flag alone for "
                                        "an automatic size";
                },
                "SIZE"));
        if (spec.flag == "--fan-angle" || spec.flag == "--sharp-edge-stop") opt->check(CLI::Range(0.0, 180.0));
        if (spec.flag == "--mixed") opt->excludes(cmd.get_option("--quads"));
    }
}

void add_common_options(CLI::App& cmd, Common& c, const std::string& output_help) {
    cmd.add_option("INPUT", c.o.surface.inputs,
                   "CAD (.step .stp .iges .igs .brep .brp .geo) or surface mesh (.stl .msh); several are read as one "
                   "surface, each keeping its patches")
        ->required();
    cmd.add_option("-o,--output", c.output, output_help)->required();
    cmd.add_option("--msh-version", c.msh_version, "MSH file version for .msh output: 4.1 or 2.2")
        ->capture_default_str();
    cmd.add_flag("--binary", c.binary,
                 "write .msh output in binary (Gmsh's binary MSH: the same mesh with every coordinate's exact bits, "
                 "written in about half the time; Gmsh and meshio read it)");
    cmd.add_flag("-q,--quiet", c.quiet, "print nothing but errors");
    cmd.add_option(
           "--timeout", c.timeout,
           "stop a run that takes longer than this many seconds (exit 124, nothing written); a stage "
           "that cannot be stopped (Gmsh reading a CAD file, OpenCASCADE's union) is ended 5 s later (0: no limit)")
        ->check(CLI::Validator(
            [](std::string& text) -> std::string {
                char* end = nullptr;
                const double v = std::strtod(text.c_str(), &end);
                if (end == text.c_str() || *end != '\0' || !std::isfinite(v) || v < 0.0)
                    return "expected a number of seconds, 0 or more (0: no limit), not '" + text + "'";
                return "";
            },
            "SECONDS"))
        ->capture_default_str();
    add_table_options(cmd, c.o, {strata::OptionStage::Surface, strata::OptionStage::Patches});
}

// ---------------------------------------------------------------------------------------
// Summaries.

/// \p key of \p n, an integer of the report, as printf's %d takes it.
int count(const strata::ReportNode& n, std::string_view key) {
    return static_cast<int>(n.integer(key));
}

/// A point of the report ([x, y, z]) as format_point writes it.
std::string point_at(const strata::ReportNode& n, std::string_view key) {
    const auto& p = n.list(key);
    return strata::format_point(strata::Vec3(p[0].number(), p[1].number(), p[2].number()));
}

/// A warning where the wall has needle faces (the surface report's "needles"), which cap the
/// layers whatever the marching does, with what to do about them given how the surface came.
void print_needles(const strata::ReportNode& s) {
    const strata::ReportNode& n = s.node("needles");
    if (n.integer("faces") == 0) return;
    const std::string aspect = n.find("worst_aspect_ratio")
                                   ? ", aspect ratio " + strata::format_number(n.number("worst_aspect_ratio"), 3)
                                   : "";
    const char* remedy = s.flag("remeshed") ? "remesh finer (a smaller --remesh SIZE) or with a smaller --feature-angle"
                         : s.flag("cad_input") ? "mesh finer (--size, --size-min) or repair the CAD model's small faces"
                                               : "add --remesh to rebuild the surface with Gmsh, or export a finer one";
    std::printf(
        "warning: %d of %d wall faces are needles (a corner under %g degrees; the sharpest, %.3g degrees%s, on %s): "
        "a layer cell on such a face has a scaled Jacobian of at most the sine of that corner (%.2g there); %s\n",
        count(n, "faces"), count(n, "wall_faces"), n.number("corner_deg"), n.number("sharpest_deg"), aspect.c_str(),
        n.text("worst_face").c_str(), std::sin(n.number("sharpest_deg") * 3.141592653589793 / 180.0), remedy);
}

/// The unit the coordinates are in, and so every length option and figure.
void print_units(const strata::ReportNode& s) {
    const std::string &unit = s.text("units"), &declared = s.text("declared_units");
    std::string text;
    if (unit.empty())
        text = "those of the file (it declares none)";
    else if (declared.empty())
        text = unit + " (the file declares no unit Strata knows: read as OpenCASCADE does, in mm)";
    else if (declared == unit)
        text = unit + ", as the file declares";
    else
        text = unit + ", converted from the file's " + declared + " (--units)";
    if (s.number("scale") != 1.0) text += ", then scaled by " + strata::format_number(s.number("scale")) + " (--scale)";
    std::printf("units: %s; every length below and every length option is in them\n", text.c_str());
}

/// What --sew-tolerance did to a CAD model's loose faces (the surface report's "sewn"; nothing
/// to say when all bound solids).
void print_sewing(const strata::ReportNode& s) {
    if (s.integer("written_twice") > 0)
        std::printf(
            "repaired: %d faces of the CAD model written twice (the same place, area and side as another) "
            "removed, the first of each kept\n",
            count(s, "written_twice"));
    if (s.integer("coincident") > 0)
        std::printf(
            "repaired: %d faces the CAD model holds twice (bounded by the same edges as another face and lying on "
            "it, within %s) not meshed (the first, surface %d, a copy of surface %d, at %s)\n",
            count(s, "coincident"), strata::format_number(s.number("coincident_distance")).c_str(),
            count(s, "coincident_surface"), count(s, "coincident_with"), point_at(s, "coincident_at").c_str());
    if (s.integer("ignored") > 0)
        std::printf(
            "repaired: %d faces of the CAD model that bound none of its solids and are open where they lie (a "
            "construction profile, a loose sheet) set aside, not meshed (the first, surface %d, at %s)\n",
            count(s, "ignored"), count(s, "ignored_surface"), point_at(s, "ignored_at").c_str());
    if (s.integer("faces") == 0) return;
    if (s.flag("rejected")) {
        std::printf(
            "warning: %d faces bound no solid, but sewing them (OpenCASCADE, tolerance %s) moved a face by %s, more "
            "than 1e-4 of the model's size: they are meshed as the file has them, unsewn (if the surface is then "
            "open, sew the model in the CAD tool)\n",
            count(s, "faces"), strata::format_number(s.number("tolerance"), 3).c_str(),
            strata::format_number(s.number("moved"), 3).c_str());
        return;
    }
    const std::string raised = s.number("first_tolerance") > 0.0
                                   ? " (" + strata::format_number(s.number("first_tolerance"), 3) + " left edges apart)"
                                   : "";
    std::printf(
        "sewn: %d faces that bounded no solid (OpenCASCADE, tolerance %s%s; their edges' widest gap %s): "
        "free edges %d -> %d, %d solids made%s\n",
        count(s, "faces"), strata::format_number(s.number("tolerance"), 3).c_str(), raised.c_str(),
        strata::format_number(s.number("gap_before"), 3).c_str(), count(s, "free_edges_before"),
        count(s, "free_edges_after"), count(s, "solids"),
        s.flag("renumbered") ? "; the faces could not all be matched to the file's, so patches follow the new numbering"
                             : "");
    if (s.integer("cracks") > 0)
        std::printf(
            "warning: %d free edges of the CAD model still miss another edge by more than the sewing tolerance (the "
            "widest gap %s, at %s): --sew-tolerance %s sews them\n",
            count(s, "cracks"), strata::format_number(s.number("widest_gap"), 3).c_str(), point_at(s, "gap_at").c_str(),
            strata::format_number(s.number("suggested_tolerance"), 2).c_str());
}

/// What --max-aspect-ratio did to the CAD walls (the surface report's "walls"; nothing to say
/// when their first layer was fine), and the default size halved for a thin part.
void print_wall_sizing(const strata::ReportNode& w) {
    if (const strata::ReportNode& n = w.node("narrow"); n.integer("faces") > 0)
        std::printf(
            n.flag("over_budget")
                ? "warning: %d CAD %s narrower than the size over %s (the narrowest %s wide, surface %d), so their "
                  "triangles are slivers and the layer cells on them far from orthogonal; meshing them at %s would "
                  "add about %.3g faces, more than Strata makes unasked: give a smaller --size there, or "
                  "--narrow-faces 0 to silence this\n"
                : "size: %d CAD %s narrower than the size over %s (the narrowest %s wide, surface %d) meshed finer "
                  "along their edges, down to %s, so that their triangles are not slivers (--narrow-faces; about "
                  "%.3g faces more at most)\n",
            count(n, "faces"), count(n, "faces") == 1 ? "face" : "faces",
            strata::format_number(n.number("ratio")).c_str(),
            strata::format_number(n.number("narrowest"), 3).c_str(), count(n, "narrowest_surface"),
            strata::format_number(n.number("size"), 3).c_str(), n.number("faces_estimate"));
    const auto size = [&w](const char* key) { return strata::format_number(w.number(key), 3); };
    const bool thin = w.number("thin_size") > 0.0;
    if (w.number("walls_default_size") > 0.0)
        std::printf("size: the walls are meshed at %s, a twentieth of their own bounding box's diagonal, the other "
                    "faces (the domain round them) up to %s, a twentieth of the model's (the default, none asked: "
                    "--size sets one for all)\n",
                    size("walls_default_size").c_str(), size(thin ? "thin_size" : "default_size").c_str());
    if (thin)
        std::printf("size: the default size %s left a part thinner than it with its two sides meshed through the "
                    "same nodes (edges of four faces) or faces crossing where parts meet closer than it; meshed at "
                    "%s instead (--size sets it)\n",
                    size("default_size").c_str(), size("thin_size").c_str());
    if (w.integer("surfaces") > 0 || w.integer("curves") > 0)
        std::printf(
            "walls: meshed again finer (%d surfaces, %d curves under fans; size %s) so that the first "
            "layer's aspect ratio stays under --max-aspect-ratio %s (OpenFOAM's checkMesh fails above 1000): worst "
            "%.4g before, %.4g after\n",
            count(w, "surfaces"), count(w, "curves"), strata::format_number(w.number("size"), 3).c_str(),
            strata::format_number(w.number("max_aspect_ratio")).c_str(), w.number("worst_before"),
            w.number("worst_after"));
    else if (w.flag("over_budget"))
        std::printf(
            "warning: the first layer over the walls reaches an aspect ratio of %.4g, above --max-aspect-ratio "
            "%s; keeping it under needs wall faces of size %s, about %.3g of them, more than Strata makes unasked "
            "(%s): give --size %s, or a thicker first layer (--max-aspect-ratio 0 silences this)\n",
            w.number("worst_before"), strata::format_number(w.number("max_aspect_ratio")).c_str(),
            strata::format_number(w.number("size"), 3).c_str(), w.number("faces_estimate"),
            strata::format_number(strata::CadParams{}.wall_faces_budget).c_str(),
            strata::format_number(w.number("size"), 3).c_str());
}

/// What --step-quality and the fans' first wedges (--max-aspect-ratio) did to the CAD walls (the
/// surface report's "steps"; nothing to say when neither asked for finer walls).
void print_step_sizing(const strata::ReportNode& st) {
    // What asked for finer walls: the steps, the fans' first wedges, or both.
    const int points = count(st, "points"), fan_points = count(st, "fan_points");
    const bool steps = points > 0, fans = fan_points > 0;
    const std::string step_part = steps ? "the layers step low at " + std::to_string(points) + " wall nodes" : "",
                      fan_part = fans ? "the fans' first wedges at " + std::to_string(fan_points) +
                                            " wall nodes would exceed --max-aspect-ratio"
                                      : "";
    const auto joined = [](const std::string& a, const std::string& b) {
        return a.empty() ? b : b.empty() ? a : a + "; and " + b;
    };
    const std::string at = joined(step_part, fan_part),
                      why = joined(steps ? step_part + ", where the cells closing the steps would be nearly flat" : "",
                                   fan_part);
    const std::string quality = strata::format_number(st.number("quality"));
    const std::string knob = steps ? "--step-quality " + quality : "their wedges";
    if (!st.text("failure").empty())
        std::printf("warning: %s; meshing the walls finer there for %s failed, so the first surface is kept: %s\n",
                    why.c_str(), knob.c_str(), st.text("failure").c_str());
    else if (st.flag("over_budget"))
        std::printf(
            "warning: %s; walls fine enough for %s there would take about %.3g faces, more than Strata makes "
            "unasked (%s times the surface's %d, at most %s): give a smaller --size there, or %s 0 to "
            "silence this\n",
            why.c_str(), knob.c_str(), st.number("faces_estimate"),
            strata::format_number(strata::kStepFacesGrowth).c_str(), count(st, "faces_before"),
            strata::format_number(strata::CadParams{}.wall_faces_budget).c_str(),
            steps ? "--step-quality" : "--max-aspect-ratio");
    else if (st.flag("kept"))
        std::printf(
            "steps: %s; walls meshed finer there for %s were dropped, as their layers would reach %.1f %% of the "
            "thickness asked instead of %.1f %% (the gap, better resolved, limits the layers round it more)\n",
            at.c_str(), knob.c_str(), 100.0 * st.number("thickness_after"), 100.0 * st.number("thickness_before"));
    else if (steps || fans) {
        std::string around, aim;
        if (steps) {
            around = std::to_string(points) + " wall nodes where the layers step low";
            aim = "a step's layer height is at least --step-quality " + quality + " of the wall spacing";
        }
        if (fans) {
            around += std::string(steps ? " and " : "") + std::to_string(fan_points) + (steps ? "" : " wall nodes") +
                      " at the ends of fan edges and along them";
            aim += std::string(steps ? ", and " : "") + "the fans' first wedges stay under --max-aspect-ratio";
        }
        char seconds[32];
        std::snprintf(seconds, sizeof seconds, "%.2f s", st.number("seconds"));
        const std::string note = (steps ? std::string(fans ? "the cells closing a step" : "the cells closing it") +
                                              " reach about half of that; "
                                        : std::string()) +
                                 seconds;
        const double raised = st.number("raised");
        std::printf(
            "steps: walls meshed again finer around %s (sizes down to %s%s), %d -> %d faces, so that %s "
            "(%s)\n",
            around.c_str(), strata::format_number(st.number("smallest"), 3).c_str(),
            raised > 1.0 ? (", raised " + strata::format_number(raised, 3) + "-fold to stay within " +
                            strata::format_number(strata::kStepFacesGrowth) + " times the faces")
                               .c_str()
                         : "",
            count(st, "faces_before"), count(st, "faces_after"), aim.c_str(), note.c_str());
    }
}

/// What the first mesh's cells above checkMesh's aspect ratio did to the CAD walls (the surface
/// report's "aspect_remesh"; nothing to say when it had none).
void print_aspect_remesh(const strata::ReportNode& a) {
    if (count(a, "cells") == 0) return;
    if (a.flag("over_budget")) {
        std::printf(
            "warning: %d cells above checkMesh's aspect ratio of 1000 (the worst %.4g, %s); walls fine enough round "
            "them would take about %.3g faces, more than Strata makes unasked (three times the surface's, at most the "
            "faces budget): give a smaller --size there or a thicker --first-height\n",
            count(a, "cells"), a.number("worst"), a.text("worst_cell").c_str(), a.number("faces_estimate"));
        return;
    }
    if (!a.text("failure").empty()) {
        std::printf(
            "warning: %d cells above checkMesh's aspect ratio of 1000 (the worst %.4g, %s); meshing the walls again "
            "finer round them failed, so the first mesh is kept: %s\n",
            count(a, "cells"), a.number("worst"), a.text("worst_cell").c_str(), a.text("failure").c_str());
        return;
    }
    const bool kept = count(a, "cells_after") < count(a, "cells");
    std::printf(
        "aspect: the first mesh had %d cells above checkMesh's aspect ratio of 1000 (the worst %.4g, %s), so the "
        "walls were meshed again finer round them (sizes down to %s, %d -> %d faces) and the mesh made again: %d "
        "such cells%s (%.2f s)\n",
        count(a, "cells"), a.number("worst"), a.text("worst_cell").c_str(),
        strata::format_number(a.number("smallest"), 3).c_str(), count(a, "faces_before"), count(a, "faces_after"),
        count(a, "cells_after"), kept ? ", kept" : ", not fewer: the first mesh is kept", a.number("seconds"));
}

/// A surface mesh kept as it is (the surface report's "wall_aspect"): where its wall faces are too
/// wide for the first layer, say so (OpenFOAM's checkMesh fails cells over 1000) with the worst
/// face and the remedy, before the solver does.
void print_wall_aspect_forecast(const strata::ReportNode& s) {
    const strata::ReportValue* forecast = s.find("wall_aspect");
    if (!forecast || forecast->node().integer("over") == 0) return;
    const strata::ReportNode& w = forecast->node();
    std::printf(
        "warning: %d of %d wall faces are too wide for the first layer (%s high): its cells on them reach an aspect "
        "ratio of %.4g (on %s), above --max-aspect-ratio %s (OpenFOAM's checkMesh fails cells over 1000); a "
        "surface mesh is kept as it is: add --remesh to mesh it again with the walls fine enough, or give a thicker "
        "first layer (--max-aspect-ratio 0 silences this)\n",
        count(w, "over"), count(w, "walls"), strata::format_number(w.number("first_height"), 3).c_str(),
        w.number("worst"), w.text("worst_face").c_str(), strata::format_number(w.number("max_aspect_ratio")).c_str());
}

/// What remeshing did (the surface report's "remesh").
void print_remesh(const strata::ReportNode& r) {
    const double angle = r.number("feature_angle_deg"), asked = r.number("asked_feature_angle_deg");
    std::printf(
        "remeshed: %d faces%s -> %d on %d Gmsh surfaces, size %s%s, feature angle %s degrees%s; needle faces %d -> "
        "%d (sharpest corner %.3g -> %.3g degrees)\n",
        count(r, "faces_before"),
        r.integer("split_edges") > 0
            ? (" (bisected to edges no longer than the size, " + std::to_string(r.integer("split_edges")) +
               " splits: as they were, every feature angle and size failed)")
                  .c_str()
            : "",
        count(r, "faces_after"), count(r, "surfaces"), strata::format_number(r.number("size")).c_str(),
        r.flag("size_halved") ? " (half the input's median edge: at the median every feature angle failed)" : "",
        strata::format_number(angle).c_str(),
        angle < asked   ? " (lowered: larger angles left folded faces)"
        : angle > asked ? " (raised: at smaller angles Gmsh could not parametrize the surfaces or left folded faces)"
                        : "",
        count(r, "needles_before"), count(r, "needles_after"), r.number("sharpest_before_deg"),
        r.number("sharpest_after_deg"));
}

/// What the alpha wrap did (the surface report's "wrap").
void print_wrap(const strata::ReportNode& w) {
    std::printf(
        "wrapped: %d faces -> one watertight surface of %d triangles (--wrap: alpha %s, offset %s, %.2f s); it lies "
        "within %s of the input (farthest at %s), and every point of the input within %s of it (farthest at %s%s)\n",
        count(w, "input_faces"), count(w, "faces"), strata::format_number(w.number("alpha")).c_str(),
        strata::format_number(w.number("offset")).c_str(), w.number("seconds"),
        strata::format_number(w.number("wrap_to_input")).c_str(), point_at(w, "wrap_to_input_at").c_str(),
        strata::format_number(w.number("input_to_wrap")).c_str(), point_at(w, "input_to_wrap_at").c_str(),
        w.number("input_to_wrap") > 2.0 * w.number("alpha")
            ? ": inside the wrap, where parts overlap, or a gap narrower than alpha closed over"
            : "");
}

/// The CAD bodies the file names and their patches (the patch table's "body"), on one line:
/// "'Fuselage' (patches 1-6), 'Wing' (patches 7-9, 12)".
void print_bodies(const std::vector<strata::ReportValue>& table) {
    auto body = [&](std::size_t i) {
        const strata::ReportValue* b = table[i].node().find("body");
        return b ? table[i].node().text("body") : std::string{};
    };
    std::vector<std::pair<std::string, std::string>> bodies;  // name, its patches
    for (std::size_t i = 0; i < table.size(); ++i) {
        const std::string name = body(i);
        if (name.empty()) continue;
        auto it = std::find_if(bodies.begin(), bodies.end(), [&](const auto& b) { return b.first == name; });
        if (it == bodies.end()) it = bodies.insert(bodies.end(), {name, ""});
        std::string& list = it->second;
        const bool run = i > 0 && body(i - 1) == name;  // "1-6" for a run of patches
        if (run && list.find_last_of("-,") != std::string::npos && list[list.find_last_of("-,")] == '-')
            list.erase(list.find_last_of('-'));
        list += (run ? "-" : list.empty() ? "" : ", ") + std::to_string(i + 1);
    }
    if (bodies.empty()) return;
    std::string line;
    for (const auto& [name, list] : bodies) {
        const bool one = list.find_first_of("-,") == std::string::npos;
        line += (line.empty() ? "" : ", ") + ("'" + name + "' (patch" + (one ? " " : "es ") + list + ")");
    }
    std::printf("  bodies: %s; --patch BODY=KIND[:NAME] sets all of a body's patches at once\n", line.c_str());
}

/// The surface and what preparing it did (the report's "surface", surface_report).
void print_surface_summary(const strata::ReportNode& s) {
    std::printf("surface: %d nodes, %d triangles, %d quadrilaterals, %d patches\n", count(s, "nodes"),
                count(s, "triangles"), count(s, "quads"), count(s, "patches"));
    const auto& table = s.list("patch_table");
    for (std::size_t i = 0; i < table.size(); ++i)
        std::printf("  patch %zu %-24s %-9s %d faces\n", i + 1, table[i].node().text("name").c_str(),
                    table[i].node().text("kind").c_str(), count(table[i].node(), "faces"));
    print_bodies(table);
    std::printf(
        "topology: %d connected components (%d closed), %d open boundary loops, %d merged nodes, %d faces "
        "re-oriented\n",
        count(s, "components"), count(s, "closed_components"), count(s, "open_loops"), count(s, "merged_nodes"),
        count(s, "flipped_faces"));
    if (s.integer("collapsed_faces") > 0)
        std::printf("repaired: %d faces with a repeated node (no area) removed or made triangles\n",
                    count(s, "collapsed_faces"));
    if (s.node("cracks").integer("split_faces") > 0)
        std::printf(
            "repaired: cracks closed where each side of an edge was meshed with nodes of its own, %d faces split at "
            "the other side's nodes, gaps up to %s (the widest at %s)\n",
            count(s.node("cracks"), "split_faces"), strata::format_number(s.node("cracks").number("widest_gap")).c_str(),
            point_at(s.node("cracks"), "at").c_str());
    if (s.node("hanging_sheets").integer("faces") > 0)
        std::printf(
            "repaired: %d sheets of %d faces hanging off the surface on edges of three or more faces (a flap, a "
            "zero-thickness fin: no layer can grow on both sides of one) removed (the first at %s); --wrap keeps such "
            "a sheet, thickened\n",
            count(s.node("hanging_sheets"), "sheets"), count(s.node("hanging_sheets"), "faces"),
            point_at(s.node("hanging_sheets"), "at").c_str());
    if (s.integer("t_junctions") > 0)
        std::printf(
            "repaired: %d faces split where nodes of the faces beside them lay inside their edge (T-junctions)\n",
            count(s, "t_junctions"));
    const strata::ReportNode& holes = s.node("holes");
    if (holes.integer("filled") > 0 && holes.flag("caps"))
        std::printf(
            "caps: %d openings closed each by a cap of its own, %d triangles (--fill-holes --caps: patches cap_1 to "
            "cap_%d, kind other unless --patch says otherwise; the largest opening, %d edges, around %s)\n",
            count(holes, "filled"), count(holes, "triangles"), count(holes, "filled"), count(holes, "largest"),
            point_at(holes, "where").c_str());
    else if (holes.integer("filled") > 0)
        std::printf("repaired: %d holes closed with %d triangles (--fill-holes; the largest, %d edges, around %s)\n",
                    count(holes, "filled"), count(holes, "triangles"), count(holes, "largest"),
                    point_at(holes, "where").c_str());
    if (holes.integer("max_edges") > 0 && holes.integer("left") > 0)
        std::printf("note: %d open loops left open by --fill-holes %d (the largest has %d edges)\n",
                    count(holes, "left"), count(holes, "max_edges"), count(holes, "largest_left"));
    if (s.integer("duplicate_faces") > 0)
        std::printf(
            "repaired: %d faces written twice (the same nodes in the same order) removed, the first of each kept\n",
            count(s, "duplicate_faces"));
    print_units(s);
    print_sewing(s.node("sewn"));
    if (s.flag("internal_flow"))
        std::printf("flow: inside the walls (--internal): the outermost closed surface points inward\n");
    if (s.integer("touching_faces") > 0)
        std::printf("fused: %d faces removed where bodies touch back to back along a common face (--fuse)\n",
                    count(s, "touching_faces"));
    if (s.integer("fused_components") > 0)
        std::printf("fused: %d overlapping components replaced by their union (--fuse)%s\n",
                    count(s, "fused_components"),
                    s.integer("fused_slivers") > 0 ? ("; " + std::to_string(s.integer("fused_slivers")) +
                                                      " flat slivers where their facets nearly coincide flipped away")
                                                         .c_str()
                                                   : "");
    if (const strata::ReportNode& e = s.node("short_edges"); e.integer("collapsed") > 0)
        std::printf(
            "short edges: %d collapsed (shorter than --collapse-edges of the edges around them; the longest %s, %.3g "
            "of "
            "its neighbourhood, a node moved that far at %s)%s\n",
            count(e, "collapsed"), strata::format_number(e.number("longest")).c_str(), e.number("largest_share"),
            point_at(e, "where").c_str(),
            e.integer("left") > 0
                ? (", " + std::to_string(e.integer("left")) + " left where collapsing was not safe").c_str()
                : "");
    if (s.flag("touching_wrapped"))
        std::printf(
            "fused: parts touch along a line or a point only, which no Boolean union joins (--fuse), so the walls "
            "were wrapped into one instead (--wrap; a smaller --wrap SIZE keeps more detail)\n");
    if (s.flag("wrapped")) print_wrap(s.node("wrap"));
    if (s.flag("remeshed")) print_remesh(s.node("remesh"));
    if (s.flag("blossom_folded"))
        std::printf(
            "quads: Gmsh's Blossom quads folded where the surface nearly touches itself (%s), so the surfaces were "
            "recombined with Gmsh's simple algorithm instead, which leaves more triangles\n",
            s.text("blossom_failure").c_str());
    else if (!s.text("blossom_failure").empty())
        std::printf(
            "quads: Gmsh's Blossom recombination would have ended the process on this model (\"%s\"), so the surfaces "
            "were recombined with Gmsh's simple algorithm instead, which leaves more triangles\n",
            s.text("blossom_failure").c_str());
    print_wall_sizing(s.node("walls"));
    print_step_sizing(s.node("steps"));
    print_aspect_remesh(s.node("aspect_remesh"));
    print_needles(s);
}

/// Where layers were thinned (scaled down: proximity, front rounds), so the user knows they are thinner there.
void print_thinned(const strata::ReportNode& r) {
    if (r.integer("thinned_nodes") == 0) return;
    std::printf(
        "thinned: layers scaled down at %d wall nodes, down to %.1f %% of the thickness asked (the coverage table "
        "says why)\n",
        count(r, "thinned_nodes"), 100.0 * r.number("min_thickness_share"));
}

/// Where layers were held back to stay valid (LayerParams::hold_back), per the report's layer_stats.
void print_held_back(const strata::ReportNode& r) {
    int layers = 0, most = 0, first = 0;
    const auto& stats = r.list("layer_stats");
    for (std::size_t k = 0; k < stats.size(); ++k) {
        if (stats[k].node().integer("held_nodes") == 0) continue;
        if (layers++ == 0) first = static_cast<int>(k) + 1;
        most = std::max(most, count(stats[k].node(), "held_nodes"));
    }
    if (layers > 0)
        std::printf(
            "note: from layer %d on, %d layers were held back (lowered, unsmoothed) at up to %d nodes where their "
            "cells would have inverted; the layers are thinner there\n",
            first, layers, most);
}

/// Why a wall node got no fan, as the summary says it.
const char* no_fan_reason(strata::NoFan reason) {
    switch (reason) {
        case strata::NoFan::Unusable:
            return "its first cells would have been unusable (a needle face or a narrow gap beside it)";
        case strata::NoFan::Uncapped:
            return "a fan's face on the layer top could not be capped with a pyramid (its columns twist: the wall "
                   "there is small against the layers' thickness)";
        case strata::NoFan::Skewed:
            return "a fan's cells had faces OpenFOAM's checkMesh would fail as skewed (a fan over a coarsely faceted "
                   "wall; a finer wall keeps it)";
        case strata::NoFan::Open:
            return "their sharp edge reaches the wall's open boundary where no fan ends (an open edge in no plane of a "
                   "symmetry, outflow or box patch, a node where two such planes meet, or one with two sharp edges), "
                   "so the edge's fan ends one node before it: one column each, stopped at the wall on an edge sharper "
                   "than --sharp-edge-stop (sharp)";
        case strata::NoFan::Unclosed:
            break;
    }
    return "their sharp edge's chain could take no fan (a single sharp edge between two nodes that end it, or a "
           "corner's fan edge dropped where its cells would be flat): one column each, stopped at the wall on an edge "
           "sharper than --sharp-edge-stop (sharp)";
}

/// The fans at sharp convex edges, if any, and the wall nodes where none could be built (the
/// report's no_fan_nodes), each reason with the first such node's position.
void print_fans(const strata::ReportNode& r) {
    if (r.integer("fan_edges") > 0) {
        const int on_plane = count(r, "fan_plane_nodes");
        std::printf(
            "fans: %d sharp convex edges, %d wall nodes with a column per side and between (%d corners%s)\n",
            count(r, "fan_edges"), count(r, "fan_nodes"), count(r, "fan_corners"),
            on_plane > 0 ? (", " + std::to_string(on_plane) + " ending on a symmetry or other plane").c_str() : "");
    }
    for (std::size_t k = 0; k < strata::kNoFanReasons; ++k) {
        const auto reason = static_cast<strata::NoFan>(k);
        const std::string name(strata::to_string(reason));
        int n = 0;
        const strata::ReportNode* first = nullptr;
        for (const strata::ReportValue& v : r.list("no_fan_nodes"))
            if (v.node().text("reason") == name) {
                if (n++ == 0) first = &v.node();
            }
        if (n == 0) continue;
        const auto& p = first->list("position");
        std::printf("note: no fan at %d wall nodes where %s;%s node %d at %s (in OUT.report.json with positions)\n", n,
                    no_fan_reason(reason), n > 1 ? " the first," : "", count(*first, "node"),
                    strata::format_point(strata::Vec3(p[0].number(), p[1].number(), p[2].number())).c_str());
    }
}

void print_layer_table(const strata::ReportNode& r) {
    std::printf("layer  height       min SJ  mean SJ  max orth  mean orth  sweeps  columns  stopped  steps  step SJ\n");
    for (const strata::ReportValue& row : r.list("layer_stats")) {
        const strata::ReportNode& s = row.node();
        std::printf("%5d  %-11.4g  %6.3f  %7.3f  %7.1f°  %8.2f°  %6d  %7d  %7d  %5d  %7.3g\n", count(s, "layer"),
                    s.number("height"), s.number("min_scaled_jacobian"), s.number("mean_scaled_jacobian"),
                    s.number("max_orthogonality_deg"), s.number("mean_orthogonality_deg"), count(s, "sweeps"),
                    count(s, "columns"), count(s, "stopped_nodes"), count(s, "transition_cells"),
                    s.integer("transition_cells") > 0 ? s.number("min_transition_jacobian") : 1.0);
    }
    std::printf(
        "  (columns: wall nodes with the layer; stopped: columns ending below it; steps: cells closing the steps "
        "where they end, pyramids, side-on prisms, tetrahedra; their apex at a stopped column sees the step's thin "
        "side edge-on, hence step SJ about layer height / edge length)\n");
    print_fans(r);
    if (r.integer("unsmoothed_nodes") > 0)
        std::printf(
            "note: %d nodes (sharp convex edges, corners of open edges, ends of needle triangles) were extruded along "
            "their normal without smoothing\n",
            count(r, "unsmoothed_nodes"));
    print_held_back(r);
    print_thinned(r);
}

/// The whole wall's coverage in one line (the report's "coverage"): every layer, the same where
/// no proximity limit binds, the mean thickness, and the short nodes by whether their own reason
/// stopped them (each such reason with its nodes) or only a neighbour.
void print_wall_coverage(const strata::ReportNode& w) {
    std::string own;
    for (const strata::ReportNode::Entry& e : w.node("short").entries())
        if (e.key != strata::to_string(strata::Shortfall::Neighbours) && e.value.integer() > 0)
            own += (own.empty() ? " (" : ", ") + e.key + " " + std::to_string(e.value.integer());
    std::printf(
        "coverage: every layer on %.1f %% of %d wall nodes (%.1f %% of the %d where no proximity limit binds), %.1f %% "
        "of the thickness asked on average (%.1f %% there); short: %d for their own reason%s, %d only because of a "
        "neighbour\n",
        100.0 * w.number("all_layers_share"), count(w, "nodes"), 100.0 * w.number("unbound_all_layers_share"),
        count(w, "unbound_nodes"), 100.0 * w.number("mean_share"), 100.0 * w.number("unbound_mean_share"),
        count(w, "own_reason_nodes"),
        (own.empty() ? own : own + ")").c_str(), count(w, "neighbour_nodes"));
}

/// The coverage table: per wall patch, the columns with every layer at full thickness, the
/// layers reached and why the others fell short (one column per reason, the report's "short").
void print_coverage(const strata::ReportNode& r) {
    std::printf("coverage: %d layers asked, %.4g thick (first %.3g); per wall patch, what the columns reached:\n",
                count(r, "layers"), r.number("thickness"), r.number("first_height"));
    std::printf("  %-20s %7s %7s %6s %6s %6s %6s %6s  short: %5s %5s %5s %5s %5s %5s %5s %5s %5s %5s\n", "patch",
                "faces", "nodes", "full", "all L", "mean L", "min L", "thick", "prox", "front", "held", "qual", "turn",
                "twist", "nbrs", "nan", "sharp", "iso");
    for (const strata::ReportValue& row : r.list("patches")) {
        const strata::ReportNode& c = row.node();
        const double n = c.integer("nodes") > 0 ? c.number("nodes") : 1.0;
        std::string short_by;
        for (const strata::ReportNode::Entry& e : c.node("short").entries()) {
            char cell[24];
            std::snprintf(cell, sizeof cell, " %5d", static_cast<int>(e.value.integer()));
            short_by += cell;
        }
        std::printf("  %-20s %7d %7d %5.1f%% %5.1f%% %6.1f %6d %5.1f%%        %s\n", c.text("name").c_str(),
                    count(c, "faces"), count(c, "nodes"), 100.0 * c.number("full_nodes") / n,
                    100.0 * c.number("all_layers") / n, c.number("mean_layers"), count(c, "min_layers"),
                    100.0 * c.number("mean_share"), short_by.c_str());
    }
    std::printf(
        "  (full: every layer at the thickness asked; all L: every layer; thick: mean thickness reached; short: "
        "nodes by why their column fell short, in OUT.report.json with positions; sharp: stopped at the wall on a "
        "convex edge too sharp for one direction that got no fan, --sharp-edge-stop; iso: stopped where the next layer "
        "would be taller than the layer front is wide, --isotropy)\n");
    print_wall_coverage(r.node("coverage"));
}

/// Scaled Jacobian below which the summary warns that a solver may not use the cells.
constexpr double kSolverQuality = 0.01;

/// OpenFOAM checkMesh's figures (the report's quality.openfoam), and what it would fail on.
/// \p kept_surface: the surface mesh was kept as it is (neither CAD nor --remesh), so a failure on
/// the layers' aspect ratio has one more remedy.
void print_solver_checks(const strata::ReportNode& s, bool kept_surface) {
    std::printf(
        "openfoam: non-orthogonality max %.3g deg (mean %.3g, %d faces above %g), skewness max %.3g (%d faces above "
        "%g), aspect ratio max %.4g (%d cells above %g): checkMesh would %s\n",
        s.number("max_non_orthogonality_deg"), s.number("mean_non_orthogonality_deg"),
        count(s, "severely_non_orthogonal_faces"), strata::kFoamNonOrthogonalDeg, s.number("max_skewness"),
        count(s, "skew_faces"), strata::kFoamSkewness, s.number("max_aspect_ratio"), count(s, "high_aspect_cells"),
        strata::kFoamAspectRatio, s.flag("check_mesh_ok") ? "say \"Mesh OK\"" : "fail it");
    for (const strata::ReportValue& line : s.list("failures"))
        std::printf("warning: checkMesh would fail: %s\n", line.text().c_str());
    if (kept_surface && s.integer("high_aspect_cells") > 0 &&
        s.text("worst_aspect_type") != strata::to_string(strata::CellType::Tet))
        std::printf(
            "  the surface mesh was kept as it is: --remesh meshes it again, its walls fine enough for the first "
            "layer (--max-aspect-ratio)\n");
}

/// The cells by type, the validation's figures, the worst cell of each type, and a warning
/// below what a solver can use.
void print_cells(const strata::ReportNode& r, bool kept_surface) {
    using strata::CellType;
    const strata::ReportNode &cells = r.node("cells"), &q = r.node("quality");
    const auto cells_of = [&](CellType t) { return count(cells, strata::to_string(t)); };
    std::printf(
        "cells: %d hexahedra, %d prisms, %d pyramids, %d tetrahedra (%d in all), %d nodes\n", cells_of(CellType::Hex),
        cells_of(CellType::Prism), cells_of(CellType::Pyramid), cells_of(CellType::Tet),
        cells_of(CellType::Hex) + cells_of(CellType::Prism) + cells_of(CellType::Pyramid) + cells_of(CellType::Tet),
        count(r, "nodes"));
    const strata::ReportNode &min_sj = q.node("min_scaled_jacobian"), &worst = q.node("worst_cell");
    std::printf("valid: min scaled Jacobian %.3g (%s), volume %.6g (boundary %.6g)\n", min_sj.number("all"),
                worst.text("all").c_str(), q.number("cell_volume"), q.number("boundary_volume"));
    // Per cell type, hexahedra first (the order of the cells line), the worst cell of each.
    for (const CellType t : {CellType::Hex, CellType::Prism, CellType::Pyramid, CellType::Tet}) {
        if (cells_of(t) == 0) continue;
        const std::string name(strata::to_string(t));
        std::printf("  %-12s min scaled Jacobian %.3g (%s)\n", (name + ":").c_str(), min_sj.number(name),
                    worst.text(name).c_str());
    }
    if (min_sj.number("all") < kSolverQuality)
        std::printf(
            "warning: cells below a scaled Jacobian of %g, which a solver may reject or converge poorly on; "
            "the worst is %s\n",
            kSolverQuality, worst.text("all").c_str());
    print_solver_checks(q.node("openfoam"), kept_surface);
}

/// What improve_tets did (the report's tet_improve), if anything.
void print_tet_improve(const strata::ReportNode& ti) {
    if (ti.integer("flips") + ti.integer("edge_removals") + ti.integer("moved_nodes") + ti.integer("inserted_nodes") >
        0)
        std::printf(
            "tetrahedra improved: %lld flips, %lld edges removed, %lld interior nodes moved, %lld inserted; below a "
            "scaled Jacobian of %g: %lld -> %lld, the worst %.3g -> %.3g (%.2f s%s)\n",
            static_cast<long long>(ti.integer("flips")), static_cast<long long>(ti.integer("edge_removals")),
            static_cast<long long>(ti.integer("moved_nodes")), static_cast<long long>(ti.integer("inserted_nodes")),
            ti.number("below"), static_cast<long long>(ti.integer("below_before")),
            static_cast<long long>(ti.integer("below_after")), ti.number("min_before"), ti.number("min_after"),
            ti.number("seconds"), ti.flag("budget_reached") ? "; stopped at its work budget" : "");
    if (ti.integer("skewed_before") + ti.integer("skew_changes") > 0)
        std::printf(
            "tetrahedra de-skewed: %lld flips and edge removals for faces above a skewness of %g (checkMesh fails "
            "above 4); faces between tetrahedra above 4: %lld -> %lld\n",
            static_cast<long long>(ti.integer("skew_changes")), strata::kTetSkewTarget,
            static_cast<long long>(ti.integer("skewed_before")), static_cast<long long>(ti.integer("skewed_after")));
}

void print_hybrid_summary(const strata::ReportNode& r, bool kept_surface) {
    double jmin = 1.0;
    for (const strata::ReportValue& s : r.list("layer_stats"))
        jmin = std::min(jmin, s.node().number("min_scaled_jacobian"));
    std::printf("layers: %zu, min scaled Jacobian %.3f\n", r.list("layer_stats").size(), jmin);
    if (r.flag("internal_flow")) std::printf("domain: inside the walls (internal flow), no farfield generated\n");
    if (r.flag("closed_half_model"))
        std::printf("domain: a half model, closed by a generated half farfield and a symmetry plane\n");
    print_fans(r);
    print_held_back(r);
    print_thinned(r);
    print_coverage(r);
    if (const int retries = count(r, "tet_retries"); r.integer("front_rounds") > 0)
        std::printf(
            "front: %d column lowerings in %d rounds where the layers folded, left no room for a pyramid or "
            "their top intersected itself%s\n",
            count(r, "front_lowered_nodes"), count(r, "front_rounds"),
            retries > 0 ? (" (in " + std::to_string(retries) +
                           " of them TetGen failed recovering a layer-top face, and the columns around it were "
                           "lowered)")
                              .c_str()
                        : "");
    if (r.flag("skew_capped"))
        std::printf(
            "skew: faces between layer cells that checkMesh would fail as skewed (above 4) were found, and the mesh made "
            "again with their columns capped below them (counted as quality stops, every layer kept)\n");
    if (r.integer("split_quads") > 0)
        std::printf(
            "quads: %d wall quads could take no pyramid on the layer top (too warped for an apex, their columns at the "
            "wall or lowered for it before) and were split into two triangles, their columns prisms\n",
            count(r, "split_quads"));
    if (const std::string why = r.text("tets_fallback"); !why.empty())
        std::printf("note: TetGen filled the domain with tetrahedra where HXT (--tets hxt) could not: %s\n", why.c_str());
    print_tet_improve(r.node("tet_improve"));
    for (const strata::ReportNode::Entry& e : r.node("planes_of_patches").entries())
        std::printf(
            "planes: patch '%s' is %d planes, the layers end on it; each was re-meshed round them as a "
            "plane, and it is one patch in the mesh\n",
            e.key.c_str(), static_cast<int>(e.value.integer()));
    if (!r.list("remeshed_patches").empty()) {
        std::string names;
        for (const strata::ReportValue& p : r.list("remeshed_patches")) names += (names.empty() ? "" : ", ") + p.text();
        std::printf("planes re-meshed around the layers' sides: %s\n", names.c_str());
    }
    print_cells(r, kept_surface);
}

/// "first height:" where none was asked (the report's "automatic_first_height"): the one chosen
/// and from what.
void print_first_height(const strata::ReportNode& r, const strata::Options& o) {
    const strata::ReportValue* chosen = r.find("automatic_first_height");
    if (!chosen) return;
    const strata::ReportNode& a = chosen->node();
    const strata::DistributionParams& d = o.layers.params.distribution;
    const double growth = d.growth > 0.0 ? d.growth : strata::kDefaultGrowth;
    const std::string what =
        a.number("thickness_share") > 0.0
            ? strata::format_number(100.0 * a.number("thickness_share"), 3) + " % of the walls' length " +
                  strata::format_number(a.number("walls_length"), 4)
            : "the thickness " + strata::format_number(d.thickness, 4) + " asked";
    std::printf(
        "first height: %s, none asked: %d layers at growth %s reach %s (--first-height H, or --yplus Y with "
        "--reynolds RE, sets it)\n",
        strata::format_number(a.number("first_height"), 3).c_str(), d.layers,
        strata::format_number(growth, 3).c_str(), what.c_str());
}

/// "time: " and each stage of the report's times with its seconds.
void print_times(const strata::ReportNode& r) {
    std::string line;
    for (const strata::ReportNode::Entry& e : r.node("times").entries()) {
        char seconds[32];
        std::snprintf(seconds, sizeof seconds, "%.2f", e.value.number());
        line += (line.empty() ? "" : ", ") + e.key + " " + seconds + " s";
    }
    std::printf("time: %s\n", line.c_str());
}

/// What --foam-case wrote (nothing without it): the case's flow, its files written and kept,
/// how to run it, and what the user should know (warnings).
void print_foam_case(const strata::WrittenOutputs& written, const strata::Options& options) {
    if (!written.foam_case) return;
    const strata::FoamCaseWritten& w = *written.foam_case;
    const strata::FoamCaseParams p = strata::foam_case_params(options);
    auto joined = [](const std::vector<std::string>& names) {
        std::string s;
        for (const std::string& n : names) s += (s.empty() ? "" : " ") + n;
        return s;
    };
    std::printf("case: %s, simpleFoam with k-omega SST: U (%s %s %s), Re %s on L %s, nu %s", w.case_dir.c_str(),
                strata::format_number(p.velocity.x()).c_str(), strata::format_number(p.velocity.y()).c_str(),
                strata::format_number(p.velocity.z()).c_str(), strata::format_number(p.reynolds).c_str(),
                strata::format_number(p.reference_length).c_str(),
                strata::format_number(strata::foam_viscosity(p)).c_str());
    if (p.yplus > 0.0) std::printf(", first cells at y+ about %s", strata::format_number(p.yplus, 3).c_str());
    std::printf("; wrote %s%s0/ (a copy of 0.orig/)", joined(w.written).c_str(), w.written.empty() ? "" : " ");
    if (!w.kept.empty())
        std::printf("; kept the case's own %s (delete one to have Strata's)", joined(w.kept).c_str());
    std::printf("\nrun: potentialFoam -case %s && simpleFoam -case %s\n", w.case_dir.c_str(), w.case_dir.c_str());
    for (const std::string& warning : w.warnings) std::printf("warning: %s\n", warning.c_str());
}

void print_written(const std::vector<std::string>& files) {
    std::string list;
    for (std::size_t i = 0; i < files.size(); ++i)
        list += (i == 0 ? "" : i + 1 == files.size() ? " and " : ", ") + files[i];
    std::printf("wrote %s\n", list.c_str());
}

// ---------------------------------------------------------------------------------------
// The plots: drawn by the Python package (strata.report, matplotlib) from the report.

/// What `--plots DIR` adds to `strata mesh`.
struct PlotOptions {
    std::string dir;  ///< empty: no plots
    std::string cut;  ///< "AXIS=VALUE", or empty: across the body's longest side through its centre
};

/// The axis and value of --plot-cut "AXIS=VALUE" (axis -1 for none given).
std::pair<int, double> parse_cut(const std::string& cut) {
    if (cut.empty()) return {-1, 0.0};
    const auto eq = cut.find('=');
    char* end = nullptr;
    const double value = eq == std::string::npos ? 0.0 : std::strtod(cut.c_str() + eq + 1, &end);
    if (eq != 1 || std::string("xyz").find(cut[0]) == std::string::npos || end == cut.c_str() + eq + 1 || *end ||
        !std::isfinite(value))
        throw strata::InputError("--plot-cut " + cut + ": expected AXIS=VALUE, AXIS x, y or z (e.g. y=0.5)");
    return {static_cast<int>(std::string("xyz").find(cut[0])), value};
}

/// Run `python3 -m strata.report REPORT --plots DIR` (the Python package's report, which the
/// CLI delegates to so the plots have one implementation): the interpreter STRATA_PYTHON or the
/// one the package is built for, the build tree's package first on PYTHONPATH. Its exit status.
int run_report_script(const std::string& report, const std::string& dir, bool quiet) {
    const char* env_python = std::getenv("STRATA_PYTHON");
    const std::string python = env_python && *env_python ? env_python : STRATA_REPORT_PYTHON;
    std::string path = STRATA_PYTHON_PATH;
    struct stat st {};
    if (::stat((path + "/strata/report.py").c_str(), &st) != 0) path.clear();  // an installed strata: the .pth's
    if (const char* old = std::getenv("PYTHONPATH"); old && *old) path = path.empty() ? old : path + ":" + old;
    std::vector<std::string> args{python, "-m", "strata.report", report, "--plots", dir};
    if (quiet) args.emplace_back("-q");
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::fflush(stdout);
    const pid_t pid = ::fork();
    if (pid < 0) throw strata::Error("cannot start " + python + " for the plots (fork failed)");
    if (pid == 0) {
        if (!path.empty()) ::setenv("PYTHONPATH", path.c_str(), 1);
        ::execvp(argv[0], argv.data());
        std::fprintf(stderr,
                     "strata: error: cannot run %s for the plots; set STRATA_PYTHON to a Python 3 with "
                     "matplotlib and the strata package\n",
                     argv[0]);
        ::_exit(127);
    }
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) throw strata::Error("waiting for the plots' Python failed");
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

// ---------------------------------------------------------------------------------------
// The subcommands.

/// Before the work: the output's format, and every output can be created and none replaces an
/// input (a typo in its name should not cost a meshing run). \p plots: the run writes the plots'
/// data too. The MSH version and encoding asked.
strata::MshFormat check_run_outputs(const Common& c, strata::Job job, bool plots = false) {
    const strata::MshFormat msh(strata::parse_msh_version(c.msh_version), c.binary);
    std::vector<std::string> extra;
    if (plots) extra.push_back(strata::plot_data_path(c.output));
    strata::check_outputs(job, c.output, msh, c.o.surface.inputs, extra, c.o.output);
    return msh;
}

/// Before writing: a warning when the file system of the output has less free space than the
/// mesh will take (the run goes on: the previous output stays if the disk fills).
void warn_if_short_of_space(const Common& c, std::size_t nodes, std::size_t cells) {
    const std::int64_t need = strata::estimate_output_bytes(c.output, nodes, cells);
    const std::int64_t free = strata::free_bytes_at(c.output);
    if (free < 0 || need <= free) return;
    std::fprintf(stderr,
                 "%sstrata: warning: the file system of '%s' has %.1f MB free and the mesh takes about %.1f MB; "
                 "writing will likely fail (the previous output then stays as it was)\n",
                 after_bar(), c.output.c_str(), static_cast<double>(free) / 1e6, static_cast<double>(need) / 1e6);
}

int run_surface(const Common& c) {
    const auto t0 = std::chrono::steady_clock::now();
    Terminal terminal(c.quiet, c.o.surface.input);
    const strata::Request request = strata::make_request(strata::Job::Surface, c.o);
    const strata::MshFormat msh = check_run_outputs(c, request.job);
    const strata::Result r = strata::run(request, &terminal);
    warn_if_short_of_space(c, r.surface.points.size(), static_cast<std::size_t>(r.surface.num_faces()));
    begin_writing();
    strata::OutputSet outputs;
    strata::write_outputs(r, c.output, msh, &terminal, outputs);
    outputs.commit();
    if (c.quiet) return 0;
    print_surface_summary(r.report);
    std::printf("wrote %s (%.2f s)\n", c.output.c_str(), seconds_since(t0));
    return 0;
}

int run_layers(const Common& c) {
    const strata::Request request = strata::make_request(strata::Job::Layers, c.o);
    Terminal terminal(c.quiet, c.o.surface.input);
    const strata::MshFormat msh = check_run_outputs(c, request.job);
    strata::Result r = strata::run(request, &terminal);
    const auto t1 = std::chrono::steady_clock::now();
    warn_if_short_of_space(c, r.layers.mesh.points.size(), static_cast<std::size_t>(r.layers.mesh.num_cells()));
    begin_writing();
    strata::OutputSet outputs;  // the mesh and its report (a case's files), all or none
    const strata::WrittenOutputs written = strata::write_outputs(r, c.output, msh, &terminal, outputs);
    outputs.commit();
    strata::set_time(r.report, "write", seconds_since(t1));
    if (c.quiet) return 0;
    print_surface_summary(r.report.node("surface"));
    print_wall_aspect_forecast(r.report.node("surface"));
    print_first_height(r.report, r.options);
    print_layer_table(r.report);
    print_coverage(r.report);
    print_cells(r.report, !r.any_cad && !r.prepare.remeshed);
    print_times(r.report);
    print_foam_case(written, r.options);
    print_written(written.files);
    return 0;
}

int run_mesh(const Common& c, const PlotOptions& po) {
    const strata::Request request = strata::make_request(strata::Job::Mesh, c.o);
    const auto [cut_axis, cut_value] = parse_cut(po.cut);
    Terminal terminal(c.quiet, c.o.surface.input);
    const strata::MshFormat msh = check_run_outputs(c, request.job, !po.dir.empty());
    strata::Result r = strata::run(request, &terminal);
    const auto t1 = std::chrono::steady_clock::now();
    warn_if_short_of_space(c, r.mesh.points.size(), static_cast<std::size_t>(r.mesh.num_cells()));
    begin_writing();
    strata::OutputSet outputs;  // the mesh, its report (a case's files) and the plots' data, all or none
    const strata::WrittenOutputs written = strata::write_outputs(r, c.output, msh, &terminal, outputs);
    if (!po.dir.empty())
        strata::write_plot_data(strata::node_layers(r.hybrid.coverage, r.surface.points.size()),
                                strata::node_shares(r.hybrid.coverage, r.surface.points.size()), r.surface, r.mesh,
                                strata::plot_data_path(c.output), cut_axis, cut_value, &outputs);
    outputs.commit();
    strata::set_time(r.report, "write", seconds_since(t1));
    if (!c.quiet) {
        print_surface_summary(r.report.node("surface"));
        print_wall_aspect_forecast(r.report.node("surface"));
        print_first_height(r.report, r.options);
        print_hybrid_summary(r.report, !r.any_cad && !r.prepare.remeshed);
        print_times(r.report);
        print_foam_case(written, r.options);
        std::vector<std::string> files = written.files;
        if (!po.dir.empty()) files.push_back(strata::plot_data_path(c.output));
        print_written(files);
    }
    if (po.dir.empty()) return 0;
    const int rc = run_report_script(strata::report_path(c.output), po.dir, c.quiet);
    if (rc != 0) std::fprintf(stderr, "strata: error: the mesh is written, but the plots failed (status %d)\n", rc);
    return rc;
}

/// The command line's arguments with each optional SIZE (OptionSpec::optional_size: --remesh,
/// --wrap) joined to its flag: "--remesh 20" is "--remesh=20", a bare "--remesh" is
/// "--remesh=0" (automatic size), so that "--remesh wing.stl" leaves the input alone.
std::vector<std::string> with_optional_sizes(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    const auto& table = strata::option_table();
    const auto takes_size = [&](const std::string& a) {
        return std::any_of(table.begin(), table.end(),
                           [&](const strata::OptionSpec& s) { return s.optional_size && s.flag == a; });
    };
    for (std::size_t i = 0; i < args.size(); ++i) {
        if (!takes_size(args[i])) continue;
        char* end = nullptr;
        const bool size = i + 1 < args.size() && !args[i + 1].empty() &&
                          (std::strtod(args[i + 1].c_str(), &end), end && *end == '\0');
        if (size) {
            args[i] += "=" + args[i + 1];
            args.erase(args.begin() + static_cast<std::ptrdiff_t>(i) + 1);
        } else {
            args[i] += "=0";
        }
    }
    return args;
}

}  // namespace

int main(int argc, char** argv) {
    install_stop_handlers();
    std::set_terminate(on_terminate);
    install_crash_handler();
    CLI::App app{
        "Strata: near-body hybrid meshes for viscous CFD.\n"
        "Boundary-layer prisms and hexahedra marched from the wall, tetrahedra beyond.",
        "strata"};
    // The commit is the source tree's when it was configured (frontend/CMakeLists.txt), as in
    // every report's provenance.
    app.set_version_flag("--version",
                         std::string("strata ") + STRATA_VERSION + " (commit " + strata::strata_commit() + ")");
    app.footer(
        "Volume outputs (layers, mesh: -o OUT) by name: .cgr/.cog/.grd Cobalt60 (with a .bc patch map), .cgns CGNS, "
        ".vtu/.vtm VTK XML for ParaView (cell quality fields; .vtm adds a block per patch), "
        "a directory named polyMesh (CASE/constant/polyMesh) OpenFOAM, .msh (--msh-version 4.1 or 2.2), and through "
        "Gmsh .vtk .su2 .unv .mesh .bdf .nas .inp .med .key.");
    app.require_subcommand(1);

    Common sc;
    CLI::App* surface = app.add_subcommand(
        "surface", "read CAD or a surface mesh; write the checked, oriented surface mesh with patches");
    add_common_options(*surface, sc, "output surface mesh (.msh; .vtk, .stl, ... by extension)");

    Common lc;
    CLI::App* layers =
        app.add_subcommand("layers", "extrude boundary-layer prisms and hexahedra from the walls; write the layers");
    add_common_options(*layers, lc,
                       "output volume mesh: .msh, .cgr/.cog/.grd (Cobalt60), .cgns (CGNS), .vtu/.vtm (ParaView), "
                       "CASE/constant/polyMesh (OpenFOAM, a directory), .vtk, .su2, ... by extension");
    add_table_options(*layers, lc.o, {strata::OptionStage::Layers, strata::OptionStage::Output});

    Common mc;
    CLI::App* meshcmd = app.add_subcommand("mesh",
                                           "the whole pipeline: surface, boundary layers, pyramids, tetrahedra; "
                                           "write one validated hybrid mesh");
    add_common_options(*meshcmd, mc,
                       "output: .cgr/.cog/.grd (Cobalt60, with a .bc patch map), .cgns (CGNS), .vtu/.vtm (ParaView), "
                       "CASE/constant/polyMesh (OpenFOAM polyMesh, a directory), .msh, .vtk, .su2, ...");
    add_table_options(*meshcmd, mc.o,
                      {strata::OptionStage::Layers, strata::OptionStage::Mesh, strata::OptionStage::Output});
    PlotOptions po;
    meshcmd->add_option("--plots", po.dir,
                        "also draw the quality report's plots into DIR (PNG and index.md: strata report; writes "
                        "OUT.plot.json, the wall and a cut for them; needs Python's matplotlib)");
    meshcmd->add_option("--plot-cut", po.cut,
                        "with --plots: the cut's plane AXIS=VALUE (e.g. y=0.5); default across the body's longest "
                        "side through its centre");

    std::string report_file, report_dir;
    bool report_quiet = false;
    CLI::App* reportcmd = app.add_subcommand(
        "report",
        "draw a mesh's quality report as plots: scaled-Jacobian histograms, the layers' figures, layers "
        "reached over the wall, a cut (PNG and DIR/index.md; runs python3 -m strata.report)");
    reportcmd
        ->add_option("REPORT", report_file,
                     "OUT.report.json, written next to every mesh (OUT.plot.json beside "
                     "it, from strata mesh --plots, adds the wall and the cut)")
        ->required();
    reportcmd->add_option("--plots", report_dir, "directory for the plots (created)")->required();
    reportcmd->add_flag("-q,--quiet", report_quiet, "print nothing but errors");

    std::vector<std::string> args = with_optional_sizes(argc, argv);
    std::reverse(args.begin(), args.end());  // CLI11 takes them last first
    try {
        app.parse(args);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "strata: error: " << e.what() << " (see strata --help)\n";
        return 2;
    }

    for (Common* c : {&sc, &lc, &mc}) c->o.surface.input = strata::input_name(c->o.surface.inputs);
    // A case's mesh is its CASE/constant/polyMesh: the report and the plots' data go beside it.
    for (Common* c : {&lc, &mc}) c->output = strata::mesh_output(strata::Job::Mesh, c->output, c->o.output);
    const Watchdog watchdog(*surface ? sc.timeout : *layers ? lc.timeout : *meshcmd ? mc.timeout : 0.0);
    try {
        if (*surface) return run_surface(sc);
        if (*layers) return run_layers(lc);
        if (*meshcmd) return run_mesh(mc, po);
        if (*reportcmd) return run_report_script(report_file, report_dir, report_quiet);
    } catch (const strata::Cancelled& e) {
        if (g_timed_out.load()) {
            const double t = *surface ? sc.timeout : *layers ? lc.timeout : mc.timeout;
            std::cerr << after_bar() << "strata: error: stopped by --timeout " << t << " s; nothing was written\n";
            return 124;
        }
        const int sig = g_signal.load();
        std::cerr << after_bar() << "strata: cancelled by " << signal_name(sig)
                  << "; nothing was written, and the previous output is as it was\n";
        return 128 + (sig != 0 ? sig : SIGINT);
    } catch (const std::exception& e) {
        std::string msg = in_flags(e.what());
        for (char& ch : msg)
            if (ch == '\n') ch = ' ';  // one line, whatever a backend said
        std::cerr << "strata: error: " << msg << "\n";
        return 1;
    }
    return 0;
}
