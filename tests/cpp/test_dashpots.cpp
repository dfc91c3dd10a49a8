// The bars' dashpots (dynamics/BarDashpots.hpp, BarDashpot.hpp): on bars that
// all carry one they are stiffness-proportional damping C = beta K, so mode i
// has the ratio beta omega_i / 2 (zeta_high at omega_max, zeta_high
// omega_1/omega_max at omega_1); the stable time step shrinks to
// (2/omega_max)(sqrt(1 + zeta^2) - zeta), no more and no less; their work is
// counted exactly; a run with them is bit-identical across thread counts and
// restarts. Read at the predicted velocity (dashpot_velocity predicted): one
// mode follows its recurrence (BarDashpots.hpp), stable to h = omega dt = 2 while
// zeta h <= 1, with the damping ratio the recurrence gives at omega_1 and omega_max.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "Assembled.hpp"
#include "ldem/InternalForces.hpp"
#include "ldem/Integrator.hpp"
#include "ldem/Modal.hpp"
#include "ldem/RandomField.hpp"
#include "ldem/Simulation.hpp"
#include "ldem/dynamics/BarDashpots.hpp"

using namespace ldem;

namespace {

const double kL0 = 0.02;

// Every bar on the law's path, elastic, with a dashpot of ratio 1 (a bar law's
// row functor, laws/BarLaw.hpp): the force pass is then K x and C v = beta K v.
// someBars: a dashpot on about half the bars only (drawn per bar), C no longer beta K.
struct ElasticWithDashpots {
    static constexpr bool kElasticOnly = false;
    bool withElastic = true;
    bool someBars = false;
    std::int64_t from = 0, below = -1;  // below >= 0: a dashpot on the bars numbered [from, below) only
    std::int64_t first = 0;   // the row's first bar
    ElasticWithDashpots forRow(std::int32_t, std::int64_t rowFirst) const {
        ElasticWithDashpots row = *this;
        row.first = rowFirst;
        return row;
    }
    std::uint8_t path() const { return kExactPath; }
    void setPath(std::uint8_t) const {}
    double elastic(std::int64_t, const BarFamily&, double, double, double, double, double&, double&, double&) const {
        return 1;
    }
    template <class Stretch>
    double operator()(std::int64_t p, double EA, const Stretch& s, double& gx, double& gy, double& gz) const {
        const double Fl = withElastic ? s.elasticForcePerLength(EA) : 0.0;
        gx = Fl * s.dx, gy = Fl * s.dy, gz = Fl * s.dz;
        if (below >= 0) return double(first + p >= from && first + p < below);
        return someBars ? double(hashedUniform(11, std::uint64_t(first + p), 0) < 0.5) : 1.0;
    }
};

struct Cube {
    Specimen specimen;
    Frequencies freq;
};

Cube cube3() {
    Material m;
    LoadingParams lp;
    Cube s{cubeTestSpecimen(3, 3, 3, kL0, m, lp), {}};
    s.freq = latticeFrequencies(s.specimen.lattice, s.specimen.prescribed.mask);
    return s;
}

// A 3 x 3 x 8 cube: 17 node layers, enough for layer rings of three buffers.
Specimen tallCube() {
    Material m;
    LoadingParams lp;
    return cubeTestSpecimen(3, 3, 8, kL0, m, lp);
}

DashpotState dashpots(const Lattice& lat, double beta, double dt, bool predicted = false, bool slab = false) {
    DashpotState d = dashpotState(beta, lat.numBars(), lat.numLayers(), std::int64_t(lat.barRows.size()),
                                  lat.numNodes(), predicted, slab);
    d.halfDt = 0.5 * dt;
    return d;
}

// One step of central differences with the dashpots of d: in one pass (lagged), or the force
// pass moving the layers that do not wait, then the dashpots at the predicted velocity, then
// the layers that waited (predicted: Simulation's way).
void step(const Lattice& lat, const std::vector<std::uint8_t>& mask, const ElasticWithDashpots& law,
          const CentralDifference& cd, DashpotState& d, BarForceBuffers& g, Field3& u, Field3& v, Field3& f) {
    if (!d.predicted) {
        layeredForces(lat, u, g, f, law, [&](int m) { advanceLayer(lat, m, cd, mask, f, u, v); }, DashpotPass{&d, &v});
        return;
    }
    layeredForces(lat, u, g, f, law, [&](int m) {
        if (!d.waits(m)) advanceLayer(lat, m, cd, mask, f, u, v);
    }, DashpotPass{&d, &v});
    predictedDashpots(lat, mask, u, v, d, f, [&](int m) { advanceLayer(lat, m, cd, mask, f, u, v); });
}

Field3 randomField(std::int64_t n, unsigned seed, const std::vector<std::uint8_t>& mask) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(-1, 1);
    Field3 x(n);
    for (std::int64_t i = 0; i < n; ++i) {
        x.x[i] = mask[i] & 1 ? 0 : U(rng), x.y[i] = mask[i] & 2 ? 0 : U(rng), x.z[i] = mask[i] & 4 ? 0 : U(rng);
    }
    return x;
}

double dot(const Field3& a, const Field3& b) {
    double s = 0;
    for (std::size_t i = 0; i < a.x.size(); ++i) s += a.x[i] * b.x[i] + a.y[i] * b.y[i] + a.z[i] * b.z[i];
    return s;
}

// Energy 1/2 v.M v + 1/2 x.K x of the free vibration with dashpots on every
// bar (someBars: on half of them), after `steps` steps of dt from a random state (all modes present).
double freeVibrationEnergy(const Cube& s, double zeta, double dt, int steps, bool predicted = false,
                           bool someBars = false) {
    const Lattice& lat = s.specimen.lattice;
    const auto& mask = s.specimen.prescribed.mask;
    DashpotState d = dashpots(lat, dashpotBeta(zeta, s.freq.omegaMax), dt, predicted);
    Field3 u = randomField(lat.numNodes(), 7, mask), v(lat.numNodes()), f(lat.numNodes());
    for (double* c : {u.x.data(), u.y.data(), u.z.data()})
        for (std::int64_t i = 0; i < lat.numNodes(); ++i) c[i] *= 1e-9;  // small strains: linear
    BarForceBuffers g;
    const CentralDifference cd(dt, 0.0);
    ElasticWithDashpots law;
    law.someBars = someBars;
    for (int k = 0; k < steps; ++k) step(lat, mask, law, cd, d, g, u, v, f);
    Field3 Ku(lat.numNodes());
    linearStiffnessProduct(lat, u, g, Ku);
    double kinetic = 0;
    for (std::int64_t i = 0; i < lat.numNodes(); ++i)
        kinetic += 0.5 * lat.mass[i] * (v.x[i] * v.x[i] + v.y[i] * v.y[i] + v.z[i] * v.z[i]);
    return kinetic + 0.5 * dot(u, Ku);
}

}  // namespace

// C = beta K: the dashpots' forces at u = 0 and velocity x are -beta K x, so
// every mode i has the damping ratio beta omega_i / 2: zeta_high at omega_max,
// zeta_high omega_1/omega_max at omega_1.
TEST(BarDashpots, AreStiffnessProportionalDamping) {
    const Cube s = cube3();
    const Lattice& lat = s.specimen.lattice;
    const double zeta = 0.1, beta = dashpotBeta(zeta, s.freq.omegaMax);
    EXPECT_DOUBLE_EQ(beta * s.freq.omegaMax / 2, zeta);                              // at omega_max
    EXPECT_DOUBLE_EQ(beta * s.freq.omega1 / 2, zeta * s.freq.omega1 / s.freq.omegaMax);  // at omega_1

    DashpotState d = dashpots(lat, beta, 1e-7);
    const Field3 x = randomField(lat.numNodes(), 3, s.specimen.prescribed.mask);
    const Field3 zero(lat.numNodes());
    Field3 fd(lat.numNodes()), Kx(lat.numNodes());
    BarForceBuffers g;
    layeredForces(lat, zero, g, fd, ElasticWithDashpots{false}, [](int) {}, DashpotPass{&d, &x});
    linearStiffnessProduct(lat, x, g, Kx);
    double worst = 0, scale = 0;
    for (std::int64_t i = 0; i < lat.numNodes(); ++i)
        for (auto [a, b] : {std::pair{fd.x[i], Kx.x[i]}, {fd.y[i], Kx.y[i]}, {fd.z[i], Kx.z[i]}})
            worst = std::max(worst, std::abs(a + beta * b)), scale = std::max(scale, std::abs(beta * b));
    EXPECT_LT(worst, 1e-12 * scale);
    // Their power, -v.f_d = beta v.K v >= 0: the two halves of the bar loop's work sums
    // (opening = s F dt/2 with F = beta (EA/L) s) add up to it.
    double opening = 0;
    for (double w : d.opening) opening += w;
    EXPECT_NEAR(opening, -0.5 * 1e-7 * dot(x, fd), 1e-12 * std::abs(opening));
    EXPECT_GT(opening, 0);
}

// The stable step with an explicit damping ratio zeta on the highest mode is
// (2/omega_max)(sqrt(1 + zeta^2) - zeta): free vibration with dashpots on every
// bar decays 1 % below it and blows up 1 % above it, and the undamped limit
// 2/omega_max is unstable with zeta = 0.3.
TEST(BarDashpots, ShrinkTheStableTimeStepByTheirFactor) {
    const Cube s = cube3();
    const double zeta = 0.3, bound = 2 / s.freq.omegaMax * dampedStepFactor(zeta);
    EXPECT_NEAR(dampedStepFactor(zeta), 0.7440306509, 1e-9);
    // (1/2 v.M v + 1/2 x.K x is not what central differences conserve: near the
    // limit it swings by a factor of a few; a blow-up is a factor of 1e6 or NaN.)
    const double e0 = freeVibrationEnergy(s, zeta, 0.99 * bound, 0);
    auto stable = [&](double zeta, double dt) { return freeVibrationEnergy(s, zeta, dt, 3000) < 10 * e0; };
    EXPECT_TRUE(stable(zeta, 0.99 * bound));
    EXPECT_FALSE(stable(zeta, 1.01 * bound));
    EXPECT_FALSE(stable(zeta, 0.9 * 2 / s.freq.omegaMax));
    EXPECT_TRUE(stable(0.0, 0.9 * 2 / s.freq.omegaMax));  // undamped, the same step is stable
}

// A run takes them into its time step, its energy balance and its checkpoints;
// 1, 2 and 3 threads give the same bits; off (zeta_high 0) nothing changes.
// Read at the predicted velocity, the step is 0.8 of the undamped limit.
void runIsBalancedAndDeterministic(bool predicted) {
    Material m;
    LoadingParams lp;
    lp.bottomLateralFree = true;  // rollers: faces that clap once the crack has run
    RunParams rp;
    rp.zetaHigh = 0.1, rp.dtSafety = 0.8, rp.finalStrain = 1.5e-3, rp.threads = 1, rp.dashpotPredicted = predicted;
    Simulation one(cubeTestSpecimen(4, 4, 4, kL0, m, lp), m, lp, rp);
    EXPECT_NEAR(one.stableTimeStepLimit(),
                0.8 * 2 / one.frequencies().omegaMax * (predicted ? 1.0 : dampedStepFactor(0.1)), 1e-14 * one.dt());
    std::vector<CurvePoint> rows;
    const RunSummary a = one.run([&](const CurvePoint& p) { return rows.push_back(p), true; });
    ASSERT_GT(a.loadLoss.step, 0) << "the cube must break for the test to mean anything";
    EXPECT_LT(a.energyBalanceError, 1e-2);
    EXPECT_GT(rows.back().damping, rows[rows.size() / 2].damping);
    for (int threads : {2, 3}) {
        RunParams rt = rp;
        rt.threads = threads;
        Simulation other(cubeTestSpecimen(4, 4, 4, kL0, m, lp), m, lp, rt);
        const RunSummary b = other.run();
        EXPECT_EQ(std::memcmp(&a.peakStress, &b.peakStress, sizeof(double)), 0) << threads << " threads";
        EXPECT_EQ(std::memcmp(&a.fractureEnergy, &b.fractureEnergy, sizeof(double)), 0) << threads << " threads";
        EXPECT_EQ(std::memcmp(&a.energyBalanceError, &b.energyBalanceError, sizeof(double)), 0) << threads;
        EXPECT_EQ(a.steps, b.steps);
    }
    std::printf("[ dashpots ] %s: dt %.4g s, %lld steps, balance error %.3g, load lost at %.4g\n",
                predicted ? "predicted" : "lagged", one.dt(), (long long)a.steps, a.energyBalanceError,
                a.loadLoss.meanStrain);
}
TEST(BarDashpots, RunWithThemIsBalancedAndDeterministic) { runIsBalancedAndDeterministic(false); }
TEST(BarDashpots, RunWithPredictedOnesIsBalancedAndDeterministic) { runIsBalancedAndDeterministic(true); }

// Their state (each bar's last dashpot force) goes through a checkpoint: a run
// stopped at a record and restored in a new simulation ends bit for bit as
// the straight one.
void checkpointRoundTrip(bool predicted) {
    Material m;
    LoadingParams lp;
    lp.bottomLateralFree = true;
    RunParams rp;
    rp.zetaHigh = 0.1, rp.dtSafety = 0.8, rp.finalStrain = 4e-4, rp.threads = 1, rp.dashpotPredicted = predicted;
    Simulation straight(cubeTestSpecimen(3, 3, 3, kL0, m, lp), m, lp, rp);
    const RunSummary want = straight.run();
    Simulation first(cubeTestSpecimen(3, 3, 3, kL0, m, lp), m, lp, rp);
    Checkpoint c;
    bool taken = false;
    first.run([&](const CurvePoint& p) {
        if (p.broken > 0 && !taken) c = first.checkpoint(), taken = true;
        return !taken;
    });
    ASSERT_TRUE(taken);
    Simulation second(cubeTestSpecimen(3, 3, 3, kL0, m, lp), m, lp, rp);
    second.restore(c);
    const RunSummary got = second.run();
    EXPECT_EQ(std::memcmp(&want.fractureEnergy, &got.fractureEnergy, sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(&want.energyBalanceError, &got.energyBalanceError, sizeof(double)), 0);
    EXPECT_EQ(want.steps, got.steps);
}
TEST(BarDashpots, CheckpointRoundTrip) { checkpointRoundTrip(false); }
TEST(BarDashpots, PredictedCheckpointRoundTrip) { checkpointRoundTrip(true); }

namespace {
// The recurrence of one mode with the dashpot read at the predicted velocity (BarDashpots.hpp):
// x_n, w_n = dt v(n-1/2); its amplification matrix's trace and determinant.
struct Recurrence {
    double trace, det;
};
Recurrence predictedRecurrence(double h, double zeta) {
    return {2 - 2 * zeta * h - h * h * (1 - zeta * h), 1 - 2 * zeta * h};
}
// The damping ratio of a recurrence whose roots are r e^(+-i theta): r = exp(-zeta_e omega_e dt),
// theta = omega_e sqrt(1 - zeta_e^2) dt (a double root -r: theta = pi).
double effectiveZeta(const Recurrence& a) {
    const double r = std::sqrt(a.det), theta = std::acos(std::clamp(a.trace / (2 * r), -1.0, 1.0));
    return -std::log(r) / std::hypot(theta, std::log(r));
}
// trace and det of q_n+1 = trace q_n - det q_n-1, fitted to q (least squares).
Recurrence fitted(const std::vector<double>& q) {
    Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
    Eigen::Vector2d b = Eigen::Vector2d::Zero();
    for (std::size_t n = 1; n + 1 < q.size(); ++n) {
        const Eigen::Vector2d row(q[n], -q[n - 1]);
        A += row * row.transpose(), b += row * q[n + 1];
    }
    const Eigen::Vector2d x = A.ldlt().solve(b);
    return {x(0), x(1)};
}
}  // namespace

// One free DOF (the centre node of one module along z, every other DOF held), dashpots on its 8
// bars read at the predicted velocity: x_n follows the recurrence of BarDashpots.hpp,
//   w_n+1 = (1 - 2 zeta h) w_n - h^2 (1 - zeta h) x_n,  x_n+1 = x_n + w_n+1,  zeta = beta omega / 2,
// and its energy decays just inside h <= 2, zeta h <= 1 and grows just outside either bound.
TEST(DirectBarDashpots, PredictedOneDofFollowsItsRecurrence) {
    Material m;
    Specimen one = cubeTestSpecimen(1, 1, 1, kL0, m, LoadingParams{});
    const Lattice& lat = one.lattice;
    const std::int32_t centre = lat.centreId(0, 0, 0);
    for (std::int32_t i = 0; i < std::int32_t(lat.numNodes()); ++i)
        for (int c = 0; c < 3; ++c)
            if (!(one.prescribed.mask[i] & (1u << c)) && !(i == centre && c == 2)) one.prescribed.add(i, c, 0.0);
    const auto& mask = one.prescribed.mask;
    // omega^2 = K_zz / m: 8 diagonals of EA_d/L_d with n_z^2 = 1/3, on half a module's mass.
    const double Ld = std::sqrt(3.0) / 2 * kL0, EAd = m.E * 2 * nayfehDelta(m.nu) / std::sqrt(3.0) * nayfehPhi(m.nu) * kL0 * kL0;
    const double omega = std::sqrt(8 * EAd / Ld / 3 / (0.5 * m.rho * std::pow(kL0, 3)));
    EXPECT_NEAR(latticeFrequencies(lat, mask).omega1, omega, 1e-9 * omega);
    auto run = [&](double h, double zeta, int steps, std::vector<double>* x) {
        const double dt = h / omega;
        DashpotState d = dashpots(lat, 2 * zeta / omega, dt, true);
        Field3 u(lat.numNodes()), v(lat.numNodes()), f(lat.numNodes());
        BarForceBuffers g;
        u.z[centre] = 1e-9;
        for (int k = 0; k < steps; ++k) {
            if (x) x->push_back(u.z[centre]);
            step(lat, mask, ElasticWithDashpots{}, CentralDifference(dt, 0.0), d, g, u, v, f);
        }
        return std::hypot(u.z[centre] * omega, v.z[centre]) / (1e-9 * omega);  // ~ the amplitude
    };
    for (auto [h, zeta] : {std::pair{1.99, 0.3}, {1.2, 0.5}, {0.5, 1.9}, {1.6, 0.2}}) {
        std::vector<double> x;
        run(h, zeta, 60, &x);
        double xr = x[0], wr = 0, worst = 0;  // the recurrence from the same start, w_0 = 0
        for (std::size_t n = 0; n < x.size(); ++n) {
            worst = std::max(worst, std::abs(x[n] - xr));
            wr = (1 - 2 * zeta * h) * wr - h * h * (1 - zeta * h) * xr, xr += wr;
        }
        EXPECT_LT(worst, 1e-7 * x[0]) << "h " << h << ", zeta " << zeta;
    }
    // (grown past 1e6 or to NaN: the bars' geometry does not survive a blow-up)
    auto unstable = [&](double h, double zeta) { return !(run(h, zeta, 3000, nullptr) < 1e6); };
    EXPECT_LT(run(0.99 * 2, 0.3, 3000, nullptr), 1.0);  // h just below 2, zeta h = 0.59
    EXPECT_TRUE(unstable(1.01 * 2, 0.3));                // h just above 2
    EXPECT_LT(run(1.5, 0.99 / 1.5, 3000, nullptr), 1.0); // zeta h = 0.99
    EXPECT_TRUE(unstable(1.5, 1.01 / 1.5));              // zeta h = 1.01, h < 2
}

// The same bound on a lattice, all its modes at once (the 3^3 cube, a random start): with the
// dashpots read at the predicted velocity, 2/omega_max is stable with zeta_high 0.3, where the
// lagged dashpots need 0.744 of it; zeta_high 0.7 holds the step to 1/(zeta_high omega_max).
// With dashpots on half the bars only (C no longer proportional to K) the same bounds hold.
TEST(BarDashpots, PredictedReachTheUndampedStableStep) {
    const Cube s = cube3();
    const double limit = 2 / s.freq.omegaMax;
    EXPECT_DOUBLE_EQ(predictedStepFactor(0.3), 1.0);
    EXPECT_DOUBLE_EQ(predictedStepFactor(0.7), 0.5 / 0.7);
    const double e0 = freeVibrationEnergy(s, 0.3, 0.99 * limit, 0, true);
    auto stable = [&](double zeta, double dt, bool someBars) {
        return freeVibrationEnergy(s, zeta, dt, 3000, true, someBars) < 10 * e0;
    };
    for (bool someBars : {false, true}) {
        SCOPED_TRACE(someBars ? "dashpots on half the bars" : "dashpots on every bar");
        EXPECT_TRUE(stable(0.3, 0.99 * limit, someBars));
        EXPECT_FALSE(stable(0.3, 1.01 * limit, someBars));
        EXPECT_TRUE(stable(0.7, 0.99 * limit * predictedStepFactor(0.7), someBars));
    }
    EXPECT_FALSE(stable(0.7, 1.01 * limit * predictedStepFactor(0.7), false));
    EXPECT_FALSE(freeVibrationEnergy(s, 0.3, 0.99 * limit, 3000, false) < 10 * e0);  // lagged: unstable there
}

// Only the node layers an acting dashpot pulls wait for the predicted pass; the others move in
// the force sweep. Dashpots in one bar layer of a 3 x 3 x 8 cube (they pull three node layers):
// the run is the one where every layer waits (a slab's way), bit for bit.
TEST(BarDashpots, OnlyTheLayersTheActingDashpotsPullWait) {
    const Specimen sp = tallCube();
    const Lattice& lat = sp.lattice;
    const auto& mask = sp.prescribed.mask;
    const double omegaMax = latticeFrequencies(lat, mask).omegaMax, dt = 0.9 * 2 / omegaMax;
    ElasticWithDashpots law;
    const int k = lat.numLayers() / 2;  // the bar layer with the dashpots
    law.from = lat.barRows[std::size_t(lat.barLayerStart[k])].first;
    law.below = lat.barRows[std::size_t(lat.barLayerStart[k + 1])].first;
    const CentralDifference cd(dt, 0.0);
    auto run = [&](bool everyLayer, int& waiting) {
        DashpotState d = dashpots(lat, dashpotBeta(0.5, omegaMax), dt, true, everyLayer);
        Field3 u = randomField(lat.numNodes(), 5, mask), v(lat.numNodes()), f(lat.numNodes());
        for (double* c : {u.x.data(), u.y.data(), u.z.data()})
            for (std::int64_t i = 0; i < lat.numNodes(); ++i) c[i] *= 1e-9;
        BarForceBuffers g;
        for (int k = 0; k < 200; ++k) step(lat, mask, law, cd, d, g, u, v, f);
        waiting = 0;
        for (int l = 0; l < lat.numLayers(); ++l) waiting += d.waits(l);
        return u;
    };
    int some = 0, all = 0;
    const Field3 a = run(false, some), b = run(true, all);
    EXPECT_EQ(some, 3);
    EXPECT_EQ(all, lat.numLayers());
    for (std::int64_t i = 0; i < lat.numNodes(); ++i) {
        ASSERT_EQ(a.x[i], b.x[i]) << i;
        ASSERT_EQ(a.y[i], b.y[i]) << i;
        ASSERT_EQ(a.z[i], b.z[i]) << i;
    }
}

// The damping ratio a mode gets (the 3^3 cube's omega_1 and omega_max, dense modes, dashpots on
// every bar: C = beta K, zeta_i = beta omega_i / 2): started in the mode, the mode's coordinate
// q_n = phi'M x_n follows q_n+1 = trace q_n - det q_n-1 with the trace and det of the predicted
// recurrence at h_i = omega_i dt and zeta_i, whence its damping ratio per step.
TEST(BarDashpots, PredictedDampingRatioAtOmega1AndOmegaMax) {
    const Cube s = cube3();
    const Lattice& lat = s.specimen.lattice;
    const auto& mask = s.specimen.prescribed.mask;
    const Eigen::MatrixXd K = assembleStiffness(lat);
    std::vector<Eigen::Index> dofs;
    for (std::int64_t i = 0; i < lat.numNodes(); ++i)
        for (int c = 0; c < 3; ++c)
            if (!(mask[i] & (1u << c))) dofs.push_back(3 * i + c);
    const Eigen::Index n = Eigen::Index(dofs.size());
    Eigen::MatrixXd A(n, n);
    Eigen::VectorXd sq(n);  // M^-1/2
    for (Eigen::Index a = 0; a < n; ++a) sq(a) = 1 / std::sqrt(lat.mass[dofs[a] / 3]);
    for (Eigen::Index a = 0; a < n; ++a)
        for (Eigen::Index c = 0; c < n; ++c) A(a, c) = sq(a) * K(dofs[a], dofs[c]) * sq(c);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(A);
    const double zetaHigh = 0.2, beta = dashpotBeta(zetaHigh, s.freq.omegaMax), dt = 0.8 * 2 / s.freq.omegaMax;
    for (const Eigen::Index mode : {Eigen::Index(0), n - 1}) {
        const double omega = std::sqrt(es.eigenvalues()(mode)), h = omega * dt, zeta = beta * omega / 2;
        Field3 phi(lat.numNodes()), u(lat.numNodes()), v(lat.numNodes()), f(lat.numNodes());
        for (Eigen::Index a = 0; a < n; ++a) phi[int(dofs[a] % 3)][dofs[a] / 3] = sq(a) * es.eigenvectors()(a, mode);
        const double amplitude = 1e-10;  // displacements ~ 1e-9 m (phi M-normal: entries ~ 1/sqrt(node mass) ~ 10)
        for (int c = 0; c < 3; ++c)
            for (std::size_t i = 0; i < phi.x.size(); ++i) u[c][i] = amplitude * phi[c][i];
        DashpotState d = dashpots(lat, beta, dt, true);
        BarForceBuffers g;
        std::vector<double> q;
        const int steps = mode == 0 ? 400 : 25;  // (at omega_max the mode is gone to 3e-6 in 25 steps)
        for (int k = 0; k < steps; ++k) {
            double qk = 0;
            for (std::size_t i = 0; i < phi.x.size(); ++i)
                for (int c = 0; c < 3; ++c) qk += lat.mass[i] * phi[c][i] * u[c][i];
            q.push_back(qk / amplitude);
            step(lat, mask, ElasticWithDashpots{}, CentralDifference(dt, 0.0), d, g, u, v, f);
        }
        const Recurrence want = predictedRecurrence(h, zeta), got = fitted(q);
        SCOPED_TRACE(testing::Message() << (mode == 0 ? "omega_1" : "omega_max") << " = " << omega << ", h = " << h);
        EXPECT_NEAR(got.trace, want.trace, 1e-6);
        EXPECT_NEAR(got.det, want.det, 1e-6);
        EXPECT_NEAR(effectiveZeta(got), effectiveZeta(want), 1e-5 * effectiveZeta(want));
        std::printf("[ dashpots ] predicted, %s: h %.4f, zeta = beta omega/2 %.5f, per step %.5f (recurrence %.5f), "
                    "lagged's %.5f\n", mode == 0 ? "omega_1  " : "omega_max", h, zeta, effectiveZeta(got),
                    effectiveZeta(want), effectiveZeta({2 - 2 * zeta * h - h * h, 1 - 2 * zeta * h}));
        if (mode == 0) EXPECT_NEAR(effectiveZeta(got), zeta, 0.02 * zeta);  // h small: the continuous ratio
    }
}

// The dashpots' forces on the nodes, read at the predicted velocity, are the sum bar by bar of
// F = beta (EA/L) r d.(v~_B - v~_A)/L, whatever the layer buffers held before (here NaN): half
// the bars of two bar layers that share a buffer act, each row with bars that do not.
TEST(BarDashpots, PredictedForcesAreTheBarByBarSum) {
    const Specimen sp = tallCube();
    const Lattice& lat = sp.lattice;
    const auto& mask = sp.prescribed.mask;
    const double dt = 1e-6, beta = 1e-7;
    DashpotState d = dashpots(lat, beta, dt, true);
    Field3 u = randomField(lat.numNodes(), 3, mask), v = randomField(lat.numNodes(), 4, mask),
           f = randomField(lat.numNodes(), 6, mask);
    for (double* c : {u.x.data(), u.y.data(), u.z.data()})
        for (std::int64_t i = 0; i < lat.numNodes(); ++i) c[i] *= 1e-6;
    const Field3 fStar = f;
    for (int k : {3, 6}) {  // (one thread: ring buffer (k - 0) % 3 for both)
        d.layers[std::size_t(k)] = 1;
        for (std::int32_t r = lat.barLayerStart[k]; r < lat.barLayerStart[k + 1]; ++r) {
            d.rows[std::size_t(r)] = 1;
            const BarRow& row = lat.barRows[r];
            for (int p = 0; p < row.count; p += 2)
                d.coefficient[std::size_t(row.first + p)] = beta * lat.families[row.family].EA / lat.families[row.family].L;
        }
    }
    setThreads(1);
    d.forces.prepare(lat, 1);
    for (int k = 0; k < lat.numLayers(); ++k)
        for (double* g : {d.forces.x(k), d.forces.y(k), d.forces.z(k)})
            std::fill(g, g + lat.maxBarsInLayer, std::nan(""));
    predictedDashpots(lat, mask, u, v, d, f, [](int) {});
    Field3 expected = fStar;
    for (std::int64_t r = 0; r < std::int64_t(lat.barRows.size()); ++r) {
        const BarRow& row = lat.barRows[std::size_t(r)];
        const BarFamily& fam = lat.families[row.family];
        for (int p = 0; p < row.count; ++p) {
            const double c = d.coefficient[std::size_t(row.first + p)];
            if (c == 0) continue;
            const std::int32_t A = row.nodeA + p, B = row.nodeB + p;
            const auto vTilde = [&](std::int32_t i, int dim) {
                const double* vc[3] = {v.x.data(), v.y.data(), v.z.data()};
                const double* fc[3] = {fStar.x.data(), fStar.y.data(), fStar.z.data()};
                return (mask[i] >> dim) & 1 ? vc[dim][i] : vc[dim][i] + 0.5 * dt * fc[dim][i] * lat.invMass[i];
            };
            double dv[3], sp = 0;
            const double* uc[3] = {u.x.data(), u.y.data(), u.z.data()};
            for (int c3 = 0; c3 < 3; ++c3) dv[c3] = fam.d0[c3] + uc[c3][B] - uc[c3][A];
            for (int c3 = 0; c3 < 3; ++c3) sp += dv[c3] * (vTilde(B, c3) - vTilde(A, c3));
            const double Fl = c * sp * fam.invL * fam.invL;
            double* ec[3] = {expected.x.data(), expected.y.data(), expected.z.data()};
            for (int c3 = 0; c3 < 3; ++c3) ec[c3][A] += Fl * dv[c3], ec[c3][B] -= Fl * dv[c3];
        }
    }
    double scale = 0;
    for (std::int64_t i = 0; i < lat.numNodes(); ++i) scale = std::max(scale, std::abs(expected.x[i] - fStar.x[i]));
    ASSERT_GT(scale, 0);
    for (std::int64_t i = 0; i < lat.numNodes(); ++i) {
        ASSERT_NEAR(f.x[i], expected.x[i], 1e-9 * scale) << i;
        ASSERT_NEAR(f.y[i], expected.y[i], 1e-9 * scale) << i;
        ASSERT_NEAR(f.z[i], expected.z[i], 1e-9 * scale) << i;
    }
}
