#include "ldem/dynamics/Registry.hpp"

#include <stdexcept>

namespace ldem {

namespace {
template <class... D>
std::tuple<D...> makeEach(const std::tuple<D...>*, const RunParams& run, const DampingSetup& s) {
    return {D(run, s)...};
}
}  // namespace

Dampings makeDampings(const RunParams& run, const DampingSetup& s) {
    return makeEach(static_cast<const Dampings*>(nullptr), run, s);
}

double dampingCoefficient(const Dampings& d) { return std::get<MassDamping>(d).coefficient(); }

ConstantRateDrive fixedDrive(const LoadingParams& load, const DynamicsSetup& s) {
    constexpr double pi = 3.14159265358979323846;
    ConstantRateDrive::Params p;
    {
        auto& to = p;
        const auto& from = load;
        LDEM_DRIVE_PARAMETERS(LDEM_COPY_MEMBER)
        LDEM_SPEEDUP_PARAMETERS(LDEM_COPY_MEMBER)
    }
    return ConstantRateDrive(p, s.gaugeLength, 2 * pi / s.omega1);
}

Drives makeDrive(const LoadingParams& load, const Material& m, const DynamicsSetup& s, const Dampings& d) {
    const ConstantRateDrive fixed = fixedDrive(load, s);
    if (load.tailDrive == TailDrive::Adaptive && load.tailMaxSpeedup < load.lossSpeedup)
        throw std::invalid_argument("tail_max_speedup (" + formatNumber(load.tailMaxSpeedup) +
                                    ") must be at least loss_speedup (" + formatNumber(load.lossSpeedup) +
                                    ") for the adaptive drive");
    if (s.openingControl != (load.openingRate > 0))
        throw std::invalid_argument(s.openingControl ? "opening control (a controlled probe) needs opening_rate > 0"
                                                     : "opening_rate needs a controlled probe (measure.control)");
    const double Df = dampingCoefficient(d);
    if (s.openingControl) return ServoDrive(LDEM_PART_PARAMS(ServoDrive::Params, LDEM_SERVO_PARAMETERS, load), fixed, Df);
    // Undamped (D_f = 0) the drive stays fixed: nothing would damp the ringing
    // its changes of speed set off (measured, 0.08 m on rollers, zeta 0: balance
    // error 0.015 against 0.008 fixed, and another path to separation).
    if (load.tailDrive != TailDrive::Adaptive || !(Df > 0)) return fixed;
    const auto p = LDEM_PART_PARAMS(AdaptiveTailDrive::Params, LDEM_ADAPTIVE_DRIVE_PARAMETERS, load);
    // rho H v0 / T: the face stress of a unit change of S over a record, were a column of the
    // specimen's height to follow the drive; D_f T its drag's share. Damped relative to
    // the mean velocity (tail_damping relative, from the load loss on, as this bound) a
    // steady motion has no drag: the bound is inertia's, m a, and the lag of the mean
    // behind a speed-up, at most D_f tau m a (MassDamping.hpp): rho H v0 (1 + D_f tau) / T, D_f T = 0.
    const double T = s.recordEvery * s.dt;
    const MassDamping& mass = std::get<MassDamping>(d);
    const double column = m.rho * s.gaugeLength * fixed.program().v0 / T;
    const AdaptiveDrive::Limits limits{load.lossSpeedup, p.tailMaxSpeedup, p.tailLoad, p.tailDrag, p.tailStep,
                                       s.splitWindow,
                                       mass.relative() ? column * (1 + Df * mass.filterTime()) : column,
                                       mass.relative() ? 0.0 : Df * T, T};
    // The pace's brake: a drop of the pace by dP in a record decelerates the column by dP v0 / T.
    // It acts before the load loss, where the damping is of the absolute velocity whatever
    // tail_damping says: the plain column, never the relative damping's lag.
    const CrackPace::Limits pace{p.crackPace,   p.crackKinetic, column > 0 ? p.tailDrag / column : 0.0,
                                 p.tailStep,    p.crackSecant,  p.crackBand};
    return AdaptiveTailDrive(fixed, limits, pace);
}

std::vector<StopRules> makeStops(const RunParams& run) {
    std::vector<StopRules> stops{SeparationStop()};
    if (run.stopAt == StopAt::LoadLoss)
        stops.emplace_back(LoadLossStop(LDEM_PART_PARAMS(LoadLossStop::Params, LDEM_LOAD_LOSS_STOP_PARAMETERS, run)));
    if (run.stopAt == StopAt::Converged)
        stops.emplace_back(ConvergedStop(LDEM_PART_PARAMS(ConvergedStop::Params, LDEM_CONVERGED_STOP_PARAMETERS, run)));
    if (run.stopAt == StopAt::PastPeak)
        stops.emplace_back(PastPeakStop(LDEM_PART_PARAMS(PastPeakStop::Params, LDEM_PAST_PEAK_STOP_PARAMETERS, run)));
    stops.emplace_back(FinalStrainStop(LDEM_PART_PARAMS(FinalStrainStop::Params, LDEM_FINAL_STRAIN_STOP_PARAMETERS, run)));
    return stops;
}

}  // namespace ldem
