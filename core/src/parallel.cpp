#include <strata/core/parallel.h>

#include <strata/core/error.h>

#include <algorithm>
#include <cstdlib>
#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace strata {

int thread_count(int requested) {
    if (requested > 0) return requested;
    // Not omp_get_max_threads(): Gmsh's initialisation sets it to its General.NumThreads (1 by
    // default) for the whole process, so after the surface stage "all cores" was one core (the
    // airliner stand-in's layer stage: 57.5 s by default against 32.6 s with --threads 2).
    static const int all = [] {
        if (const char* given = std::getenv("OMP_NUM_THREADS"); given != nullptr && std::atoi(given) > 0)
            return std::atoi(given);
#ifdef _OPENMP
        return std::max(omp_get_num_procs(), 1);
#else
        return 1;
#endif
    }();
    return all;
}

void check_threads(int threads, const char* parameter) {
    if (threads < 0)
        throw InputError(std::string(parameter) + " is " + std::to_string(threads) +
                         ": give 0 (all cores) or a positive count");
}

int thread_count(int requested, long long items) {
    return items < kParallelItems ? 1 : thread_count(requested);
}

}  // namespace strata
