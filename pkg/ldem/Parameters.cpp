#include "ldem/Parameters.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace ldem {

std::string formatNumber(double x) {
    std::ostringstream s;
    s.precision(6);
    s << x;
    return s.str();
}

std::string formatWhole(double x) {
    char s[400];  // the largest double has 309 digits
    std::snprintf(s, sizeof s, "%.0f", x);
    return s;
}

std::string Domain::describe() const {
    if (isChoice()) {
        std::string s = several ? "some of" : "one of";
        for (std::size_t i = 0; i < names.size(); ++i) s += (i ? ", " : " ") + names[i];
        return several ? s + ", separated by commas, or none" : s;
    }
    if (std::isinf(hi)) return std::string(loClosed ? ">= " : "> ") + formatNumber(lo);
    return std::string("in ") + (loClosed ? "[" : "(") + formatNumber(lo) + ", " + formatNumber(hi) + (hiClosed ? "]" : ")");
}

std::string Domain::namesOf(std::uint64_t bits) const {
    std::string s;
    for (std::size_t i = 0; i < names.size(); ++i)
        if (bits >> i & 1) s += (s.empty() ? "" : ",") + names[i];
    return s.empty() ? "none" : s;
}

std::uint64_t Domain::setOf(const std::string& parameter, const std::string& list) const {
    std::vector<std::string> given;  // the comma-separated names, without the spaces around them
    for (std::size_t from = 0, to;; from = to + 1) {
        to = std::min(list.find(',', from), list.size());
        const std::string name = list.substr(from, to - from);
        const std::size_t a = name.find_first_not_of(' '), b = name.find_last_not_of(' ');
        given.push_back(a == std::string::npos ? "" : name.substr(a, b + 1 - a));
        if (to == list.size()) break;
    }
    const auto refuse = [&](const std::string& what) {
        throw std::invalid_argument(what + " (expected " + describe() + ")");
    };
    if (given == std::vector<std::string>{"none"}) return 0;
    std::uint64_t bits = 0;
    for (const std::string& name : given) {
        const auto i = std::size_t(std::find(names.begin(), names.end(), name) - names.begin());
        if (name == "none") refuse(parameter + " '" + list + "': none stands alone");
        if (i == names.size())
            refuse("unknown " + parameter + " '" + name + "'" + (given.size() > 1 ? " in '" + list + "'" : ""));
        if (bits >> i & 1) refuse(parameter + " '" + list + "' names " + name + " twice");
        bits |= std::uint64_t(1) << i;
    }
    return bits;
}

}  // namespace ldem
