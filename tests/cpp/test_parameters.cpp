// The parameter table (Parameters.hpp, ParameterTable.hpp): every parameter once,
// with a default inside its domain, reachable by name, checked on validate().
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "ldem/ParameterTable.hpp"
#include "ldem/Simulation.hpp"

using namespace ldem;

TEST(Parameters, EveryNameOnceAndEveryDefaultInsideItsDomain) {
    const auto& table = cubeTestParameters();
    ASSERT_EQ(table.size(), 54u);  // 2 geometry + 13 material + 18 loading + 21 run
    std::set<std::string> names;
    const CubeTestParams defaults;
    for (const ParamInfo& p : table) {
        EXPECT_TRUE(names.insert(p.name).second) << p.name;
        EXPECT_FALSE(p.help.empty()) << p.name;
        // The table's default is the struct's default member initializer.
        EXPECT_EQ(getParameter(defaults, p.name), p.defaultValue) << p.name;
        if (p.kind == "choice") {
            EXPECT_GE(p.domain.names.size(), 2u) << p.name;
            const auto& d = std::get<std::string>(p.defaultValue);
            EXPECT_NE(std::find(p.domain.names.begin(), p.domain.names.end(), d), p.domain.names.end()) << p.name;
        } else if (p.kind == "names") {  // some of the choices: its default read back is itself
            const auto& d = std::get<std::string>(p.defaultValue);
            EXPECT_EQ(p.domain.namesOf(p.domain.setOf(p.name, d)), d) << p.name;
        } else {
            const double x = p.kind == "float" ? std::get<double>(p.defaultValue)
                                               : double(std::get<std::int64_t>(p.defaultValue));
            EXPECT_TRUE(p.domain.contains(x)) << p.name << " default " << x << " not " << p.domain.describe();
        }
    }
    EXPECT_NO_THROW(defaults.validate());
    // The study's values (LDEM_SPEC Table 2) are the defaults.
    EXPECT_EQ(defaults.material.E, 3.5e10);
    EXPECT_EQ(defaults.material.nu, 0.25);
    EXPECT_EQ(defaults.material.epsP, 6.3e-5);
    EXPECT_EQ(defaults.material.ca, 0.1385);
    EXPECT_EQ(defaults.run.zeta, 0.02);
    // Every registered damping applied, as before they were chosen by name.
    EXPECT_EQ(getParameter(defaults, "dampings"), ParamValue(std::string("mass,bar_dashpots")));
    EXPECT_EQ(std::uint64_t(defaults.run.dampings), (std::uint64_t(1) << dampingNames().size()) - 1);
}

// dampings: some of the registered dampings, comma-separated in any order and
// read back in the registry's, or none; a name it does not know, one given twice or
// none beside another is one line naming the parameter and what it expects.
TEST(Parameters, TheDampingsAreSomeOfTheRegisteredNames) {
    CubeTestParams p;
    const auto value = [&](const std::string& names) {
        try {
            setParameter(p, "dampings", names);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::get<std::string>(getParameter(p, "dampings"));
    };
    EXPECT_EQ(value("mass"), "mass");
    EXPECT_EQ(value("bar_dashpots, mass"), "mass,bar_dashpots");
    EXPECT_EQ(value("none"), "none");
    EXPECT_EQ(std::uint64_t(p.run.dampings), 0u);
    const std::string expected = " (expected some of mass, bar_dashpots, separated by commas, or none)";
    EXPECT_EQ(value("viscous"), "unknown dampings 'viscous'" + expected);
    EXPECT_EQ(value("mass,viscous"), "unknown dampings 'viscous' in 'mass,viscous'" + expected);
    EXPECT_EQ(value("mass,"), "unknown dampings '' in 'mass,'" + expected);
    EXPECT_EQ(value(""), "unknown dampings ''" + expected);
    EXPECT_EQ(value("mass,mass"), "dampings 'mass,mass' names mass twice" + expected);
    EXPECT_EQ(value("none,mass"), "dampings 'none,mass': none stands alone" + expected);
    EXPECT_EQ(std::uint64_t(p.run.dampings), 0u);  // a refused value leaves the last one
    EXPECT_EQ(dampingsNamed("bar_dashpots"), DampingSet(2));
}

TEST(Parameters, SetAndGetByNameReachTheMembers) {
    CubeTestParams p;
    setParameter(p, "nu", 0.2);
    setParameter(p, "Gf_draw", std::string("module"));
    setParameter(p, "load", std::string("triangular"));
    setParameter(p, "bottom_lateral", std::string("free"));
    setParameter(p, "seed", std::int64_t(7));
    setParameter(p, "record_every", 3.0);  // a whole number given as a float
    setParameter(p, "stop_at", std::string("load_loss"));
    EXPECT_EQ(p.material.nu, 0.2);
    EXPECT_TRUE(p.material.GfPerModule);
    EXPECT_EQ(p.loading.shape, LoadShape::Triangular);
    EXPECT_TRUE(p.loading.bottomLateralFree);
    EXPECT_TRUE(p.loading.topLateralFree);
    EXPECT_EQ(p.run.seed, 7);
    EXPECT_EQ(p.run.recordEvery, 3);
    EXPECT_EQ(p.run.stopAt, stopNamed("load_loss"));
    EXPECT_EQ(getParameter(p, "load"), ParamValue(std::string("triangular")));
    EXPECT_EQ(getParameter(p, "seed"), ParamValue(std::int64_t(7)));
    EXPECT_EQ(getParameter(p.material, "nu"), ParamValue(0.2));
}

TEST(Parameters, BadNamesTypesAndValuesAreOneLineErrorsNamingTheParameter) {
    CubeTestParams p;
    auto message = [&](auto f) {
        try {
            f();
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(message([&] { setParameter(p, "Young", 1.0); }), "unknown parameter 'Young'");
    EXPECT_EQ(message([&] { setParameter(p, "load", std::string("shear")); }),
              "unknown load 'shear' (expected uniform or triangular)");
    EXPECT_EQ(message([&] { setParameter(p, "E", std::string("abc")); }), "E must be a number (got 'abc')");
    EXPECT_EQ(message([&] { setParameter(p, "threads", 1.5); }), "threads must be a whole number");
    p.material.nu = 0.5;
    EXPECT_EQ(message([&] { p.validate(); }), "nu must be in (0, 0.5) (got 0.5)");
    p.material.nu = 0.25, p.run.dtSafety = 0;
    EXPECT_EQ(message([&] { p.validate(); }), "dt_safety must be in (0, 1] (got 0)");
    p.run.dtSafety = 0.4, p.loading.strainRate = std::nan("");
    EXPECT_EQ(message([&] { p.validate(); }), "strain_rate must be > 0 (got nan 1/s)");
    p.loading.strainRate = 0.02, p.geometry.size = 0.13;
    EXPECT_EQ(message([&] { p.validate(); }), "cube size 0.13 m is not a multiple of L0 = 0.02 m");
    p.geometry.size = 0.12;
    EXPECT_EQ(message([&] { p.validate(); }), "no error");
    EXPECT_EQ(p.geometry.modules(), 6);
}

TEST(Parameters, SimulationOfTheParametersIsTheCubeTheyDescribe) {
    CubeTestParams p;
    setParameter(p, "size", 0.06);
    const Simulation sim(cubeTestSpecimen(p), p.material, p.loading, p.run);
    EXPECT_EQ(sim.lattice().nx, 3);
    EXPECT_EQ(sim.lattice().nz, 3);
    EXPECT_EQ(sim.lattice().L0, 0.02);
}
