#include "ldem/Slab.hpp"

namespace ldem {

namespace {
// x, y, z of the nodes of layers [m, m + 2), packed, and back.
std::vector<double> packLayers(const Lattice& lat, int m, const Field3& x) {
    std::vector<double> buf;
    for (int l = m; l < m + 2; ++l) {
        const auto [first, count] = lat.layerNodes(l);
        for (const auto* c : {&x.x, &x.y, &x.z}) buf.insert(buf.end(), c->begin() + first, c->begin() + first + count);
    }
    return buf;
}

void unpackLayers(const Lattice& lat, int m, const std::vector<double>& buf, Field3& x) {
    std::size_t at = 0;
    for (int l = m; l < m + 2; ++l) {
        const auto [first, count] = lat.layerNodes(l);
        for (auto* c : {&x.x, &x.y, &x.z}) {
            std::copy(buf.begin() + at, buf.begin() + at + count, c->begin() + first);
            at += count;
        }
    }
}

std::size_t layersSize(const Lattice& lat, int m) {
    return 3 * std::size_t(lat.layerNodes(m).second + lat.layerNodes(m + 1).second);
}
}  // namespace

void exchangeHalo(const Lattice& lat, Field3& x) {
    const Comm& comm = commOf(lat);
    if (comm.size() == 1) return;
    const bool below = comm.rank() > 0, above = comm.rank() + 1 < comm.size();
    // My two lowest owned layers are the upper halo of the rank below; my two
    // highest, the lower halo of the rank above.
    std::vector<double> fromBelow(below ? layersSize(lat, lat.ownBegin - 2) : 0);
    std::vector<double> fromAbove(above ? layersSize(lat, lat.ownEnd) : 0);
    comm.exchangeWithNeighbours(below ? packLayers(lat, lat.ownBegin, x) : std::vector<double>{},
                                above ? packLayers(lat, lat.ownEnd - 2, x) : std::vector<double>{}, fromBelow,
                                fromAbove);
    if (below) unpackLayers(lat, lat.ownBegin - 2, fromBelow, x);
    if (above) unpackLayers(lat, lat.ownEnd, fromAbove, x);
}

std::vector<double> gatherLayerSums(const Comm& comm, const std::vector<double>& ownedPartials, int K) {
    const std::vector<double> all = comm.allGather(ownedPartials);  // every layer's, in global layer order
    std::vector<double> total(K, 0.0);
    for (std::size_t i = 0; i < all.size(); ++i) total[i % K] += all[i];
    return total;
}

}  // namespace ldem
