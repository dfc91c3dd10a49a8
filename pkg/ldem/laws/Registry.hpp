// Every bar law, one line each in BarLaws. A Simulation holds one of them,
// chosen once at set-up (makeBarLaw); its time step visits it once per step,
// and the loops inside are compiled for that law (no call per bar).
// A new law: one header in pkg/ldem/laws/ (the interface: BarLaw.hpp) and its line here.
#pragma once
#include <cstddef>
#include <variant>
#include <vector>

#include "ldem/Lattice.hpp"
#include "ldem/Material.hpp"
#include "ldem/laws/Bilinear.hpp"
#include "ldem/laws/Hillerborg.hpp"

namespace ldem {

using BarLaws = std::variant<HillerborgLaw, BilinearLaw>;

// Law number `which` of BarLaws for the bars of lat, of material m, with fracture energies Gf.
template <std::size_t I = 0>
BarLaws makeBarLaw(std::size_t which, const Lattice& lat, const Material& m, const std::vector<double>& Gf) {
    if constexpr (I + 1 < std::variant_size_v<BarLaws>)
        if (which != I) return makeBarLaw<I + 1>(which, lat, m, Gf);
    return BarLaws(std::in_place_index<I>, lat, m, Gf);
}

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
