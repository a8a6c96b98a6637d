// Team sizes (parallel.h): the count asked, all cores, and one thread for small loops.
#include <strata/core/error.h>
#include <strata/core/parallel.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace strata {
namespace {

TEST(ThreadCount, AskedOrAllCores) {
    EXPECT_EQ(thread_count(3), 3);
    EXPECT_GE(thread_count(0), 1);
}

// Gmsh's initialisation sets OpenMP's default to its General.NumThreads (1) for the whole
// process: "all cores" stays all cores after it (the layer stage ran on one core of two after
// Gmsh meshed the surface).
TEST(ThreadCount, AllCoresWhateverAnotherLibrarySetsAsOpenMPsDefault) {
#ifdef _OPENMP
    const int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    const char* given = std::getenv("OMP_NUM_THREADS");
    if (given == nullptr || std::atoi(given) <= 0)
        EXPECT_EQ(thread_count(0), omp_get_num_procs());
    else
        EXPECT_EQ(thread_count(0), std::atoi(given));
    omp_set_num_threads(saved);
#else
    EXPECT_EQ(thread_count(0), 1);
#endif
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
