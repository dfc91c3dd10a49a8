// OpenMP helpers. Sums over the lattice are not here: Slab.hpp adds them
// layer by layer, the same bits for any number of threads and MPI ranks.
#pragma once
#include <algorithm>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace ldem {

// threads <= 0: all the machine's cores (not whatever an earlier run set);
// more threads than cores are clamped to the cores (oversubscribed OpenMP
// threads wait at every barrier for one another: a run 100 times slower).
inline void setThreads(int threads) {
#ifdef _OPENMP
    omp_set_num_threads(threads > 0 ? std::min(threads, omp_get_num_procs()) : omp_get_num_procs());
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
