#include "ldem/dynamics/Registry.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace ldem {

namespace {
// The names of a family's choices, in registry order, each with its doc.
template <class Parts>
std::vector<std::pair<std::string, std::string>> choices() {
    std::vector<std::pair<std::string, std::string>> c;
    forEachPartType(static_cast<const Parts*>(nullptr), [&](auto* part) {
        using P = std::remove_pointer_t<decltype(part)>;
        if (P::kChoice) c.emplace_back(P::name, P::doc);
    });
    return c;
}

template <class Parts>
std::vector<std::string> namesOf() {
    std::vector<std::string> n;
    for (const auto& [name, doc] : choices<Parts>()) n.push_back(name);
    return n;
}

// "what: a (doc), b (doc) or c (doc)"
template <class Parts>
std::string helpOf(const std::string& what) {
    const auto c = choices<Parts>();
    std::string h = what + ": ";
    for (std::size_t i = 0; i < c.size(); ++i)
        h += (i == 0 ? "" : i + 1 < c.size() ? ", " : " or ") + c[i].first + " (" + c[i].second + ")";
    return h;
}

template <class Parts>
std::size_t indexOf(const std::string& name) {
    const auto n = namesOf<Parts>();
    for (std::size_t i = 0; i < n.size(); ++i)
        if (n[i] == name) return i;
    throw std::logic_error("no registered part is named '" + name + "'");
}
}  // namespace

std::vector<std::string> driveNames() { return namesOf<Drives>(); }
std::vector<std::string> stopNames() { return namesOf<StopRules>(); }
std::string driveHelp() { return helpOf<Drives>("the drive"); }
std::string stopHelp() { return helpOf<StopRules>("the event that ends the run"); }
DriveId driveNamed(const std::string& name) { return DriveId(indexOf<Drives>(name)); }
StopId stopNamed(const std::string& name) { return StopId(indexOf<StopRules>(name)); }

}  // namespace ldem
