#include <strata/core/progress.h>

#include <time.h>

namespace strata {

namespace {

/// The CPU seconds process \p pid has used, or a negative number where they cannot be read (the
/// process has ended and been reaped).
double process_cpu_seconds(int pid) {
    clockid_t clock;
    if (::clock_getcpuclockid(static_cast<pid_t>(pid), &clock) != 0) return -1.0;
    timespec t{};
    if (::clock_gettime(clock, &t) != 0) return -1.0;
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

DeadlineProgress::DeadlineProgress(double seconds, const Progress* inner)
    : inner_(inner), seconds_(seconds), start_(std::chrono::steady_clock::now()) {}

void DeadlineProgress::watch_child(int pid) const {
    if (child_ != 0) children_done_ += child_last_;
    child_ = pid;
    child_last_ = 0.0;
}

double DeadlineProgress::spent() const {
    if (child_ == 0) return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double now = process_cpu_seconds(child_);
    if (now >= child_last_) child_last_ = now;  // an ended child keeps its last reading
    return children_done_ + child_last_;
}

bool DeadlineProgress::cancelled() const {
    if (inner_ && inner_->cancelled()) return true;
    if (expired_) return true;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (spent() >= seconds_ || wall >= kWallFactor * seconds_) expired_ = true;
    return expired_;
}

}  // namespace strata
