// Deterministic parallel reductions: the range is cut into fixed blocks whose
// partial sums are added in block order, so a sum is bit-identical whatever
// the number of OpenMP threads (no floating-point atomics, no thread-order sums).
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace ldem {

constexpr std::int64_t kReductionBlock = 4096;

// Returns sum over i in [0, n) of the K quantities that add(i, acc) adds to acc.
template <int K, class Add>
std::array<double, K> blockSum(std::int64_t n, Add add) {
    const std::int64_t nblocks = (n + kReductionBlock - 1) / kReductionBlock;
    std::vector<std::array<double, K>> partial(nblocks);
#pragma omp parallel for schedule(static)
    for (std::int64_t blk = 0; blk < nblocks; ++blk) {
        std::array<double, K> acc{};
        const std::int64_t end = std::min(n, (blk + 1) * kReductionBlock);
        for (std::int64_t i = blk * kReductionBlock; i < end; ++i) add(i, acc);
        partial[blk] = acc;
    }
    std::array<double, K> total{};
    for (const auto& p : partial)
        for (int k = 0; k < K; ++k) total[k] += p[k];
    return total;
}

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
