// A forked child (child_process.h): what it sends, how it ends, and an OpenMP team in the
// child after the parent had one.
#include <strata/core/child_process.h>

#include <gtest/gtest.h>

#include <chrono>
#include <ctime>

#include <unistd.h>

#include <csignal>
#include <stdexcept>
#include <string>
#include <vector>

namespace strata {
namespace {

std::string text(const std::vector<char>& bytes) {
    return std::string(bytes.begin(), bytes.end());
}

TEST(ChildProcess, SendsWhatItsBodyPuts) {
    const ChildResult r = run_in_child([](std::vector<char>& out) { out = {'o', 'k', '\0', 'x'}; });
    ASSERT_TRUE(r.forked);
    EXPECT_EQ(r.signal, 0);
    EXPECT_EQ(r.exit_status, 0);
    EXPECT_EQ(r.sent, (std::vector<char>{'o', 'k', '\0', 'x'}));
}

TEST(ChildProcess, LargeResultsArriveWhole) {
    // Larger than a pipe's buffer and the parent's read chunk.
    const ChildResult r = run_in_child([](std::vector<char>& out) {
        out.resize(3'000'000);
        for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<char>(i % 251);
    });
    ASSERT_TRUE(r.forked);
    ASSERT_EQ(r.sent.size(), 3'000'000u);
    for (std::size_t i = 0; i < r.sent.size(); i += 99'991) EXPECT_EQ(r.sent[i], static_cast<char>(i % 251));
}

TEST(ChildProcess, ItsChangesStayInTheChild) {
    int value = 1;
    const ChildResult r = run_in_child([&](std::vector<char>&) { value = 2; });
    ASSERT_TRUE(r.forked);
    EXPECT_EQ(value, 1);
}

TEST(ChildProcess, ACrashIsItsSignal) {
    const ChildResult r = run_in_child([](std::vector<char>& out) {
        out = {'x'};
        std::raise(SIGSEGV);
    });
    ASSERT_TRUE(r.forked);
    EXPECT_EQ(r.signal, SIGSEGV);
    EXPECT_TRUE(r.sent.empty());
}

TEST(ChildProcess, AnExceptionIsExitStatusOneAndNothingSent) {
    const ChildResult r = run_in_child([](std::vector<char>& out) {
        out = {'x'};
        throw std::runtime_error("no");
    });
    ASSERT_TRUE(r.forked);
    EXPECT_EQ(r.signal, 0);
    EXPECT_EQ(r.exit_status, 1);
    EXPECT_TRUE(r.sent.empty());
}

TEST(ChildProcess, ChildExitSendsFromAnywhere) {
    // As from a terminate handler deep inside a library: the body never returns.
    const ChildResult r = run_in_child([](std::vector<char>& out) {
        out = {'n', 'o'};
        child_exit({'y', 'e', 's'}, 3);
        out = {'n', 'e', 'v', 'e', 'r'};
    });
    ASSERT_TRUE(r.forked);
    EXPECT_EQ(r.exit_status, 3);
    EXPECT_EQ(text(r.sent), "yes");
    child_exit({'z'}, 4);  // outside a child: nothing happens
    SUCCEED();
}

TEST(ChildProcess, ACancelledRunKillsTheChild) {
    struct Stop : Progress {
        void report(std::string_view, double) override {}
        bool cancelled() const override { return true; }
    } stop;
    EXPECT_THROW(run_in_child([](std::vector<char>&) { ::pause(); }, &stop), Cancelled);
}

TEST(ChildProcess, ADeadlineKillsAChildThatRunsOn) {
    // DeadlineProgress: past its seconds it asks to stop, and says that it was the deadline
    // (remeshing's trial of Gmsh's classification, which can split a surface for ever); a stop
    // asked by the Progress it wraps is not one.
    const auto t0 = std::chrono::steady_clock::now();
    DeadlineProgress deadline(0.3);
    EXPECT_THROW(run_in_child(
                     [](std::vector<char>&) {
                         for (volatile unsigned long i = 0;; i = i + 1) {
                         }
                     },
                     &deadline),
                 Cancelled);
    EXPECT_TRUE(deadline.expired());
    EXPECT_GE(deadline.spent(), 0.3);  // the child's CPU seconds, not before its time
    const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_GE(waited, 0.3);
    struct Stop : Progress {
        void report(std::string_view, double) override {}
        bool cancelled() const override { return true; }
    } stop;
    DeadlineProgress later(100.0, &stop);
    EXPECT_THROW(run_in_child([](std::vector<char>&) { ::pause(); }, &later), Cancelled);
    EXPECT_FALSE(later.expired());
    DeadlineProgress ample(100.0);
    EXPECT_TRUE(run_in_child([](std::vector<char>& out) { out = {'o', 'k'}; }, &ample).forked);
    EXPECT_FALSE(ample.expired());
}

TEST(ChildProcess, ADeadlineCountsTheChildsWorkNotTheClock) {
    // A child that waits (for a CPU other jobs hold, here asleep) has not used its seconds: on a
    // loaded machine the work gets the same budget as on an idle one, so an attempt's outcome
    // (remeshing's, which picks the mesh) does not depend on the load. With the clock's seconds
    // this child would be killed after 0.2 of its 0.6.
    DeadlineProgress deadline(0.2);
    const ChildResult r = run_in_child(
        [](std::vector<char>& out) {
            ::usleep(600000);
            out = {'o', 'k'};
        },
        &deadline);
    EXPECT_FALSE(deadline.expired());
    EXPECT_EQ(r.sent, (std::vector<char>{'o', 'k'}));
    EXPECT_LT(deadline.spent(), 0.2);
    // The children given in turn share the budget (Blossom's attempt, then the simple
    // recombination's): after one that used 0.15 of 0.3, the next is stopped with less than 0.3.
    DeadlineProgress shared(0.3);
    run_in_child(
        [](std::vector<char>& out) {
            while (std::clock() < CLOCKS_PER_SEC * 15 / 100) {
            }
            out = {'a'};
        },
        &shared);
    const double first = shared.spent();
    EXPECT_GE(first, 0.15);
    EXPECT_FALSE(shared.expired());
    EXPECT_THROW(run_in_child(
                     [](std::vector<char>&) {
                         for (;;) {
                             while (std::clock() < 0) {
                             }
                         }
                     },
                     &shared),
                 Cancelled);
    EXPECT_TRUE(shared.expired());
    EXPECT_GE(shared.spent(), 0.3);
    EXPECT_LT(shared.spent() - first, 0.3);
    // One that never computes (a deadlock) is stopped after DeadlineProgress::kWallFactor times
    // the seconds on the clock: it must not hang the run.
    const auto t0 = std::chrono::steady_clock::now();
    DeadlineProgress idle(0.1);
    EXPECT_THROW(run_in_child([](std::vector<char>&) { ::pause(); }, &idle), Cancelled);
    EXPECT_TRUE(idle.expired());
    const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_GE(waited, DeadlineProgress::kWallFactor * 0.1);
}

#ifdef _OPENMP
TEST(ChildProcess, OpenMPInTheChildAfterTheParentsTeam) {
    // Without freeing the parent's workers first, the child's team waits for ever on workers
    // fork did not copy (GCC's libgomp); the test would then hang until ctest's timeout.
    long parent = 0;
#pragma omp parallel for reduction(+ : parent) num_threads(2)
    for (int i = 0; i < 1000; ++i) parent += i;
    ChildOptions options;
    options.free_openmp_threads = true;
    const ChildResult r = run_in_child(
        [](std::vector<char>& out) {
            long sum = 0;
#pragma omp parallel for reduction(+ : sum) num_threads(2)
            for (int i = 0; i < 1000; ++i) sum += i;
            const std::string s = std::to_string(sum);
            out.assign(s.begin(), s.end());
        },
        nullptr, options);
    ASSERT_TRUE(r.forked);
    EXPECT_EQ(text(r.sent), "499500");
    long again = 0;  // the parent's next team is made anew
#pragma omp parallel for reduction(+ : again) num_threads(2)
    for (int i = 0; i < 1000; ++i) again += i;
    EXPECT_EQ(parent, 499500);
    EXPECT_EQ(again, 499500);
}
#endif

}  // namespace
}  // namespace strata
