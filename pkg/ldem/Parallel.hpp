// OpenMP helpers. Sums over the lattice are not here: Slab.hpp adds them
// layer by layer, the same bits for any number of threads and MPI ranks.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace ldem {

// Bars per thread of the default count: below 2 x kBarsPerThread bars a run
// takes one thread. A second thread halves the work of a step but costs its
// three synchronisations (the parallel region, the ring of buffers, the join:
// InternalForces.hpp), each a futex wake-up under the passive wait; measured
// on 2 cores (README, Performance: threads), 2 threads gained nothing up to
// 12^3 modules (24,660 bars) and 1.3 times at 24^3 (195,336 bars).
inline constexpr std::int64_t kBarsPerThread = 50000;

// The default thread count (threads = 0), a pure function: one per
// kBarsPerThread bars of the lattice, at most the cores free to this process
// (freeCores: the cores it may run on less those others keep busy, shared by
// the processes of an MPI run on the machine), at least one.
inline int defaultThreadCount(std::int64_t bars, double freeCores, int processes) {
    const std::int64_t lattice = bars / kBarsPerThread;
    const std::int64_t cores = std::int64_t(std::floor(freeCores / std::max(1, processes) + 0.5));
    return int(std::max<std::int64_t>(1, std::min(lattice, cores)));
}

// The cores this process may run on (sched_getaffinity, and a cgroup's CPU
// quota), and of those the ones idle: /proc/stat sampled over 0.1 s, the
// allowed cores only (the 1-minute load average lags: a job started seconds
// before is not in it, one ended seconds before still is).
int allowedCores();
double idleCores(double seconds = 0.1);

// OMP_NUM_THREADS if it is set to a positive count (its first entry: "4,2" is
// per nesting level), as users of OpenMP programs expect; else 0.
int environmentThreads();

// The threads a run of `bars` bars uses: `requested` if positive (at most the
// allowed cores: oversubscribed OpenMP threads wait at every barrier for one
// another, a run 100 times slower), else OMP_NUM_THREADS, else
// defaultThreadCount (the machine is sampled only for a lattice large enough
// for two threads).
int threadsFor(int requested, std::int64_t bars, int processes);

inline void setThreads(int threads) {
#ifdef _OPENMP
    omp_set_num_threads(std::max(1, threads));
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
