// The registry of the dynamic parts (Part.hpp): which exist, and the ones a
// run is built with, chosen by name (tail_drive, stop_at; opening control when
// the specimen has a controlled probe).
//
// A new part is a header (and .cpp) in this folder, its line below, its
// parameters' list in Parameters.hpp and, for a drive or a stop, its choice's
// name in that parameter's domain and its case in makeDrive / makeStops.
// A new damping: its header (a constructor from the RunParams and DampingSetup,
// the hooks of Part.hpp), and its type at the end of Dampings.
#pragma once
#include <cstddef>
#include <string>
#include <tuple>
#include <utility>
#include <variant>
#include <vector>

#include "ldem/Loading.hpp"
#include "ldem/Material.hpp"
#include "ldem/RunParams.hpp"
#include "ldem/dynamics/AdaptiveDrive.hpp"
#include "ldem/dynamics/BarDashpots.hpp"
#include "ldem/dynamics/ConstantRateDrive.hpp"
#include "ldem/dynamics/ConvergedStop.hpp"
#include "ldem/dynamics/FinalStrainStop.hpp"
#include "ldem/dynamics/LoadLoss.hpp"
#include "ldem/dynamics/LoadLossStop.hpp"
#include "ldem/dynamics/MassDamping.hpp"
#include "ldem/dynamics/PastPeakStop.hpp"
#include "ldem/dynamics/SeparationStop.hpp"
#include "ldem/dynamics/ServoDrive.hpp"

namespace ldem {

using Drives = std::variant<ConstantRateDrive, AdaptiveTailDrive, ServoDrive>;
using StopRules = std::variant<SeparationStop, LoadLossStop, ConvergedStop, PastPeakStop, FinalStrainStop>;
using Dampings = std::tuple<MassDamping, BarDashpots>;  // every one applied, in this order

// What the parts are built from, beyond their parameters.
struct DynamicsSetup {
    double omega1 = 0;       // [rad/s]
    double dt = 0;           // [s]
    double gaugeLength = 0;  // [m]
    double splitWindow = 0;  // [s]
    int recordEvery = 1;
    bool openingControl = false;  // the specimen has a controlled probe
};

Dampings makeDampings(const RunParams& run, const DampingSetup& s);
double dampingCoefficient(const Dampings& d);  // D_f of the mass-proportional damping [1/s]
// The program of every drive (v0, the ramp, the speed-up), whatever the drive.
ConstantRateDrive fixedDrive(const LoadingParams& load, const DynamicsSetup& s);
// servo under opening control, else tail_drive: adaptive (if damped: D_f > 0) or fixed. Checks their parameters.
Drives makeDrive(const LoadingParams& load, const Material& m, const DynamicsSetup& s, const Dampings& d);
// separation, then stop_at's rule (load_loss, converged, past_peak; none for separation), then the final strain.
std::vector<StopRules> makeStops(const RunParams& run);

// The node update with every damping's terms, from the undamped one.
inline CentralDifference nodeUpdate(Dampings& d, double dt) {
    return std::apply([&](auto&... damping) {
        CentralDifference cd(dt, 0.0);
        ((cd = damping.nodeUpdate(cd)), ...);
        return cd;
    }, d);
}

// Every damping's record.
inline void recordDampings(Dampings& d, const DampingRecord& r) {
    std::apply([&](auto&... damping) { (damping.record(r), ...); }, d);
}

// The stable time step's factor of all the dampings together.
inline double stepFactor(const Dampings& d) {
    return std::apply([](const auto&... damping) { return (1.0 * ... * damping.stepFactor()); }, d);
}

// The bar forces of the damping that has them in the force pass (one at most), or none.
inline DashpotPass barPass(Dampings& d, const Field3& v) {
    return std::apply([&](auto&... damping) {
        DashpotPass pass;
        ((pass = pass.state ? pass : damping.barPass(v)), ...);
        return pass;
    }, d);
}

// f(damping) summed over the dampings (their layer works).
template <class F>
double sumOver(const Dampings& d, F f) {
    return std::apply([&](const auto&... damping) { return (0.0 + ... + f(damping)); }, d);
}

// A part's name and state, for checkpoints: "drive_fixed", "stop_separation", "damping_mass", ...
template <class Part>
std::pair<std::string, std::vector<double>> partState(const char* role, const Part& p) {
    return {std::string(role) + "_" + Part::name, p.state()};
}

}  // namespace ldem
