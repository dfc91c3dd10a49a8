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
// (pkg/ldem/dynamics/) has a list of its own, spliced into its group's list.
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
      "rule (c) as the rate: > 0 drives at eps_p omega_1 / (2 pi N), so that the gauge strains by eps_p in N "  \
      "of the specimen's own fundamental periods, and strain_rate is not used (dynamics/QuasiStatic.hpp); "   \
      "0, the cube's default: strain_rate; a specimen file's default is 12 unless it gives strain_rate")       \
    X(double, rampTime, "ramp_time", 0.0, "s", Domain::atLeast(0),                                           \
      "smooth start of the loading (0: two fundamental periods); at most eps_p / strain_rate: the ramp ends "   \
      "before the mean strain reaches eps_p / 2, before any bar can crack")

// The fixed speed-up after the load loss (dynamics/ConstantRateDrive.hpp; the adaptive drive's floor).
#define LDEM_SPEEDUP_PARAMETERS(X)                                                                           \
    X(double, lossSpeedup, "loss_speedup", 20.0, "", Domain::atLeast(1),                                     \
      "drive velocity factor once the load is lost; tail_drive adaptive: the most its floor (the factor it "\
      "returns to while bars soften) may be")

// The adaptive tail (dynamics/AdaptiveDrive.hpp).
#define LDEM_ADAPTIVE_DRIVE_PARAMETERS(X)                                                                    \
    X(double, tailMaxSpeedup, "tail_max_speedup", 2000.0, "", Domain::atLeast(1),                            \
      "tail_drive adaptive: the largest velocity factor (over strain_rate) once the load is lost")           \
    X(double, tailLoad, "tail_load", 0.005, "", Domain::open(0, 1),                                          \
      "tail_drive adaptive: the support's stress, over the peak, at which the drive is back at its floor "   \
      "(the chains are taut); below, at most floor x tail_load / (support stress / peak)")                   \
    X(double, tailDrag, "tail_drag", 0.03, "", Domain::open(0, 1),                                           \
      "tail_drive adaptive: the largest stress, over the peak, that the drive's drag and inertia may put on "\
      "the part of the specimen that hangs from it, rho H (a + D_f v) with H the height, at every instant "  \
      "from the load loss on")                                                                               \
    X(double, tailStep, "tail_step", 1.1, "", Domain::openClosed(1, 2),                                      \
      "tail_drive adaptive: the velocity factor changes by at most this ratio per record, ramped linearly "  \
      "over the record's steps")                                                                             \
    X(double, crackPace, "crack_pace", 1.0, "", Domain::openClosed(0, 1),                                    \
      "tail_drive adaptive: the drive's velocity factor (over strain_rate) before the load loss while the "  \
      "lattice moves by itself (crack_kinetic; 1: never slowed, a file's default; 0.0625: the cube's, "       \
      "cubeOwnDefaults in ParameterTable.hpp; dynamics/CrackPace.hpp)")                                     \
    X(double, crackKinetic, "crack_kinetic", 1e-3, "", Domain::open(0, 1),                                   \
      "tail_drive adaptive: the kinetic energy less the drive's quasi-static motion, over the external "     \
      "work, above which the drive slows to crack_pace (a tenth of the quasi-static flag's 1 % at the peak)") \
    X(double, crackSecant, "crack_secant", 0.0, "", Domain::closed(0, 1),                                    \
      "tail_drive adaptive: the drive also slows to crack_pace near the peak, while the curve's secant "      \
      "stress / strain is below crack_secant x its elastic value and the stress above crack_band x the "     \
      "peak so far (0: off, a file's default; 0.9: the cube's; dynamics/CrackPace.hpp)")                     \
    X(double, crackBand, "crack_band", 0.5, "", Domain::open(0, 1),                                          \
      "tail_drive adaptive: crack_secant's band: the stress, over the peak so far, below which the curve "    \
      "is past its snap and the drive is no longer slowed for its secant")

// Opening control (dynamics/ServoDrive.hpp).
#define LDEM_SERVO_PARAMETERS(X)                                                                             \
    X(double, openingRate, "opening_rate", 0.0, "m/s", Domain::atLeast(0),                                   \
      "opening control: the rate of the specimen's controlled probe (0: displacement control at strain_rate)")

// The loading: the dynamic parts' lists above, in the table's order, and the choice of the tail drive.
#define LDEM_LOADING_PARAMETERS(X)                                                                           \
    X(LoadShape, shape, "load", LoadShape::Uniform, "", Domain::choices({"uniform", "triangular"}),          \
      "upper-face displacement: uniform or triangular")                                                      \
    LDEM_DRIVE_PARAMETERS(X)                                                                                 \
    X(bool, topLateralFree, "top_lateral", true, "", Domain::choices({"fixed", "free"}),                     \
      "lateral DOFs of the upper nodes: free or fixed")                                                      \
    X(bool, bottomLateralFree, "bottom_lateral", false, "", Domain::choices({"fixed", "free"}),              \
      "lateral DOFs of the lower nodes: fixed, or free (rollers)")                                           \
    X(TailDrive, tailDrive, "tail_drive", TailDrive::Adaptive, "", Domain::choices({"fixed", "adaptive"}),   \
      "the drive once the load is lost: fixed (loss_speedup times as fast, ramped in once), or adaptive "    \
      "(ramped in to loss_speedup the same way, then faster while no bar softens and the chains are slack, " \
      "within bounds of drag and inertia: tail_max_speedup, tail_load, tail_drag, tail_step)")               \
    LDEM_SPEEDUP_PARAMETERS(X)                                                                               \
    LDEM_ADAPTIVE_DRIVE_PARAMETERS(X)                                                                        \
    LDEM_SERVO_PARAMETERS(X)

// Mass-proportional damping (dynamics/MassDamping.hpp).
#define LDEM_MASS_DAMPING_PARAMETERS(X)                                                                      \
    X(double, zeta, "zeta", 0.02, "", Domain::closed(0, 10),                                                 \
      "damping ratio on the fundamental mode (D_f = 2 zeta omega_1); at most 10: above, the damping forces, "\
      "not the bars, carry the load (at 10 they take 5% of the work by the peak, the peak 3% lower than at 0.02)")\
    X(double, dampingOmega, "damping_omega", 0.0, "rad/s", Domain::atLeast(0),                              \
      "the circular frequency zeta is stated on: D_f = 2 zeta damping_omega (0: omega_1, the fundamental "    \
      "mode; another mode's, or one D_f for specimens of every size)")                                       \
    X(bool, tailDampingRelative, "tail_damping", false, "", Domain::choices({"absolute", "relative"}),        \
      "the mass-proportional damping from the load loss on: on each node's absolute velocity, or relative "  \
      "to its mean velocity (low-passed over damping_filter_periods): a part that moves with the drive is "  \
      "then not dragged, a vibration at omega_1 damped by zeta x 0.994 (2 periods)")                          \
    X(double, dampingFilterPeriods, "damping_filter_periods", 2.0, "", Domain::closed(0.5, 100),             \
      "tail_damping relative: the time constant of each node's mean velocity, in fundamental periods "       \
      "2 pi/omega_1; a vibration at omega keeps the ratio (omega tau)^2 / (1 + (omega tau)^2) of its damping")

// Dashpots in the bars that have left their elastic branch (dynamics/BarDashpots.hpp).
#define LDEM_BAR_DASHPOT_PARAMETERS(X)                                                                       \
    X(double, zetaHigh, "zeta_high", 0.2, "", Domain::closedOpen(0, 1),                                      \
      "numerical damping: the ratio, on the highest mode omega_max, of dashpots in the bars that have left "   \
      "their elastic branch, acting while such a bar is in compression (zeta_high omega/omega_max on mode "    \
      "omega); they damp the modes that clap across closing cracks; 0: none (then keep dt_safety at 0.4); "    \
      "the stable time step shrinks by the factor sqrt(1 + zeta_high^2) - zeta_high")

// The converged stop (dynamics/ConvergedStop.hpp).
#define LDEM_CONVERGED_STOP_PARAMETERS(X)                                                                    \
    X(double, convergedGrowth, "converged_growth", 0.01, "", Domain::open(0, 1),                             \
      "stop_at converged: U has converged when it grew by less than this fraction over the last doubling of "\
      "the mean strain since load loss, with the load still below stop_fraction x peak")

// The load-loss stop (dynamics/LoadLossStop.hpp).
#define LDEM_LOAD_LOSS_STOP_PARAMETERS(X)                                                                    \
    X(double, lossStopStrainRatio, "loss_stop_strain_ratio", 10.0, "", Domain::atLeast(0),                   \
      "stop_at load_loss: the run goes on at least to this multiple of the mean strain at the peak, so that " \
      "the softening branch and the crack are in the record")

// The past-the-peak stop (dynamics/PastPeakStop.hpp).
#define LDEM_PAST_PEAK_STOP_PARAMETERS(X)                                                                    \
    X(double, peakStopStrainRatio, "peak_stop_strain_ratio", 10.0, "", Domain::atLeast(1),                   \
      "stop_at past_peak: the run ends at this multiple of the mean strain at the peak, lost load or not")

// The final-strain stop (dynamics/FinalStrainStop.hpp).
#define LDEM_FINAL_STRAIN_STOP_PARAMETERS(X)                                                                 \
    X(double, finalStrain, "final_strain", 0.5, "", Domain::positive(),                                      \
      "stop at this mean strain if the event has not come; one before the first record is refused (exit 2): "\
      "it can never reach the peak")

// The load-loss detector (dynamics/LoadLoss.hpp).
#define LDEM_LOAD_LOSS_PARAMETERS(X)                                                                         \
    X(double, stopFraction, "stop_fraction", 0.01, "", Domain::closedOpen(0, 1),                             \
      "the load is lost when the stress, averaged over the split window, is below this fraction of the peak")\
    X(double, splitWindow, "split_window", 0.0, "s", Domain::atLeast(0),                                     \
      "averaging time of the load-loss test (0: two fundamental periods)")

// The run: the dynamic parts' lists above, in the table's order, and the choice of the stop.
#define LDEM_RUN_PARAMETERS(X)                                                                               \
    X(std::int64_t, seed, "seed", 1, "", Domain::atLeast(0), "random specimen (same seed, same specimen)")   \
    X(double, gravity, "gravity", 0.0, "m/s^2", Domain::closed(0, 100),                                      \
      "the specimen's weight: a body force m g along -z on every free DOF, rising over the drive's smooth "    \
      "start (9.81: a beam lying on its supports); its work counts as external work")                        \
    LDEM_MASS_DAMPING_PARAMETERS(X)                                                                          \
    LDEM_BAR_DASHPOT_PARAMETERS(X)                                                                           \
    X(StopAt, stopAt, "stop_at", StopAt::Separation, "",                                                     \
      Domain::choices({"separation", "load_loss", "converged", "past_peak"}),                                \
      "the event that ends the run: separation (no chain of intact bars joins the faces), load_loss, "       \
      "converged: separation or, for a specimen that hinges (triangular), U no longer growing after load "  \
      "loss, or past_peak: peak_stop_strain_ratio x the strain at the peak")                                 \
    LDEM_LOAD_LOSS_STOP_PARAMETERS(X)                                                                        \
    LDEM_PAST_PEAK_STOP_PARAMETERS(X)                                                                        \
    LDEM_CONVERGED_STOP_PARAMETERS(X)                                                                        \
    LDEM_FINAL_STRAIN_STOP_PARAMETERS(X)                                                                     \
    X(double, dt, "dt", 0.0, "s", Domain::atLeast(0), "time step (0: safety x stability limit)")             \
    X(double, dtSafety, "dt_safety", 0.8, "", Domain::openClosed(0, 1),                                      \
      "fraction of the stability limit allowed, 2/omega_max x (sqrt(1 + zeta_high^2) - zeta_high); without "\
      "the dashpots (zeta_high 0) keep it at 0.4: above, closing cracks pump energy into the highest modes")  \
    LDEM_LOAD_LOSS_PARAMETERS(X)                                                                             \
    X(double, energyTolerance, "energy_tolerance", 0.01, "", Domain::positive(),                             \
      "a run whose energy balance error exceeds this is flagged energy_error (and ldem exits 1)")            \
    X(int, recordEvery, "record_every", 0, "steps", Domain::atLeast(0),                                      \
      "steps between curve rows (0: one per eps_p/50 of mean strain at the initial rate)")                   \
    X(int, threads, "threads", 0, "", Domain::atLeast(0),                                                   \
      "OpenMP threads (0: OMP_NUM_THREADS if set, else one per 50,000 bars of the lattice, at most the cores " \
      "free to this process: those it may run on less those busy over 0.1 s; at least one)")

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

// The values a parameter may take: an interval of numbers, or one of named
// choices (a bool or an enum: the value is the index of its name).
struct Domain {
    double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
    bool loClosed = true, hiClosed = true;
    std::vector<std::string> names;  // non-empty: a choice

    static Domain positive() { return {0, std::numeric_limits<double>::infinity(), false, true, {}}; }
    static Domain atLeast(double a) { return {a, std::numeric_limits<double>::infinity(), true, true, {}}; }
    static Domain closed(double a, double b) { return {a, b, true, true, {}}; }
    static Domain closedOpen(double a, double b) { return {a, b, true, false, {}}; }
    static Domain openClosed(double a, double b) { return {a, b, false, true, {}}; }
    static Domain open(double a, double b) { return {a, b, false, false, {}}; }
    static Domain choices(std::vector<std::string> n) { return {0, 0, true, true, std::move(n)}; }

    bool isChoice() const { return !names.empty(); }
    bool contains(double x) const {
        return std::isfinite(x) && (loClosed ? x >= lo : x > lo) && (hiClosed ? x <= hi : x < hi);
    }
    // "> 0", ">= 1", "in [0, 0.5)", "one of bar, module"
    std::string describe() const;
};

std::string formatNumber(double x);  // shortest form of 6 significant digits
std::string formatWhole(double x);   // a whole number as all its digits: 2^70 is not 1.18059e+21

// The bar laws by name, in the registry's order (laws/Registry.hpp): the choices of `law`,
// whose value is a BarLawId, the law's index in the registry.
enum class BarLawId : std::uint8_t {};
std::vector<std::string> barLawNames();

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
