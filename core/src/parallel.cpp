#include <strata/core/parallel.h>

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

int thread_count(int requested, long long items) {
    return items < kParallelItems ? 1 : thread_count(requested);
}

}  // namespace strata
