// A specimen is data (Specimen.hpp): Simulation reads the stress, the strain
// and the separation from the groups its measures name, in any direction.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "ldem/Simulation.hpp"
#include "ldem/Specimen.hpp"

using namespace ldem;

namespace {
// The cube test's prism of 4 x 2 x 2 modules turned on its side: held at
// x = 0 (all three DOFs), pulled along x at x = 4 L0, lateral DOFs free.
Specimen prismPulledAlongX(const Material& m) {
    Specimen s;
    s.lattice = buildCubicLattice(4, 2, 2, 0.02, m);
    const Lattice& lat = s.lattice;
    s.prescribed.mask.assign(lat.numNodes(), 0);
    for (int k = 0; k <= lat.nz; ++k)
        for (int j = 0; j <= lat.ny; ++j) {
            const auto held = lat.cornerId(0, j, k), pulled = lat.cornerId(lat.nx, j, k);
            s.groups["held"].push_back(held), s.groups["pulled"].push_back(pulled);
            for (int d = 0; d < 3; ++d) s.prescribed.add(held, d, 0.0);
            s.prescribed.add(pulled, 0, 1.0);
        }
    s.measures = {"held", "pulled", 0, lat.ny * lat.L0 * lat.nz * lat.L0, lat.nx * lat.L0, 1.0};
    return s;
}
}  // namespace

TEST(Specimen, APrismPulledAlongXIsTheCubeTestsPrismPulledAlongZ) {
    Material m;
    m.GfCV = 0;  // every bar alike: the two lattices are the same up to a rotation
    RunParams rp;
    rp.threads = 1, rp.stopAt = StopAt::LoadLoss, rp.recordEvery = 50;
    LoadingParams lp;
    lp.strainRate = 0.1;
    Simulation alongX(prismPulledAlongX(m), m, lp, rp);
    Simulation alongZ(2, 2, 4, 0.02, m, lp, rp);
    EXPECT_NEAR(alongX.frequencies().omegaMax, alongZ.frequencies().omegaMax, 1e-9 * alongZ.frequencies().omegaMax);
    EXPECT_NEAR(alongX.frequencies().omega1, alongZ.frequencies().omega1, 1e-6 * alongZ.frequencies().omega1);
    EXPECT_NEAR(alongX.dt(), alongZ.dt(), 1e-9 * alongZ.dt());
    std::vector<CurvePoint> x, z;
    alongX.run([&](const CurvePoint& p) { x.push_back(p); return x.size() < 40; });
    alongZ.run([&](const CurvePoint& p) { z.push_back(p); return z.size() < 40; });
    ASSERT_EQ(x.size(), z.size());
    double peak = 0;
    for (const auto& p : z) peak = std::max(peak, p.stress);
    ASSERT_GT(peak, 1e6);  // a real load, up to the elastic range's end
    for (std::size_t i = 0; i < x.size(); ++i) {
        EXPECT_NEAR(x[i].meanStrain, z[i].meanStrain, 1e-9 * z[i].meanStrain);  // dt: Lanczos to rounding
        EXPECT_NEAR(x[i].stress, z[i].stress, 1e-9 * peak) << "record " << i;
        EXPECT_NEAR(x[i].stressLoaded, z[i].stressLoaded, 1e-9 * peak) << "record " << i;
        EXPECT_NEAR(x[i].elastic, z[i].elastic, 1e-9 * (z[i].elastic + 1e-30)) << "record " << i;
    }
}

TEST(Specimen, MeasuresMustNameItsGroups) {
    Material m;
    Specimen s = prismPulledAlongX(m);
    s.measures.support = "base";
    try {
        Simulation sim(std::move(s), m, LoadingParams{}, RunParams{});
        ADD_FAILURE() << "accepted a measure on a missing group";
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(), "the specimen's measures name no node group 'base'");
    }
}
