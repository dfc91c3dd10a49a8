// Hillerborg's triangle (LDEM_SPEC section 3): the pure functions of one bar,
// then the same law driven through the force loop (computeInternalForces) and
// the energy bookkeeping (barEnergies) on a one-module lattice, and the limit
// strain each bar of a Simulation gets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "StudyBar.hpp"
#include "ldem/InternalForces.hpp"
#include "ldem/Lattice.hpp"
#include "ldem/Parallel.hpp"
#include "ldem/RandomField.hpp"
#include "ldem/Simulation.hpp"
#include "ldem/laws/Hillerborg.hpp"

using namespace ldem;
using namespace ldem::hillerborg;

namespace {

// One normal bar of the study's material.
struct Bar : StudyBar {
    double epsR() const { return limitStrain(Af, Gf, EA, epsP, L).epsR; }
};

// Force along the loading envelope (monotonic pull): kappa = eps.
double envelope(const Bar& b, double eps) {
    return axialForce(eps, updateDamage(0.0, eps), b.EA, b.epsP, b.epsR());
}

// Work of the envelope force from 0 to e, L * integral F d(eps), by a fine
// trapezoid rule (the law is only evaluated, never integrated in closed form).
double envelopeWork(const Bar& b, double e, int n = 400000) {
    const double h = e / n;
    double w = 0.5 * (envelope(b, 0) + envelope(b, e));
    for (int i = 1; i < n; ++i) w += envelope(b, i * h);
    return w * h * b.L;
}

}  // namespace

TEST(HillerborgLaw, LimitStrainFromTriangleArea) {
    const Bar b;
    const LimitStrain ls = limitStrain(b.Af, b.Gf, b.EA, b.epsP, b.L);
    EXPECT_FALSE(ls.clamped);
    // 1/2 EA eps_p eps_r L = A_f G_f.
    EXPECT_NEAR(0.5 * b.EA * b.epsP * ls.epsR * b.L, b.Af * b.Gf, 1e-12 * b.Af * b.Gf);
    EXPECT_GT(ls.epsR, 10 * b.epsP);  // G_f = 100 N/m: a long softening branch (eps_r ~ 1.6e-3)
}

TEST(HillerborgLaw, MonotonicPullDissipatesAfGf) {
    const Bar b;
    const double epsR = b.epsR();
    // Up to eps_p: elastic.
    EXPECT_DOUBLE_EQ(envelope(b, 0.5 * b.epsP), b.EA * 0.5 * b.epsP);
    EXPECT_DOUBLE_EQ(envelope(b, b.epsP), b.EA * b.epsP);
    // Softening is linear: half way from eps_p to eps_r carries half the peak force.
    EXPECT_NEAR(envelope(b, 0.5 * (b.epsP + epsR)), 0.5 * b.EA * b.epsP, 1e-9 * b.EA * b.epsP);
    // No tension at and beyond eps_r.
    EXPECT_EQ(envelope(b, epsR), 0.0);
    EXPECT_EQ(envelope(b, 2 * epsR), 0.0);
    // Total work of a monotonic pull past eps_r = A_f G_f.
    const double W = envelopeWork(b, 1.3 * epsR);
    EXPECT_NEAR(W, b.Af * b.Gf, 1e-6 * b.Af * b.Gf);
    EXPECT_DOUBLE_EQ(dissipatedEnergy(epsR, b.EA, b.epsP, epsR, b.L), b.Af * b.Gf);
    EXPECT_DOUBLE_EQ(dissipatedEnergy(3 * epsR, b.EA, b.epsP, epsR, b.L), b.Af * b.Gf);
    EXPECT_EQ(dissipatedEnergy(0.9 * b.epsP, b.EA, b.epsP, epsR, b.L), 0.0);
}

TEST(HillerborgLaw, DissipatedPlusStoredEqualsEnvelopeWork) {
    const Bar b;
    const double epsR = b.epsR();
    for (double f : {0.3, 0.9, 1.0, 1.5, 4.0, 10.0, 20.0}) {
        const double kappa = std::min(f * b.epsP, 1.2 * epsR);
        const double W = envelopeWork(b, kappa, 200000);
        const double D = dissipatedEnergy(kappa, b.EA, b.epsP, epsR, b.L);
        const double S = storedEnergy(kappa, kappa, b.EA, b.epsP, epsR, b.L);
        EXPECT_NEAR(D + S, W, 1e-7 * b.Af * b.Gf) << "kappa = " << kappa;
        EXPECT_GE(D, 0.0);
        EXPECT_GE(S, 0.0);
    }
    // Dissipation grows monotonically with damage.
    double prev = -1;
    for (double k = 0; k <= 1.1 * epsR; k += epsR / 97) {
        const double D = dissipatedEnergy(k, b.EA, b.epsP, epsR, b.L);
        EXPECT_GE(D, prev);
        prev = D;
    }
}

// Direct check (run first by tests/mutation/run.py): a damaged bar unloads on
// the secant to the origin, F = EA eps eps_p (eps_r - kappa) / (kappa (eps_r - eps_p))
// (the envelope's force at kappa, scaled by eps/kappa), never with its initial
// stiffness EA: the law to round-off (1e-12 relative), and the force loop on
// one module to 1e-9 (the strains of a uniform expansion, to round-off).
TEST(DirectLaw, DamagedBarUnloadsOnItsSecant) {
    const Bar b;
    const double epsR = b.epsR();
    for (double kappa : {2 * b.epsP, 0.5 * (b.epsP + epsR), 0.9 * epsR}) {
        const double Fk = axialForce(kappa, kappa, b.EA, b.epsP, epsR);
        ASSERT_GT(Fk, 0.0);
        ASSERT_LT(Fk, b.EA * b.epsP);
        const double secant = b.EA * b.epsP * (epsR - kappa) / (kappa * (epsR - b.epsP));  // by hand
        for (double eps : {0.9 * kappa, 0.5 * kappa, 1e-3 * kappa})
            EXPECT_NEAR(axialForce(eps, kappa, b.EA, b.epsP, epsR), secant * eps, 1e-12 * secant * eps)
                << "kappa " << kappa << ", eps " << eps;
        // Force at kappa/2 on the unloading branch = half the envelope force at kappa.
        EXPECT_NEAR(axialForce(0.5 * kappa, kappa, b.EA, b.epsP, epsR), 0.5 * Fk, 1e-12 * Fk);
        // Linear through the origin everywhere below kappa.
        EXPECT_NEAR(axialForce(0.2 * kappa, kappa, b.EA, b.epsP, epsR), 0.2 * Fk, 1e-12 * Fk);
        // Reloading to kappa gets back the envelope; damage does not grow below kappa.
        EXPECT_EQ(updateDamage(kappa, 0.5 * kappa), kappa);
        EXPECT_EQ(updateDamage(kappa, -kappa), kappa);
        EXPECT_EQ(updateDamage(kappa, 1.1 * kappa), 1.1 * kappa);
        // Stored energy on the secant at kappa/2 is a quarter of that at kappa.
        EXPECT_NEAR(storedEnergy(0.5 * kappa, kappa, b.EA, b.epsP, epsR, b.L),
                    0.25 * storedEnergy(kappa, kappa, b.EA, b.epsP, epsR, b.L), 1e-15);
        // Secant ratio.
        EXPECT_NEAR(secantRatio(kappa, b.epsP, epsR), Fk / (b.EA * kappa), 1e-12);
    }
    // Below eps_p there is no damage: unloading is elastic with full stiffness.
    EXPECT_DOUBLE_EQ(axialForce(0.3 * b.epsP, 0.8 * b.epsP, b.EA, b.epsP, epsR), 0.3 * b.EA * b.epsP);

    // The same through the force loop: one module expanded uniformly by
    // eps = 1.5 eps_p, every bar damaged to kappa = 3 eps_p with eps_r = 10 eps_p,
    // so every bar carries EA eps s, s = eps_p (eps_r - kappa) / (kappa (eps_r - eps_p)) = 7/27.
    // Corner (0, 0, 0) feels along x its edge (EA_n / 4: one module of four)
    // and its diagonal (EA_d, direction (1, 1, 1)/sqrt 3): f_x = (EA_n / 4 + EA_d / sqrt 3) eps s.
    const Material m;
    const double L0 = 0.02, eps = 1.5 * m.epsP, s = 7.0 / 27;
    const Lattice lat = buildCubicLattice(1, 1, 1, L0, m);
    HillerborgLaw bars(lat, m.epsP, std::vector<double>(lat.numBars(), 10 * m.epsP));
    std::fill(bars.kappa.begin(), bars.kappa.end(), 3 * m.epsP);
    bars.softening.assign(bars.softening.size(), 1);
    const auto x0 = nodePositions(lat);
    Field3 u(lat.numNodes()), f(lat.numNodes());
    for (std::int64_t i = 0; i < lat.numNodes(); ++i)
        u.x[i] = eps * x0[0][i], u.y[i] = eps * x0[1][i], u.z[i] = eps * x0[2][i];
    BarForceBuffers g;
    computeInternalForces(lat, u, bars, g, f);
    const double An = 0.4 * L0 * L0, Ad = 2 * 1.125 / std::sqrt(3.0) * An;
    const double want = m.E * (An / 4 + Ad / std::sqrt(3.0)) * eps * s;
    EXPECT_NEAR(f.x[lat.cornerId(0, 0, 0)], want, 1e-9 * want);
    for (double k : bars.kappa) EXPECT_EQ(k, 3 * m.epsP);  // unloading: no new damage
}

// Direct check (run first by tests/mutation/run.py): each bar's limit strain
// in a Simulation is eps_r = 2 A_f G_f / (EA eps_p L) with its own length L,
// by hand: L0 for edges and centre-centre bars, sqrt(3)/2 L0 for diagonals
// (uniform G_f, so every bar is known). A_f and EA are the bar's own (its
// share included: it cancels). Exact to round-off (1e-13 relative).
TEST(DirectLaw, EachBarsLimitStrainUsesItsOwnLength) {
    Material m;
    m.GfCV = 0;
    RunParams rp;
    rp.threads = 1;
    const double L0 = 0.02;
    const LoadingParams lp;
    const Simulation sim(cubeTestSpecimen(2, 2, 2, L0, m, lp), m, lp, rp);
    const BarTable t = listBars(sim.lattice());
    const std::vector<double>& epsR = std::get<HillerborgLaw>(sim.law()).epsR;
    ASSERT_EQ(epsR.size(), t.L.size());
    int diagonals = 0;
    for (std::size_t b = 0; b < epsR.size(); ++b) {
        const bool diagonal = sim.lattice().families[t.family[b]].kind == BarKind::Diagonal;
        diagonals += diagonal;
        const double L = diagonal ? std::sqrt(3.0) / 2 * L0 : L0;
        EXPECT_NEAR(t.L[b], L, 1e-15 * L0) << "bar " << b;
        const double want = 2 * t.Af[b] * m.GfMean / (t.EA[b] * m.epsP * L);
        ASSERT_GT(want, m.epsP);  // not clamped
        EXPECT_NEAR(epsR[b], want, 1e-13 * want) << "bar " << b << (diagonal ? " (diagonal)" : "");
    }
    EXPECT_EQ(diagonals, 8 * 8);
}

TEST(HillerborgLaw, CompressionIsElasticEvenAfterRupture) {
    const Bar b;
    const double epsR = b.epsR();
    for (double kappa : {0.0, 0.5 * b.epsP, 3 * b.epsP, epsR, 5 * epsR}) {
        for (double eps : {-1e-5, -1e-3}) {
            EXPECT_DOUBLE_EQ(axialForce(eps, kappa, b.EA, b.epsP, epsR), b.EA * eps);
            EXPECT_DOUBLE_EQ(storedEnergy(eps, kappa, b.EA, b.epsP, epsR, b.L), 0.5 * b.EA * eps * eps * b.L);
        }
    }
    // A broken bar carries no tension at any strain.
    EXPECT_EQ(axialForce(0.5 * epsR, 2 * epsR, b.EA, b.epsP, epsR), 0.0);
}

TEST(HillerborgLaw, SnapBackIsClampedToPerfectlyBrittle) {
    Bar b;
    b.Gf = 1.0;  // eps_r = 1.57e-5 < eps_p
    const double raw = 2 * b.Af * b.Gf / (b.EA * b.epsP * b.L);
    ASSERT_LT(raw, b.epsP);
    const LimitStrain ls = limitStrain(b.Af, b.Gf, b.EA, b.epsP, b.L);
    EXPECT_TRUE(ls.clamped);
    EXPECT_EQ(ls.epsR, b.epsP);
    // The clamped bar is elastic up to eps_p (inclusive), then carries nothing.
    const double past = b.epsP * (1 + 1e-12);
    EXPECT_DOUBLE_EQ(axialForce(b.epsP, b.epsP, b.EA, b.epsP, ls.epsR), b.EA * b.epsP);
    EXPECT_EQ(axialForce(past, past, b.EA, b.epsP, ls.epsR), 0.0);
    EXPECT_EQ(axialForce(0.5 * b.epsP, past, b.EA, b.epsP, ls.epsR), 0.0);
    EXPECT_DOUBLE_EQ(axialForce(0.99 * b.epsP, 0.99 * b.epsP, b.EA, b.epsP, ls.epsR), 0.99 * b.EA * b.epsP);
    // It dissipates its whole elastic energy 1/2 L EA eps_p^2 (> A_f G_f) once past eps_p.
    EXPECT_EQ(dissipatedEnergy(b.epsP, b.EA, b.epsP, ls.epsR, b.L), 0.0);
    EXPECT_DOUBLE_EQ(dissipatedEnergy(past, b.EA, b.epsP, ls.epsR, b.L), 0.5 * b.L * b.EA * b.epsP * b.epsP);
    EXPECT_GT(0.5 * b.L * b.EA * b.epsP * b.epsP, b.Af * b.Gf);
    EXPECT_EQ(damageState(past, b.epsP, ls.epsR), DamageState::Broken);
    // Exactly at the boundary, eps_r = eps_p is not a clamp.
    const double GfEdge = b.EA * b.epsP * b.epsP * b.L / (2 * b.Af);
    EXPECT_FALSE(limitStrain(b.Af, GfEdge * (1 + 1e-9), b.EA, b.epsP, b.L).clamped);
}

TEST(HillerborgLaw, DamageStates) {
    const Bar b;
    const double epsR = b.epsR();
    EXPECT_EQ(damageState(0.0, b.epsP, epsR), DamageState::Undamaged);
    EXPECT_EQ(damageState(b.epsP, b.epsP, epsR), DamageState::Undamaged);
    EXPECT_EQ(damageState(1.01 * b.epsP, b.epsP, epsR), DamageState::Damaged);
    EXPECT_EQ(damageState(epsR, b.epsP, epsR), DamageState::Broken);
    EXPECT_EQ(damageState(2 * epsR, b.epsP, epsR), DamageState::Broken);
}

// The law inside the force loop. A one-module lattice under the homogeneous
// expansion u = s x stretches every bar to strain exactly s, so the work of the
// external forces (-f, quasi-static) is L_b F_b summed over bars, integrated
// over s. Path: pull into softening, unload into compression, pull past every
// eps_r, compress again. At every checkpoint the external work must equal
// elastic + fracture energy from barEnergies; at the end the fracture energy is
// sum A_f G_f and compression is elastic.
TEST(HillerborgLaw, OneModuleExpansionThroughForceLoop) {
    setThreads(1);  // ~30000 force evaluations of 20 bars: threads would only add overhead
    Material m;
    const double L0 = 0.02;
    const Lattice lat = buildCubicLattice(1, 1, 1, L0, m);
    const std::int64_t nb = lat.numBars();
    const BarTable t = listBars(lat);
    const auto x0 = nodePositions(lat);
    std::vector<double> epsR(nb);
    double sumAfGf = 0, maxEpsR = 0, minEpsR = 1;
    for (std::int64_t b = 0; b < nb; ++b) {
        const double Gf = 50 + 100 * hashedUniform(3, b, 0);  // in [50, 150]: no clamped bar
        const LimitStrain ls = limitStrain(t.Af[b], Gf, t.EA[b], m.epsP, t.L[b]);
        ASSERT_FALSE(ls.clamped);
        epsR[b] = ls.epsR;
        sumAfGf += t.Af[b] * Gf;
        maxEpsR = std::max(maxEpsR, ls.epsR);
        minEpsR = std::min(minEpsR, ls.epsR);
    }
    HillerborgLaw bars(lat, m.epsP, std::move(epsR));
    Field3 u(lat.numNodes()), f(lat.numNodes());
    BarForceBuffers g;
    // Generalised force conjugate to s: dW = -f . x0 ds (the force the loader applies is -f).
    auto load = [&](double s) {
        for (std::int64_t i = 0; i < lat.numNodes(); ++i)
            u.x[i] = s * x0[0][i], u.y[i] = s * x0[1][i], u.z[i] = s * x0[2][i];
        computeInternalForces(lat, u, bars, g, f);
        double Q = 0;
        for (std::int64_t i = 0; i < lat.numNodes(); ++i)
            Q -= f.x[i] * x0[0][i] + f.y[i] * x0[1][i] + f.z[i] * x0[2][i];
        return Q;
    };
    double s = 0, Q = load(0), W = 0;
    auto goTo = [&](double target, int n) {
        const double h = (target - s) / n;
        for (int i = 1; i <= n; ++i) {
            const double sNext = s + h;
            const double QNext = load(sNext);
            W += 0.5 * (Q + QNext) * h;
            s = sNext, Q = QNext;
        }
    };
    auto checkBalance = [&](const char* where) {
        const BarEnergies e = barEnergies(lat, u, bars);
        EXPECT_NEAR(W, e.elastic + e.fracture, 2e-6 * sumAfGf) << where;
        return e;
    };
    // Pull into the softening branch of every bar (but break none).
    const double s1 = 0.5 * (m.epsP + minEpsR);
    goTo(s1, 5000);
    BarEnergies e = checkBalance("softening");
    EXPECT_EQ(e.damaged, nb);
    EXPECT_EQ(e.broken, 0);
    EXPECT_GT(e.fracture, 0.0);
    // Unload into compression: the secants, then full stiffness.
    goTo(0.0, 2000);  // grid point at the kink s = 0 (secant -> full stiffness)
    goTo(-0.5 * s1, 1000);
    e = checkBalance("compressed after damage");
    // Compression is elastic: every bar at strain -s1/2 stores 1/2 EA L eps^2 and
    // the loader's force is sum EA L eps (all bars at the same strain).
    double stored = 0, Qel = 0;
    for (std::int64_t b = 0; b < nb; ++b) {
        stored += 0.5 * t.EA[b] * t.L[b] * s * s;
        Qel += t.EA[b] * t.L[b] * s;
    }
    EXPECT_NEAR(e.elastic, stored, 1e-9 * stored);
    EXPECT_NEAR(Q, Qel, 1e-6 * std::abs(Qel));
    // Pull past every eps_r.
    goTo(1.2 * maxEpsR, 20000);
    e = checkBalance("all broken");
    EXPECT_EQ(e.broken, nb);
    EXPECT_EQ(e.elastic, 0.0);
    EXPECT_NEAR(e.fracture, sumAfGf, 1e-12 * sumAfGf);
    EXPECT_NEAR(W, sumAfGf, 2e-6 * sumAfGf);
    EXPECT_EQ(Q, 0.0);
    // Close the cracks: compression after rupture is elastic again.
    goTo(0.0, 100);  // broken bars carry nothing until the crack closes at s = 0
    goTo(-1e-4, 100);
    e = checkBalance("compressed after rupture");
    EXPECT_NEAR(Q, -1e-4 * Qel / (-0.5 * s1), 1e-6 * std::abs(Qel));
    EXPECT_NEAR(e.fracture, sumAfGf, 1e-12 * sumAfGf);
}

// The elastic fast path (laws/BarLaw.hpp: the binomial series of F/l, no
// square root, no division) against the exact force of a stretched diagonal in
// long double: within rounding over the series' range in tension and
// compression, with a lateral displacement too; past its range, or past
// eps_p, it hands the bar to the law (returns > 0).
TEST(HillerborgLaw, ElasticSeriesIsTheExactForceWithinItsRange) {
    const Material m;
    const Lattice lat = buildCubicLattice(1, 1, 1, 0.02, m);
    const BarFamily& fam = lat.families.back();  // a diagonal: d0 = (1, 1, 1) L0 / 2
    const double EA = fam.EA, xP = stretchOfStrain(m.epsP);
    double worst = 0;
    for (int k = -100; k <= 100; ++k) {
        const double eps = 2.1e-3 * k / 100;  // axial strain, then a lateral slip of eps L
        const double du[3] = {eps * fam.d0[0] + eps * fam.L * 0.3, eps * fam.d0[1] - eps * fam.L * 0.3, eps * fam.d0[2]};
        double g[3];
        const double excess = elasticBarForce(fam, EA, xP, du[0], du[1], du[2], g[0], g[1], g[2]);
        const long double d[3] = {fam.d0[0] + (long double)du[0], fam.d0[1] + (long double)du[1],
                                  fam.d0[2] + (long double)du[2]};
        // the length of d0 (fam.L is its rounding): a bar at rest has no strain
        const long double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]),
                          l0 = std::sqrt((long double)fam.d0[0] * fam.d0[0] + (long double)fam.d0[1] * fam.d0[1] +
                                         (long double)fam.d0[2] * fam.d0[2]);
        const long double e = (l - l0) / l0, x = (l * l - l0 * l0) / (l0 * l0);
        if (std::abs(x) > kElasticSeriesLimit || e > m.epsP) {
            EXPECT_GT(excess, 0) << "eps " << double(e);
            continue;
        }
        EXPECT_LE(excess, 0) << "eps " << double(e);
        for (int i = 0; i < 3; ++i) {
            const long double exact = EA * e * d[i] / l;
            if (k != 0) worst = std::max(worst, double(std::abs(g[i] - exact) / std::abs(exact)));
            else EXPECT_EQ(g[i], 0.0);
        }
    }
    EXPECT_LT(worst, 1e-14);  // (the lateral slip makes n = 2 d0.du + du.du lose a digit or so)
    EXPECT_GT(worst, 0);  // the exact force differs by rounding: a wrong coefficient would show
}

// The force loop takes a fast path for the rows whose bars are all elastic
// (InternalForces.hpp). Against the law applied bar by bar (long double, from
// the bar table): on a lattice where some rows carry earlier damage and the
// displacements put bars in every regime (elastic, loading past eps_p,
// unloading on a secant, broken, compressed), in rows of every mix.
TEST(HillerborgLaw, ForceLoopIsTheLawBarByBar) {
    const Material m;
    // Rows of 20 and 19 nodes: the node pass's blocks of 8, the last one shifted
    // back, and its ends one by one (InternalForces.cpp).
    const Lattice lat = buildCubicLattice(19, 3, 4, 0.02, m);
    const std::int64_t nb = lat.numBars();
    const BarTable t = listBars(lat);
    const auto x0 = nodePositions(lat);
    std::vector<double> epsR(nb);
    for (std::int64_t b = 0; b < nb; ++b) epsR[b] = m.epsP * (1 + 4 * hashedUniform(5, b, 0));
    HillerborgLaw bars(lat, m.epsP, epsR);
    // Damaged bars, all of some rows of the upper half, marked softening
    // as the force loop marks a row when a bar passes eps_p (the fast path
    // reads no damage). The other rows start on the fast path; every other row
    // of the two layers where the expansion crosses eps_p stays there, so that
    // some of its bars pass eps_p in it.
    for (int layer = lat.numLayers() / 2; layer < lat.numLayers(); ++layer)
        for (std::int32_t r = lat.barLayerStart[layer]; r < lat.barLayerStart[layer + 1]; ++r) {
            if (layer < lat.numLayers() / 2 + 3 && r % 2 == 0) continue;
            bars.softening[r] = 1;
            for (std::int64_t b = lat.barRows[r].first; b < lat.barRows[r].first + lat.barRows[r].count; ++b)
                bars.kappa[b] = m.epsP + (epsR[b] - m.epsP) * hashedUniform(5, b, 2);
        }
    const std::vector<std::uint8_t> softening0 = bars.softening;
    const std::vector<double> kappa0 = bars.kappa;
    Field3 u(lat.numNodes()), f(lat.numNodes());
    // An expansion growing with z from -1 eps_p to 2 eps_p (so that the lower
    // rows are elastic but for their damaged bars), with random displacements of
    // +-eps_p L0 on top.
    for (std::int64_t i = 0; i < lat.numNodes(); ++i) {
        const double s = m.epsP * (3 * x0[2][i] / 0.08 - 1.0), a = m.epsP * 0.02;
        u.x[i] = s * x0[0][i] + a * (2 * hashedUniform(6, i, 0) - 1);
        u.y[i] = s * x0[1][i] + a * (2 * hashedUniform(6, i, 1) - 1);
        u.z[i] = s * x0[2][i] + a * (2 * hashedUniform(6, i, 2) - 1);
        // and one node in 61 pulled along x by 10 % of a module: its bars' |x|
        // go beyond the series (InternalForces.hpp: the rows' exact path)
        if (i % 61 == 0) u.x[i] += 0.1 * 0.02;
    }
    std::vector<long double> rx(lat.numNodes(), 0), ry(lat.numNodes(), 0), rz(lat.numNodes(), 0);
    std::vector<double> kappa1(nb);
    int regimes[5] = {};  // elastic, loading past eps_p, unloading, broken in tension, compressed
    long double fmax = 0;
    for (std::int64_t b = 0; b < nb; ++b) {
        const auto a = t.n1[b], c = t.n2[b];
        const auto& d0 = lat.families[t.family[b]].d0;  // exact A -> B (node positions are rounded)
        const long double d[3] = {d0[0] + ((long double)u.x[c] - u.x[a]), d0[1] + ((long double)u.y[c] - u.y[a]),
                                  d0[2] + ((long double)u.z[c] - u.z[a])};
        const long double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        const double eps = double((l - t.L[b]) / t.L[b]);
        const double k = updateDamage(kappa0[b], eps);
        kappa1[b] = k > m.epsP ? k : kappa0[b];
        const long double F = axialForce(eps, k, t.EA[b], m.epsP, epsR[b]);
        regimes[eps <= 0 ? 4 : k <= m.epsP ? 0 : k >= epsR[b] ? 3 : eps >= kappa0[b] ? 1 : 2]++;
        for (int i = 0; i < 3; ++i) {
            std::vector<long double>& r = i == 0 ? rx : i == 1 ? ry : rz;
            r[a] += F * d[i] / l, r[c] -= F * d[i] / l;
        }
        fmax = std::max(fmax, std::abs(F));
    }
    for (int r : regimes)
        EXPECT_GT(r, int(nb / 10)) << "too few bars in some regime: " << regimes[0] << " " << regimes[1] << " "
                                   << regimes[2] << " " << regimes[3] << " " << regimes[4];
    BarForceBuffers g;
    for (int pass = 0; pass < 2; ++pass) {  // the second with the rows already marked softening
        bars.kappa = kappa0;
        computeInternalForces(lat, u, bars, g, f);
        if (pass == 0) {
            auto rows = [&](std::uint8_t path) { return std::count(bars.softening.begin(), bars.softening.end(), path); };
            EXPECT_GT(rows(kSeriesPath) + rows(kExactPath), std::count(softening0.begin(), softening0.end(), 1) + 10)
                << "rows whose bars pass eps_p on the fast path go to the law";
            EXPECT_GT(rows(kExactPath), 10) << "rows with a bar beyond the series take the exact path";
            EXPECT_GT(rows(kSeriesPath), 10);
            EXPECT_GT(rows(kElasticPath), 10);
        }
        for (std::int64_t i = 0; i < lat.numNodes(); ++i) {
            ASSERT_NEAR(f.x[i], double(rx[i]), 1e-10 * double(fmax)) << "pass " << pass << " node " << i;
            ASSERT_NEAR(f.y[i], double(ry[i]), 1e-10 * double(fmax)) << "pass " << pass << " node " << i;
            ASSERT_NEAR(f.z[i], double(rz[i]), 1e-10 * double(fmax)) << "pass " << pass << " node " << i;
        }
        for (std::int64_t b = 0; b < nb; ++b) ASSERT_NEAR(bars.kappa[b], kappa1[b], 1e-12 * m.epsP) << "bar " << b;
    }
}
