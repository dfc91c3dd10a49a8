// Every law of the registry (laws/Registry.hpp), through the interface alone
// (laws/BarLaw.hpp): realised from the material and a G_f field as Simulation
// does, each bar, surface edges with their share k/4 of EA and A_f, dissipates
// exactly its own A_f G_f when it breaks (1/2 L EA eps_p^2 if its envelope
// would snap back whole: perfectly brittle), carries no tension then and is
// broken; undamaged, it is intact and elastic. A law added to the registry is
// tested here with no change to this file.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "ldem/Lattice.hpp"
#include "ldem/ParameterTable.hpp"
#include "ldem/RandomField.hpp"
#include "ldem/laws/Registry.hpp"

using namespace ldem;

namespace {

template <class Law>
void realisedBarsDissipateTheirOwnAfGf() {
    const Material m;
    const Lattice lat = buildCubicLattice(3, 2, 2, 0.02, m);
    const BarTable t = listBars(lat);
    const std::int64_t nb = lat.numBars();
    std::vector<double> Gf(nb);
    for (std::int64_t b = 0; b < nb; ++b) Gf[b] = 0.5 + 150 * hashedUniform(7, b, 0);  // some bars snap back
    const Law law(lat, m, Gf);
    std::int64_t brittleBars = 0, surfaceEdges = 0;
    for (std::int64_t b = 0; b < nb; ++b) {
        const double brittle = 0.5 * t.L[b] * t.EA[b] * m.epsP * m.epsP;  // the elastic triangle up to eps_p
        const bool snapsBack = t.Af[b] * Gf[b] < brittle;
        brittleBars += snapsBack;
        surfaceEdges += t.share[b] < 1;
        const double expected = snapsBack ? brittle : t.Af[b] * Gf[b];
        EXPECT_NEAR(law.ruptureEnergy(b, t.EA[b], t.L[b]), expected, 1e-12 * expected) << Law::name << " bar " << b;
        // Pulled past its rupture strain, it has dissipated exactly that, carries no tension and is broken.
        const double past = 1.01 * law.epsR[b];
        EXPECT_NEAR(law.dissipated(b, t.EA[b], t.L[b], past), expected, 1e-12 * expected) << Law::name << " bar " << b;
        EXPECT_EQ(law.damage(b, past), DamageState::Broken) << Law::name;
        EXPECT_EQ(law.stored(b, t.EA[b], t.L[b], past), 0.0) << Law::name;
        // one that would snap back whole is perfectly brittle: no force at all once past eps_p
        if (snapsBack) EXPECT_EQ(law.stored(b, t.EA[b], t.L[b], 1.001 * m.epsP), 0.0) << Law::name << " bar " << b;
        // Unloaded and undamaged: intact, elastic force EA eps.
        EXPECT_TRUE(law.intact(b)) << Law::name;
        EXPECT_DOUBLE_EQ(law.force(b, t.EA[b], -1e-4), -1e-4 * t.EA[b]) << Law::name;
        EXPECT_EQ(law.damage(b, 0.5 * m.epsP), DamageState::Undamaged) << Law::name;
    }
    // every bar that would snap back whole is counted clamped (a law may clamp more: the bilinear's initial line)
    EXPECT_GE(law.clampedOwnedBars(), brittleBars) << Law::name;
    EXPECT_GT(brittleBars, 0);
    EXPECT_LT(brittleBars, nb / 2);
    EXPECT_GT(surfaceEdges, 0);
}

}  // namespace

TEST(EveryLaw, RealisedBarsDissipateTheirOwnAfGf) {
    forEachLawType([](auto* law) { realisedBarsDissipateTheirOwnAfGf<std::remove_pointer_t<decltype(law)>>(); });
}

// SecantLaw counts the bars its shape clamped: for the triangle, exactly those that would snap back.
TEST(EveryLaw, TheTriangleClampsTheBarsThatSnapBack) {
    const Material m;
    const Lattice lat = buildCubicLattice(3, 2, 2, 0.02, m);
    const BarTable t = listBars(lat);
    std::vector<double> Gf(lat.numBars());
    std::int64_t brittleBars = 0;
    for (std::int64_t b = 0; b < lat.numBars(); ++b) {
        Gf[b] = 0.5 + 150 * hashedUniform(7, b, 0);
        brittleBars += t.Af[b] * Gf[b] < 0.5 * t.L[b] * t.EA[b] * m.epsP * m.epsP;
    }
    EXPECT_EQ(HillerborgLaw(lat, m, Gf).clampedOwnedBars(), brittleBars);
}

// The registry's names are the laws' own, in its order: the `law` parameter's choices, its default the first.
TEST(EveryLaw, TheLawParameterChoosesAmongTheRegisteredNames) {
    const std::vector<std::string> names = barLawNames();
    ASSERT_EQ(names.size(), std::variant_size_v<BarLaws>);
    EXPECT_EQ(names[0], "hillerborg");
    EXPECT_EQ(names[std::size_t(barLawId<BilinearLaw>())], "bilinear");
    Material m;
    EXPECT_EQ(m.law, barLawId<HillerborgLaw>());
    const Lattice lat = buildCubicLattice(1, 1, 1, 0.02, m);
    for (std::size_t i = 0; i < names.size(); ++i) {
        setParameter(m, "law", names[i]);
        EXPECT_EQ(m.law, BarLawId(i));
        const BarLaws law = makeBarLaw(m.law, lat, m, std::vector<double>(lat.numBars(), 100.0));
        EXPECT_EQ(law.index(), i);
        EXPECT_EQ(std::visit([](const auto& l) { return std::string(l.name); }, law), names[i]);
    }
}
