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
//
// The exact values are the static ones, by the reference's stiffness matrix
// and a direct solve (tests/reference/elastic_static.py):
//
//   n   E_app / E (static)    nu (static)         dynamic run here
//   4   0.808789906250692     0.2253797078491795  +0.047 %, -0.029 %
//   6   0.8699782209635861    0.23704368273979165 +0.055 %, -0.035 %
//   8   0.9018194200807457    0.24136551792152708 +0.055 %, -0.036 %
//
// The dynamic run differs by what is left of inertia and damping at this rate
// (four times slower with twice the damping: +0.024 %, -0.014 % at n = 4), so
// the tests allow 0.2 %: a 1 % error of the modulus or of Poisson's ratio fails.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "ldem/Simulation.hpp"

using namespace ldem;

namespace {

// The static solution (see above), E_app / E and nu per cube size n.
struct StaticRef {
    double E, nu;
};
const StaticRef kStatic4{0.808789906250692, 0.2253797078491795};
const StaticRef kStatic6{0.8699782209635861, 0.23704368273979165};
const StaticRef kStatic8{0.9018194200807457, 0.24136551792152708};
constexpr double kDynamicTol = 2e-3;  // relative: measured 5.5e-4 at most

struct ElasticResult {
    double Eapp, nuX, nuY, strain, stress, stressLoaded;
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
    Simulation sim(cubeTestSpecimen(n, n, n, L0, m, lp), m, lp, rp);
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
    const double stress = 0.5 * (last.stress + last.stressLoaded);
    ElasticResult r{stress / last.meanStrain / m.E,
                    -ex / last.meanStrain,
                    -ey / last.meanStrain,
                    last.meanStrain,
                    last.stress,
                    last.stressLoaded,
                    last.damaged + last.broken};
    std::printf(
        "[ elastic ] %d^3 rollers, zeta %.2f, rate %.3g/s: strain %.4g, stress bottom %.5g top %.5g Pa, "
        "E_app = %.6f E, nu_x = %.6f, nu_y = %.6f\n",
        n, zeta, strainRate, r.strain, r.stress, r.stressLoaded, r.Eapp, r.nuX, r.nuY);
    return r;
}

}  // namespace

TEST(ElasticEquivalence, SixCubeOnRollersApparentModulusAndPoisson) {
    const ElasticResult r = pullOnRollers(6);
    EXPECT_EQ(r.damaged, 0);  // well below eps_p: purely elastic
    EXPECT_NEAR(r.strain, 2e-5, 1e-6);
    // Quasi-static: both faces carry the same stress.
    EXPECT_NEAR(r.stressLoaded, r.stress, 0.005 * r.stress);
    // The surface layer makes a 6^3 cube 13 % softer than E and its nu 0.237:
    // the static solution, within what is left of the dynamics (measured
    // +0.055 % and -0.035 %).
    EXPECT_NEAR(r.Eapp, kStatic6.E, kDynamicTol * kStatic6.E);
    EXPECT_NEAR(r.nuX, kStatic6.nu, kDynamicTol * kStatic6.nu);
    EXPECT_NEAR(r.nuX, r.nuY, 1e-5);  // symmetric in x and y (measured 1e-6)
}

// The difference from (E, 0.25) is a boundary layer: it shrinks like 1/n.
// Each size against its static solution, and the extrapolation of 1/E_app and
// nu linearly in 1/n from the 6^3 and 8^3 cubes against the same extrapolation
// of the static values (1.013053 E and 0.254331: the boundary layer is not
// exactly 1/n); measured 1.013618 and 0.254232 (+0.056 %, -0.039 %).
TEST(ElasticEquivalence, SurfaceEffectVanishesWithSize) {
    const ElasticResult r4 = pullOnRollers(4), r6 = pullOnRollers(6), r8 = pullOnRollers(8);
    for (const auto& [r, ref] : {std::pair{r4, kStatic4}, std::pair{r6, kStatic6}, std::pair{r8, kStatic8}}) {
        EXPECT_NEAR(r.Eapp, ref.E, kDynamicTol * ref.E);
        EXPECT_NEAR(r.nuX, ref.nu, kDynamicTol * ref.nu);
    }
    EXPECT_LT(r4.Eapp, r6.Eapp);
    EXPECT_LT(r6.Eapp, r8.Eapp);
    EXPECT_LT(r4.nuX, r6.nuX);
    EXPECT_LT(r6.nuX, r8.nuX);
    const double invE = (8 / r8.Eapp - 6 / r6.Eapp) / 2;  // value of 1/E_app at 1/n = 0
    const double nuInf = (8 * r8.nuX - 6 * r6.nuX) / 2;
    const double refInvE = (8 / kStatic8.E - 6 / kStatic6.E) / 2, refNuInf = (8 * kStatic8.nu - 6 * kStatic6.nu) / 2;
    std::printf("[ elastic ] extrapolated to an infinite cube: E_app = %.6f E, nu = %.6f (static: %.6f E, %.6f)\n",
                1 / invE, nuInf, 1 / refInvE, refNuInf);
    EXPECT_NEAR(1 / invE, 1 / refInvE, kDynamicTol / refInvE);
    EXPECT_NEAR(nuInf, refNuInf, kDynamicTol * refNuInf);
}

// Quasi-static: a four times slower pull and twice the damping give the same
// apparent modulus within 0.3 %.
TEST(ElasticEquivalence, ResultDoesNotDependOnRateOrDamping) {
    const ElasticResult a = pullOnRollers(4), b = pullOnRollers(4, 1.0, 0.005);
    EXPECT_NEAR(a.Eapp, b.Eapp, 0.003 * a.Eapp);
    EXPECT_NEAR(a.nuX, b.nuX, 0.003);
}
