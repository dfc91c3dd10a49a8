// The recorded load is a load cell's (Simulation::measure): a record's stress
// is the mean of the support's (and the loaded group's) stress over the states
// of its record interval, the impulse over the interval divided by it; the
// peak is the largest record.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "ldem/Simulation.hpp"

using namespace ldem;

TEST(LoadCell, RecordIsTheMeanOfItsIntervalsStates) {
    Material m;
    LoadingParams lp;
    RunParams rp;
    rp.threads = 1, rp.finalStrain = 2.6e-4;  // past the peak: the load rings as bars break
    const int R = 10;
    auto rows = [&](int every) {
        RunParams r = rp;
        r.recordEvery = every;
        Simulation sim(cubeTestSpecimen(3, 3, 3, 0.02, m, lp), m, lp, r);
        std::vector<CurvePoint> out;
        const RunSummary s = sim.run([&](const CurvePoint& p) { return out.push_back(p), true; });
        return std::make_pair(out, s);
    };
    const auto [each, eachSummary] = rows(1);  // one state a record: each state's own stress
    const auto [cells, summary] = rows(R);
    ASSERT_GT(cells.size(), 20u);
    double worst = 0, ringing = 0;
    for (std::size_t j = 1; j < cells.size() && j * R < each.size(); ++j) {
        double support = 0, loaded = 0;
        for (int k = 0; k < R; ++k)
            support += each[j * R - k].stress, loaded += each[j * R - k].stressLoaded;
        ASSERT_EQ(cells[j].step, each[j * R].step);
        worst = std::max({worst, std::abs(cells[j].stress - support / R), std::abs(cells[j].stressLoaded - loaded / R)});
        ringing = std::max(ringing, std::abs(cells[j].stress - each[j * R].stress));
    }
    EXPECT_LT(worst, 1e-9 * summary.peakStress);
    EXPECT_GT(ringing, 1e-4 * summary.peakStress) << "the states of an interval differ: the test must see a mean";
    // The peak is the largest record: of the cells when recorded every R steps.
    double top = 0;
    for (const CurvePoint& p : cells) top = std::max(top, p.stress);
    EXPECT_EQ(summary.peakStress, top);
    EXPECT_LT(summary.peakStress, eachSummary.peakStress);  // the mean is below the top of the ringing
}
