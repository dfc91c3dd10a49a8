// The exponential softening law (laws/Exponential.hpp): the envelope against
// its closed form, the cut at eps_r where the force is kTailForce of the peak,
// the dissipated energy (exactly A_f G_f at rupture, and the envelope's work
// minus the stored energy on the way), the secant unloading, the snap-back
// clamp, and a Simulation that selects it by name (its realised bars: test_laws.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "StudyBar.hpp"
#include "ldem/ParameterTable.hpp"
#include "ldem/Simulation.hpp"
#include "ldem/laws/Exponential.hpp"

using namespace ldem;
using namespace ldem::exponential;

namespace {

// One normal bar of the study's material.
struct Bar : StudyBar {
    SofteningStrains s() const { return softeningStrains(Af, Gf, EA, epsP, L); }
    double envelope(double eps) const { return exponentialForce(eps, eps, EA, epsP, s().epsS, s().epsR); }
    double dissipated(double kappa) const { return exponentialDissipated(kappa, EA, epsP, s().epsS, s().epsR, L); }
};

}  // namespace

TEST(ExponentialLaw, EnvelopeIsItsClosedFormCutAtTheTailForce) {
    const Bar b;
    const auto s = b.s();
    const double Fp = b.EA * b.epsP;
    EXPECT_FALSE(s.clamped);
    EXPECT_NEAR(b.envelope(0.5 * b.epsP), 0.5 * Fp, 1e-12 * Fp);
    EXPECT_NEAR(b.envelope(b.epsP), Fp, 1e-12 * Fp);
    for (double x : {0.1, 1.0, 2.5}) {
        const double kappa = b.epsP + x * s.epsS;
        EXPECT_NEAR(b.envelope(kappa), Fp * std::exp(-x), 1e-12 * Fp) << x;
    }
    // just before the cut the force is kTailForce of the peak; from the cut on, none
    EXPECT_NEAR(b.envelope(s.epsR * (1 - 1e-15)), kTailForce * Fp, 1e-9 * Fp);
    EXPECT_EQ(b.envelope(s.epsR), 0.0);
    EXPECT_EQ(b.envelope(2 * s.epsR), 0.0);
    // A_f G_f = 1/2 F_p eps_p L + F_p eps_s (1 - c) L by the construction of eps_s
    EXPECT_NEAR(b.L * (0.5 * Fp * b.epsP + Fp * s.epsS * (1 - kTailForce)), b.Af * b.Gf, 1e-13 * b.Af * b.Gf);
}

TEST(ExponentialLaw, RuptureDissipatesExactlyAfGf) {
    for (double Gf : {20.0, 60.0, 100.0, 400.0}) {
        Bar b;
        b.Gf = Gf;
        const double AfGf = b.Af * b.Gf;
        ASSERT_FALSE(b.s().clamped) << Gf;
        EXPECT_NEAR(b.dissipated(b.s().epsR), AfGf, 1e-12 * AfGf) << Gf;
        EXPECT_NEAR(b.dissipated(3 * b.s().epsR), AfGf, 1e-12 * AfGf) << Gf;
    }
}

// A bar pulled monotonically by the law's row functor (what the force loop
// calls) to past its rupture: the work of its force, by a fine trapezoid rule
// (the drop at eps_r inside one step of 1e-6 of the range), less the energy
// stored, is the dissipated energy on the way and A_f G_f at the end.
TEST(ExponentialLaw, APulledBarDissipatesItsEnvelopeWorkAndAtRuptureAfGf) {
    const Material m;
    const Lattice lat = buildCubicLattice(1, 1, 1, 0.02, m);
    const std::int64_t bar = 0;
    const BarRow& row = lat.barRows[0];
    const BarFamily& fam = lat.families[row.family];
    const double EA = fam.EA * row.shareAt(0), L = fam.L;
    const std::vector<double> Gf(lat.numBars(), 100.0);
    ExponentialLaw law(lat, m, Gf);
    const double epsR = law.epsR[bar], AfGf = fam.Af * row.shareAt(0) * 100.0;
    ASSERT_GT(epsR, 10 * m.epsP);
    const auto rows = law.rows().forRow(0, row.first);
    const int n = 1000000;
    const double h = 1.2 * epsR / n;
    double work = 0, F = 0, gx, gy, gz;
    for (int i = 1; i <= n; ++i) {
        const double eps = i * h;
        // the stretch of a bar of length L at strain eps along x
        const BarStretch s{L * (1 + eps), 0, 0, L * (1 + eps), L * L * ((1 + eps) * (1 + eps) - 1),
                           1 / ((L * (1 + eps) + L) * L * L * (1 + eps))};
        rows(bar - row.first, EA, s, gx, gy, gz);
        const double Fe = gx;  // F/l times dx = l: the axial force
        work += 0.5 * (F + Fe) * h * L;
        F = Fe;
        if (i % (n / 8) == 0 && eps < epsR) {
            const double D = law.dissipated(bar, EA, L, eps), S = law.stored(bar, EA, L, eps);
            EXPECT_NEAR(D + S, work, 1e-6 * AfGf) << eps;
        }
    }
    EXPECT_NEAR(law.kappa[bar], 1.2 * epsR, 1e-12 * epsR);
    EXPECT_EQ(law.damage(bar), DamageState::Broken);
    EXPECT_NEAR(work, AfGf, 1e-6 * AfGf);  // the trapezoid rule's error at the drop: measured 9e-9 relative
    EXPECT_NEAR(law.dissipated(bar, EA, L, 0.0), AfGf, 1e-12 * AfGf);
    EXPECT_NEAR(law.ruptureEnergy(bar, EA, L), AfGf, 1e-12 * AfGf);
}

TEST(ExponentialLaw, UnloadsOnItsSecantAndIsElasticInCompression) {
    const Bar b;
    const auto s = b.s();
    for (double kappa : {2 * b.epsP, 0.5 * (b.epsP + s.epsR)}) {
        const double Fk = b.envelope(kappa);
        for (double f : {0.25, 0.5, 1.0})
            EXPECT_NEAR(exponentialForce(f * kappa, kappa, b.EA, b.epsP, s.epsS, s.epsR), f * Fk, 1e-12 * Fk);
        EXPECT_EQ(exponentialForce(-kappa, kappa, b.EA, b.epsP, s.epsS, s.epsR), -b.EA * kappa);
        // on the secant, the stored energy is 1/2 F kappa L, the rest of the work dissipated
        EXPECT_GT(b.dissipated(kappa), 0.0);
    }
}

// (Its energy and force once past eps_p: test_laws.cpp, for every law.)
TEST(ExponentialLaw, SnapBackIsPerfectlyBrittle) {
    Bar b;
    b.Gf = 0.4 * b.EA * b.epsP * b.epsP * b.L / b.Af;  // W = 0.4 F_p eps_p < 1/2 F_p eps_p
    EXPECT_TRUE(b.s().clamped);
    EXPECT_EQ(b.s().epsR, b.epsP);
}

TEST(ExponentialLaw, SimulationSelectsItByItsName) {
    CubeTestParams p;
    setParameter(p, "law", std::string("exponential"));
    EXPECT_EQ(p.material.law, barLawId<ExponentialLaw>());
    EXPECT_EQ(std::get<std::string>(getParameter(p, "law")), "exponential");
    const Simulation sim(cubeTestSpecimen(2, 2, 2, 0.02, p.material, p.loading), p.material, p.loading, p.run);
    const auto& epsS = sim.barArray("eps_s");
    const auto& epsR = sim.barArray("eps_r");
    ASSERT_FALSE(epsR.empty());
    for (std::size_t b = 0; b < epsR.size(); ++b) EXPECT_GE(epsR[b], sim.lawConstant("eps_p") + epsS[b]);
}
