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
    /// Told by run_in_child that the process \p pid does the work from now on (until the next
    /// call), for a Progress that measures the work's time (DeadlineProgress). Nothing by default.
    virtual void watch_child(int pid) const { (void)pid; }
};

/// A Progress that asks to stop once the work has had \p seconds (or when \p inner does), for work
/// that may run for ever (Gmsh's reparametrization and meshing, tried in a child process:
/// gmsh_probe); expired() tells the two apart. Reports go to \p inner.
///
/// While a child process does the work (run_in_child tells it: watch_child), the seconds counted
/// are that child's CPU time, summed over the children it is given in turn; before any, the
/// clock's. A machine loaded by other jobs then gives the work the same budget as an idle one,
/// so whether an attempt ends in time, and with it which mesh comes out, does not depend on
/// what else runs. A child that waits without computing (a deadlock) is stopped too, once
/// kWallFactor times the seconds have passed on the clock.
class DeadlineProgress : public Progress {
public:
    /// The clock's seconds past which a child that has not used its CPU seconds is stopped anyway,
    /// as a multiple of them: ten times covers a machine shared by ten jobs per core.
    static constexpr double kWallFactor = 10.0;

    explicit DeadlineProgress(double seconds, const Progress* inner = nullptr);
    void report(std::string_view, double) override {}
    bool cancelled() const override;
    void watch_child(int pid) const override;
    bool expired() const { return expired_; }
    /// The seconds counted so far: the children's CPU time, or the clock's before any child.
    double spent() const;

private:
    const Progress* inner_;
    double seconds_;
    std::chrono::steady_clock::time_point start_;
    mutable int child_ = 0;             ///< the child watched, 0 before any
    mutable double children_done_ = 0;  ///< the CPU seconds of the children watched before it
    mutable double child_last_ = 0;     ///< the watched child's CPU seconds at the last reading
    mutable bool expired_ = false;
};

/// A part of a stage that reports its own 0 to 1 (TetGen's run, then the tetrahedra's
/// improvement), its fractions mapped into [\p from, \p to] of the stage for \p inner (may be
/// null: nothing is reported). Cancellation and the children watched pass through.
class ProgressRange : public Progress {
public:
    ProgressRange(Progress* inner, double from, double to) : inner_(inner), from_(from), to_(to) {}
    void report(std::string_view stage, double fraction) override {
        const double f = fraction < 0.0 ? 0.0 : fraction > 1.0 ? 1.0 : fraction;
        if (inner_) inner_->report(stage, from_ + f * (to_ - from_));
    }
    bool cancelled() const override { return inner_ && inner_->cancelled(); }
    void watch_child(int pid) const override {
        if (inner_) inner_->watch_child(pid);
    }

private:
    Progress* inner_;
    double from_, to_;
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
