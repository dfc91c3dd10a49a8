// Every bar law, one line in BarLaws. A Simulation holds one of them,
// chosen once at set-up (makeBarLaw); its time step visits it once per step,
// and the loops inside are compiled for that law (no call per bar).
// A new law: one header in pkg/ldem/laws/ (the interface: BarLaw.hpp; a law
// of the secant family: SecantLaw.hpp) and its type in BarLaws. Its name (the
// law's `name`) is the `law` parameter's choice; the checks below run at compile time.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <cstddef>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "ldem/Lattice.hpp"
#include "ldem/Material.hpp"
#include "ldem/laws/Bilinear.hpp"
#include "ldem/laws/Exponential.hpp"
#include "ldem/laws/Hillerborg.hpp"

namespace ldem {

using BarLaws = std::variant<HillerborgLaw, BilinearLaw, ExponentialLaw>;

// The laws' names, in registry order: the choices of the `law` parameter (barLawNames).
template <std::size_t... I>
constexpr std::array<std::string_view, sizeof...(I)> lawNames(std::index_sequence<I...>) {
    return {std::variant_alternative_t<I, BarLaws>::name...};
}
inline constexpr auto kBarLawNames = lawNames(std::make_index_sequence<std::variant_size_v<BarLaws>>{});

constexpr bool namesAreUnique() {
    for (std::size_t i = 0; i < kBarLawNames.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (kBarLawNames[i] == kBarLawNames[j] || kBarLawNames[i].empty()) return false;
    return true;
}
static_assert(namesAreUnique(), "two bar laws of BarLaws share a name (or one has none)");

// What the force loop and Simulation ask of every law (laws/BarLaw.hpp), checked on each.
template <class Law>
constexpr bool isBarLaw() {
    using Rows = decltype(std::declval<Law&>().rows());
    using Stretch = SeriesStretch;
    double g = 0;
    static_assert(std::is_same_v<decltype(Rows::kElasticOnly), const bool>, "a law's Rows needs kElasticOnly");
    static_assert(std::is_same_v<decltype(std::declval<const Rows&>().forRow(0, 0)), Rows>, "Rows::forRow");
    static_assert(std::is_same_v<decltype(std::declval<const Rows&>()(0, 1.0, std::declval<const Stretch&>(), g, g, g)),
                                 double>, "the row functor returns the dashpot's ratio");
    static_assert(std::is_constructible_v<Law, const Lattice&, const Material&, const std::vector<double>&>,
                  "a law is built from the lattice, the material and the G_f field");
    static_assert(std::is_same_v<decltype(std::declval<const Law&>().damage(0, 0.0)), DamageState>, "damage(b, eps)");
    static_assert(std::is_same_v<decltype(std::declval<const Law&>().dissipated(0, 1.0, 1.0, 0.0)), double>,
                  "dissipated(b, EA, L, eps)");
    return true;
}
template <std::size_t... I>
constexpr bool allAreBarLaws(std::index_sequence<I...>) {
    return (isBarLaw<std::variant_alternative_t<I, BarLaws>>() && ...);
}
static_assert(allAreBarLaws(std::make_index_sequence<std::variant_size_v<BarLaws>>{}));

// The BarLawId of Law (its index in BarLaws), e.g. material.law = barLawId<BilinearLaw>().
template <class Law, std::size_t I = 0>
constexpr BarLawId barLawId() {
    if constexpr (std::is_same_v<Law, std::variant_alternative_t<I, BarLaws>>)
        return BarLawId(I);
    else
        return barLawId<Law, I + 1>();
}

// Law `which` of BarLaws for the bars of lat, of material m, with fracture energies Gf.
template <std::size_t I = 0>
BarLaws makeBarLaw(BarLawId which, const Lattice& lat, const Material& m, const std::vector<double>& Gf) {
    if constexpr (I + 1 < std::variant_size_v<BarLaws>)
        if (std::size_t(which) != I) return makeBarLaw<I + 1>(which, lat, m, Gf);
    return BarLaws(std::in_place_index<I>, lat, m, Gf);
}

// What Python, the writers and checkpoints ask of the law chosen (any law), for the bars of lat:
// a per-bar array and a constant by name (throw on an unknown name), the DamageState of every
// bar, the energy each bar dissipates when it breaks, the axial force of every bar at u [N].
const std::vector<double>& lawArray(const BarLaws& law, const std::string& name);
double lawConstant(const BarLaws& law, const std::string& name);
std::vector<std::uint8_t> damageStates(const BarLaws& law, std::int64_t bars);
std::vector<double> ruptureEnergies(const BarLaws& law, const Lattice& lat);
std::vector<double> barForces(const BarLaws& law, const Lattice& lat, const std::vector<double>& strains);
// The law's per-bar state (its arrays by name, its softening rows), and back: throws
// std::invalid_argument if the arrays are of another law or another lattice.
void lawState(const BarLaws& law, std::vector<std::pair<std::string, std::vector<double>>>& bars,
              std::vector<std::uint8_t>& softening);
void setLawState(BarLaws& law, const std::vector<std::pair<std::string, std::vector<double>>>& bars,
                 const std::vector<std::uint8_t>& softening);

// f(static_cast<Law*>(nullptr)) for every law type, in registry order.
template <class F, std::size_t... I>
void forEachLawType(F f, std::index_sequence<I...>) {
    (f(static_cast<std::variant_alternative_t<I, BarLaws>*>(nullptr)), ...);
}
template <class F>
void forEachLawType(F f) {
    forEachLawType(f, std::make_index_sequence<std::variant_size_v<BarLaws>>{});
}

}  // namespace ldem
