#include "ldem/laws/Registry.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace ldem {

std::vector<std::string> barLawNames() { return {kBarLawNames.begin(), kBarLawNames.end()}; }

const std::vector<double>& lawArray(const BarLaws& law, const std::string& name) {
    return std::visit([&](const auto& l) -> const std::vector<double>& {
        for (const auto& [key, values] : l.arrays())
            if (key == name) return *values;
        throw std::invalid_argument("the bar law has no per-bar array '" + name + "'");
    }, law);
}

double lawConstant(const BarLaws& law, const std::string& name) {
    return std::visit([&](const auto& l) {
        for (const auto& [key, value] : l.constants())
            if (key == name) return value;
        throw std::invalid_argument("the bar law has no constant '" + name + "'");
    }, law);
}

std::vector<std::uint8_t> damageStates(const BarLaws& law, std::int64_t bars) {
    std::vector<std::uint8_t> s(static_cast<std::size_t>(bars));
    std::visit([&](const auto& l) {
        for (std::size_t b = 0; b < s.size(); ++b) s[b] = std::uint8_t(l.damage(std::int64_t(b)));
    }, law);
    return s;
}

std::vector<double> ruptureEnergies(const BarLaws& law, const Lattice& lat) {
    std::vector<double> e(lat.numBars());
    std::visit([&](const auto& l) {
        forEachBar(lat, [&](std::int64_t b, std::int32_t, std::int32_t, const BarRow& row, int p) {
            const BarFamily& fam = lat.families[row.family];
            e[b] = l.ruptureEnergy(b, fam.EA * row.shareAt(p), fam.L);
        });
    }, law);
    return e;
}

std::vector<double> barForces(const BarLaws& law, const Lattice& lat, const std::vector<double>& strains) {
    std::vector<double> f(lat.numBars());
    std::visit([&](const auto& l) {
        forEachBar(lat, [&](std::int64_t b, std::int32_t, std::int32_t, const BarRow& row, int p) {
            f[b] = l.force(b, lat.families[row.family].EA * row.shareAt(p), strains[b]);
        });
    }, law);
    return f;
}

void lawState(const BarLaws& law, std::vector<std::pair<std::string, std::vector<double>>>& bars,
              std::vector<std::uint8_t>& softening) {
    std::visit([&](const auto& l) {
        for (const auto& [name, values] : l.arrays()) bars.emplace_back(name, *values);
        softening = l.softeningRows();
    }, law);
}

void setLawState(BarLaws& law, const std::vector<std::pair<std::string, std::vector<double>>>& bars,
                 const std::vector<std::uint8_t>& softening) {
    std::visit([&](auto& l) {
        const auto arrays = l.arrays();
        bool sameLaw = arrays.size() == bars.size();
        for (std::size_t k = 0; sameLaw && k < arrays.size(); ++k) sameLaw = arrays[k].first == bars[k].first;
        if (!sameLaw) throw std::invalid_argument("the checkpoint is of another bar law (its per-bar arrays differ)");
        for (std::size_t k = 0; k < arrays.size(); ++k) *arrays[k].second = bars[k].second;
        l.softeningRows() = softening;
    }, law);
}

}  // namespace ldem
