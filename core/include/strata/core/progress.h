#pragma once
/// \file
/// The one small interface through which long stages report progress and learn of
/// cancellation. Library users pass nothing (a null pointer); the CLI draws a bar and cancels
/// on Ctrl-C. Stages report at their start (fraction 0) and between steps: "surface", "layers",
/// "pyramids", "tetrahedra", "validation", "writing". A stage that sees cancelled() throws
/// Cancelled at its next check; writers then leave no output file. (Gmsh's meshing cannot be
/// interrupted: the check comes when it returns. TetGen runs in a child process, killed
/// within 0.1 s of cancelled().)

#include <string_view>

namespace strata {

class Progress {
public:
    virtual ~Progress() = default;
    /// A stage reports how far it is, \p fraction in [0, 1].
    virtual void report(std::string_view stage, double fraction) = 0;
    /// Polled by stages between steps; true makes the stage throw strata::Cancelled.
    virtual bool cancelled() const { return false; }
};

/// Thrown by a stage that saw Progress::cancelled().
class Cancelled : public std::exception {
public:
    const char* what() const noexcept override { return "cancelled by the user"; }
};

/// Report through \p p if there is one, and throw Cancelled if it asks to stop.
inline void report(Progress* p, std::string_view stage, double fraction) {
    if (!p) return;
    p->report(stage, fraction);
    if (p->cancelled()) throw Cancelled();
}

/// Throw Cancelled if \p p asks to stop (a check without a report, inside a loop).
inline void check_cancelled(const Progress* p) {
    if (p && p->cancelled()) throw Cancelled();
}

}  // namespace strata
