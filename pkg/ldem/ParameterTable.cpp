#include "ldem/ParameterTable.hpp"

#include "ldem/Relations.hpp"
#include "ldem/dynamics/QuasiStatic.hpp"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <limits>
#include <cmath>
#include <stdexcept>
#include <type_traits>

namespace ldem {

namespace {
std::invalid_argument unknownParameter(const std::string& name) {
    return std::invalid_argument("unknown parameter '" + name + "'");
}

// A set of named choices (its domain someOf): its value is a bit per name.
template <class T>
constexpr bool isChoiceSet = std::is_same_v<T, DampingSet>;
template <class T>
constexpr bool isChoice = (std::is_same_v<T, bool> || std::is_enum_v<T>) && !isChoiceSet<T>;

template <class T>
const char* kindOf() {
    if constexpr (std::is_same_v<T, double>) return "float";
    else if constexpr (isChoiceSet<T>) return "names";
    else if constexpr (isChoice<T>) return "choice";
    else return "int";
}

// A member's value as a ParamValue: a choice by its name (a bool or an enum
// is the index of its name in the domain).
template <class T>
ParamValue toValue(const T& v, const Domain& d) {
    if constexpr (std::is_same_v<T, double>) return v;
    else if constexpr (isChoiceSet<T>) return d.namesOf(std::uint64_t(v));
    else if constexpr (isChoice<T>) return d.names.at(std::size_t(v));
    else return std::int64_t(v);
}

template <class T>
T fromValue(const std::string& name, const ParamValue& v, const Domain& d) {
    if constexpr (std::is_same_v<T, double>) {
        if (const auto* x = std::get_if<double>(&v)) return *x;
        if (const auto* n = std::get_if<std::int64_t>(&v)) return double(*n);
        throw std::invalid_argument(name + " must be a number (got '" + std::get<std::string>(v) + "')");
    } else if constexpr (isChoiceSet<T>) {
        if (const auto* s = std::get_if<std::string>(&v)) return T(d.setOf(name, *s));
        throw std::invalid_argument(name + " must be names, comma-separated (expected " + d.describe() + ")");
    } else if constexpr (isChoice<T>) {
        const auto* s = std::get_if<std::string>(&v);
        for (std::size_t i = 0; s && i < d.names.size(); ++i)
            if (d.names[i] == *s) return T(i);
        std::string expected;
        for (std::size_t i = 0; i < d.names.size(); ++i) expected += (i ? " or " : "") + d.names[i];
        throw std::invalid_argument("unknown " + name + " '" + (s ? *s : std::string("?")) + "' (expected " +
                                    expected + ")");
    } else {
        const auto* i = std::get_if<std::int64_t>(&v);
        const auto* x = std::get_if<double>(&v);
        if (!i && !(x && std::floor(*x) == *x)) throw std::invalid_argument(name + " must be a whole number");
        // What T holds (an int64 seed, an int count), from the domain's lower end:
        // the message says the range, not only that the value does not fit.
        const std::int64_t lo = std::max<std::int64_t>(std::numeric_limits<T>::min(),
                                                       d.lo > -9.2e18 ? std::int64_t(d.lo) : INT64_MIN);
        const std::int64_t hi = std::numeric_limits<T>::max();
        const bool fits = i ? *i >= std::numeric_limits<T>::min() && *i <= hi
                            : *x >= double(std::numeric_limits<T>::min()) && *x < 0x1p63 && std::int64_t(*x) <= hi;
        if (!fits)
            throw std::invalid_argument(name + " is out of range: a whole number from " + std::to_string(lo) + " to " +
                                        std::to_string(hi) + " (got " + (i ? std::to_string(*i) : formatWhole(*x)) + ")");
        return T(i ? *i : std::int64_t(*x));
    }
}
}  // namespace

// Access by name, one function pair per group, generated from the lists.
#define LDEM_GET(type, member, name, def, unit, domain, help) \
    if (key == name) return toValue<type>(s.member, domain);
#define LDEM_SET(type, member, name, def, unit, domain, help) \
    if (key == name) {                                         \
        s.member = fromValue<type>(key, v, domain);            \
        return;                                                \
    }
#define LDEM_ACCESS(Struct, LIST)                                                          \
    ParamValue getParameter(const Struct& s, const std::string& key) {                     \
        LIST(LDEM_GET) throw unknownParameter(key);                                        \
    }                                                                                      \
    void setParameter(Struct& s, const std::string& key, const ParamValue& v) {            \
        LIST(LDEM_SET) throw unknownParameter(key);                                        \
    }
LDEM_ACCESS(CubeGeometry, LDEM_GEOMETRY_PARAMETERS)
LDEM_ACCESS(Material, LDEM_MATERIAL_PARAMETERS)
LDEM_ACCESS(LoadingParams, LDEM_LOADING_PARAMETERS)
LDEM_ACCESS(RunParams, LDEM_RUN_PARAMETERS)

const std::vector<ParamInfo>& cubeTestParameters() {
    static const std::vector<ParamInfo> table = [] {
        std::vector<ParamInfo> rows;
        std::string group;
#define LDEM_ROW(type, member, name, def, unit, domain, help) \
    rows.push_back({group, name, unit, help, kindOf<type>(), domain, toValue<type>(type(def), domain)});
        group = "geometry";
        LDEM_GEOMETRY_PARAMETERS(LDEM_ROW)
        group = "material";
        LDEM_MATERIAL_PARAMETERS(LDEM_ROW)
        group = "loading";
        LDEM_LOADING_PARAMETERS(LDEM_ROW)
        group = "run";
        LDEM_RUN_PARAMETERS(LDEM_ROW)
#undef LDEM_ROW
        return rows;
    }();
    return table;
}

const std::vector<std::pair<std::string, ParamValue>>& cubeOwnDefaults() {
    static const std::vector<std::pair<std::string, ParamValue>> own = {
        {"crack_pace", 0.0625}, {"crack_secant", 0.9}, {"crack_kinetic", 0.01}};
    return own;
}

const std::vector<std::pair<std::string, ParamValue>>& specimenOwnDefaults() {
    static const std::vector<std::pair<std::string, ParamValue>> own = {{"rate_periods", kRatePeriods}};
    return own;
}

CubeTestParams cubeTestDefaults() {
    CubeTestParams p;
    for (const auto& [name, value] : cubeOwnDefaults()) setParameter(p, name, value);
    return p;
}

namespace {
const std::string& groupOf(const std::string& name) {
    for (const ParamInfo& p : cubeTestParameters())
        if (p.name == name) return p.group;
    throw unknownParameter(name);
}
}  // namespace

ParamValue getParameter(const CubeTestParams& p, const std::string& name) {
    const std::string& g = groupOf(name);
    if (g == "geometry") return getParameter(p.geometry, name);
    if (g == "material") return getParameter(p.material, name);
    if (g == "loading") return getParameter(p.loading, name);
    return getParameter(p.run, name);
}

void setParameter(CubeTestParams& p, const std::string& name, const ParamValue& v) {
    const std::string& g = groupOf(name);
    if (g == "geometry") return setParameter(p.geometry, name, v);
    if (g == "material") return setParameter(p.material, name, v);
    if (g == "loading") return setParameter(p.loading, name, v);
    return setParameter(p.run, name, v);
}

int CubeGeometry::modules() const {
    LDEM_GEOMETRY_PARAMETERS(LDEM_CHECK_MEMBER)
    const double n = size / L0;
    if (n > 1e5)  // 1e15 modules: far beyond memory; and no overflow in the cast below
        throw std::invalid_argument("cube size " + formatNumber(size) + " m is " + formatNumber(n) +
                                    " modules of L0 = " + formatNumber(L0) + " m a side: far beyond any machine");
    if (std::abs(n - std::round(n)) > 1e-9 * std::max(1.0, n))
        throw std::invalid_argument("cube size " + formatNumber(size) + " m is not a multiple of L0 = " +
                                    formatNumber(L0) + " m");
    return int(std::round(n));
}

void CubeGeometry::validate() const { modules(); }

void CubeTestParams::validate() const {
    geometry.validate();
    material.validate();
    loading.validate();
    run.validate();
    checkRelations(material, loading, run, geometry.L0);
}

}  // namespace ldem
