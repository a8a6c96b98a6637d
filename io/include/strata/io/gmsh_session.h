#pragma once
/// \file
/// The one adapter between Strata and Gmsh's global state. Gmsh is a process-wide singleton
/// and not thread-safe, so every use goes through a GmshSession (a lock, initialisation if
/// nobody else did it, a scratch model removed at the end) and gmsh_call (Gmsh's failures
/// re-thrown as BackendError with context and Gmsh's last logged error).

#include <strata/core/error.h>
#include <strata/core/progress.h>

#include <gmsh.h>

#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace strata {

class GmshSession {
public:
    /// Lock Gmsh for this thread; initialise it (quiet) unless a GmshSession or the user
    /// already did; start a fresh model named \p model_name and make it current.
    explicit GmshSession(const std::string& model_name = "strata");
    /// Remove the scratch model, restore the previously current model, finalise Gmsh if this
    /// session initialised it.
    ~GmshSession();
    GmshSession(const GmshSession&) = delete;
    GmshSession& operator=(const GmshSession&) = delete;

    /// Gmsh's most recent error message ("" if none).
    static std::string last_error();

private:
    std::unique_lock<std::recursive_mutex> lock_;
    std::string model_;
    std::string previous_model_;
    bool initialised_here_ = false;
};

/// Gmsh's lock alone, for functions that work on the caller's CURRENT model (the Gmsh-API
/// entry points, surface_from_gmsh_model, add_volume_to_gmsh_model) rather than a scratch
/// model. Gmsh must already be initialised, by the user or by an enclosing GmshSession;
/// otherwise InputError "<context>: Gmsh is not initialised: call gmsh::initialize() first".
/// When no GmshSession is open, the initialisation is the user's: that is recorded, so a later
/// GmshSession neither initialises Gmsh again (nor resets its options) nor finalises it.
class GmshLock {
public:
    explicit GmshLock(const std::string& context);
    GmshLock(const GmshLock&) = delete;
    GmshLock& operator=(const GmshLock&) = delete;

private:
    std::unique_lock<std::recursive_mutex> lock_;
};

/// Gmsh options are process-wide: a scope sets Strata's for one operation and puts the
/// caller's values back when it ends, so one call does not leave its sizes to the next and a Gmsh
/// user embedding Strata keeps their settings. Declare it after the GmshSession (or GmshLock) so
/// it is restored while Gmsh is still locked.
class GmshOptionScope {
public:
    GmshOptionScope() = default;
    GmshOptionScope(const GmshOptionScope&) = delete;
    GmshOptionScope& operator=(const GmshOptionScope&) = delete;
    ~GmshOptionScope();

    /// Remember the current values of the numeric options \p names (names this Gmsh version
    /// does not know are skipped), to be restored at the end even if something else (a .geo
    /// script) changes them meanwhile.
    void save(const std::vector<std::string>& names);
    /// Remember the current value of the string option \p name.
    void save_string(const std::string& name);
    /// Remember the current value of numeric option \p name (once) and set it to \p value.
    void set(const std::string& name, double value);
    /// True if the saved numeric option \p name now differs from its saved value (false if it
    /// was not saved).
    bool changed(const std::string& name) const;

private:
    std::vector<std::pair<std::string, double>> numbers_;
    std::vector<std::pair<std::string, std::string>> strings_;
};

/// While it lives, a std::terminate ends the process with one line on stderr, "strata: error:
/// <context>: Gmsh aborted the process (<its message>) ...", and status 1, instead of
/// "terminate called after throwing an instance of std::string" and SIGABRT: Gmsh 4.8 throws
/// its error text out of its OpenMP meshing loops when it cannot mesh a face, and no caller can
/// catch that. The process cannot go on; this says why. (Hosts that must live on have Gmsh mesh
/// in a child: generate_in_child.)
/// Nested scopes stack; the handler before the outermost is put back at its end.
class GmshAbortScope {
public:
    explicit GmshAbortScope(std::string context);
    ~GmshAbortScope();
    GmshAbortScope(const GmshAbortScope&) = delete;
    GmshAbortScope& operator=(const GmshAbortScope&) = delete;

private:
    std::string previous_context_;
    std::terminate_handler previous_handler_ = nullptr;
};

/// How gmsh_probe's trial of a Gmsh call ended.
struct GmshProbe {
    bool ran = false;          ///< false: no child process could be started; nothing was tried
    bool returned = false;     ///< the call returned
    bool aborted = false;      ///< Gmsh ended the process (a std::terminate, GmshAbortScope): \p message is its text
    bool threw = false;        ///< the call threw: \p message is the exception's text
    int signal = 0;            ///< the call crashed the process on this signal
    std::string message;       ///< how it aborted or threw
    std::vector<char> result;  ///< where it returned: what gmsh_probe_result's call put there
};

/// \p f (calls into gmsh::) tried in a forked child on a copy of Gmsh's state
/// (run_in_child, its OpenMP threads freed first: Gmsh meshes surfaces in an OpenMP loop), to
/// learn whether it would abort or crash the process before running it here; nothing it does
/// reaches this process. Gmsh prints nothing in the child. Costs the call's time once more.
/// Where \p progress asks to stop (polled every 0.1 s), the child is killed and Cancelled
/// thrown: unlike Gmsh in this process, a trial can be stopped.
/// The caller holds Gmsh (GmshSession or GmshLock) and is not inside an OpenMP parallel region.
GmshProbe gmsh_probe(const std::function<void()>& f, const Progress* progress = nullptr);

/// As gmsh_probe, \p f also putting bytes into its argument, which come back in
/// GmshProbe::result where it returned: what the child made, for the parent to take.
GmshProbe gmsh_probe_result(const std::function<void(std::vector<char>&)>& f, const Progress* progress = nullptr);

/// The current model's mesh (each entity's nodes with their parametric coordinates, its
/// elements by type), as bytes; and put back, into the same model (the same entities: a forked
/// child's copy of it) in place of the whole mesh it has there.
std::vector<char> pack_model_mesh();
void unpack_model_mesh(const std::vector<char>& bytes);

/// \p generate (the caller's generate(2)) run in a forked child (gmsh_probe_result), and the
/// mesh it made put into the current model here (pack_model_mesh): so a Gmsh that aborts,
/// crashes or runs on for ever (MeshAdapt's refinement on a poorly parametrized discrete
/// surface) never takes this process with it. Where \p progress asks to stop, the child is
/// killed and Cancelled thrown; where it aborts, crashes or throws, a BackendError
/// "<context>: Gmsh <how_it_failed> meshing the surfaces"; where no child can be started,
/// \p generate runs here. Costs the mesh's copy between the processes, not a second meshing.
void generate_in_child(const std::string& context, const std::function<void()>& generate,
                       const Progress* progress = nullptr);

/// How a trial that did not return ended, for a message: "crashes (signal 11)", "aborts
/// (<its text>)", "fails (<its text>)".
std::string how_it_failed(const GmshProbe& p);

/// generate_in_child where Gmsh's Blossom recombination may fail: Gmsh 4.8's Blossom
/// (Mesh.RecombinationAlgorithm 1) throws "Perfect Match failed in quadrangulation" out of its
/// OpenMP surface-meshing loop on some surfaces (the apex of a cone, a tiny hole in a large
/// face), and crashes on others (a segmentation fault on a body with a mirror on a thin stalk).
/// So where \p quads_asked (Mesh.RecombineAll, or some surfaces' own recombination) and Blossom
/// is the algorithm and its child does not return, Mesh.RecombinationAlgorithm is set to 0
/// through \p options (Gmsh's simple recombination, which never needs a perfect matching and
/// leaves more triangles), the surfaces are meshed by it in another child, and Blossom's
/// message (or how_it_failed) is returned, for the caller's report; "" where nothing needed
/// saying. Either way the mesh made is brought back into the current model, made once where
/// Blossom goes through. Where the simple recombination fails too: BackendError "<context>:
/// quads cannot be made here: ...". Otherwise as generate_in_child (\p progress's stop, no
/// child: here); without quads, or with another algorithm, generate_in_child itself.
std::string generate_surfaces_in_child(const std::string& context, bool quads_asked, GmshOptionScope& options,
                                       const std::function<void()>& generate, const Progress* progress = nullptr);

/// Run \p f (calls into gmsh::), turning any exception Gmsh throws into a BackendError
/// "<context>: <Gmsh's message>". strata::Error and Cancelled pass through unchanged. An abort inside it
/// (GmshAbortScope) names \p context.
template <class F>
auto gmsh_call(const std::string& context, F&& f) -> decltype(f()) {
    const GmshAbortScope abort_scope(context);
    try {
        return std::forward<F>(f)();
    } catch (const Error&) {
        throw;
    } catch (const Cancelled&) {  // a stop asked for (generate_in_child), not Gmsh's failure
        throw;
    } catch (const std::exception& e) {
        std::string last = GmshSession::last_error();
        throw BackendError(context + ": " + (last.empty() ? std::string(e.what()) : last));
    } catch (...) {
        std::string last = GmshSession::last_error();
        throw BackendError(context + ": " + (last.empty() ? std::string("Gmsh failed") : last));
    }
}

}  // namespace strata
