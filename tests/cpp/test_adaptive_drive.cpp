// The adaptive drive after the load loss (tail_drive adaptive, AdaptiveDrive in
// Loading.hpp): a quiescent lattice (no bar softening, the faces carrying
// nothing) speeds the drive up, by at most `step` per record, to its ceiling; a
// softening bar (the fracture energy growing) or faces carrying tail_load x
// peak bring it back to the floor (loss_speedup); within a record interval the
// velocity ramps linearly, so that it never jumps by more than
// (step - 1) S v0 / R in a step, and U is the integral of that velocity.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "ldem/Loading.hpp"

namespace {

using ldem::AdaptiveDrive;

constexpr double kFloor = 20, kCeiling = 2000, kLoad = 0.05, kStep = 1.2;
constexpr double kPeak = 2.4e6;  // [Pa]

AdaptiveDrive started(double factor = 1.0, double fracture = 1.0) {
    AdaptiveDrive d(kFloor, kCeiling, kLoad, kStep);
    d.start(0.0, 0.0, factor, fracture);
    return d;
}

TEST(AdaptiveDrive, TheCriterionIsFloorWhileSofteningAndInverseInTheFaceLoad) {
    // Softening: the floor, whatever the faces carry.
    EXPECT_EQ(AdaptiveDrive::target(kFloor, kCeiling, kLoad, true, 0.0), kFloor);
    EXPECT_EQ(AdaptiveDrive::target(kFloor, kCeiling, kLoad, true, 1e-6), kFloor);
    // Quiet: floor x load / face load, between floor and ceiling.
    EXPECT_DOUBLE_EQ(AdaptiveDrive::target(kFloor, kCeiling, kLoad, false, 0.005), 200.0);
    EXPECT_DOUBLE_EQ(AdaptiveDrive::target(kFloor, kCeiling, kLoad, false, 0.025), 40.0);
    EXPECT_EQ(AdaptiveDrive::target(kFloor, kCeiling, kLoad, false, kLoad), kFloor);
    EXPECT_EQ(AdaptiveDrive::target(kFloor, kCeiling, kLoad, false, 0.3), kFloor);
    EXPECT_EQ(AdaptiveDrive::target(kFloor, kCeiling, kLoad, false, 1e-9), kCeiling);
    EXPECT_EQ(AdaptiveDrive::target(kFloor, kCeiling, kLoad, false, 0.0), kCeiling);
    EXPECT_EQ(AdaptiveDrive::target(kFloor, kCeiling, kLoad, false, std::nan("")), kFloor);
}

TEST(AdaptiveDrive, AQuiescentLatticeSpeedsUpByStepPerRecordToTheCeiling) {
    AdaptiveDrive d = started();
    double s = 1.0;
    int records = 0;
    while (d.speedFactor() < kCeiling && records < 1000) {
        d.record(1.0, 1e-7 * kPeak, -2e-7 * kPeak, kPeak);  // nothing softens, the faces carry nothing
        const double expected = std::min(s * kStep, kCeiling);
        EXPECT_DOUBLE_EQ(d.speedFactor(), expected) << "record " << records;
        s = d.speedFactor();
        ++records;
    }
    // 1.2^42 = 2116: the ceiling at the 42nd record, not before.
    EXPECT_EQ(records, int(std::ceil(std::log(kCeiling) / std::log(kStep))));
    for (int k = 0; k < 10; ++k) d.record(1.0, 0.0, 0.0, kPeak);
    EXPECT_EQ(d.speedFactor(), kCeiling);
}

TEST(AdaptiveDrive, ASofteningBarSlowsItDownToTheFloorAndNoFurther) {
    AdaptiveDrive d = started();
    for (int k = 0; k < 60; ++k) d.record(1.0, 0.0, 0.0, kPeak);
    ASSERT_EQ(d.speedFactor(), kCeiling);
    // A bar softens at every record: the fracture energy grows a little each time.
    double fracture = 1.0, s = kCeiling;
    for (int k = 0; k < 60; ++k) {
        fracture += 1e-9;
        d.record(fracture, 0.0, 0.0, kPeak);
        EXPECT_DOUBLE_EQ(d.speedFactor(), std::max(s / kStep, kFloor)) << "record " << k;
        s = d.speedFactor();
    }
    EXPECT_EQ(d.speedFactor(), kFloor);
    // Quiet again: the same fracture energy twice, the faces slack: it speeds up again.
    d.record(fracture, 0.0, 0.0, kPeak);
    EXPECT_DOUBLE_EQ(d.speedFactor(), kFloor * kStep);
}

TEST(AdaptiveDrive, LoadedFacesBringItBackWithoutAnyBarSoftening) {
    AdaptiveDrive d = started();
    for (int k = 0; k < 60; ++k) d.record(1.0, 0.0, 0.0, kPeak);
    // A chain straightens: the support carries 10 % of the peak (the loaded face a little less).
    for (int k = 0; k < 60; ++k) d.record(1.0, 0.1 * kPeak, 0.09 * kPeak, kPeak);
    EXPECT_EQ(d.speedFactor(), kFloor);
    // The drag and inertia on the loaded face alone count as much (its sign does not matter).
    AdaptiveDrive e = started();
    for (int k = 0; k < 60; ++k) e.record(1.0, 0.0, -0.01 * kPeak, kPeak);
    EXPECT_DOUBLE_EQ(e.speedFactor(), kFloor * kLoad / 0.01);
}

TEST(AdaptiveDrive, BelowTheFloorAtTheLoadLossItRampsUpEvenWhileBarsSoften) {
    AdaptiveDrive d = started(1.0, 1.0);
    double fracture = 1.0;
    for (int k = 0; k < 16; ++k) d.record(fracture += 0.01, 0.0, 0.0, kPeak);
    EXPECT_DOUBLE_EQ(d.speedFactor(), std::pow(kStep, 16));  // 18.5; 1.2^17 = 22.2 > floor: the floor next
    d.record(fracture += 0.01, 0.0, 0.0, kPeak);
    EXPECT_EQ(d.speedFactor(), kFloor);
}

// Random records (softening or not, face loads from 0 to the peak), R steps
// between them: the velocity of consecutive steps never differs by more than
// (step - 1) max(S_0, S_1) v0 / R, also across records, and U is the sum of dt v.
TEST(AdaptiveDrive, TheVelocityNeverJumpsByMoreThanTheStepAllows) {
    const double v0 = 2.4e-3, dt = 1.3e-6;
    for (int R : {1, 7, 48}) {
        AdaptiveDrive d = started(1.0, 1.0);
        std::mt19937_64 rng(R);
        std::uniform_real_distribution<double> u01(0, 1);
        double fracture = 1.0, vPrev = v0, U = 0, maxJump = 0, maxRatio = 0;
        for (int rec = 0; rec < 400; ++rec) {
            if (u01(rng) < 0.3) fracture += 1e-3;
            const double face = u01(rng) < 0.5 ? 0.0 : std::pow(10.0, -5 * u01(rng));
            const double s0 = d.speedFactor();
            d.record(fracture, face * kPeak, 0.0, kPeak);
            const double s1 = d.speedFactor();
            EXPECT_LE(s1, s0 * kStep * (1 + 1e-15));
            EXPECT_GE(s1, s0 / kStep * (1 - 1e-15));
            const double bound = (kStep - 1) * std::max(s0, s1) * v0 / R;
            for (int k = 0; k < R; ++k) {
                const double Ubefore = d.U;
                d.advance(dt, v0, k, R);
                EXPECT_EQ(d.Uprev, Ubefore);
                const double v = (d.U - Ubefore) / dt;
                EXPECT_NEAR(v, v0 * d.factor(k, R), 1e-9 * v);
                const double jump = std::abs(v - vPrev);
                EXPECT_LE(jump, bound * (1 + 1e-6)) << "R " << R << " record " << rec << " step " << k;
                maxJump = std::max(maxJump, jump), maxRatio = std::max(maxRatio, jump / bound);
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
    AdaptiveDrive d = started(1.0, 2.0);
    for (int k = 0; k < 5; ++k) d.record(2.0, 0.0, 0.0, kPeak), d.advance(1e-6, 1e-3, 0, 1);
    AdaptiveDrive e(kFloor, kCeiling, kLoad, kStep);
    EXPECT_FALSE(e.active());
    e.setState(d.state());
    EXPECT_TRUE(e.active());
    EXPECT_EQ(e.state(), d.state());
    d.record(2.5, 0.0, 0.0, kPeak), e.record(2.5, 0.0, 0.0, kPeak);
    EXPECT_EQ(e.state(), d.state());
}

}  // namespace
