// Slabs (Slab.hpp, Lattice.hpp buildSlab): the pieces a lattice is split into
// over MPI ranks. Whatever the split, the bars the ranks own, taken in rank
// order, are the whole lattice's bars in its order (their global ends, shares,
// stiffness, fracture area, G_f), and every owned node has the whole
// lattice's mass and position: the run of the split lattice can then only
// differ from the whole one by its sums, which Slab.hpp adds by layer.
// Checked here without MPI, by building every rank's slab in one process.
#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "ldem/Lattice.hpp"
#include "ldem/RandomField.hpp"
#include "ldem/Slab.hpp"

using namespace ldem;

namespace {

using Bar = std::tuple<std::int64_t, std::int64_t, int, double, double, double, double>;

// Bars [first, end) of lat: global ends, family, share, EA, Af, G_f.
std::vector<Bar> barsOf(const Lattice& lat, const Material& m, std::int64_t first, std::int64_t end) {
    const BarTable t = listBars(lat);
    const std::vector<double> gf = fractureEnergyField(lat, m, 11);
    std::vector<Bar> out;
    for (std::int64_t b = first; b < end; ++b)
        out.emplace_back(lat.globalNode(t.n1[b]), lat.globalNode(t.n2[b]), t.family[b], t.share[b], t.EA[b], t.Af[b],
                         gf[b]);
    return out;
}

// A 3 x 2 x 5 box without two modules (a notch at the bottom, a hole higher up).
std::vector<std::uint8_t> notchedMask() {
    std::vector<std::uint8_t> mask(3 * 2 * 5, 1);
    mask[1 + 3 * (0 + 2 * 0)] = 0;
    mask[2 + 3 * (1 + 2 * 3)] = 0;
    return mask;
}

void expectSplitIsWhole(const Material& m, const std::vector<std::uint8_t>& mask) {
    const int nx = 3, ny = 2, nz = 5;
    const Lattice whole = buildLattice(nx, ny, nz, 0.02, m, mask);
    const std::vector<Bar> all = barsOf(whole, m, 0, whole.numBars());
    for (int ranks = 1; ranks <= nz; ++ranks) {
        std::vector<Bar> joined;
        std::int64_t ownedNodes = 0;
        for (int r = 0; r < ranks; ++r) {
            const auto [k0, k1] = slabLayers(nz, r, ranks);
            const Lattice slab = buildSlab(nx, ny, nz, 0.02, m, mask, k0, k1);
            EXPECT_EQ(slab.isSlab(), ranks > 1);
            const auto [first, end] = slab.ownedBars();
            const std::vector<Bar> mine = barsOf(slab, m, first, end);
            joined.insert(joined.end(), mine.begin(), mine.end());
            for (int layer = slab.ownBegin; layer < slab.ownEnd; ++layer) {
                const auto [n0, count] = slab.layerNodes(layer);
                for (std::int32_t n = n0; n < n0 + count; ++n, ++ownedNodes) {
                    const std::int64_t g = slab.globalNode(n);
                    ASSERT_EQ(slab.localNode(g), n);
                    EXPECT_EQ(slab.mass[n], whole.mass[g]) << ranks << " ranks, rank " << r << ", node " << g;
                    EXPECT_EQ(slab.position(n), whole.position(std::int32_t(g)));
                }
            }
        }
        EXPECT_EQ(ownedNodes, whole.numNodes()) << ranks << " ranks";
        ASSERT_EQ(joined.size(), all.size()) << ranks << " ranks";
        EXPECT_TRUE(joined == all) << ranks << " ranks: the owned bars are not the whole lattice's";
    }
}

}  // namespace

TEST(Slab, OwnedBarsOfAnySplitAreTheWholeLatticesBars) {
    Material m;
    m.GfCV = 0.4;
    expectSplitIsWhole(m, {});
    expectSplitIsWhole(m, notchedMask());
}

TEST(Slab, ACorrelatedFieldIsAFunctionOfSpaceNotOfTheRank) {
    Material m;
    m.GfCV = 0.4, m.corrLength = 0.03;
    expectSplitIsWhole(m, notchedMask());
}

TEST(Slab, LayersTileTheLatticeAndRanksAreAtMostLayers) {
    for (int ranks = 1; ranks <= 7; ++ranks) {
        int next = 0;
        for (int r = 0; r < ranks; ++r) {
            const auto [k0, k1] = slabLayers(7, r, ranks);
            EXPECT_EQ(k0, next);
            EXPECT_GE(k1 - k0, 1);
            next = k1;
        }
        EXPECT_EQ(next, 7);
    }
    EXPECT_THROW(slabLayers(3, 0, 4), std::invalid_argument);
    const Material m;
    EXPECT_THROW(buildSlab(2, 2, 3, 0.02, m, {}, 2, 2), std::invalid_argument);
}
