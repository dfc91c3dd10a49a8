// The layer-by-layer sweep that the force pass and the predicted dashpots'
// pass share (InternalForces.hpp): a bar stage per bar layer, then a node
// stage per node layer once the bar layers it reads (m-2 .. m) are done. Each
// thread takes a range of layers; the two lowest node layers of a range read
// bars of the range below and wait for one barrier. A node sums its bars in a
// fixed order, so no result depends on the thread count.
#pragma once
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "ldem/Lattice.hpp"
#include "ldem/Parallel.hpp"

namespace ldem {

// Layers [first, second) of thread t out of T.
inline std::pair<int, int> layerRange(int layers, int t, int T) {
    return {int(std::int64_t(layers) * t / T), int(std::int64_t(layers) * (t + 1) / T)};
}

// A vector per bar (its force on its A node) for the bar layers in use. Bar
// layer m is needed until node layer m + 2 is summed, so each thread cycles its
// layers through three buffers; the two lowest and two highest layers of its
// range keep their own, because the neighbouring range reads them after the barrier.
class BarForceBuffers {
public:
    // Assigns buffers to layers for `threads` threads (no-op if unchanged).
    void prepare(const Lattice& lat, int threads);
    double* x(int m) const { return base_[m]; }
    double* y(int m) const { return base_[m] + stride_; }
    double* z(int m) const { return base_[m] + 2 * stride_; }

private:
    int threads_ = 0;
    std::size_t stride_ = 0;
    std::vector<double> storage_;
    std::vector<double*> base_;  // per layer
};

// bar(m) for every bar layer, node(m) once bar layers m-2 .. m are done, inside one
// parallel region (g prepared for its threads): node(m) may move node layer m, as no
// bar stage still to come reads it.
template <class BarStage, class NodeStage>
void layerSweep(const Lattice& lat, BarForceBuffers& g, BarStage bar, NodeStage node) {
#pragma omp parallel
    {
#pragma omp single
        g.prepare(lat, threadCount());
        const auto [m0, m1] = layerRange(lat.forceLayers(), threadIndex(), threadCount());
        for (int m = m0; m < m1; ++m) {
            bar(m);
            if (m0 == 0 || m >= m0 + 2) node(m);
        }
#pragma omp barrier
        if (m0 > 0)
            for (int m = m0; m < std::min(m0 + 2, m1); ++m) node(m);
    }
}

}  // namespace ldem
