#include <strata/io/gmsh_session.h>

#include <strata/core/bytes.h>
#include <strata/core/child_process.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <vector>

#include <unistd.h>

namespace strata {
namespace {

// Gmsh keeps one global state per process; Strata serialises access to it. The mutex is
// recursive so a stage that holds a session may call a helper that opens another.
std::recursive_mutex& gmsh_mutex() {
    static std::recursive_mutex m;
    return m;
}
int& strata_sessions() {  // sessions currently open that Strata initialised Gmsh for
    static int n = 0;
    return n;
}
bool& user_initialised() {  // a GmshLock found Gmsh initialised by the user
    static bool b = false;
    return b;
}

/// Gmsh 4.8 has no isInitialized(). Its API functions check a flag themselves: before the first
/// gmsh::initialize() they log an error and return without touching their outputs; after a
/// gmsh::finalize() they throw. So: a numeric option that always exists, read into a NaN.
/// Not called on Strata's usual path (it would print Gmsh's "not initialized" error after a
/// finalize): only from GmshLock and to re-check a user initialisation GmshLock recorded.
bool gmsh_is_initialised() {
    double value = std::numeric_limits<double>::quiet_NaN();
    try {
        gmsh::option::getNumber("General.Verbosity", value);
    } catch (...) {
        return false;
    }
    return !std::isnan(value);
}

}  // namespace

GmshLock::GmshLock(const std::string& context) : lock_(gmsh_mutex()) {
    // Inside a GmshSession (this thread: the mutex is recursive) Gmsh is initialised.
    if (strata_sessions() > 0) return;
    if (!gmsh_is_initialised()) {
        user_initialised() = false;
        throw InputError(context + ": Gmsh is not initialised: call gmsh::initialize() first");
    }
    user_initialised() = true;
}

GmshSession::GmshSession(const std::string& model_name) : lock_(gmsh_mutex()) {
    // A user initialisation recorded by GmshLock is checked again: the user may have finalised
    // Gmsh since.
    if (strata_sessions() == 0 && user_initialised() && !gmsh_is_initialised()) user_initialised() = false;
    if (strata_sessions() == 0 && !user_initialised()) {
        // Gmsh 4.8 has no isInitialized(); Strata's own entry points decide. The Gmsh-API
        // entry points (user already initialised) mark that through GmshLock.
        // Not the user's ~/.gmshrc and ~/.gmsh-options: options saved there (a mesh size factor,
        // an algorithm, the solvers Strata registers with the gmsh program) would change or slow
        // Strata's meshes from one account to the next.
        gmsh::initialize(0, nullptr, false);
        initialised_here_ = true;
        gmsh::option::setNumber("General.Terminal", 0);
        gmsh::option::setNumber("General.Verbosity", 2);
    }
    ++strata_sessions();
    // Keep Gmsh's messages so failures can be reported with its own words.
    gmsh_call("starting Gmsh", [] { gmsh::logger::start(); });
    gmsh::model::getCurrent(previous_model_);
    model_ = model_name + "_" + std::to_string(strata_sessions());
    gmsh::model::add(model_);
    gmsh::model::setCurrent(model_);
}

GmshSession::~GmshSession() {
    try {
        gmsh::model::setCurrent(model_);
        gmsh::model::remove();
        if (!previous_model_.empty()) gmsh::model::setCurrent(previous_model_);
        gmsh::logger::stop();
    } catch (...) {
        // Cleanup must not throw; Gmsh's state is reset by finalize below if we own it.
    }
    --strata_sessions();
    if (initialised_here_) {
        try {
            gmsh::finalize();
        } catch (...) {
        }
    }
}

GmshOptionScope::~GmshOptionScope() {
    for (auto it = numbers_.rbegin(); it != numbers_.rend(); ++it) {
        try {
            gmsh::option::setNumber(it->first, it->second);
        } catch (...) {
        }
    }
    for (auto it = strings_.rbegin(); it != strings_.rend(); ++it) {
        try {
            gmsh::option::setString(it->first, it->second);
        } catch (...) {
        }
    }
}

void GmshOptionScope::save(const std::vector<std::string>& names) {
    for (const std::string& name : names) {
        if (std::any_of(numbers_.begin(), numbers_.end(), [&](const auto& nv) { return nv.first == name; })) continue;
        double v = 0.0;
        try {
            gmsh::option::getNumber(name, v);
            numbers_.emplace_back(name, v);
        } catch (...) {
            // Not an option of this Gmsh version: nothing to save.
        }
    }
}

void GmshOptionScope::save_string(const std::string& name) {
    try {
        std::string v;
        gmsh::option::getString(name, v);
        strings_.emplace_back(name, v);
    } catch (...) {
    }
}

void GmshOptionScope::set(const std::string& name, double value) {
    save({name});
    gmsh::option::setNumber(name, value);
}

bool GmshOptionScope::changed(const std::string& name) const {
    for (const auto& [n, v] : numbers_) {
        if (n != name) continue;
        double now = v;
        try {
            gmsh::option::getNumber(name, now);
        } catch (...) {
        }
        return now != v;
    }
    return false;
}

namespace {

std::string g_abort_context;  // Gmsh is locked by whoever calls it: one context at a time

[[noreturn]] void on_gmsh_abort() {
    const std::string line = g_abort_context + ": Gmsh aborted the process (" + current_exception_text() +
                             "), as it does on a face it cannot mesh; nothing was written";
    // After a line break where a progress bar may be drawn on the line (a terminal).
    std::fprintf(stderr, "%sstrata: error: %s\n", ::isatty(2) ? "\n" : "", line.c_str());
    std::fflush(stderr);
    std::_Exit(1);
}

}  // namespace

GmshAbortScope::GmshAbortScope(std::string context) : previous_context_(std::move(g_abort_context)) {
    g_abort_context = std::move(context);
    previous_handler_ = std::set_terminate(on_gmsh_abort);
}

GmshAbortScope::~GmshAbortScope() {
    g_abort_context = std::move(previous_context_);
    std::set_terminate(previous_handler_);
}

namespace {

// In gmsh_probe's child: an abort is sent to the parent as 'A' and its text, not printed.
[[noreturn]] void on_probe_abort() {
    const std::string sent = "A" + current_exception_text();
    child_exit(std::vector<char>(sent.begin(), sent.end()), 0);
    std::_Exit(1);
}

}  // namespace

GmshProbe gmsh_probe_result(const std::function<void(std::vector<char>&)>& f, const Progress* progress) {
    ChildOptions options;
    options.free_openmp_threads = true;
    const ChildResult child = run_in_child(
        [&](std::vector<char>& sent) {
            std::set_terminate(on_probe_abort);
            try {
                gmsh::option::setNumber("General.Terminal", 0);
            } catch (...) {
            }
            std::vector<char> result;
            std::string outcome = "R";
            try {
                f(result);
            } catch (...) {
                outcome = "E" + current_exception_text();
                result.clear();
            }
            sent.assign(outcome.begin(), outcome.end());
            sent.insert(sent.end(), result.begin(), result.end());
        },
        progress, options);
    GmshProbe probe;
    probe.ran = child.forked;
    if (!child.forked) return probe;
    probe.signal = child.signal;
    if (child.signal == 0 && !child.sent.empty()) {
        probe.returned = child.sent[0] == 'R';
        probe.aborted = child.sent[0] == 'A';
        probe.threw = child.sent[0] == 'E';
        if (probe.returned)
            probe.result.assign(child.sent.begin() + 1, child.sent.end());
        else
            probe.message.assign(child.sent.begin() + 1, child.sent.end());
    }
    return probe;
}

GmshProbe gmsh_probe(const std::function<void()>& f, const Progress* progress) {
    return gmsh_probe_result([&](std::vector<char>&) { f(); }, progress);
}

std::vector<char> pack_model_mesh() {
    Bytes b;
    gmsh::vectorpair entities;
    gmsh::model::getEntities(entities);
    for (const auto& [dim, tag] : entities) {
        std::vector<std::size_t> nodes;  // Gmsh 4.8: output vectors must start empty
        std::vector<double> xyz, uvw;
        gmsh::model::mesh::getNodes(nodes, xyz, uvw, dim, tag, false, true);
        std::vector<int> types;
        std::vector<std::vector<std::size_t>> elements, element_nodes;
        gmsh::model::mesh::getElements(types, elements, element_nodes, dim, tag);
        b.put<int>(dim);
        b.put<int>(tag);
        b.put_vector(nodes);
        b.put_vector(xyz);
        b.put_vector(uvw.size() == static_cast<std::size_t>(dim) * nodes.size() ? uvw : std::vector<double>{});
        b.put_vector(types);
        for (std::size_t t = 0; t < types.size(); ++t) {
            b.put_vector(elements[t]);
            b.put_vector(element_nodes[t]);
        }
    }
    return std::move(b.data);
}

void unpack_model_mesh(const std::vector<char>& bytes) {
    // The whole model's mesh: Gmsh 4.8's clear of a list of entities leaves some of their
    // boundaries' nodes, whose tags the child's nodes then meet.
    gmsh::model::mesh::clear();
    Bytes b{bytes, 0, "Gmsh's child process"};
    // Every entity's nodes before any element: an element may use the nodes of its boundary's
    // entities, which come later in Gmsh's order of entities by tag than some of theirs.
    struct Elements {
        int dim, tag;
        std::vector<int> types;
        std::vector<std::vector<std::size_t>> tags, nodes;
    };
    std::vector<Elements> all;
    while (b.at < b.data.size()) {
        Elements e;
        e.dim = b.get<int>();
        e.tag = b.get<int>();
        const auto nodes = b.get_vector<std::size_t>();
        const auto xyz = b.get_vector<double>();
        const auto uvw = b.get_vector<double>();
        e.types = b.get_vector<int>();
        for (std::size_t t = 0; t < e.types.size(); ++t) {
            e.tags.push_back(b.get_vector<std::size_t>());
            e.nodes.push_back(b.get_vector<std::size_t>());
        }
        if (!nodes.empty()) gmsh::model::mesh::addNodes(e.dim, e.tag, nodes, xyz, uvw);
        all.push_back(std::move(e));
    }
    for (const Elements& e : all)
        if (!e.types.empty()) gmsh::model::mesh::addElements(e.dim, e.tag, e.types, e.tags, e.nodes);
}

namespace {

/// \p generate run in a forked child (gmsh_probe_result), the mesh it made packed as its result.
GmshProbe generate_and_pack(const std::function<void()>& generate, const Progress* progress) {
    return gmsh_probe_result(
        [&](std::vector<char>& result) {
            generate();
            result = pack_model_mesh();
        },
        progress);
}

/// The mesh \p made brought into the current model, or \p generate run here where no child
/// could be started; false where the child did not return (nothing changed here).
bool take_mesh(const GmshProbe& made, const std::function<void()>& generate) {
    if (!made.ran) {
        generate();
        return true;
    }
    if (!made.returned) return false;
    unpack_model_mesh(made.result);
    return true;
}

}  // namespace

void generate_in_child(const std::string& context, const std::function<void()>& generate, const Progress* progress) {
    const GmshProbe made = generate_and_pack(generate, progress);
    if (!take_mesh(made, generate))
        throw BackendError(context + ": Gmsh " + how_it_failed(made) +
                           " meshing the surfaces (in a child process: nothing else is lost, and a Python or "
                           "FreeCAD session goes on)");
}

std::string how_it_failed(const GmshProbe& p) {
    return p.signal != 0 ? "crashes (signal " + std::to_string(p.signal) + ")"
           : p.aborted   ? "aborts (" + p.message + ")"
                         : "fails (" + p.message + ")";
}

std::string generate_surfaces_in_child(const std::string& context, bool quads_asked, GmshOptionScope& options,
                                       const std::function<void()>& generate, const Progress* progress) {
    double algorithm = 0.0;
    gmsh::option::getNumber("Mesh.RecombinationAlgorithm", algorithm);
    if (!(quads_asked && algorithm == 1.0)) {
        generate_in_child(context, generate, progress);
        return "";
    }
    const GmshProbe first = generate_and_pack(generate, progress);
    if (take_mesh(first, generate)) return "";
    // Blossom aborts with its own words on some surfaces (Gmsh 4.8, meshGFaceOptimize.cpp:
    // "Perfect Match") and crashes on others (a segmentation fault on a body with a mirror on a
    // thin stalk, and on a drone's rotors, where the simple recombination meshes both): the
    // simple recombination is tried as well, and used where it works.
    options.set("Mesh.RecombinationAlgorithm", 0);
    const GmshProbe simple = generate_and_pack(generate, progress);
    const bool blossoms_words = first.aborted && first.message.find("Perfect Match") != std::string::npos;
    const std::string blossom_failure = blossoms_words ? first.message : how_it_failed(first);
    if (take_mesh(simple, generate)) return blossom_failure;
    throw BackendError(context + ": quads cannot be made here: Gmsh's Blossom recombination " +
                       (blossoms_words ? "fails (" + first.message + ")" : how_it_failed(first)) +
                       " and with its simple recombination Gmsh " + how_it_failed(simple) +
                       "; mesh triangles instead, or with another size");
}

std::string GmshSession::last_error() {
    std::string e;
    try {
        gmsh::logger::getLastError(e);
    } catch (...) {
    }
    return e;
}

}  // namespace strata
