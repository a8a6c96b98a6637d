#pragma once
/// \file
/// The one small interface through which long stages report progress and learn of
/// cancellation. Library users pass nothing (a null pointer); the CLI draws a bar and cancels
/// on Ctrl-C. Stages report at their start (fraction 0) and between steps: "surface", "layers",
/// "pyramids", "tetrahedra", "validation", "writing". A stage that sees cancelled() throws
/// Cancelled at its next check; writers then leave no output file. (Gmsh's meshing cannot be
/// interrupted: the check comes when it returns. TetGen runs in a child process, killed
/// within 0.1 s of cancelled().)

#include <chrono>
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

/// A Progress that asks to stop once \p seconds have passed from its making (or when \p inner
/// does), for work that may run for ever (Gmsh's reparametrization, tried in a child process:
/// gmsh_probe); expired() tells the two apart. Reports go to \p inner.
class DeadlineProgress : public Progress {
public:
    DeadlineProgress(double seconds, const Progress* inner = nullptr)
        : inner_(inner),
          end_(std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                      std::chrono::duration<double>(seconds))) {}
    void report(std::string_view, double) override {}
    bool cancelled() const override {
        if (inner_ && inner_->cancelled()) return true;
        if (std::chrono::steady_clock::now() >= end_) expired_ = true;
        return expired_;
    }
    bool expired() const { return expired_; }

private:
    const Progress* inner_;
    std::chrono::steady_clock::time_point end_;
    mutable bool expired_ = false;
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
