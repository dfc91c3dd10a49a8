// Every parameter of a cube test, declared once: its C++ member, its name (in
// Python, on the command line, in summary.json and in a study's case keys), its
// default, unit, domain and help. The structs Material, LoadingParams and
// RunParams are generated from these lists (LDEM_DECLARE_MEMBER), so are their
// validation (LDEM_CHECK_MEMBER) and the access by name behind the Python
// bindings (ParameterTable.hpp); ldem.CubeTest and `ldem cube --help` are generated
// from the table the bindings export. The defaults are the study's
// (LDEM_SPEC section 6, Table 2).
//
// Adding a parameter: one line in a list below, then its use. A dynamic part
// (pkg/ldem/dynamics/) declares its list in its header; the registry splices it
// into its group's (LDEM_LOADING_PARAMETERS, LDEM_RUN_PARAMETERS).
//
// X(type, member, "name", default, "unit", domain, "help")
#pragma once
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#define LDEM_GEOMETRY_PARAMETERS(X)                                                                          \
    X(double, size, "size", 0.12, "m", Domain::positive(), "side of the cube (a multiple of L0)")             \
    X(double, L0, "L0", 0.02, "m", Domain::positive(), "side of a cubic module")

/* nu >= 0.5 is incompressible and delta = 9nu/(4-8nu) blows up; nu < 0 makes
   the diagonal area negative; nu = 0 gives the diagonals no area, and the
   normal bars alone have no shear stiffness (a mechanism): the lattice
   represents none of these. E and rho beyond any solid would overflow the
   energies (E A L eps^2, rho L0^3 v^2). */
#define LDEM_MATERIAL_PARAMETERS(X)                                                                          \
    X(double, E, "E", 3.5e10, "Pa", Domain::openClosed(0, 1e14), "Young's modulus")                           \
    X(double, nu, "nu", 0.25, "", Domain::open(0, 0.5), "Poisson's ratio")                                    \
    X(double, rho, "rho", 2400.0, "kg/m^3", Domain::openClosed(0, 1e6), "density")                             \
    X(double, GfMean, "Gf_mean", 100.0, "N/m", Domain::positive(),                                            \
      "mean specific fracture energy E[G_f]; a bar whose G_f is below E A eps_p^2 L / (2 A_f) (4.0 N/m for a "  \
      "normal bar at the defaults) is perfectly brittle (eps_r < eps_p): a warning when the mean is, refused when "\
      "every bar is; at most the G_f that makes eps_r of a normal bar 1 (6.4e4 N/m at the defaults): the "      \
      "geometry is of small strains (pkg/ldem/Relations.hpp)")                                                 \
    X(double, GfCV, "Gf_cv", 1.0, "", Domain::closed(0, 10), "coefficient of variation of G_f (1 = 100%)")     \
    X(double, GfMin, "Gf_min", 0.0, "N/m", Domain::atLeast(0),                                                 \
      "lower bound of G_f, the Weibull's location (below Gf_mean): its shape and scale keep E[G_f] and CV(G_f); "\
      "0: the two-parameter Weibull (CV 1 is then an exponential)")                                            \
    X(double, corrLength, "corr_length", 0.0, "m", Domain::atLeast(0),                                         \
      "correlation length of G_f (0: one draw per bar)")                                                      \
    X(bool, GfPerModule, "Gf_draw", false, "", Domain::choices({"bar", "module"}),                             \
      "G_f drawn per bar, or per module (the bars of a module alike)")                                         \
    X(double, epsP, "eps_p", 6.3e-5, "", Domain::openClosed(0, 1e-2),                                         \
      "critical strain of a bar (end of the elastic branch); at most 1%: concrete's is ~1e-4, and the lattice's "  \
      "geometry is that of small strains")                                                                     \
    X(double, ca, "c_a", 0.1385, "", Domain::openClosed(0, 1),                                               \
      "fracture-area coefficient c_a (A_f = c_a L0^2); at most 1: a bar's fracture area at most a module's face "\
      "(0.1385 makes one crack across a module dissipate G_f L0^2); a small c_a makes bars brittle (Gf_mean)")   \
    X(BarLawId, law, "law", BarLawId{}, "", Domain::choices(barLawNames()),                                    \
      "softening law of a bar (one header each in pkg/ldem/laws/; the bilinear law's constants: kink_stress, " \
      "Gf_ratio)")                                                                                             \
    LDEM_BILINEAR_LAW_PARAMETERS(X)

// The bilinear law's constants (laws/Bilinear.hpp).
#define LDEM_BILINEAR_LAW_PARAMETERS(X)                                                                      \
    X(double, kinkStress, "kink_stress", 0.2, "", Domain::openClosed(0, 1),                                   \
      "bilinear law: force at the kink over the peak force (MC2010: 0.2)")                                      \
    X(double, GfRatio, "Gf_ratio", 0.625, "", Domain::openClosed(0, 1),                                       \
      "bilinear law: G_f/G_F, the share of the fracture energy under the initial line (MC2010: 0.625; 1: the triangle)")

// The drive's program, shared by every drive (dynamics/ConstantRateDrive.hpp).
#define LDEM_DRIVE_PARAMETERS(X)                                                                             \
    X(double, strainRate, "strain_rate", 0.02, "1/s", Domain::positive(),                                    \
      "vertical strain rate at the most-pulled edge; the drive must move less than eps_p and more than 1e-6 "    \
      "eps_p in one step (dynamics/QuasiStatic.hpp)")                                                           \
    X(double, ratePeriods, "rate_periods", 0.0, "", Domain::atLeast(0),                                      \
      "rule (c) as the rate: > 0 drives at eps_p omega_d / (2 pi N), so that the gauge strains by eps_p in N "  \
      "periods of the mode the drive moves (omega_d: summary.json's omega_d_rad_s), and strain_rate is not "   \
      "used (dynamics/QuasiStatic.hpp); 0, the cube's default: strain_rate; a specimen file's default is 12 "  \
      "unless it gives strain_rate")                                                                           \
    X(double, rampTime, "ramp_time", 0.0, "s", Domain::atLeast(0),                                           \
      "smooth start of the loading (0: two periods 2 pi/omega_d of the mode the drive moves); at most eps_p / " \
      "strain_rate: the ramp ends before the mean strain reaches eps_p / 2, before any bar can crack")

// The fixed speed-up after the load loss (dynamics/ConstantRateDrive.hpp; the adaptive drive's floor).
#define LDEM_SPEEDUP_PARAMETERS(X)                                                                           \
    X(double, lossSpeedup, "loss_speedup", 20.0, "", Domain::atLeast(1),                                     \
      "drive velocity factor once the load is lost; tail_drive adaptive: the most its floor (the factor it "\
      "returns to while bars soften) may be")

// None: the list of a part without parameters.
#define LDEM_NO_PARAMETERS(X)
// A struct member with its default.
#define LDEM_DECLARE_MEMBER(type, member, name, def, unit, domain, help) type member = def;
// Its check against its domain, inside the struct's validate().
#define LDEM_CHECK_MEMBER(type, member, name, def, unit, domain, help) ::ldem::checkParameter(name, unit, member, domain);
// A dynamic part's own Params (its list) taken from the struct `from` whose list splices it in: `to.x = from.x;`.
#define LDEM_COPY_MEMBER(type, member, name, def, unit, domain, help) to.member = from.member;
// A part's Params (its list LIST) from the struct its list is spliced into.
#define LDEM_PART_PARAMS(Params, LIST, source) \
    [&] {                                      \
        Params to;                             \
        const auto& from = source;             \
        LIST(LDEM_COPY_MEMBER)                 \
        return to;                             \
    }()

namespace ldem {

// The values a parameter may take: an interval of numbers, one of named
// choices (a bool or an enum: the value is the index of its name), or some of
// them (a set: bit i the i-th name; said comma-separated, "none" the empty set).
struct Domain {
    double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
    bool loClosed = true, hiClosed = true;
    std::vector<std::string> names;  // non-empty: a choice
    bool several = false;            // some of the names, not one

    static Domain positive() { return {0, std::numeric_limits<double>::infinity(), false, true, {}}; }
    static Domain atLeast(double a) { return {a, std::numeric_limits<double>::infinity(), true, true, {}}; }
    static Domain closed(double a, double b) { return {a, b, true, true, {}}; }
    static Domain closedOpen(double a, double b) { return {a, b, true, false, {}}; }
    static Domain openClosed(double a, double b) { return {a, b, false, true, {}}; }
    static Domain open(double a, double b) { return {a, b, false, false, {}}; }
    static Domain choices(std::vector<std::string> n) { return {0, 0, true, true, std::move(n)}; }
    static Domain someOf(std::vector<std::string> n) { return {0, 0, true, true, std::move(n), true}; }

    bool isChoice() const { return !names.empty(); }
    bool contains(double x) const {
        return std::isfinite(x) && (loClosed ? x >= lo : x > lo) && (hiClosed ? x <= hi : x < hi);
    }
    // "> 0", ">= 1", "in [0, 0.5)", "one of bar, module", "some of mass, bar_dashpots, separated by commas, or none"
    std::string describe() const;
    // A set of the names and back: "mass,bar_dashpots" (in the names' order; "none": no bit). An unknown
    // name, one given twice, or "none" beside another throws std::invalid_argument naming the parameter.
    std::string namesOf(std::uint64_t bits) const;
    std::uint64_t setOf(const std::string& parameter, const std::string& list) const;
};

std::string formatNumber(double x);  // shortest form of 6 significant digits
std::string formatWhole(double x);   // a whole number as all its digits: 2^70 is not 1.18059e+21

// The bar laws by name, in the registry's order (laws/Registry.hpp): the choices of `law`,
// whose value is a BarLawId, the law's index in the registry.
enum class BarLawId : std::uint8_t {};
std::vector<std::string> barLawNames();

// The drives and the stop rules a run may choose by name (dynamics/Registry.hpp): the
// choices of tail_drive and stop_at, whose values are the index of the name; the
// dampings, the set `dampings` names (bit i the registry's i-th damping); each
// parameter's help from each choice's doc.
enum class DriveId : std::uint8_t {};
enum class StopId : std::uint8_t {};
enum class DampingSet : std::uint8_t {};
std::vector<std::string> driveNames();
std::vector<std::string> stopNames();
std::vector<std::string> dampingNames();
std::string driveHelp();
std::string stopHelp();
std::string dampingHelp();
DriveId driveNamed(const std::string& name);
StopId stopNamed(const std::string& name);
DampingSet dampingsNamed(const std::string& names);  // "mass,bar_dashpots", or "none"

template <class T>
void checkParameter(const char* name, const char* unit, const T& value, const Domain& d) {
    if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
        if (!d.contains(double(value)))
            throw std::invalid_argument(std::string(name) + " must be " + d.describe() + " (got " +
                                        (std::is_integral_v<T> ? std::to_string(value) : formatNumber(double(value))) +
                                        (*unit ? std::string(" ") + unit : "") + ")");
    }
}

}  // namespace ldem
