// Nayfeh-Hefzy equivalence (LDEM_SPEC section 2): the closed-form constants,
// the areas the built lattice gives each bar family, and the elastic tensor of
// the infinite lattice computed from the built lattice's own bar families
// (affine deformation), which must be the isotropic tensor of (E, nu) for
// nu = 0.25.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "ldem/Lattice.hpp"
#include "ldem/Material.hpp"

using namespace ldem;

TEST(Material, NayfehHefzyConstantsForNuQuarter) {
    EXPECT_NEAR(nayfehDelta(0.25), 1.125, 1e-12);
    EXPECT_NEAR(nayfehPhi(0.25), 0.4, 1e-12);
    const double L0 = 0.02;
    EXPECT_NEAR(normalBarArea(0.25, L0), 0.4 * L0 * L0, 1e-12 * L0 * L0);
    EXPECT_NEAR(diagonalBarArea(0.25, L0), 2 * 1.125 / std::sqrt(3.0) * 0.4 * L0 * L0, 1e-12 * L0 * L0);
    // nu = 0: no diagonal stiffness, normal bars carry E alone (phi = 1/2).
    EXPECT_NEAR(nayfehDelta(0.0), 0.0, 1e-15);
    EXPECT_NEAR(nayfehPhi(0.0), 0.5, 1e-15);
    EXPECT_NEAR(normalFractureArea(0.1385, L0), 0.1385 * L0 * L0, 1e-18);
    EXPECT_NEAR(diagonalFractureArea(0.1385, L0), 0.1385 * 1.3225 * L0 * L0, 1e-18);
}

// Direct check (run first by tests/mutation/run.py): every family of the built
// lattice carries the area of the spec's closed form, worked by hand here:
//   nu = 0.25: delta = 9/8, phi = (9 + 9)/(18 + 27) = 2/5;
//   nu = 0.2:  delta = 3/4, phi = (9 + 6)/(18 + 18) = 5/12;
//   A_n = phi L0^2, A_d = (2 delta / sqrt 3) A_n, A_f = c_a L0^2 and c_a (1.15 L0)^2.
// Exact to round-off (1e-14 relative).
TEST(DirectMaterial, BarAreasOfEachFamilyAreNayfehHefzys) {
    const double L0 = 0.02;
    for (const auto& [nu, delta, phi] : {std::array<double, 3>{0.25, 9.0 / 8, 2.0 / 5},
                                         std::array<double, 3>{0.2, 3.0 / 4, 5.0 / 12}}) {
        Material m;
        m.nu = nu;
        const Lattice lat = buildCubicLattice(2, 2, 2, L0, m);
        const double An = phi * L0 * L0, Ad = 2 * delta / std::sqrt(3.0) * An;
        const double Afn = m.ca * L0 * L0, Afd = m.ca * 1.3225 * L0 * L0;
        ASSERT_EQ(lat.families.size(), 14u);
        for (const BarFamily& f : lat.families) {
            const bool diagonal = f.kind == BarKind::Diagonal;
            SCOPED_TRACE(testing::Message() << "nu " << nu << ", family of kind " << int(f.kind));
            EXPECT_NEAR(f.EA, m.E * (diagonal ? Ad : An), 1e-14 * m.E * An);
            EXPECT_NEAR(f.Af, diagonal ? Afd : Afn, 1e-14 * Afn);
        }
    }
}

TEST(Material, ValidateRejectsNonsense) {
    Material m;
    EXPECT_NO_THROW(m.validate());
    auto bad = [](auto mutate) {
        Material x;
        mutate(x);
        EXPECT_THROW(x.validate(), std::invalid_argument);
    };
    bad([](Material& x) { x.E = -1; });
    bad([](Material& x) { x.nu = 0.5; });
    bad([](Material& x) { x.nu = -0.1; });
    bad([](Material& x) { x.rho = 0; });
    bad([](Material& x) { x.GfMean = 0; });
    bad([](Material& x) { x.GfCV = -0.1; });
    bad([](Material& x) { x.corrLength = -1; });
    bad([](Material& x) { x.GfMin = -1; });
    bad([](Material& x) { x.GfMin = x.GfMean; });  // no variable part left to keep the CV
    bad([](Material& x) { x.epsP = 0; });
    bad([](Material& x) { x.ca = 0; });
}

// Per module of an infinite lattice there is one full edge bar per axis (12
// edges x 1/4), one centre-centre bar per axis and 8 diagonals, i.e. exactly
// one bar of each of the 14 families. Under a homogeneous strain eps a bar of
// direction n stretches by n.eps.n, so the energy density is
//   W = 1/(2 L0^3) sum_f EA_f L_f (n.eps.n)^2  =>  C_ijkl = sum_f EA_f L_f n_i n_j n_k n_l / L0^3.
TEST(Material, InfiniteLatticeIsIsotropicWithEAndNuQuarter) {
    Material m;  // E = 3.5e10, nu = 0.25
    const double L0 = 0.02;
    const Lattice lat = buildCubicLattice(2, 2, 2, L0, m);
    double C[3][3][3][3] = {};
    for (const BarFamily& f : lat.families) {
        const double n[3] = {f.d0[0] / f.L, f.d0[1] / f.L, f.d0[2] / f.L};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                for (int k = 0; k < 3; ++k)
                    for (int l = 0; l < 3; ++l)
                        C[i][j][k][l] += f.EA * f.L * n[i] * n[j] * n[k] * n[l] / (L0 * L0 * L0);
    }
    const double E = m.E, nu = m.nu;
    const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k)
                for (int l = 0; l < 3; ++l) {
                    const double iso = lambda * (i == j) * (k == l) + mu * ((i == k) * (j == l) + (i == l) * (j == k));
                    EXPECT_NEAR(C[i][j][k][l], iso, 1e-12 * E) << i << j << k << l;
                }
    // In numbers: C11 = 1.2 E, C12 = C44 = 0.4 E.
    EXPECT_NEAR(C[0][0][0][0] / E, 1.2, 1e-12);
    EXPECT_NEAR(C[0][0][1][1] / E, 0.4, 1e-12);
    EXPECT_NEAR(C[0][1][0][1] / E, 0.4, 1e-12);
}
