// What every bar law of the registry (laws/Registry.hpp: BarLaws) owes the
// rest of ldem, checked on each law with its own default constants, bar by
// bar on a 2 x 2 x 2 lattice (interior bars and surface edges of share 1/4
// and 1/2) with a spread G_F field:
//  - a bar's rupture energy, the capacity of that bar in the cheapest cut
//    (py/ldem/mincut.py: the lower bound U_num >= U_mincut), is A_f G_F
//    (LDEM_SPEC: each bar dissipates its A_f G_F), whatever the law's shape;
//  - the separation test's intact(b) (Separation.hpp: "a broken bar carries
//    no tension, ever again; any other bar can") is the law's own force: a bar
//    counts as broken exactly when its envelope has no force left at its
//    largest strain, and then, and only then, it has dissipated its whole
//    rupture energy.
// The damage kappa is set by hand at and around each strain the law keeps
// per bar (eps_p, the bilinear law's kink eps_k, eps_r) and along the envelope.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "ldem/Lattice.hpp"
#include "ldem/Material.hpp"
#include "ldem/laws/Registry.hpp"

using namespace ldem;

namespace {

struct Bar {
    std::int64_t b;
    double EA, Af, L;  // with the surface edge's share
};

std::vector<Bar> barsOf(const Lattice& lat) {
    std::vector<Bar> bars;
    for (const BarRow& row : lat.barRows) {
        const BarFamily& fam = lat.families[row.family];
        for (int p = 0; p < row.count; ++p)
            bars.push_back({row.first + p, fam.EA * row.shareAt(p), fam.Af * row.shareAt(p), fam.L});
    }
    return bars;
}

// 60 to 140 J/m^2, every bar its own, but every 7th bar 1 J/m^2 (perfectly
// brittle: 2 A_f G_F / L < EA eps_p^2) and every 11th 5 J/m^2 (the bilinear
// law's initial line snaps back: eps_1 < eps_p < 2 A_f G_F / (L EA eps_p)).
std::vector<double> spreadField(std::int64_t n) {
    std::vector<double> gf(n);
    for (std::int64_t b = 0; b < n; ++b)
        gf[b] = b % 7 == 0 ? 1.0 : b % 11 == 0 ? 5.0 : 60.0 + 80.0 * double((b * 37) % 101) / 100.0;
    return gf;
}

// A_f G_F; a bar too brittle for any softening branch breaks at eps_p with its elastic energy.
double ruptureEnergyOf(const Bar& bar, double gf, double epsP) {
    return std::max(bar.Af * gf, 0.5 * bar.L * bar.EA * epsP * epsP);
}

// The strains to set kappa at for bar b: just below, at and just above each
// strain the law keeps for it (its arrays but kappa) and eps_p, and 40 points
// along the envelope up to 1.5 times the largest; never eps_p itself (kappa
// is stored only past eps_p: laws/BarLaw.hpp).
template <class Law>
std::vector<double> damagesToTry(const Law& law, std::int64_t b, double epsP) {
    std::vector<double> marks{epsP};
    for (const auto& [name, values] : law.arrays())
        if (name != "kappa" && (*values)[b] > 0) marks.push_back((*values)[b]);  // a strain of the law (eps_s may be 0)
    std::vector<double> k;
    for (double m : marks)
        for (double f : {1 - 1e-9, 1.0, 1 + 1e-9}) k.push_back(m * f);
    const double top = 1.5 * *std::max_element(marks.begin(), marks.end());
    for (int i = 1; i <= 40; ++i) k.push_back(epsP * std::pow(top / epsP, i / 40.0));
    k.erase(std::remove(k.begin(), k.end(), epsP), k.end());
    return k;
}

template <class Law>
std::vector<double>& kappaOf(Law& law) {
    for (const auto& [name, values] : law.arrays())
        if (name == "kappa") return *values;
    throw std::logic_error("a law without its damage kappa");
}

template <class F>
void forEveryLaw(F check) {
    const Material m;
    const Lattice lat = buildCubicLattice(2, 2, 2, 0.02, m);
    const std::vector<double> gf = spreadField(lat.numBars());
    for (std::size_t which = 0; which < std::variant_size_v<BarLaws>; ++which) {
        BarLaws law = makeBarLaw(BarLawId(which), lat, m, gf);
        std::visit([&](auto& l) {
            SCOPED_TRACE(std::string("law ") + l.name);
            ASSERT_GT(l.clampedOwnedBars(), 0);  // the brittle bars are there
            check(l, lat, gf, m.epsP);
        }, law);
    }
}

}  // namespace

// The capacity of each bar in the cheapest cut: A_f G_F (Simulation::ruptureEnergies),
// 1/2 L EA eps_p^2 for a perfectly brittle bar.
TEST(DirectEveryLaw, RuptureEnergyOfEachBarIsAfGF) {
    forEveryLaw([](auto& law, const Lattice& lat, const std::vector<double>& gf, double epsP) {
        for (const Bar& bar : barsOf(lat)) {
            const double expected = ruptureEnergyOf(bar, gf[bar.b], epsP);
            ASSERT_NEAR(law.ruptureEnergy(bar.b, bar.EA, bar.L), expected, 1e-12 * expected)
                << "bar " << bar.b << " of G_F " << gf[bar.b];
        }
    });
}

// intact(b) is "still carries tension at its largest strain": a bar past the
// bilinear law's kink but short of eps_r is intact.
TEST(DirectEveryLaw, ABarIsBrokenExactlyWhenItsEnvelopeHasNoForceLeft) {
    forEveryLaw([](auto& law, const Lattice& lat, const std::vector<double>&, double epsP) {
        std::vector<double>& kappa = kappaOf(law);
        for (const Bar& bar : barsOf(lat)) {
            for (double k : damagesToTry(law, bar.b, epsP)) {
                kappa[bar.b] = k;
                const double F = law.force(bar.b, bar.EA, k);  // on the envelope: eps = kappa
                ASSERT_EQ(law.intact(bar.b), F > 0.0) << "bar " << bar.b << " at kappa " << k << ": force " << F;
            }
            kappa[bar.b] = 0.0;
        }
    });
}

// Broken: the whole rupture energy dissipated; intact with force left: less of it.
TEST(DirectEveryLaw, ABrokenBarHasDissipatedItsWholeRuptureEnergyAndAnIntactOneLess) {
    forEveryLaw([](auto& law, const Lattice& lat, const std::vector<double>&, double epsP) {
        std::vector<double>& kappa = kappaOf(law);
        for (const Bar& bar : barsOf(lat)) {
            const double full = law.ruptureEnergy(bar.b, bar.EA, bar.L), Fp = bar.EA * epsP;
            for (double k : damagesToTry(law, bar.b, epsP)) {
                kappa[bar.b] = k;
                const double D = law.dissipated(bar.b, bar.EA, bar.L, 0.0);
                if (!law.intact(bar.b))
                    ASSERT_NEAR(D, full, 1e-12 * full) << "broken bar " << bar.b << " at kappa " << k;
                else if (law.force(bar.b, bar.EA, k) > 1e-3 * Fp)  // (the last force's energy is below round-off)
                    ASSERT_LT(D, full * (1 - 1e-9)) << "intact bar " << bar.b << " at kappa " << k;
            }
            kappa[bar.b] = 0.0;
        }
    });
}
