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
    EXPECT_EQ(CrackPace::target(l, 0.9e-3, 1.0, true, false, false), 1.0);     // K/W below crack_kinetic: led by the drive
    EXPECT_EQ(CrackPace::target(l, 1.1e-3, 1.0, true, false, false), 0.0625);  // above while bars soften: a crack runs
    EXPECT_EQ(CrackPace::target(l, 1.1e-3, 1.0, false, false, false), 1.0);    // no bar softens: the start's own motion
    EXPECT_EQ(CrackPace::target(l, 1.1e-3, 1.0, true, false, true), 1.0);      // the load lost: the tail's
    EXPECT_EQ(CrackPace::target(l, 0.0, 0.0, false, false, false), 1.0);       // at rest
    EXPECT_EQ(CrackPace::target(l, 0.0, 1.0, false, true, false), 0.0625);     // near the peak: slow, however quiet
    EXPECT_EQ(CrackPace::target(l, 0.0, 1.0, false, true, true), 1.0);         // but not once the load is lost
}

// Near the peak: S < crack_secant E_0 and sigma >= crack_band x peak; off at crack_secant 0.
TEST(CrackPace, NearThePeakIsTheBentCurveAboveTheBand) {
    CrackPace::Limits l = limits();
    l.secant = 0.9, l.band = 0.5;
    const double E0 = 3.4e10, peak = 2.2e6;
    EXPECT_FALSE(CrackPace::nearPeak(l, 0.95 * E0, E0, 2.0e6, peak));  // still straight
    EXPECT_TRUE(CrackPace::nearPeak(l, 0.85 * E0, E0, 2.0e6, peak));   // bent, above the band
    EXPECT_TRUE(CrackPace::nearPeak(l, 0.85 * E0, E0, 1.1e6, peak));   // at the band's edge
    EXPECT_FALSE(CrackPace::nearPeak(l, 0.20 * E0, E0, 0.5e6, peak));  // past the snap, below the band
    EXPECT_FALSE(CrackPace::nearPeak(l, 0.85 * E0, 0.0, 2.0e6, peak));  // no elastic secant yet
    l.secant = 0;
    EXPECT_FALSE(CrackPace::nearPeak(l, 0.10 * E0, E0, 2.0e6, peak));  // off
}

// E_0 is the largest secant while no bar has softened, and only then: a quiet
// record past the first softening with a secant far below E_0 and the stress in
// the band slows the drive; one with the stress below the band does not.
TEST(CrackPace, TheElasticSecantIsLearntBeforeTheFirstCrackAndKept) {
    CrackPace::Limits l = limits();
    l.secant = 0.9, l.band = 0.5, l.brake = 0;  // brake at once: the pace is the target
    CrackPace p(l);
    const double E = 3.4e10, peak = 2.2e6;
    p.record(0, 1, 0.0, false, 1.0e6, 1.0e6, 1.0e6 / E);  // elastic: E_0 = E
    EXPECT_EQ(p.pace(), 1.0);
    p.record(0, 1, 0.0, false, 1.5e6, 1.6e6, 1.6e6 / (2 * E));  // a secant above E before any crack: E_0 = 2E
    p.record(0, 1, 0.1, false, 2.0e6, 2.0e6, 2.0e6 / (0.95 * E));  // cracking, S = 0.95 E < 0.9 x 2E
    EXPECT_EQ(p.pace(), 0.0625);
    CrackPace q(l);
    q.record(0, 1, 0.0, false, 1.0e6, 1.0e6, 1.0e6 / E);
    q.record(0, 1, 0.1, false, 2.0e6, 2.0e6, 2.0e6 / (0.95 * E));  // bent by 5 %: not yet
    EXPECT_EQ(q.pace(), 1.0);
    q.record(0, 1, 0.2, false, 2.1e6, 2.1e6, 2.1e6 / (2 * E));  // a secant of 2E after the first crack: not learnt
    q.record(0, 1, 0.3, false, 2.1e6, 2.1e6, 2.1e6 / (1.5 * E));  // 1.5 E: not near against E (it would be against 2E)
    EXPECT_EQ(q.pace(), 1.0);
    q.record(0, 1, 0.4, false, peak, 2.2e6, 2.2e6 / (0.85 * E));  // bent by 15 % against E
    EXPECT_EQ(q.pace(), 0.0625);
    q.record(0, 1, 0.5, false, peak, 0.6e6, 0.6e6 / (0.1 * E));  // below the band: the snap is over
    EXPECT_DOUBLE_EQ(q.pace(), 0.0625 * 1.1);
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

// T / t_r bounds the change of a record either way: from 1 to crack_pace over no less than
// the smooth start's time, so that the drive's own mode is not set ringing.
TEST(CrackPace, ChangesNoFasterThanTheSmoothStart) {
    CrackPace::Limits l = limits();
    l.glide = 0.05;  // T / t_r: t_r is 20 records
    const double peak = 2e6;  // the brake alone would allow 0.2
    EXPECT_DOUBLE_EQ(CrackPace::next(l, 1.0, 0.0625, peak), 0.95);
    EXPECT_DOUBLE_EQ(CrackPace::next(l, 0.1, 0.0625, peak), 0.0625);  // not below the target
    EXPECT_DOUBLE_EQ(CrackPace::next(l, 0.9, 1.0, peak), 0.95);       // the ratio alone would allow 0.99
    EXPECT_DOUBLE_EQ(CrackPace::next(l, 0.0625, 1.0, peak), 0.0625 * 1.1);  // the ratio, the tighter here
    l.brake = 0;
    EXPECT_DOUBLE_EQ(CrackPace::next(l, 1.0, 0.0625, peak), 0.95);  // no brake: the glide still bounds it
}

// The clock over a record interval of R steps ramps the pace linearly from P_0 to P_1:
// tau advances by dt sum_k (P_0 + (P_1 - P_0)(k + 1)/R) = dt (R P_0 + (P_1 - P_0)(R + 1)/2).
TEST(CrackPace, TheClockIntegratesTheRampedPace) {
    CrackPace p(limits());
    const double dt = 1e-6, peak = 2e6;
    const int R = 40;
    p.record(0.01, 1.0, 0.1, false, peak, 0.0, 0.0);  // brake: P from 1 to 0.8
    for (int k = 0; k < R; ++k) p.advance(dt, k, R);
    EXPECT_NEAR(p.tau, dt * (R * 1.0 + (0.8 - 1.0) * (R + 1) / 2.0), 1e-18);
    EXPECT_NEAR(p.tau - p.tauBefore, dt * 0.8, 1e-20);  // the last step at P_1
    EXPECT_DOUBLE_EQ(p.pace(), 0.8);
}

TEST(CrackPace, OffAtOneAndItsStateRoundTrips) {
    CrackPace::Limits l = limits();
    l.slowest = 1;
    EXPECT_FALSE(CrackPace(l).on());
    l = limits();
    l.secant = 0.95;  // the state carries E_0: b slows where a does
    CrackPace a(l), b(l);
    for (int k = 0; k < 5; ++k) {
        a.record(k % 2 ? 0.01 : 0.0, 1.0, 0.1 * k, false, 2e6, 1e6 * (k + 1), 3e-5 * (k + 1));  // E_0 at k = 0
        for (int j = 0; j < 10; ++j) a.advance(1e-6, j, 10);
    }
    b.setState(a.state());
    for (int k = 0; k < 5; ++k) {
        a.record(0.0, 1.0, 0.5 + 0.1 * k, false, 2e6, 2e6, 2e6 / (3.3e10 - 1e9 * k));
        b.record(0.0, 1.0, 0.5 + 0.1 * k, false, 2e6, 2e6, 2e6 / (3.3e10 - 1e9 * k));
        for (int j = 0; j < 10; ++j) a.advance(1e-6, j, 10), b.advance(1e-6, j, 10);
        EXPECT_EQ(a.tau, b.tau);
        EXPECT_EQ(a.pace(), b.pace());
    }
}

}  // namespace
