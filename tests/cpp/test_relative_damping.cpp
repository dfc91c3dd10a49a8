// tail_damping relative (dynamics/MassDamping.hpp): from the load loss on the
// mass-proportional damping acts on v - vbar, vbar each node's velocity
// low-passed over tau. A rigid drift is then not damped (absolute: it is); a
// vibration at omega keeps the ratio (omega tau)^2 / (1 + (omega tau)^2) of
// its damping; the energy balance counts the work of the force applied; a run
// is bit-identical to the absolute one up to its load loss, across threads and
// through a checkpoint.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <tuple>
#include <vector>

#include "ldem/Simulation.hpp"

using namespace ldem;

namespace {

constexpr double pi = 3.14159265358979323846;

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// A mass damping on relative velocity, switched by a load loss at record `loss`.
MassDamping relativeDamping(double zeta, double omega1, const Field3& v) {
    MassDamping::Params p;
    p.zeta = zeta, p.tailDampingRelative = true, p.dampingFilterPeriods = 2;
    MassDamping d(p, omega1);
    RunSummary s;
    s.loadLoss.step = 100;
    d.record(DampingRecord{s, v});
    return d;
}

}  // namespace

// A drift at constant velocity V (no force): relative damping leaves it at V
// (v+ = (a + b D_f) V = V), absolute damping takes a^N of it.
TEST(DirectRelativeDamping, DoesNotDampARigidDrift) {
    const int n = 11;  // a block of 8 nodes and 3 one by one
    const std::vector<double> mass(n, 2.0), invMass(n, 0.5);
    const std::vector<std::uint8_t> mask(n, 0);
    const double dt = 1e-5, omega1 = 800, V = 0.3;
    Field3 u(n), v(n), f(n);
    for (int i = 0; i < n; ++i) v.x[i] = V, v.y[i] = -V, v.z[i] = 0.5 * V;
    Field3 ua = u, va = v;
    MassDamping rel = relativeDamping(0.02, omega1, v);
    MassDamping::Params p;
    p.zeta = 0.02;
    MassDamping abs(p, omega1);
    const CentralDifference cdRel = rel.nodeUpdate(CentralDifference(dt, 0)), cdAbs = abs.nodeUpdate(CentralDifference(dt, 0));
    ASSERT_NE(cdRel.mean, nullptr);
    EXPECT_EQ(cdAbs.mean, nullptr);
    double workRel = 0, workAbs = 0;
    const int steps = 2000;
    for (int k = 0; k < steps; ++k) {
        workRel += advanceNodes(0, n, mass, invMass, mask, cdRel, f, u, v);
        workAbs += advanceNodes(0, n, mass, invMass, mask, cdAbs, f, ua, va);
    }
    for (int i = 0; i < n; ++i) {
        EXPECT_NEAR(v.x[i], V, 1e-13 * V);
        EXPECT_NEAR(v.y[i], -V, 1e-13 * V);
        EXPECT_NEAR(u.x[i], V * dt * steps, 1e-10 * V * dt * steps);
        EXPECT_NEAR(va.x[i], std::pow(cdAbs.a, steps) * V, 1e-12 * V);
    }
    EXPECT_LT(va.x[0], 0.7 * V);  // D_f t = 0.64: absolute damping took a third of it
    // The work: none relative; absolute, the kinetic energy it took, exactly.
    const double k0 = 0.5 * 2.0 * n * (1 + 1 + 0.25) * V * V, ratio = va.x[0] / V;
    EXPECT_LT(std::abs(workRel), 1e-12 * k0);
    EXPECT_NEAR(workAbs, k0 * (1 - ratio * ratio), 1e-9 * k0);
}

// Free vibration of one DOF per node at omega (f = -k u), relative damping with
// tau = 2 periods: the amplitude decays at the rate (D_f/2) (omega tau)^2 /
// (1 + (omega tau)^2) = 0.9937 D_f/2 (absolute: D_f/2).
TEST(RelativeDamping, DampsAVibrationWithTheStatedRatio) {
    const int n = 11;
    const double m = 2.0, omega = 800, k = m * omega * omega, zeta = 0.02, dt = 2 * pi / omega / 2000;
    const std::vector<double> mass(n, m), invMass(n, 1 / m);
    const std::vector<std::uint8_t> mask(n, 0);
    Field3 u(n), v(n), f(n);
    for (int i = 0; i < n; ++i) u.x[i] = 1e-3 * (1 + 0.1 * i), u.y[i] = -1e-3, u.z[i] = 2e-3;
    MassDamping rel = relativeDamping(zeta, omega, v);  // vbar = v = 0
    const CentralDifference cd = rel.nodeUpdate(CentralDifference(dt, 0));
    const double tau = rel.filterTime(), share = relativeDampingShare(omega, tau);
    EXPECT_NEAR(share, 0.99371, 1e-5);  // omega tau = 4 pi
    // Amplitude peaks of u.x of the last node (the one-by-one path) and of the first (the block's).
    std::vector<std::pair<double, double>> peaks[2];
    double prev[2][2] = {{0, 0}, {0, 0}};
    const int nodes[2] = {0, n - 1};
    for (int s = 0; s < 2000 * 40; ++s) {
        for (int i = 0; i < n; ++i) f.x[i] = -k * u.x[i], f.y[i] = -k * u.y[i], f.z[i] = -k * u.z[i];
        advanceNodes(0, n, mass, invMass, mask, cd, f, u, v);
        for (int j = 0; j < 2; ++j) {
            const double x = u.x[nodes[j]];
            if (s > 1 && prev[j][1] > prev[j][0] && prev[j][1] > x) peaks[j].emplace_back((s - 1) * dt, prev[j][1]);
            prev[j][0] = prev[j][1], prev[j][1] = x;
        }
    }
    const double Df = 2 * zeta * omega;
    for (int j = 0; j < 2; ++j) {
        ASSERT_GE(peaks[j].size(), 38u);
        const auto& a = peaks[j][9];  // after the mean's transient (tau = 2 periods)
        const auto& b = peaks[j].back();
        const double rate = std::log(a.second / b.second) / (b.first - a.first);
        EXPECT_NEAR(rate / (Df / 2), share, 1e-3) << j;
    }
}

// One step from random v, vbar and f: the kinetic energy changes by the work
// of f over dt vmid less the damping work returned, sum D_f m (vmid - vbar) vmid dt,
// to round-off (the discrete balance is exact).
TEST(DirectRelativeDamping, ItsWorkIsTheWorkOfTheForceApplied) {
    const int n = 11;
    std::vector<double> mass(n), invMass(n);
    const std::vector<std::uint8_t> mask(n, 0);
    Field3 u(n), v(n), f(n), mean(n);
    for (int i = 0; i < n; ++i) {
        mass[i] = 1 + 0.3 * i, invMass[i] = 1 / mass[i];
        v.x[i] = std::sin(1.3 * i), v.y[i] = std::cos(0.7 * i), v.z[i] = 0.2;
        mean.x[i] = 0.5 * std::cos(2.1 * i), mean.y[i] = -0.4, mean.z[i] = 0.3 * std::sin(i);
        f.x[i] = 1e3 * std::cos(i), f.y[i] = -2e3, f.z[i] = 5e2 * std::sin(3.0 * i);
    }
    CentralDifference cd(1e-4, 500.0);
    cd.mean = &mean, cd.filter = 1e-2;
    const Field3 v0 = v, mean0 = mean;
    const double work = advanceNodes(0, n, mass, invMass, mask, cd, f, u, v);
    double dK = 0, fWork = 0, scale = 0;
    for (int i = 0; i < n; ++i)
        for (auto [a, b, fi, w0, w1] : {std::tuple{v0.x[i], v.x[i], f.x[i], mean0.x[i], mean.x[i]},
                                        {v0.y[i], v.y[i], f.y[i], mean0.y[i], mean.y[i]},
                                        {v0.z[i], v.z[i], f.z[i], mean0.z[i], mean.z[i]}}) {
            dK += 0.5 * mass[i] * (b * b - a * a), fWork += fi * 0.5 * (a + b) * cd.dt;
            scale += std::abs(fi * 0.5 * (a + b) * cd.dt);
            EXPECT_NEAR(w1, w0 + (b - w0) * cd.filter, 1e-15);  // the mean moved on
        }
    EXPECT_NEAR(dK, fWork - work, 1e-12 * scale);
    EXPECT_GT(std::abs(work), 1e-3 * scale);
}

namespace {

Simulation cube(bool relative, int threads, double finalStrain = 0.5) {
    Material m;
    LoadingParams lp;
    RunParams rp;
    rp.threads = threads, rp.finalStrain = finalStrain, rp.tailDampingRelative = relative;
    return Simulation(cubeTestSpecimen(4, 4, 4, 0.02, m, lp), m, lp, rp);
}

}  // namespace

// The 0.08 m cube to separation: up to the load loss the same bits as with
// absolute damping, then relative (switched); its energy balance closes as
// tightly as the absolute run's; 1, 2 and 3 threads give the same bits.
TEST(RelativeDamping, RunIsBalancedBitIdenticalBeforeTheLossAndAcrossThreads) {
    std::vector<CurvePoint> rowsAbs, rowsRel;
    Simulation a = cube(false, 1), r = cube(true, 1);
    const RunSummary sa = a.run([&](const CurvePoint& p) { return rowsAbs.push_back(p), true; });
    const RunSummary sr = r.run([&](const CurvePoint& p) { return rowsRel.push_back(p), true; });
    ASSERT_TRUE(sr.loadLoss.reached());
    ASSERT_EQ(sr.loadLoss.step, sa.loadLoss.step);
    EXPECT_TRUE(r.parts().damping<MassDamping>()->switched());
    EXPECT_FALSE(a.parts().damping<MassDamping>()->switched());
    std::size_t i = 0;
    for (; i < rowsAbs.size() && i < rowsRel.size() && rowsRel[i].step <= sr.loadLoss.step; ++i) {
        EXPECT_TRUE(sameBits(rowsAbs[i].stress, rowsRel[i].stress)) << i;
        EXPECT_TRUE(sameBits(rowsAbs[i].damping, rowsRel[i].damping)) << i;
        EXPECT_TRUE(sameBits(rowsAbs[i].kinetic, rowsRel[i].kinetic)) << i;
    }
    ASSERT_GT(i, 20u);
    ASSERT_LT(i + 5, rowsRel.size()) << "the run must go on past its load loss";
    EXPECT_FALSE(sameBits(rowsAbs[i + 5].damping, rowsRel[i + 5].damping));
    // The damping work past the loss is far below the absolute damping's (no drag on the moving part).
    const double lossDamping = rowsRel[i - 1].damping;
    EXPECT_LT(rowsRel[i + 5].damping - lossDamping, rowsAbs[i + 5].damping - lossDamping);
    // The suite's tolerance (test_dashpots.cpp); measured 1.8e-3, against 3.3e-4 absolute (the work per
    // step is exact: ItsWorkIsTheWorkOfTheForceApplied; the tails differ past the loss).
    EXPECT_LT(sr.energyBalanceError, 1e-2);
    for (int threads : {2, 3}) {
        Simulation other = cube(true, threads);
        const RunSummary b = other.run();
        EXPECT_TRUE(sameBits(sr.fractureEnergy, b.fractureEnergy)) << threads << " threads";
        EXPECT_TRUE(sameBits(sr.energyBalanceError, b.energyBalanceError)) << threads << " threads";
        EXPECT_EQ(sr.steps, b.steps) << threads << " threads";
    }
}

// Its state (switched, vbar of every node) goes through a checkpoint taken
// after the load loss: the restored run ends bit for bit as the straight one.
TEST(RelativeDamping, CheckpointRoundTrip) {
    const double finalStrain = 4e-3;
    Simulation straight = cube(true, 1, finalStrain);
    const RunSummary want = straight.run();
    ASSERT_TRUE(want.loadLoss.reached());
    Simulation first = cube(true, 1, finalStrain);
    Checkpoint c;
    int after = 0;
    first.run([&](const CurvePoint&) {
        if (first.summarySoFar().loadLoss.reached() && ++after == 3) c = first.checkpoint();
        return after < 3;
    });
    ASSERT_EQ(after, 3);
    Simulation second = cube(true, 1, finalStrain);
    second.restore(c);
    EXPECT_TRUE(second.parts().damping<MassDamping>()->switched());
    const RunSummary got = second.run();
    EXPECT_TRUE(sameBits(want.fractureEnergy, got.fractureEnergy));
    EXPECT_TRUE(sameBits(want.energyBalanceError, got.energyBalanceError));
    EXPECT_EQ(want.steps, got.steps);
}

// The adaptive drive with relative damping: no drag on a steady motion, so no
// steady bound (S_d infinite: the floor is loss_speedup) and a ramp bounded by
// inertia and the mean's lag alone, rho H v0 (1 + D_f tau) dS/dt <= tail_drag
// peak: its column carries 1 + D_f tau, its D_f T is 0.
TEST(RelativeDamping, TheAdaptiveDriveBoundsInertiaAlone) {
    Material m;
    LoadingParams lp;
    RunParams rp;
    rp.threads = 1, rp.tailDampingRelative = true;
    Simulation rel(cubeTestSpecimen(4, 4, 4, 0.02, m, lp), m, lp, rp);
    rp.tailDampingRelative = false;
    Simulation abs(cubeTestSpecimen(4, 4, 4, 0.02, m, lp), m, lp, rp);
    const AdaptiveDrive::Limits& lr = std::get<AdaptiveTailDrive>(rel.parts().drive()).adaptive().limits();
    const AdaptiveDrive::Limits& la = std::get<AdaptiveTailDrive>(abs.parts().drive()).adaptive().limits();
    const MassDamping& mass = *rel.parts().damping<MassDamping>();
    EXPECT_EQ(lr.dampingT, 0.0);
    EXPECT_GT(la.dampingT, 0.0);
    EXPECT_NEAR(lr.column, la.column * (1 + mass.coefficient() * mass.filterTime()), 1e-12 * lr.column);
    EXPECT_NEAR(mass.filterTime(), 2 * 2 * pi / rel.frequencies().omega1, 1e-12 * mass.filterTime());
    const double peak = 2.3e6;
    EXPECT_TRUE(std::isinf(AdaptiveDrive::steadyBound(lr, peak)));
    // The ramp to loss_speedup: the shortest whose largest rate pi (S_f - 1) / (2 t_q) is the budget's B / T.
    AdaptiveDrive::Limits tight = lr;
    tight.drag = 1e-4;  // a budget that makes the ramp longer than the smooth start's
    const AdaptiveDrive::Ramp r = AdaptiveDrive::rampAfterLoss(tight, peak, 1e-6);
    EXPECT_EQ(r.floor, lp.lossSpeedup);
    const double B = tight.drag * peak / tight.column;
    EXPECT_NEAR(pi * (r.floor - 1) / (2 * r.time) * tight.interval, B, 1e-12 * B);
    // The record-wise bound: S_1 <= S_0 + B, the drag's share gone.
    EXPECT_NEAR(AdaptiveDrive(tight).next(r.floor, false, 0.0, peak), r.floor + B, 1e-12 * r.floor);
}
