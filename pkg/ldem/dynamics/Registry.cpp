#include "ldem/dynamics/Registry.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace ldem {

namespace {
// Whether a part is chosen by name: a drive or a stop rule says (kChoice), every damping is.
template <class P, class = void>
struct Choosable : std::true_type {};
template <class P>
struct Choosable<P, std::void_t<decltype(P::kChoice)>> : std::bool_constant<P::kChoice> {};

// The names of a family's choices, in registry order, each with its doc.
template <class Parts>
std::vector<std::pair<std::string, std::string>> choices() {
    std::vector<std::pair<std::string, std::string>> c;
    forEachPartType(static_cast<const Parts*>(nullptr), [&](auto* part) {
        using P = std::remove_pointer_t<decltype(part)>;
        if (Choosable<P>::value) c.emplace_back(P::name, P::doc);
    });
    return c;
}

template <class Parts>
std::vector<std::string> namesOf() {
    std::vector<std::string> n;
    for (const auto& [name, doc] : choices<Parts>()) n.push_back(name);
    return n;
}

// "what: a (doc), b (doc) or c (doc)" (last: " and " where the choices are a set)
template <class Parts>
std::string helpOf(const std::string& what, const char* last = " or ") {
    const auto c = choices<Parts>();
    std::string h = what + ": ";
    for (std::size_t i = 0; i < c.size(); ++i)
        h += (i == 0 ? "" : i + 1 < c.size() ? ", " : last) + c[i].first + " (" + c[i].second + ")";
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
std::vector<std::string> dampingNames() { return namesOf<Dampings>(); }
std::string driveHelp() { return helpOf<Drives>("the drive"); }
std::string stopHelp() { return helpOf<StopRules>("the event that ends the run"); }
std::string dampingHelp() {
    return helpOf<Dampings>("the dampings applied (one not named is not built, its parameters unread)", " and ");
}
DriveId driveNamed(const std::string& name) { return DriveId(indexOf<Drives>(name)); }
StopId stopNamed(const std::string& name) { return StopId(indexOf<StopRules>(name)); }
DampingSet dampingsNamed(const std::string& names) {
    return DampingSet(Domain::someOf(dampingNames()).setOf("dampings", names));
}

}  // namespace ldem
