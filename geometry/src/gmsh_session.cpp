#include <strata/geometry/gmsh_session.h>

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
bool& user_initialised() {  // Gmsh was already initialised when Strata first came
    static bool b = false;
    return b;
}

}  // namespace

GmshSession::GmshSession(const std::string& model_name) : lock_(gmsh_mutex()) {
    if (strata_sessions() == 0 && !user_initialised()) {
        // Gmsh 4.8 has no isInitialized(); Strata's own entry points decide. The Gmsh-API
        // entry point (user already initialised) marks that with user_initialised().
        gmsh::initialize();
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

std::string GmshSession::last_error() {
    std::string e;
    try {
        gmsh::logger::getLastError(e);
    } catch (...) {
    }
    return e;
}

}  // namespace strata
