#pragma once
/// \file
/// A library call that may end the whole process (a crash, or a std::terminate from an
/// exception thrown out of an OpenMP loop) run in a forked child instead, so that the caller
/// (the CLI, or a FreeCAD or Python session) lives on and learns how it ended. TetGen runs
/// this way (hybrid/src/tetgen_library.cpp), and Gmsh's surface meshing is tried this way
/// where it may abort (io/gmsh_session.h, gmsh_probe).

#include <strata/core/progress.h>

#include <functional>
#include <vector>

namespace strata {

/// How run_in_child's child ended.
struct ChildResult {
    bool forked = false;     ///< false: fork() was not available (EAGAIN, ENOMEM, a sandbox); nothing ran
    int signal = 0;          ///< the signal that ended the child (0: it exited)
    int exit_status = -1;    ///< its exit status, if it exited
    std::vector<char> sent;  ///< the bytes it sent (what its body put in its buffer, or child_exit's)
};

struct ChildOptions {
    /// Free this thread's OpenMP worker threads before forking (omp_pause_resource_all): a
    /// child that starts an OpenMP team after its parent has had one hangs for ever in GCC's
    /// libgomp, which believes the parent's workers (not copied by fork) are still there. The
    /// parent makes new ones at its next parallel loop. Needed when the child's work uses
    /// OpenMP (Gmsh's surface meshing does); the caller must not be inside a parallel region.
    bool free_openmp_threads = false;
};

/// Run \p body in a forked child and return how it ended. The child runs body(buffer), sends
/// the buffer down a pipe and _exit()s with status 0 (1 if body threw: nothing is sent), never
/// unwinding into the parent's state or running its atexit handlers. A crash ends it by its
/// signal (the default actions of SIGSEGV, SIGBUS, SIGFPE and SIGILL are restored in it: a
/// handler the program installed would exit with a status instead), and it dies with this
/// process. Every 0.1 s the parent asks \p progress (may be null) whether to stop: then the
/// child is killed and Cancelled thrown. Where fork() is not available, forked is false and
/// the caller runs the work itself if it can.
ChildResult run_in_child(const std::function<void(std::vector<char>&)>& body, const Progress* progress = nullptr,
                         const ChildOptions& options = {});

/// In run_in_child's child only (a terminate handler, a callback deep inside a library): send
/// \p bytes as the child's result and end it with \p status at once. Outside a child it does
/// nothing and returns.
void child_exit(const std::vector<char>& bytes, int status);

}  // namespace strata
