// Elastic equivalence of the finite lattice (LDEM_SPEC section 2): a cube on
// rollers (only rigid motion pinned at the bottom, top laterally free) in
// slow, heavily damped uniaxial tension well below eps_p, through the whole
// Simulation. Apparent Young's modulus = mean of the two face stresses over
// the mean strain; Poisson's ratio from the lateral displacement of the
// mid-height surface corner nodes.
//
// The Nayfeh-Hefzy areas make the infinite lattice exactly isotropic with
// (E, nu = 0.25) (test_material.cpp checks the tensor). A finite cube is
// softer near its surfaces: a surface module has no centre-centre bar
// leaving it outwards, so under an affine strain its centre node is out of
// balance and relaxes. The loaded faces add an end compliance of roughly
// half a module each. Measured (zeta 0.5, strain rate 0.02/s, mean strain 2e-5):
//
//   n (modules)   E_app / E   nu (mid-height faces)
//        4         0.809        0.225
//        6         0.870        0.237
//        8         0.902        0.241
//       10         0.922        0.244
//       12         0.935        0.245
//
// 1/E_app is linear in 1/n (slope ~0.95, intercept ~0.99-1.0) and nu tends to
// 0.25: a pure boundary-layer effect that vanishes with size. Halving the
// strain rate or doubling zeta changes E_app by < 0.1 % (quasi-static), and the
// two face stresses agree within 0.3 %.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "ldem/Simulation.hpp"

using namespace ldem;

namespace {

struct ElasticResult {
    double Eapp, nuX, nuY, strain, stressBottom, stressTop;
    std::int64_t damaged;
};

ElasticResult pullOnRollers(int n, double zeta = 0.5, double strainRate = 0.02, double target = 2e-5) {
    Material m;  // Table 2; eps_p = 6.3e-5, three times the strain reached
    LoadingParams lp;
    lp.bottomLateralFree = true;
    lp.topLateralFree = true;
    lp.strainRate = strainRate;
    RunParams rp;
    rp.zeta = zeta;
    rp.threads = 1;
    rp.recordEvery = 1;
    const double L0 = 0.02;
    Simulation sim(n, n, n, L0, m, lp, rp);
    CurvePoint last;
    sim.run([&](const CurvePoint& p) {
        last = p;
        return p.meanStrain < target;
    });
    const Lattice& lat = sim.lattice();
    const Field3& u = sim.displacements();
    const int k = n / 2;  // mid-height corner layer
    const double W = n * L0;
    double ex = 0, ey = 0;
    for (int j = 0; j <= n; ++j) {
        ex += (u.x[lat.cornerId(n, j, k)] - u.x[lat.cornerId(0, j, k)]) / W;
        ey += (u.y[lat.cornerId(j, n, k)] - u.y[lat.cornerId(j, 0, k)]) / W;
    }
    ex /= n + 1, ey /= n + 1;
    const double stress = 0.5 * (last.stressBottom + last.stressTop);
    ElasticResult r{stress / last.meanStrain / m.E,
                    -ex / last.meanStrain,
                    -ey / last.meanStrain,
                    last.meanStrain,
                    last.stressBottom,
                    last.stressTop,
                    last.damaged + last.broken};
    std::printf(
        "[ elastic ] %d^3 rollers, zeta %.2f, rate %.3g/s: strain %.4g, stress bottom %.5g top %.5g Pa, "
        "E_app = %.4f E, nu_x = %.4f, nu_y = %.4f\n",
        n, zeta, strainRate, r.strain, r.stressBottom, r.stressTop, r.Eapp, r.nuX, r.nuY);
    return r;
}

}  // namespace

TEST(ElasticEquivalence, SixCubeOnRollersApparentModulusAndPoisson) {
    const ElasticResult r = pullOnRollers(6);
    EXPECT_EQ(r.damaged, 0);  // well below eps_p: purely elastic
    EXPECT_NEAR(r.strain, 2e-5, 1e-6);
    // Quasi-static: both faces carry the same stress.
    EXPECT_NEAR(r.stressTop, r.stressBottom, 0.005 * r.stressBottom);
    // Measured 0.8705: the surface layer makes a 6^3 cube ~13 % softer than E
    // (see the table above). The band is +-2 % around the measurement: wide
    // enough for round-off and rate effects (< 0.1 %), narrow enough to catch
    // a wrong area, share or mass.
    EXPECT_GT(r.Eapp, 0.85);
    EXPECT_LT(r.Eapp, 0.89);
    // Measured 0.2370 against nu = 0.25; symmetric in x and y.
    EXPECT_NEAR(r.nuX, 0.25, 0.02);
    EXPECT_GT(r.nuX, 0.225);
    EXPECT_LT(r.nuX, 0.25);
    EXPECT_NEAR(r.nuX, r.nuY, 1e-3);
}

// The difference from (E, 0.25) is a boundary layer: it shrinks like 1/n.
// Extrapolating 1/E_app and nu linearly in 1/n from the 6^3 and 8^3 cubes
// gives E within 3 % and nu within 0.01 (measured: 1.013 E and 0.254).
TEST(ElasticEquivalence, SurfaceEffectVanishesWithSize) {
    const ElasticResult r4 = pullOnRollers(4), r6 = pullOnRollers(6), r8 = pullOnRollers(8);
    EXPECT_LT(r4.Eapp, r6.Eapp);
    EXPECT_LT(r6.Eapp, r8.Eapp);
    EXPECT_LT(r4.nuX, r6.nuX);
    EXPECT_LT(r6.nuX, r8.nuX);
    const double invE = (8 / r8.Eapp - 6 / r6.Eapp) / 2;  // value of 1/E_app at 1/n = 0
    const double nuInf = (8 * r8.nuX - 6 * r6.nuX) / 2;
    std::printf("[ elastic ] extrapolated to an infinite cube: E_app = %.4f E, nu = %.4f\n", 1 / invE, nuInf);
    EXPECT_NEAR(1 / invE, 1.0, 0.03);
    EXPECT_NEAR(nuInf, 0.25, 0.01);
}

// Quasi-static: a four times slower pull and twice the damping give the same
// apparent modulus within 0.3 %.
TEST(ElasticEquivalence, ResultDoesNotDependOnRateOrDamping) {
    const ElasticResult a = pullOnRollers(4), b = pullOnRollers(4, 1.0, 0.005);
    EXPECT_NEAR(a.Eapp, b.Eapp, 0.003 * a.Eapp);
    EXPECT_NEAR(a.nuX, b.nuX, 0.003);
}
