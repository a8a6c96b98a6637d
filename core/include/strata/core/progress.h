#pragma once
/// \file
/// The one small interface through which long stages report progress and learn of
/// cancellation. Library users pass nothing (a null pointer); the CLI draws a bar.

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

}  // namespace strata
