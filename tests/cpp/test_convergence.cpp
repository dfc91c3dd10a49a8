// The stop of a specimen that does not separate (stop_at converged,
// EnergyConvergence in Simulation.hpp): U has converged after two quiet
// doublings of the mean strain past the load loss in a row, a quiet doubling
// being one in which U grew by less than the tolerance with the load still lost.
#include <gtest/gtest.h>

#include <cmath>

#include "ldem/Simulation.hpp"

namespace {

using ldem::EnergyConvergence;

// Feeds records at mean strains e0 2^(k/4) (four per doubling), U(e) from u(e),
// the load lost at every record unless lost(e) says not; returns the strain of
// the record at which the test says "converged", or 0.
template <class U, class Lost>
double convergedAt(EnergyConvergence c, double e0, int records, U u, Lost lost) {
    for (int k = 0; k < records; ++k) {
        const double e = e0 * std::pow(2.0, k / 4.0);
        if (c.update(e, u(e), lost(e))) return e;
    }
    return 0;
}

const auto always = [](double) { return true; };

TEST(EnergyConvergence, TwoQuietDoublingsInARowStop) {
    // U = 1 + 0.5 (1 - e0/e): a geometric tail, growth per doubling 1/2, 1/4 ... of what is left.
    const double e0 = 1e-3;
    auto u = [&](double e) { return 1.0 + 0.5 * (1 - e0 / e); };
    // Rungs at e0 2^k; growth over [e0 2^(k-1), e0 2^k] is 0.5 e0 (1/2^(k-1) - 1/2^k) / U = 0.25 2^(1-k) / U.
    // Below 1 % from k = 6 (0.0078 / 1.49); two in a row first at k = 7.
    EXPECT_DOUBLE_EQ(convergedAt(EnergyConvergence(0.01), e0, 60, u, always), e0 * 128);
}

TEST(EnergyConvergence, AQuietDoublingThenABurstDoesNotStop) {
    // Flat, then a burst of +20 % at 3 e0: one quiet rung (2 e0), then a loud one (4 e0); flat after.
    const double e0 = 1e-3;
    auto u = [&](double e) { return e < 3 * e0 ? 1.0 : 1.2; };
    // Rungs e0, 2 e0 (quiet), 4 e0 (loud: the count starts again), 8 e0 (quiet), 16 e0 (quiet: stop).
    EXPECT_DOUBLE_EQ(convergedAt(EnergyConvergence(0.01), e0, 40, u, always), 16 * e0);
}

TEST(EnergyConvergence, ARungWhereTheLoadIsBackIsNotQuiet) {
    const double e0 = 1e-3;
    auto flat = [](double) { return 1.0; };
    auto lostExceptAt4 = [&](double e) { return std::abs(e - 4 * e0) > 1e-12; };
    // Rungs 2 e0 (quiet), 4 e0 (load back: not quiet), 8 e0, 16 e0 (quiet twice: stop).
    EXPECT_DOUBLE_EQ(convergedAt(EnergyConvergence(0.01), e0, 40, flat, lostExceptAt4), 16 * e0);
    EXPECT_DOUBLE_EQ(convergedAt(EnergyConvergence(0.01), e0, 40, flat, always), 4 * e0);
}

TEST(EnergyConvergence, ItsStateContinuesBitForBit) {
    const double e0 = 1e-3;
    EnergyConvergence whole(0.01), first(0.01);
    for (int k = 0; k < 6; ++k) {
        const double e = e0 * std::pow(2.0, k / 4.0);
        whole.update(e, 1.0, true), first.update(e, 1.0, true);
    }
    EnergyConvergence second(0.01);
    second.setState(first.state());
    for (int k = 6; k < 40; ++k) {
        const double e = e0 * std::pow(2.0, k / 4.0);
        ASSERT_EQ(whole.update(e, 1.0, true), second.update(e, 1.0, true)) << "record " << k;
    }
}

}  // namespace
