// Team sizes (parallel.h): the count asked, OpenMP's default, and one thread for small loops.
#include <strata/core/error.h>
#include <strata/core/parallel.h>

#include <gtest/gtest.h>

#include <string>

namespace strata {
namespace {

TEST(ThreadCount, AskedOrOpenMPsDefault) {
    EXPECT_EQ(thread_count(3), 3);
    EXPECT_GE(thread_count(0), 1);
}

TEST(ThreadCount, ANegativeCountIsAnInputErrorNamingTheParameter) {
    EXPECT_NO_THROW(check_threads(0, "LayerParams::threads"));
    EXPECT_NO_THROW(check_threads(4, "LayerParams::threads"));
    try {
        check_threads(-1, "LayerParams::threads");
        ADD_FAILURE() << "no exception";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), "LayerParams::threads is -1: give 0 (all cores) or a positive count");
    }
}

TEST(ThreadCount, SmallLoopsRunOnOneThread) {
    // A loop of a few items costs less than a team's start and barrier (and far more on a machine
    // running more threads than it has cores): one thread below kParallelItems, the count above.
    EXPECT_EQ(thread_count(2, 14), 1);
    EXPECT_EQ(thread_count(2, kParallelItems - 1), 1);
    EXPECT_EQ(thread_count(2, kParallelItems), 2);
    EXPECT_EQ(thread_count(0, 1'000'000), thread_count(0));
}

}  // namespace
}  // namespace strata
