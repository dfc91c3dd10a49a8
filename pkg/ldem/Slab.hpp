// One lattice over several processes (MPI): slabs of module layers along z.
//
// Rank r of P owns module layers [k0, k1) = [nz r / P, nz (r + 1) / P) and
// holds one halo module layer on each side (Lattice.hpp, buildSlab). The
// time step's layered pass (InternalForces.hpp) needs, for the nodes of
// layers [a, b), the bars of layers a - 2 .. b - 1, which reach node layers up
// to b + 1: two node layers (one module layer) of halo each way, sent by the
// neighbour after every step (exchangeHalo). A bar of the two layers below a
// slab is computed by both ranks, with the same inputs and arithmetic.
//
// Bit-identical for any P: every sum over the lattice is a sum of per-layer
// partial sums (each layer summed in one fixed order by one thread), added
// in global layer order on every rank (layerSum); the random field is a
// function of the bar's global nodes and position (RandomField.hpp).
#pragma once
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "ldem/Comm.hpp"
#include "ldem/Field3.hpp"
#include "ldem/Lattice.hpp"

namespace ldem {

// Module layers [k0, k1) of rank `rank` out of `ranks`; throws std::invalid_argument
// when there are more ranks than module layers.
inline std::pair<int, int> slabLayers(int nz, int rank, int ranks) {
    if (ranks > nz)
        throw std::invalid_argument(std::to_string(ranks) + " MPI ranks for " + std::to_string(nz) +
                                    " module layers: at most one rank per module layer along z");
    return {int(std::int64_t(nz) * rank / ranks), int(std::int64_t(nz) * (rank + 1) / ranks)};
}

// This rank's module layers of nz (all of them without mpirun).
inline std::pair<int, int> worldSlab(int nz) { return slabLayers(nz, Comm::world().rank(), Comm::world().size()); }

// The ranks a lattice is split over: the world for a slab, this process alone otherwise.
inline const Comm& commOf(const Lattice& lat) { return lat.isSlab() ? Comm::world() : Comm::self(); }

// Sends the two lowest owned node layers down and the two highest up, and
// receives the halo layers from the neighbours: x of every halo node is then
// its owner's (x: displacements, or a Lanczos vector).
void exchangeHalo(const Lattice& lat, Field3& x);

// The K per-layer partial sums of the owned layers (add(m, acc) adds layer m's
// to acc), gathered from every rank and added in global layer order: the
// same bits on every rank and for any number of ranks or threads.
std::vector<double> gatherLayerSums(const Comm& comm, const std::vector<double>& ownedPartials, int K);

template <int K, class AddLayer>
std::array<double, K> layerSum(const Lattice& lat, AddLayer add) {
    const int owned = lat.ownEnd - lat.ownBegin;
    std::vector<double> partial(std::size_t(owned) * K, 0.0);
#pragma omp parallel for schedule(dynamic)
    for (int i = 0; i < owned; ++i) {
        std::array<double, K> acc{};
        add(lat.ownBegin + i, acc);
        for (int k = 0; k < K; ++k) partial[std::size_t(i) * K + k] = acc[k];
    }
    const std::vector<double> total = gatherLayerSums(commOf(lat), partial, K);
    std::array<double, K> out{};
    for (int k = 0; k < K; ++k) out[k] = total[k];
    return out;
}

// The same over nodes: add(n, acc) for every node of the owned layers, in id order within a layer.
template <int K, class AddNode>
std::array<double, K> nodeSum(const Lattice& lat, AddNode add) {
    return layerSum<K>(lat, [&](int m, std::array<double, K>& acc) {
        const auto [first, count] = lat.layerNodes(m);
        for (std::int32_t n = first; n < first + count; ++n) add(n, acc);
    });
}

// The bars and the nodes of the whole lattice, each counted by the rank that owns it (bars first).
inline std::pair<std::int64_t, std::int64_t> wholeLatticeSize(const Lattice& lat) {
    const auto owned = lat.ownedBars();
    std::int64_t nodes = 0;
    for (int m = lat.ownBegin; m < lat.ownEnd; ++m) nodes += lat.layerNodes(m).second;
    return {commOf(lat).sum(owned.second - owned.first), commOf(lat).sum(nodes)};
}

// A node's owned layer less ownBegin (its slot in partial sums of K per owned layer), or -1.
inline int ownedSlot(const Lattice& lat, std::int32_t node) {
    const int m = lat.layerOfNode(node);
    return lat.owns(m) ? m - lat.ownBegin : -1;
}

// ownedSlot of each node, looked up once (the time step's sums).
inline std::vector<std::int32_t> ownedLayerSlots(const Lattice& lat, const std::vector<std::int32_t>& nodes) {
    std::vector<std::int32_t> slot(nodes.size());
    for (std::size_t k = 0; k < nodes.size(); ++k) slot[k] = ownedSlot(lat, nodes[k]);
    return slot;
}

// Adds value(k), for each k whose node is owned (layerSlot[k] >= 0), to slot
// `slot` of its layer's K partial sums (partial: K per owned layer), in k order.
template <class Value>
void addBySlot(std::vector<double>& partial, int K, int slot, const std::vector<std::int32_t>& layerSlot,
               Value value) {
    for (std::size_t k = 0; k < layerSlot.size(); ++k)
        if (layerSlot[k] >= 0) partial[std::size_t(layerSlot[k]) * K + slot] += value(k);
}

// The sum of value(k), k in [0, count), over all ranks, layer by layer (a
// group's reactions, a probe): each added on the rank that owns node(k).
template <class Node, class Value>
double listSum(const Lattice& lat, std::size_t count, Node node, Value value) {
    std::vector<double> partial(std::size_t(lat.ownEnd - lat.ownBegin), 0.0);
    for (std::size_t k = 0; k < count; ++k)
        if (const int s = ownedSlot(lat, node(k)); s >= 0) partial[std::size_t(s)] += value(k);
    return gatherLayerSums(commOf(lat), partial, 1)[0];
}

}  // namespace ldem
