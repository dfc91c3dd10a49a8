#include "ldem/Parameters.hpp"

#include <cstdio>

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
        std::string s = "one of";
        for (std::size_t i = 0; i < names.size(); ++i) s += (i ? ", " : " ") + names[i];
        return s;
    }
    if (std::isinf(hi)) return std::string(loClosed ? ">= " : "> ") + formatNumber(lo);
    return std::string("in ") + (loClosed ? "[" : "(") + formatNumber(lo) + ", " + formatNumber(hi) + (hiClosed ? "]" : ")");
}

}  // namespace ldem
