#include "ldem/Separation.hpp"

#include <numeric>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

#include "ldem/Slab.hpp"

namespace ldem {

namespace {
// Disjoint sets of nodes with path halving and union by size.
class DisjointSets {
public:
    explicit DisjointSets(std::int64_t n) : parent_(n), size_(n, 1) { std::iota(parent_.begin(), parent_.end(), 0); }
    std::int32_t find(std::int32_t i) {
        while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
        return i;
    }
    void unite(std::int32_t a, std::int32_t b) {
        a = find(a), b = find(b);
        if (a == b) return;
        if (size_[a] < size_[b]) std::swap(a, b);
        parent_[b] = a, size_[a] += size_[b];
    }

private:
    std::vector<std::int32_t> parent_, size_;
};
}  // namespace

namespace {
// Rank 0's half of nodesJoined on a lattice split over ranks: each rank sent
// (count, pairs (node, its root), count, roots of a's nodes, count, roots of
// b's nodes), global node ids, in rank order. Two nodes with a common root on
// some rank are joined; a and b are joined if a root of a's and one of b's meet.
bool joinedAcrossRanks(const std::vector<std::int64_t>& msg) {
    std::unordered_map<std::int64_t, std::int64_t> parent;
    auto find = [&](std::int64_t i) {  // the root of i, with the path to it made direct
        std::int64_t root = i;
        while (parent.try_emplace(root, root).first->second != root) root = parent[root];
        while (i != root) {
            const std::int64_t next = parent[i];
            parent[i] = root, i = next;
        }
        return root;
    };
    std::vector<std::int64_t> rootsA, rootsB;
    for (std::size_t at = 0; at < msg.size();) {
        const std::int64_t pairs = msg[at++];
        for (std::int64_t k = 0; k < pairs; ++k, at += 2) {
            const std::int64_t x = find(msg[at]), y = find(msg[at + 1]);
            if (x != y) parent[x] = y;
        }
        for (auto* roots : {&rootsA, &rootsB}) {
            const std::int64_t count = msg[at++];
            roots->insert(roots->end(), msg.begin() + at, msg.begin() + at + count);
            at += count;
        }
    }
    std::unordered_set<std::int64_t> reached;
    for (auto r : rootsA) reached.insert(find(r));
    for (auto r : rootsB)
        if (reached.count(find(r))) return true;
    return false;
}
}  // namespace

bool nodesJoined(const Lattice& lat, const std::vector<std::uint8_t>& intact, const std::vector<std::int32_t>& a,
                 const std::vector<std::int32_t>& b) {
    if (std::int64_t(intact.size()) != lat.numBars())
        throw std::invalid_argument("nodesJoined: one flag per bar expected");
    DisjointSets sets(lat.numNodes());
    for (std::int32_t r = lat.barLayerStart[lat.ownBegin]; r < lat.barLayerStart[lat.ownEnd]; ++r) {
        const BarRow& row = lat.barRows[r];  // the owned bars: each bar counts on one rank
        for (int p = 0; p < row.count; ++p)
            if (intact[row.first + p]) sets.unite(row.nodeA + p, row.nodeB + p);
    }
    const Comm& comm = commOf(lat);
    if (comm.size() == 1) {
        std::vector<std::uint8_t> reached(lat.numNodes(), 0);
        for (auto n : a) reached[sets.find(n)] = 1;
        for (auto n : b)
            if (reached[sets.find(n)]) return true;
        return false;
    }
    // Split over ranks: the nodes my bars share with the neighbours' (my two
    // lowest owned layers, reached by the bars below; the two halo layers
    // above, reached by mine), and the roots of the owned nodes of a and b.
    std::vector<std::int64_t> msg{0};
    for (int m : {lat.ownBegin, lat.ownBegin + 1, lat.ownEnd, lat.ownEnd + 1}) {
        if ((m < lat.ownEnd && comm.rank() == 0) || m >= lat.numLayers()) continue;
        const auto [first, count] = lat.layerNodes(m);
        for (std::int32_t n = first; n < first + count; ++n)
            msg.push_back(lat.globalNode(n)), msg.push_back(lat.globalNode(sets.find(n)));
    }
    msg[0] = std::int64_t(msg.size() - 1) / 2;
    for (const auto* group : {&a, &b}) {
        const std::size_t at = msg.size();
        msg.push_back(0);
        for (auto n : *group)
            if (lat.owns(lat.layerOfNode(n))) msg.push_back(lat.globalNode(sets.find(n)));
        msg[at] = std::int64_t(msg.size() - at - 1);
    }
    const std::vector<std::int64_t> all = comm.gather(msg);
    return comm.broadcast(comm.root() && joinedAcrossRanks(all));
}

}  // namespace ldem
