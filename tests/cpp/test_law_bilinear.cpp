// The bilinear softening law (laws/Bilinear.hpp): the force on each branch
// against its closed form, the dissipated energy (exactly A_f G_F at rupture,
// and the envelope's work minus the stored energy on the way), the secant
// unloading, Hillerborg's triangle as its special case, and a Simulation that
// selects it by the `law` parameter.
#include <gtest/gtest.h>

#include <cmath>

#include "StudyBar.hpp"
#include "ldem/Simulation.hpp"
#include "ldem/laws/Bilinear.hpp"
#include "ldem/laws/Hillerborg.hpp"

using namespace ldem;

namespace {

// One normal bar of the study's material (its G_f is the bilinear law's G_F), with MC2010's kink (g = 0.625, s_k = 0.2).
struct Bar : StudyBar {
    double g = 0.625, sK = 0.2;
    bilinear::KinkStrains k() const { return bilinear::kinkStrains(Af, Gf, EA, epsP, L, g, sK); }
    double envelope(double eps) const {
        return bilinear::bilinearForce(eps, eps, EA, epsP, sK, k().epsK, k().epsR);
    }
    double dissipated(double kappa) const {
        return bilinear::bilinearDissipated(kappa, EA, epsP, sK, k().epsK, k().epsR, L);
    }
};

}  // namespace

TEST(BilinearLaw, ForceOnEachBranchIsItsClosedForm) {
    const Bar b;
    const auto k = b.k();
    const double Fp = b.EA * b.epsP, eps1 = 2 * b.g * b.Af * b.Gf / (b.L * Fp);
    ASSERT_LT(b.epsP, k.epsK);
    ASSERT_LT(k.epsK, k.epsR);
    EXPECT_FALSE(k.clamped);
    EXPECT_NEAR(b.envelope(0.5 * b.epsP), 0.5 * Fp, 1e-12 * Fp);
    EXPECT_NEAR(b.envelope(b.epsP), Fp, 1e-12 * Fp);
    // the initial line is the triangle's reaching zero at eps_1
    const double e1 = 0.5 * (b.epsP + k.epsK);
    EXPECT_NEAR(b.envelope(e1), Fp * (eps1 - e1) / (eps1 - b.epsP), 1e-12 * Fp);
    EXPECT_NEAR(b.envelope(k.epsK), b.sK * Fp, 1e-12 * Fp);
    const double e2 = 0.25 * k.epsK + 0.75 * k.epsR;
    EXPECT_NEAR(b.envelope(e2), b.sK * Fp * (k.epsR - e2) / (k.epsR - k.epsK), 1e-12 * Fp);
    EXPECT_EQ(b.envelope(k.epsR), 0.0);
    EXPECT_EQ(b.envelope(2 * k.epsR), 0.0);
    // the tail ends beyond eps_1: the tail is shallower (convex envelope)
    EXPECT_GT(k.epsR, eps1);
}

TEST(BilinearLaw, RuptureDissipatesExactlyAfGF) {
    for (double g : {0.3, 0.5, 0.625, 1.0})
        for (double sK : {0.05, 0.2, 0.33, 1.0}) {
            Bar b;
            b.g = g, b.sK = sK;
            const double AfGF = b.Af * b.Gf;
            EXPECT_NEAR(b.dissipated(b.k().epsR), AfGF, 1e-14 * AfGF) << g << " " << sK;
            EXPECT_NEAR(b.dissipated(3 * b.k().epsR), AfGF, 1e-14 * AfGF) << g << " " << sK;
        }
}

TEST(BilinearLaw, DissipatedIsEnvelopeWorkMinusStored) {
    const Bar b;
    const auto k = b.k();
    const int n = 200000;  // trapezoid rule; the envelope is linear between kinks, so a fine grid is exact to ~1e-9
    double work = 0, eps = 0, F = 0;
    for (double target : {b.epsP * 0.7, b.epsP, 0.5 * (b.epsP + k.epsK), k.epsK, 0.5 * (k.epsK + k.epsR), k.epsR}) {
        const double h = (target - eps) / n;
        for (int i = 1; i <= n; ++i) {
            const double e = eps + i * h, Fe = b.envelope(e);
            work += 0.5 * (F + Fe) * h * b.L;
            F = Fe;
        }
        eps = target;
        const double stored = 0.5 * b.envelope(eps) * eps * b.L;
        EXPECT_NEAR(b.dissipated(eps), work - stored, 1e-9 * b.Af * b.Gf) << eps;
    }
}

TEST(BilinearLaw, UnloadsOnItsSecantAndIsElasticInCompression) {
    const Bar b;
    const auto k = b.k();
    for (double kappa : {0.5 * (b.epsP + k.epsK), 0.5 * (k.epsK + k.epsR)}) {
        const double Fk = b.envelope(kappa);
        for (double f : {0.25, 0.5, 1.0})
            EXPECT_NEAR(bilinear::bilinearForce(f * kappa, kappa, b.EA, b.epsP, b.sK, k.epsK, k.epsR), f * Fk,
                        1e-12 * Fk);
        EXPECT_EQ(bilinear::bilinearForce(-kappa, kappa, b.EA, b.epsP, b.sK, k.epsK, k.epsR), -b.EA * kappa);
    }
}

TEST(BilinearLaw, WithTheWholeEnergyUnderTheInitialLineItIsTheTriangle) {
    Bar b;
    b.g = 1.0;
    const double epsR = hillerborg::limitStrain(b.Af, b.Gf, b.EA, b.epsP, b.L).epsR;
    for (double sK : {0.1, 0.2, 0.5}) {
        b.sK = sK;
        const auto k = b.k();
        EXPECT_NEAR(k.epsR, epsR, 1e-14 * epsR);
        for (double x : {0.3, 0.99, 1.0, 1.01, 1.5, 3.0, 10.0, 25.0, 40.0}) {
            const double kappa = x * b.epsP;
            const double F = hillerborg::axialForce(kappa, kappa, b.EA, b.epsP, epsR);
            EXPECT_NEAR(b.envelope(kappa), F, 1e-12 * b.EA * b.epsP) << x;
            const double D = hillerborg::dissipatedEnergy(kappa, b.EA, b.epsP, epsR, b.L);
            EXPECT_NEAR(b.dissipated(kappa), D, 1e-12 * b.Af * b.Gf) << x;
        }
    }
}

TEST(BilinearLaw, SnapBackIsClamped) {
    Bar b;
    // the initial line would snap back, the whole not: a drop to the kink at eps_p, energy still A_f G_F
    b.Gf = 0.6 * b.EA * b.epsP * b.epsP * b.L / b.Af;  // 2 W / Fp = 1.2 eps_p, eps_1 = 0.6 eps_p
    b.g = 0.5;
    auto k = b.k();
    EXPECT_TRUE(k.clamped);
    EXPECT_EQ(k.epsK, b.epsP);
    EXPECT_NEAR(b.dissipated(k.epsR), b.Af * b.Gf, 1e-14 * b.Af * b.Gf);
    EXPECT_NEAR(b.envelope(b.epsP * (1 + 1e-9)), b.sK * b.EA * b.epsP, 1e-6 * b.EA * b.epsP);
    // the whole would snap back: perfectly brittle, as the triangle
    b.Gf *= 0.5;
    k = b.k();
    EXPECT_TRUE(k.clamped);
    EXPECT_EQ(k.epsR, b.epsP);
    EXPECT_EQ(b.envelope(b.epsP * 1.001), 0.0);
    EXPECT_DOUBLE_EQ(b.dissipated(b.epsP * 1.001), 0.5 * b.L * b.EA * b.epsP * b.epsP);
}

TEST(BilinearLaw, SimulationSelectsItByTheLawParameter) {
    Material m;
    m.law = barLawId<BilinearLaw>();
    const LoadingParams lp;
    const RunParams rp;
    const Simulation sim(cubeTestSpecimen(2, 2, 2, 0.02, m, lp), m, lp, rp);
    EXPECT_EQ(sim.lawConstant("kink_stress"), 0.2);
    const auto& epsK = sim.barArray("eps_k");
    const auto& epsR = sim.barArray("eps_r");
    ASSERT_FALSE(epsR.empty());
    for (std::size_t b = 0; b < epsR.size(); ++b) EXPECT_LE(epsK[b], epsR[b]);
}
