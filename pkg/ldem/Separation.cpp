#include "ldem/Separation.hpp"

#include <numeric>
#include <stdexcept>

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

std::vector<std::uint8_t> intactBars(const BarState& bars) {
    std::vector<std::uint8_t> intact(bars.kappa.size());
#pragma omp parallel for schedule(static)
    for (std::int64_t b = 0; b < std::int64_t(intact.size()); ++b) intact[b] = bars.kappa[b] < bars.epsR[b];
    return intact;
}

bool nodesJoined(const Lattice& lat, const std::vector<std::uint8_t>& intact, const std::vector<std::int32_t>& a,
                 const std::vector<std::int32_t>& b) {
    if (std::int64_t(intact.size()) != lat.numBars())
        throw std::invalid_argument("nodesJoined: one flag per bar expected");
    DisjointSets sets(lat.numNodes());
    for (const BarRow& row : lat.barRows)
        for (int p = 0; p < row.count; ++p)
            if (intact[row.first + p]) sets.unite(row.nodeA + p, row.nodeB + p);
    std::vector<std::uint8_t> reached(lat.numNodes(), 0);
    for (auto n : a) reached[sets.find(n)] = 1;
    for (auto n : b)
        if (reached[sets.find(n)]) return true;
    return false;
}

}  // namespace ldem
