#pragma once
/// \file
/// Private to strata_hybrid: TetGen 1.5 (Debian's libtet) loaded at run time and called under
/// one process-wide lock, its failures turned into BackendError. Why it is loaded and not
/// linked, and how its crash on failure is avoided: tetgen_library.cpp.

// TETLIBRARY: TetGen's library interface (hybrid/CMakeLists.txt does not link libtet, which
// would put it on the link line; strata::tetgen gives the header only).
#ifndef TETLIBRARY
#define TETLIBRARY
#endif
#include <tetgen.h>

#include <strata/core/error.h>
#include <strata/core/progress.h>

#include <string>
#include <vector>

namespace strata::tetgen {

/// The mangled names the loader looks up and patches; a parameter so that a test can ask for
/// a symbol the library does not have.
struct Symbols {
    const char* tetrahedralize = "_Z14tetrahedralizePcP8tetgenioS1_S1_S1_";  ///< tetrahedralize(char*, tetgenio*, ...)
    const char* terminate = "_Z15terminatetetgenP10tetgenmeshi";             ///< terminatetetgen(tetgenmesh*, int)
    const char* shared_with_gmsh = "_ZN10tetgenmesh10inittablesEv";          ///< tetgenmesh::inittables()
};

using TetrahedralizeFn = void (*)(char*, tetgenio*, tetgenio*, tetgenio*, tetgenio*);

/// libtet, loaded.
struct Library {
    TetrahedralizeFn tetrahedralize = nullptr;
    int replaced_slots = 0;  ///< terminatetetgen GOT slots pointed at the throwing replacement (≥ 1)
    int assert_slots = 0;    ///< __assert_fail GOT slots pointed at a throwing replacement (0 if built with NDEBUG)
    int print_slots = 0;     ///< __printf_chk, puts, putchar GOT slots pointed at the trace's (locate_failure)
};

/// Load libtet privately (RTLD_LOCAL | RTLD_DEEPBIND) and point its terminatetetgen at a
/// replacement that throws. BackendError, saying what to do, when libtet cannot be loaded,
/// lacks \p symbols.tetrahedralize, is linked into the program after libgmsh, or when no
/// terminatetetgen slot could be patched (a TetGen failure would then crash the process, so
/// TetGen is not used at all). Loading again returns the same library (dlopen counts).
Library load(const Symbols& symbols = {});

/// tetrahedralize(\p switches, in, out, nullptr, \p background) under the process-wide lock
/// (TetGen is not reentrant: exactinit() sets process-wide predicate bounds), with the
/// library loaded once per process. TetGen runs in a forked child process (in this one where
/// fork() fails), so that its crash is an error here, not the end of the process, and
/// \p progress can stop it: Cancelled within 0.1 s of progress->cancelled(), the child killed.
/// TetGen's failures are BackendError with its code explained (failure_message), LocalFailure
/// where it failed at a place, including a crash (signal).
/// Where TetGen's printing is redirected (Library::print_slots), the child runs it without Q and
/// \p progress hears its phases as it announces them (Delaunay, boundary recovery, ...,
/// refinement, optimisation) as "tetrahedra" at each one's share of the run, within 0.1 s; the
/// mesh is the same.
void run(const std::string& switches, tetgenio& in, tetgenio& out, tetgenio* background,
         Progress* progress = nullptr);

/// A TetGen failure met at one place of the boundary, which locate_failure may find: one of
/// its assert()s (a configuration it assumes cannot happen) or its codes 2 to 5 (an internal
/// failure, a self-intersection, a very small feature, two nearly overlapping facets), all met
/// while it recovers the boundary. Not out of memory (1) or a rejected input (10).
class LocalFailure : public BackendError {
public:
    using BackendError::BackendError;
};

/// Run TetGen again as run() did when it threw LocalFailure, now with its trace (VVV,
/// captured, not printed), and return the input points of the boundary face or segment it was
/// recovering when it stopped: 2 or 3 point ids of \p in. Empty when it stopped elsewhere than
/// in the boundary recovery, did not stop, or its printing could not be redirected.
std::vector<int> locate_failure(const std::string& switches, tetgenio& in, tetgenio* background,
                                const Progress* progress = nullptr);

/// TetGen's exit code (terminatetetgen in tetgen.h) as a message saying what to do.
std::string failure_message(int code);

}  // namespace strata::tetgen
