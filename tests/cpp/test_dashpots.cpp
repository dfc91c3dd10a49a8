// The bars' dashpots (dynamics/BarDashpots.hpp, BarDashpot.hpp): on bars that
// all carry one they are stiffness-proportional damping C = beta K, so mode i
// has the ratio beta omega_i / 2 (zeta_high at omega_max, zeta_high
// omega_1/omega_max at omega_1); the stable time step shrinks to
// (2/omega_max)(sqrt(1 + zeta^2) - zeta), no more and no less; their work is
// counted exactly; a run with them is bit-identical across thread counts and
// restarts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "ldem/InternalForces.hpp"
#include "ldem/Integrator.hpp"
#include "ldem/Modal.hpp"
#include "ldem/Simulation.hpp"
#include "ldem/dynamics/BarDashpots.hpp"

using namespace ldem;

namespace {

const double kL0 = 0.02;

// Every bar on the law's path, elastic, with a dashpot of ratio 1 (a bar law's
// row functor, laws/BarLaw.hpp): the force pass is then K x and C v = beta K v.
struct ElasticWithDashpots {
    static constexpr bool kElasticOnly = false;
    bool withElastic = true;
    ElasticWithDashpots forRow(std::int32_t, std::int64_t) const { return *this; }
    std::uint8_t path() const { return kExactPath; }
    void setPath(std::uint8_t) const {}
    double elastic(std::int64_t, const BarFamily&, double, double, double, double, double&, double&, double&) const {
        return 1;
    }
    template <class Stretch>
    double operator()(std::int64_t, double EA, const Stretch& s, double& gx, double& gy, double& gz) const {
        const double Fl = withElastic ? s.elasticForcePerLength(EA) : 0.0;
        gx = Fl * s.dx, gy = Fl * s.dy, gz = Fl * s.dz;
        return 1.0;
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

DashpotState dashpots(const Lattice& lat, double beta, double dt) {
    DashpotState d;
    d.beta = beta, d.halfDt = 0.5 * dt;
    d.force.assign(lat.numBars(), 0.0), d.closing.assign(lat.numLayers(), 0.0), d.opening.assign(lat.numLayers(), 0.0);
    return d;
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
// bar, after `steps` steps of dt from a random state (all modes present).
double freeVibrationEnergy(const Cube& s, double zeta, double dt, int steps) {
    const Lattice& lat = s.specimen.lattice;
    const auto& mask = s.specimen.prescribed.mask;
    DashpotState d = dashpots(lat, dashpotBeta(zeta, s.freq.omegaMax), dt);
    Field3 u = randomField(lat.numNodes(), 7, mask), v(lat.numNodes()), f(lat.numNodes());
    for (double* c : {u.x.data(), u.y.data(), u.z.data()})
        for (std::int64_t i = 0; i < lat.numNodes(); ++i) c[i] *= 1e-9;  // small strains: linear
    BarForceBuffers g;
    const CentralDifference cd(dt, 0.0);
    for (int k = 0; k < steps; ++k)
        layeredForces(lat, u, g, f, ElasticWithDashpots{}, [&](int m) { advanceLayer(lat, m, cd, mask, f, u, v); },
                      DashpotPass{&d, &v});
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
TEST(BarDashpots, RunWithThemIsBalancedAndDeterministic) {
    Material m;
    LoadingParams lp;
    lp.bottomLateralFree = true;  // rollers: faces that clap once the crack has run
    RunParams rp;
    rp.zetaHigh = 0.1, rp.dtSafety = 0.8, rp.finalStrain = 1.5e-3, rp.threads = 1;
    Simulation one(cubeTestSpecimen(4, 4, 4, kL0, m, lp), m, lp, rp);
    EXPECT_NEAR(one.stableTimeStepLimit(), 0.8 * 2 / one.frequencies().omegaMax * dampedStepFactor(0.1),
                1e-14 * one.dt());
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
}

// Their state (each bar's last dashpot force) goes through a checkpoint: a run
// stopped at a record and restored in a new simulation ends bit for bit as
// the straight one.
TEST(BarDashpots, CheckpointRoundTrip) {
    Material m;
    LoadingParams lp;
    lp.bottomLateralFree = true;
    RunParams rp;
    rp.zetaHigh = 0.1, rp.dtSafety = 0.8, rp.finalStrain = 4e-4, rp.threads = 1;
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
