#include <strata/core/parallel.h>

#include <strata/core/error.h>

#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace strata {

int thread_count(int requested) {
    if (requested > 0) return requested;
#ifdef _OPENMP
    return omp_get_max_threads();
#else
    return 1;
#endif
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
