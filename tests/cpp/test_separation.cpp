// The separation test (LDEM_SPEC section 6: the specimen is in two pieces
// when no chain of unbroken bars joins the upper face to the lower face), on
// hand-made cuts of small lattices whose answer is known from the picture.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "ldem/Lattice.hpp"
#include "ldem/laws/Hillerborg.hpp"
#include "ldem/Separation.hpp"

using namespace ldem;

namespace {
constexpr double kL0 = 0.02;

struct Specimen {
    Lattice lat;
    BarTable bars;
    std::vector<double> z;  // reference heights of the nodes
    std::vector<std::int32_t> top, bottom;
};

Specimen column(int nz) {
    Specimen s;
    s.lat = buildCubicLattice(1, 1, nz, kL0, Material{});
    s.bars = listBars(s.lat);
    s.z = nodePositions(s.lat)[2];
    for (std::int32_t n = 0; n < s.lat.numNodes(); ++n) {
        if (s.z[n] == 0) s.bottom.push_back(n);
        if (s.z[n] == nz * kL0) s.top.push_back(n);
    }
    return s;
}

// Breaks every bar with one end at or below `plane` and the other above it.
std::vector<std::uint8_t> cutAbove(const Specimen& s, double plane) {
    std::vector<std::uint8_t> intact(s.bars.n1.size(), 1);
    for (std::size_t b = 0; b < intact.size(); ++b) {
        const double za = s.z[s.bars.n1[b]], zb = s.z[s.bars.n2[b]];
        if (std::min(za, zb) <= plane + 1e-12 && std::max(za, zb) > plane + 1e-12) intact[b] = 0;
    }
    return intact;
}
}  // namespace

TEST(Separation, IntactLatticeIsJoined) {
    const Specimen s = column(2);
    EXPECT_TRUE(nodesJoined(s.lat, std::vector<std::uint8_t>(s.bars.n1.size(), 1), s.top, s.bottom));
}

TEST(Separation, FullCutSeparates) {
    const Specimen s = column(2);
    const auto intact = cutAbove(s, kL0);
    int cut = 0;
    for (auto f : intact) cut += !f;
    // Across the middle plane of a 1x1x2 column: the 4 vertical edges and the 4
    // lower diagonals of the upper module, and the centre-centre bar.
    EXPECT_EQ(cut, 9);
    EXPECT_FALSE(nodesJoined(s.lat, intact, s.top, s.bottom));
    EXPECT_FALSE(nodesJoined(s.lat, intact, s.bottom, s.top));  // symmetric
}

TEST(Separation, OneChainOfBarsKeepsItJoined) {
    const Specimen s = column(2);
    auto intact = cutAbove(s, kL0);
    // Restore one lower diagonal of the upper module: its centre node hangs on
    // it, and the centre's upper diagonals reach the top face.
    for (std::size_t b = 0; b < intact.size(); ++b)
        if (!intact[b] && s.z[s.bars.n1[b]] != s.z[s.bars.n2[b]] &&
            s.bars.L[b] < kL0) {  // a diagonal (length sqrt(3)/2 L0)
            intact[b] = 1;
            break;
        }
    EXPECT_TRUE(nodesJoined(s.lat, intact, s.top, s.bottom));
    // ...and breaking the centre's four upper diagonals separates it again.
    const std::int32_t centre = s.lat.centreId(0, 0, 1);
    for (std::size_t b = 0; b < intact.size(); ++b)
        if ((s.bars.n1[b] == centre || s.bars.n2[b] == centre) && s.z[s.bars.n1[b] == centre ? s.bars.n2[b] : s.bars.n1[b]] > 1.5 * kL0)
            intact[b] = 0;
    EXPECT_FALSE(nodesJoined(s.lat, intact, s.top, s.bottom));
}

TEST(Separation, BrokenMeansKappaReachedEpsR) {
    const Specimen s = column(1);
    HillerborgLaw state(s.lat, 1e-4, std::vector<double>(s.lat.numBars(), 3e-4));
    state.kappa[0] = 2.999e-4;  // damaged, still carries tension
    state.kappa[1] = 3e-4;      // broken
    const auto intact = intactBars(s.lat, state);
    EXPECT_EQ(intact[0], 1);
    EXPECT_EQ(intact[1], 0);
    EXPECT_EQ(intact[2], 1);
}
