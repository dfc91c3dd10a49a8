#include "ldem/LayerSweep.hpp"

namespace ldem {

void BarForceBuffers::prepare(const Lattice& lat, int threads) {
    if (threads == threads_ && base_.size() == std::size_t(lat.numLayers())) return;
    threads_ = threads;
    stride_ = std::size_t(lat.maxBarsInLayer);
    // Buffer index of every layer: own ones at the ends of each range, a ring of three inside.
    std::vector<int> buffer(lat.numLayers(), 0);
    int count = 0;
    for (int t = 0; t < threads; ++t) {
        const auto [m0, m1] = layerRange(lat.forceLayers(), t, threads);
        const int ring = count;
        if (m1 - m0 > 4) count += 3;
        for (int m = m0; m < m1; ++m)
            buffer[m] = (m < m0 + 2 || m >= m1 - 2) ? count++ : ring + (m - m0) % 3;
    }
    storage_.assign(std::size_t(count) * 3 * stride_, 0.0);
    base_.resize(lat.numLayers());
    for (int m = 0; m < lat.numLayers(); ++m) base_[m] = storage_.data() + std::size_t(buffer[m]) * 3 * stride_;
}

}  // namespace ldem
