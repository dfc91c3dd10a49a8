// The adaptive drive after the load loss (tail_drive adaptive, AdaptiveDrive in
// Loading.hpp): a quiescent lattice (no bar softening, the chains carrying
// nothing) speeds the drive up, by at most tail_step per record, to its
// ceiling; a softening bar (the fracture energy growing) or chains carrying
// tail_load x peak bring it back to the floor (loss_speedup); drag and inertia
// of the hanging column, rho H (a + D_f v), stay below tail_drag x peak; within
// a record interval the velocity ramps linearly, so that it never jumps by
// more than (step - 1) S v0 / R in a step, and U is the integral of that velocity.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <cmath>
#include <random>
#include <vector>

#include "ldem/Loading.hpp"
#include "ldem/Simulation.hpp"

namespace {

using ldem::AdaptiveDrive;

constexpr double kFloor = 20, kCeiling = 2000, kLoad = 0.02, kDrag = 0.1, kStep = 1.2;
constexpr double kPeak = 2.4e6;  // [Pa]
// No averaging and no bound of drag and inertia: the criterion and tail_step alone.
const AdaptiveDrive::Limits kLimits{kFloor, kCeiling, kLoad, kDrag, kStep, 0.0, 0.0, 0.0};

AdaptiveDrive started(const AdaptiveDrive::Limits& l = kLimits, double fracture = 1.0) {
    AdaptiveDrive d(l);
    d.start(0.0, 0.0, fracture);
    return d;
}

double target(bool softening, double chain) { return AdaptiveDrive::target(kLimits, softening, chain); }

TEST(AdaptiveDrive, TheCriterionIsTheFloorWhileSofteningElseInverseInTheChainsLoad) {
    // Softening: the floor, whatever the chains carry.
    EXPECT_EQ(target(true, 0.0), kFloor);
    EXPECT_EQ(target(true, 1e-6), kFloor);
    // Quiet: floor x tail_load / c, between floor and ceiling.
    EXPECT_DOUBLE_EQ(target(false, 0.002), 200.0);
    EXPECT_DOUBLE_EQ(target(false, 0.01), 40.0);
    EXPECT_EQ(target(false, kLoad), kFloor);
    EXPECT_EQ(target(false, 0.3), kFloor);
    EXPECT_EQ(target(false, 1e-9), kCeiling);
    EXPECT_EQ(target(false, 0.0), kCeiling);
    EXPECT_EQ(target(false, std::nan("")), kFloor);
}

TEST(AdaptiveDrive, AQuiescentLatticeSpeedsUpByStepPerRecordToTheCeiling) {
    AdaptiveDrive d = started();
    EXPECT_EQ(d.speedFactor(), kFloor);
    double s = kFloor;
    int records = 0;
    while (d.speedFactor() < kCeiling && records < 1000) {
        d.record(0.0, 1.0, 1e-7 * kPeak, kPeak);  // nothing softens, the chains carry nothing
        EXPECT_DOUBLE_EQ(d.speedFactor(), std::min(s * kStep, kCeiling)) << "record " << records;
        s = d.speedFactor();
        ++records;
    }
    // 20 x 1.2^26 = 2293: the ceiling at the 26th record, not before.
    EXPECT_EQ(records, int(std::ceil(std::log(kCeiling / kFloor) / std::log(kStep))));
    for (int k = 0; k < 10; ++k) d.record(0.0, 1.0, 0.0, kPeak);
    EXPECT_EQ(d.speedFactor(), kCeiling);
}

TEST(AdaptiveDrive, ASofteningBarSlowsItDownToTheFloorAndNoFurther) {
    AdaptiveDrive d = started();
    for (int k = 0; k < 60; ++k) d.record(0.0, 1.0, 0.0, kPeak);
    ASSERT_EQ(d.speedFactor(), kCeiling);
    // A bar softens at every record: the fracture energy grows a little each time.
    double fracture = 1.0, s = kCeiling;
    for (int k = 0; k < 60; ++k) {
        fracture += 1e-9;
        d.record(0.0, fracture, 0.0, kPeak);
        EXPECT_DOUBLE_EQ(d.speedFactor(), std::max(s / kStep, kFloor)) << "record " << k;
        s = d.speedFactor();
    }
    EXPECT_EQ(d.speedFactor(), kFloor);
    // Quiet again: the same fracture energy twice, the chains slack: it speeds up again.
    d.record(0.0, fracture, 0.0, kPeak);
    EXPECT_DOUBLE_EQ(d.speedFactor(), kFloor * kStep);
}

TEST(AdaptiveDrive, TautChainsBringItBackWithoutAnyBarSoftening) {
    AdaptiveDrive d = started();
    for (int k = 0; k < 60; ++k) d.record(0.0, 1.0, 0.0, kPeak);
    // A chain straightens: the support carries 5 % of the peak (in tension or, ringing, compression).
    for (int k = 0; k < 60; ++k) d.record(0.0, 1.0, (k % 2 ? 0.05 : -0.05) * kPeak, kPeak);
    EXPECT_EQ(d.speedFactor(), kFloor);
    // 0.2 % of the peak: ten times the floor.
    for (int k = 0; k < 60; ++k) d.record(0.0, 1.0, 0.002 * kPeak, kPeak);
    EXPECT_DOUBLE_EQ(d.speedFactor(), 200.0);
}

// Drag and inertia of the column that hangs from the drive: with rho H v0 / T =
// column and D_f T = dampingT, the stress column (S_1 - S_0 + dampingT S_1)
// never exceeds tail_drag x peak, and the speed settles where the drag alone
// takes it all, S = tail_drag peak / (column dampingT).
TEST(AdaptiveDrive, DragAndInertiaOfTheHangingColumnStayWithinTheBudget) {
    AdaptiveDrive::Limits l = kLimits;
    l.column = 1.78e5, l.dampingT = 0.0157;  // the 0.48 m cube: rho H v0 / T [Pa], D_f T
    AdaptiveDrive d = started(l);
    const double budget = kDrag * kPeak;
    double s0 = d.speedFactor(), worst = 0;
    for (int k = 0; k < 3000; ++k) {
        d.record(0.0, 1.0, 0.0, kPeak);
        const double s1 = d.speedFactor();
        const double stress = l.column * (s1 - s0 + l.dampingT * s1);
        EXPECT_LE(stress, budget * (1 + 1e-12)) << "record " << k;
        EXPECT_GE(l.column * (s1 - s0), -budget * (1 + 1e-12)) << "record " << k;
        worst = std::max(worst, stress / budget), s0 = s1;
    }
    EXPECT_GT(worst, 0.99);  // the bound, not tail_step, held it
    EXPECT_NEAR(d.speedFactor(), budget / (l.column * l.dampingT), 1e-6 * d.speedFactor());
    // Without the bound it would have been at the ceiling long since.
    AdaptiveDrive e = started();
    for (int k = 0; k < 3000; ++k) e.record(0.0, 1.0, 0.0, kPeak);
    EXPECT_EQ(e.speedFactor(), kCeiling);
}

// A specimen that rings after its load loss: the support's stress swings by 5 %
// of the peak around the chains' (none), a free vibration of period P.
// Averaged over tau = 2 P the swing is cut to 1/sqrt(1 + (4 pi)^2) = 8 % of
// itself and the drive goes several times faster than the floor; read record
// by record the swing holds it near the floor.
TEST(AdaptiveDrive, RingingAveragedOverTauDoesNotHoldItBack) {
    const double P = 1e-3, dtRecord = P / 16, pi = 3.14159265358979323846;
    for (double tau : {0.0, 2 * P}) {
        AdaptiveDrive::Limits l = kLimits;
        l.tau = tau;
        AdaptiveDrive d = started(l);
        for (int k = 0; k < 400; ++k) {
            const double t = k * dtRecord;
            d.record(t, 1.0, 0.05 * kPeak * std::sin(2 * pi * t / P + 0.3), kPeak);
        }
        if (tau > 0) EXPECT_GT(d.speedFactor(), 4 * kFloor);
        else EXPECT_LT(d.speedFactor(), 2 * kFloor);
    }
    // A steady load is not averaged away: with tau the chains' 1 % of the peak holds it at twice the floor.
    AdaptiveDrive::Limits l = kLimits;
    l.tau = 2 * P;
    AdaptiveDrive e = started(l);
    for (int k = 0; k < 400; ++k) e.record(k * dtRecord, 1.0, 0.01 * kPeak, kPeak);
    EXPECT_NEAR(e.speedFactor(), 2 * kFloor, 1e-9);
}

// Random records (softening or not, loads from 0 to the peak), R steps
// between them: the velocity of consecutive steps never differs by more than
// (step - 1) max(S_0, S_1) v0 / R, also across records, and U is the sum of dt v.
TEST(AdaptiveDrive, TheVelocityNeverJumpsByMoreThanTheStepAllows) {
    const double v0 = 2.4e-3, dt = 1.3e-6;
    for (int R : {1, 7, 48}) {
        AdaptiveDrive d = started();
        std::mt19937_64 rng(R);
        std::uniform_real_distribution<double> u01(0, 1);
        double fracture = 1.0, vPrev = kFloor * v0, U = 0, maxRatio = 0;
        for (int rec = 0; rec < 400; ++rec) {
            if (u01(rng) < 0.3) fracture += 1e-3;
            const double chain = u01(rng) < 0.5 ? 0.0 : std::pow(10.0, -5 * u01(rng));
            const double s0 = d.speedFactor();
            d.record(0.0, fracture, chain * kPeak, kPeak);
            const double s1 = d.speedFactor();
            EXPECT_LE(s1, s0 * kStep * (1 + 1e-15));
            EXPECT_GE(s1, s0 / kStep * (1 - 1e-15));
            EXPECT_GE(s1, kFloor);
            EXPECT_LE(s1, kCeiling);
            const double bound = (kStep - 1) * std::max(s0, s1) * v0 / R;
            for (int k = 0; k < R; ++k) {
                const double Ubefore = d.U;
                d.advance(dt, v0, k, R);
                EXPECT_EQ(d.Uprev, Ubefore);
                const double v = (d.U - Ubefore) / dt;
                EXPECT_NEAR(v, v0 * d.factor(k, R), 1e-9 * v);
                const double jump = std::abs(v - vPrev);
                EXPECT_LE(jump, bound * (1 + 1e-6)) << "R " << R << " record " << rec << " step " << k;
                maxRatio = std::max(maxRatio, jump / bound);
                vPrev = v, U += dt * v0 * d.factor(k, R);
            }
            // The interval ends on S_1 exactly.
            EXPECT_DOUBLE_EQ(d.factor(R - 1, R), s1);
        }
        EXPECT_NEAR(d.U, U, 1e-12 * U);
        EXPECT_GT(maxRatio, 0.5) << "the records should have moved the velocity near its bound";
    }
}

TEST(AdaptiveDrive, ItsStateRoundTrips) {
    AdaptiveDrive::Limits l = kLimits;
    l.tau = 1e-3;
    AdaptiveDrive d = started(l, 2.0);
    for (int k = 0; k < 5; ++k) d.record(1e-4 * k, 2.0, 1e3 * k, kPeak), d.advance(1e-6, 1e-3, 0, 1);
    AdaptiveDrive e(l);
    EXPECT_FALSE(e.active());
    e.setState(d.state());
    EXPECT_TRUE(e.active());
    EXPECT_EQ(e.state(), d.state());
    d.record(1e-3, 2.5, 5e3, kPeak), e.record(1e-3, 2.5, 5e3, kPeak);
    EXPECT_EQ(e.state(), d.state());
}

}  // namespace

// The adaptive drive in a run: the 0.08 m cube (4 x 4 x 4 modules), seed 2.

namespace {

using namespace ldem;

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

struct CubeRun {
    RunSummary summary;
    std::vector<CurvePoint> rows;
};

// crackPace 1 (the default): the tail alone (the pace before the load loss: test_crack_pace.cpp).
CubeRun runCube(DriveId drive, std::int64_t seed = 2, double crackPace = 1) {
    Material m;
    LoadingParams lp;
    lp.tailDrive = drive;
    lp.crackPace = crackPace;
    RunParams rp;
    rp.threads = 1, rp.seed = seed;
    Simulation sim(cubeTestSpecimen(4, 4, 4, 0.02, m, lp), m, lp, rp);
    CubeRun r;
    r.summary = sim.run([&](const CurvePoint& p) { return r.rows.push_back(p), true; });
    return r;
}

// Before the end of the fixed ramp to loss_speedup the two drives are the same
// bits; then the adaptive one goes faster (the mean strain grows faster than
// at 20 x strain_rate), separates in fewer steps, and U_num is within 1 %
// (measured: 0.4284805 J against 0.4286039 J, 132768 steps against 209088).
TEST(AdaptiveDriveRun, SameBitsToTheLoadLossThenFewerStepsToTheSameU) {
    const CubeRun fixed = runCube(driveNamed("fixed")), adaptive = runCube(driveNamed("adaptive"));
    ASSERT_EQ(fixed.summary.stopReason, "separated");
    ASSERT_EQ(adaptive.summary.stopReason, "separated");
    EXPECT_TRUE(sameBits(fixed.summary.peakStress, adaptive.summary.peakStress));
    EXPECT_EQ(fixed.summary.loadLoss.step, adaptive.summary.loadLoss.step);
    EXPECT_TRUE(sameBits(fixed.summary.loadLoss.fracture, adaptive.summary.loadLoss.fracture));
    std::size_t same = 0;
    while (same < adaptive.rows.size() && same < fixed.rows.size() &&
           sameBits(adaptive.rows[same].meanStrain, fixed.rows[same].meanStrain) &&
           sameBits(adaptive.rows[same].fracture, fixed.rows[same].fracture))
        ++same;
    ASSERT_GT(same, 0u);
    EXPECT_GT(adaptive.rows[same - 1].step, fixed.summary.loadLoss.step);  // through the load loss and the ramp
    // Faster: the largest strain rate over a record is well above the fixed drive's 20 x 0.02 1/s.
    double fastest = 0;
    for (std::size_t k = same; k < adaptive.rows.size(); ++k)
        fastest = std::max(fastest, (adaptive.rows[k].meanStrain - adaptive.rows[k - 1].meanStrain) /
                                        (adaptive.rows[k].time - adaptive.rows[k - 1].time));
    EXPECT_GT(fastest, 2 * 20 * 0.02);
    EXPECT_LT(adaptive.summary.steps, 0.8 * fixed.summary.steps);
    EXPECT_NEAR(adaptive.summary.separation.fracture / fixed.summary.separation.fracture, 1.0, 0.01);
    EXPECT_LT(adaptive.summary.energyBalanceError, 1e-3);
}

// A run stopped at a record once the adaptive drive is going, its checkpoint
// restored into a new specimen, goes on to the same bits as a run that never
// stopped: the drive's U, U(n-1), its factors and averages are in the checkpoint.
TEST(AdaptiveDriveRun, ARestartPastTheLoadLossEndsOnTheSameBits) {
    Material m;
    LoadingParams lp;
    lp.crackPace = 0.0625;  // the pace on: its clock and pace are in the checkpoint too
    RunParams rp;
    rp.threads = 1, rp.seed = 2;
    const CubeRun whole = runCube(driveNamed("adaptive"), 2, lp.crackPace);
    Simulation first(cubeTestSpecimen(4, 4, 4, 0.02, m, lp), m, lp, rp);
    int after = 0;
    const AdaptiveDrive& tail = std::get<ldem::AdaptiveTailDrive>(first.parts().drive()).adaptive();
    first.run([&](const CurvePoint&) {
        // Stop well into the adaptive part, while the drive is faster than the floor.
        return !(tail.active() && tail.speedFactor() > 40 && ++after > 25);
    });
    ASSERT_TRUE(tail.active());
    const Checkpoint c = first.checkpoint();
    ASSERT_EQ(c.parts.front().first, "drive_adaptive");
    // the ramp's start, floor and time, the pace's state, then the adaptive drive's
    ASSERT_EQ(c.parts.front().second.size(), 3 + CrackPace::kStateSize + tail.state().size());
    Simulation second(cubeTestSpecimen(4, 4, 4, 0.02, m, lp), m, lp, rp);
    second.restore(c);
    std::vector<CurvePoint> rest;
    const RunSummary s = second.run([&](const CurvePoint& p) { return rest.push_back(p), true; });
    EXPECT_EQ(s.stopReason, "separated");
    EXPECT_EQ(s.steps, whole.summary.steps);
    EXPECT_TRUE(sameBits(s.separation.fracture, whole.summary.separation.fracture));
    EXPECT_TRUE(sameBits(s.energyBalanceError, whole.summary.energyBalanceError));
    ASSERT_FALSE(rest.empty());
    ASSERT_LE(rest.size(), whole.rows.size());
    const std::size_t offset = whole.rows.size() - rest.size();
    for (std::size_t k = 0; k < rest.size(); ++k) {
        const CurvePoint &a = rest[k], &b = whole.rows[offset + k];
        ASSERT_EQ(a.step, b.step);
        ASSERT_TRUE(sameBits(a.meanStrain, b.meanStrain) && sameBits(a.externalWork, b.externalWork) &&
                    sameBits(a.fracture, b.fracture) && sameBits(a.kinetic, b.kinetic))
            << "row at step " << a.step;
    }
}

}  // namespace
