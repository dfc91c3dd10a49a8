// The drive's pace before the load loss (dynamics/CrackPace.hpp): its
// criterion, its bounds, its clock, and that crack_pace = 1 is the fixed drive.
#include <gtest/gtest.h>

#include <cmath>

#include "ldem/dynamics/CrackPace.hpp"

namespace {
using namespace ldem;

CrackPace::Limits limits() { return {0.0625, 1e-3, 1e-7, 1.1}; }  // brake 1e-7 /Pa: 0.2 per record at a 2 MPa peak

TEST(CrackPace, SlowsOnlyWhileTheLatticeMovesByItselfAndTheLoadIsNotLost) {
    const CrackPace::Limits l = limits();
    EXPECT_EQ(CrackPace::target(l, 0.9e-3, 1.0, true, false), 1.0);     // K/W below crack_kinetic: led by the drive
    EXPECT_EQ(CrackPace::target(l, 1.1e-3, 1.0, true, false), 0.0625);  // above while bars soften: a crack runs
    EXPECT_EQ(CrackPace::target(l, 1.1e-3, 1.0, false, false), 1.0);    // no bar softens: the start's own motion
    EXPECT_EQ(CrackPace::target(l, 1.1e-3, 1.0, true, true), 1.0);      // the load lost: the tail's
    EXPECT_EQ(CrackPace::target(l, 0.0, 0.0, false, false), 1.0);       // at rest
}

TEST(CrackPace, BrakesWithinTheInertiaBudgetAndReleasesByTheRatio) {
    const CrackPace::Limits l = limits();
    const double peak = 2e6;  // B = 1e-7 x 2e6 = 0.2 per record
    EXPECT_DOUBLE_EQ(CrackPace::next(l, 1.0, 0.0625, peak), 0.8);
    EXPECT_DOUBLE_EQ(CrackPace::next(l, 0.2, 0.0625, peak), 0.0625);  // not below the target
    EXPECT_DOUBLE_EQ(CrackPace::next(l, 0.0625, 1.0, peak), 0.0625 * 1.1);
    EXPECT_DOUBLE_EQ(CrackPace::next(l, 0.95, 1.0, peak), 1.0);  // not above the target
    CrackPace::Limits free = l;
    free.brake = 0;  // no bound: at once
    EXPECT_DOUBLE_EQ(CrackPace::next(free, 1.0, 0.0625, peak), 0.0625);
}

// The clock over a record interval of R steps ramps the pace linearly from P_0 to P_1:
// tau advances by dt sum_k (P_0 + (P_1 - P_0)(k + 1)/R) = dt (R P_0 + (P_1 - P_0)(R + 1)/2).
TEST(CrackPace, TheClockIntegratesTheRampedPace) {
    CrackPace p(limits());
    const double dt = 1e-6, peak = 2e6;
    const int R = 40;
    p.record(0.01, 1.0, 0.1, false, peak);  // brake: P from 1 to 0.8
    for (int k = 0; k < R; ++k) p.advance(dt, k, R);
    EXPECT_NEAR(p.tau, dt * (R * 1.0 + (0.8 - 1.0) * (R + 1) / 2.0), 1e-18);
    EXPECT_NEAR(p.tau - p.tauBefore, dt * 0.8, 1e-20);  // the last step at P_1
    EXPECT_DOUBLE_EQ(p.pace(), 0.8);
}

TEST(CrackPace, OffAtOneAndItsStateRoundTrips) {
    CrackPace::Limits l = limits();
    l.slowest = 1;
    EXPECT_FALSE(CrackPace(l).on());
    CrackPace a(limits()), b(limits());
    for (int k = 0; k < 5; ++k) {
        a.record(k % 2 ? 0.01 : 0.0, 1.0, 0.1 * k, false, 2e6);
        for (int j = 0; j < 10; ++j) a.advance(1e-6, j, 10);
    }
    b.setState(a.state());
    for (int k = 0; k < 5; ++k) {
        a.record(0.01, 1.0, 0.5 + 0.1 * k, false, 2e6), b.record(0.01, 1.0, 0.5 + 0.1 * k, false, 2e6);
        for (int j = 0; j < 10; ++j) a.advance(1e-6, j, 10), b.advance(1e-6, j, 10);
        EXPECT_EQ(a.tau, b.tau);
        EXPECT_EQ(a.pace(), b.pace());
    }
}

}  // namespace
