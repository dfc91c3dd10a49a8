// The adaptive tail's bound of drag and inertia (AdaptiveDrive.hpp, (1)):
//   rho H v0 (dS/dt + D_f S) <= tail_drag x peak
// at every instant from the load loss on: the ramp to the floor
// S_f = clamp(S_d / 2, 1, loss_speedup), S_d = tail_drag peak / (rho H v0 D_f),
// over t_q = max(t_r, pi (S_f - 1) / (2 D_f sqrt((S_d - S_f)(S_d - 1)))), then
// the record-wise drive below S_d. On the pure functions with the 0.96 m
// triangular cube's numbers, and in a run where the bound binds, against the
// formula from the run's own rho, H, v0, D_f and peak.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <variant>
#include <vector>

#include "ldem/Simulation.hpp"

namespace {

using namespace ldem;

constexpr double pi = 3.14159265358979323846;

// (1)'s left side over the budget along a drive program, sampled every h from
// the speed-up's start to twice its ramp: the largest value.
double worstOverBudget(const Drive& d, double rhoH, double Df, double budget, double h) {
    auto velocity = [&](double t) {
        return d.v0 * (smoothRampVelocity(t, d.rampTime) + (d.speedup - 1) * smoothRampVelocity(t - d.speedupStart, d.speedupRamp));
    };
    double worst = 0;
    for (double t = d.speedupStart; t < d.speedupStart + 2 * d.speedupRamp; t += h) {
        const double a = (velocity(t + h) - velocity(t)) / h, v = velocity(t + h);
        worst = std::max(worst, rhoH * (a + Df * v) / budget);
    }
    return worst;
}

// The 0.96 m triangular cube, seed 1 (study_in_an_hour.md): rho H = 2400 x 0.96,
// v0 = 0.02 x 0.96 (the most-pulled edge), D_f = 127.6 1/s, peak 1.65 MPa, t_r = 3.94 ms,
// a record every T = 6.3e-5 s. S_d = 0.1 x 1.65e6 / (2304 x 0.0192 x 127.6) = 29.2.
struct Cube096 {
    double rhoH = 2400 * 0.96, v0 = 0.02 * 0.96, Df = 127.6, peak = 1.65e6, tr = 3.94e-3, T = 6.3e-5;
    AdaptiveDrive::Limits limits(double drag = 0.1) const {
        return {20, 2000, 0.005, drag, 1.1, 0, rhoH * v0 / T, Df * T, T};
    }
};

TEST(TailBound, TheRampAfterTheLossStaysWithinTheBudgetAndTouchesIt) {
    const Cube096 c;
    const AdaptiveDrive::Limits l = c.limits();
    const double Sd = AdaptiveDrive::steadyBound(l, c.peak);
    EXPECT_NEAR(Sd, 0.1 * c.peak / (c.rhoH * c.v0 * c.Df), 1e-12 * Sd);
    EXPECT_NEAR(Sd, 29.2, 0.05);
    const AdaptiveDrive::Ramp r = AdaptiveDrive::rampAfterLoss(l, c.peak, c.tr);
    EXPECT_DOUBLE_EQ(r.floor, Sd / 2);  // below loss_speedup's 20: half the budget left to drag
    const double tq = pi * (r.floor - 1) / (2 * c.Df * std::sqrt((Sd - r.floor) * (Sd - 1)));
    EXPECT_NEAR(r.time, tq, 1e-12 * tq);
    EXPECT_GT(r.time, 2 * c.tr);
    Drive d{c.v0, c.tr, r.floor, 0.2, r.time};
    const double budget = 0.1 * c.peak;
    const double worst = worstOverBudget(d, c.rhoH, c.Df, budget, r.time * 1e-5);
    EXPECT_LE(worst, 1 + 1e-4);
    EXPECT_GT(worst, 0.999);  // the shortest ramp: it touches the budget
    // The fixed drive's ramp (20 over t_r) is 2.4 times over it (24 % of the peak): what broke bars.
    Drive fixed{c.v0, c.tr, 20, 0.2, c.tr};
    EXPECT_NEAR(worstOverBudget(fixed, c.rhoH, c.Df, budget, c.tr * 1e-5), 2.42, 0.02);
}

TEST(TailBound, WhereTheBudgetAllowsTheFixedRampItIsThatRamp) {
    // The 0.12 m uniform cube: S_d = 320 (adaptive_drive.md); the fixed ramp to 20 over two periods.
    Cube096 c;
    c.rhoH = 2400 * 0.12, c.v0 = 0.02 * 0.12, c.Df = 1021, c.peak = 2.35e6, c.tr = 4 * pi / (c.Df / 0.04);
    const AdaptiveDrive::Ramp r = AdaptiveDrive::rampAfterLoss(c.limits(), c.peak, c.tr);
    EXPECT_EQ(r.floor, 20.0);
    EXPECT_EQ(r.time, c.tr);
    // A budget so small that even the floor 1 is above it: no speed-up at all.
    const AdaptiveDrive::Ramp none = AdaptiveDrive::rampAfterLoss(c.limits(1e-4), c.peak, c.tr);
    EXPECT_EQ(none.floor, 1.0);
    // No bound (undamped or no column): the fixed ramp.
    AdaptiveDrive::Limits free = c.limits();
    free.column = 0;
    EXPECT_TRUE(std::isinf(AdaptiveDrive::steadyBound(free, c.peak)));
    EXPECT_EQ(AdaptiveDrive::rampAfterLoss(free, c.peak, c.tr).floor, 20.0);
}

// The 0.08 m cube (4 x 4 x 4 modules), seed 2, with tail_drag 0.005: S_d ~ 25,
// so the ramp goes to S_d / 2 and the record-wise drive, once the lattice is
// quiet, up to S_d and no further. S_d from the run's rho, H, v0, D_f = 2
// zeta omega_1 and peak: a bound built on one step's D_f dt instead of the
// record's D_f T (R times too little drag) would let the drive go R times faster.
TEST(TailBound, InARunTheDriveGoesUpToTheSteadyBoundOfItsFormulaAndNoFurther) {
    Material m;
    LoadingParams lp;
    lp.tailDrag = 0.005;
    RunParams rp;
    rp.threads = 1, rp.seed = 2;
    Simulation sim(cubeTestSpecimen(4, 4, 4, 0.02, m, lp), m, lp, rp);
    const auto& part = std::get<AdaptiveTailDrive>(sim.parts().drive());
    double fastest = 0, fastestMeasured = 0;
    CurvePoint last{};
    bool any = false;
    const RunSummary s = sim.run([&](const CurvePoint& p) {
        if (part.adaptive().active()) fastest = std::max(fastest, part.adaptive().speedFactor());
        if (any && p.time > last.time)  // the drive's mean velocity over the record, over v0 (uniform: U = H x mean strain)
            fastestMeasured = std::max(fastestMeasured, (p.meanStrain - last.meanStrain) / (p.time - last.time) / lp.strainRate);
        last = p, any = true;
        return true;
    });
    ASSERT_EQ(s.stopReason, "separated");
    const double H = sim.measures().gaugeLength, v0 = lp.strainRate * H, Df = 2 * rp.zeta * sim.frequencies().omega1;
    const double Sd = lp.tailDrag * s.peakStress / (m.rho * H * v0 * Df);
    ASSERT_GT(Sd, 4) << "the bound should bind well above the initial rate";
    ASSERT_LT(Sd, 40) << "and below loss_speedup's 20 x 2";
    // The ramp: the floor and its time by the formula.
    const Drive& d = part.program();
    EXPECT_NEAR(d.speedup, Sd / 2, 1e-9 * Sd);
    const double tq = pi * (Sd / 2 - 1) / (2 * Df * std::sqrt((Sd / 2) * (Sd - 1)));
    EXPECT_NEAR(d.speedupRamp, std::max(d.rampTime, tq), 1e-9 * tq);
    EXPECT_LE(worstOverBudget(d, m.rho * H, Df, lp.tailDrag * s.peakStress, d.speedupRamp * 1e-4), 1 + 1e-3);
    // Then up to S_d, not beyond.
    EXPECT_LE(fastest, Sd * (1 + 1e-9));
    EXPECT_GT(fastest, 0.95 * Sd);
    EXPECT_LE(fastestMeasured, Sd * (1 + 1e-9));
    EXPECT_GT(fastestMeasured, 0.9 * Sd);
}

}  // namespace
