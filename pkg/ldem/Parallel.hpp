// OpenMP helpers. Sums over the lattice are not here: Slab.hpp adds them
// layer by layer, the same bits for any number of threads and MPI ranks.
#pragma once
#include <algorithm>
#include <cstdlib>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace ldem {

// The threads a run asks for when it names none (threads <= 0): OMP_NUM_THREADS
// if it is set to a positive count (its first entry: "4,2" is per nesting
// level), as users of OpenMP programs expect; else all the machine's cores.
inline int defaultThreads() {
#ifdef _OPENMP
    const char* env = std::getenv("OMP_NUM_THREADS");
    char* end = nullptr;
    const long n = env ? std::strtol(env, &end, 10) : 0;
    const bool counted = env && end != env && (*end == '\0' || *end == ',') && n > 0;
    return counted ? int(std::min<long>(n, omp_get_num_procs())) : omp_get_num_procs();
#else
    return 1;
#endif
}

// threads <= 0: defaultThreads() (not whatever an earlier run set); more
// threads than cores are clamped to the cores (oversubscribed OpenMP threads
// wait at every barrier for one another: a run 100 times slower).
inline void setThreads(int threads) {
#ifdef _OPENMP
    omp_set_num_threads(threads > 0 ? std::min(threads, omp_get_num_procs()) : defaultThreads());
#else
    (void)threads;
#endif
}

inline int threadIndex() {
#ifdef _OPENMP
    return omp_get_thread_num();
#else
    return 0;
#endif
}

inline int threadCount() {
#ifdef _OPENMP
    return omp_get_num_threads();
#else
    return 1;
#endif
}

inline int maxThreads() {
#ifdef _OPENMP
    return omp_get_max_threads();
#else
    return 1;
#endif
}

}  // namespace ldem
