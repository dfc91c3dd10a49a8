// The drive at a constant rate with a smooth start (LDEM_SPEC section 6), and its
// fixed speed-up after the load loss (tail_drive fixed). Each prescribed DOF
// follows u = weight x U(t), U the most-pulled point's displacement:
//   U(t) = v0 (t - (t_r/pi) sin(pi t / t_r)) / 2  for t < t_r,  v0 (t - t_r / 2) after,
// v0 = strain_rate x the gauge length, so that velocity and acceleration start at
// zero. Once the load is lost a faster drive reaches separation in fewer steps:
// U(t) + (S - 1) U_q(t - t_s), U_q the same ramp over t_q (fixed: S = loss_speedup,
// t_q = t_r). This program is every drive's (the shared ProgramParams).
#pragma once
#include <cmath>
#include <limits>
#include <vector>

#include "ldem/Parameters.hpp"
#include "ldem/dynamics/Part.hpp"

namespace ldem {

// Integral over [0, t] of a velocity that rises from 0 to 1 as (1 - cos(pi t/t_r))/2.
inline double smoothRampIntegral(double t, double tr) {
    constexpr double pi = 3.14159265358979323846;
    if (t <= 0) return 0;
    if (t < tr) return 0.5 * (t - tr / pi * std::sin(pi * t / tr));
    return t - 0.5 * tr;
}
// Its derivative: the velocity (1 - cos(pi t/t_r))/2, then 1.
inline double smoothRampVelocity(double t, double tr) {
    constexpr double pi = 3.14159265358979323846;
    if (t <= 0) return 0;
    return t < tr ? 0.5 * (1 - std::cos(pi * t / tr)) : 1.0;
}

struct Drive {
    double v0 = 0;        // final velocity of the most-pulled point [m/s]
    double rampTime = 0;  // [s]
    double speedup = 1;   // velocity factor after speedupStart
    double speedupStart = std::numeric_limits<double>::infinity();  // [s]; never, until the load is lost
    double speedupRamp = 0;  // t_q, the speed-up's ramp [s]
    double strainRate = 0;   // v0 / the gauge length [1/s]
    double displacement(double t) const;
};

class ConstantRateDrive {
public:
    static constexpr const char* name = "fixed";
    static constexpr const char* doc = "loss_speedup times as fast once the load is lost, ramped in once";
    static constexpr bool kChoice = true;
    struct Params {};
    ConstantRateDrive() = default;  // at rest: v0 = 0
    // v0 = strain_rate x the gauge length; the ramp ramp_time, or two periods of the drive's own mode (0).
    ConstantRateDrive(const ProgramParams& p, double gaugeLength, double periodDrive)
        : program_{p.strainRate * gaugeLength, p.rampTime > 0 ? p.rampTime : 2 * periodDrive, p.lossSpeedup} {
        program_.speedupRamp = program_.rampTime, program_.strainRate = p.strainRate;
    }
    ConstantRateDrive(const Params&, const DriveSetup& s)
        : ConstantRateDrive(s.program, s.gaugeLength, 2 * 3.14159265358979323846 / s.omegaDrive) {}
    static const char* select(const Params&, const DriveSetup&, bool) { return name; }
    void setUp(const RunSetup&) {}
    double now(double t, double) const { return program_.displacement(t); }
    double before(double t, double dt) const { return program_.displacement(t - dt); }
    double next(const DriveStep& c) const { return program_.displacement(c.time + c.dt); }
    void record(const DriveRecord& r) {
        if (r.lossNow) program_.speedupStart = r.point.time;
    }
    // From time on, factor times as fast, ramped in over ramp.
    void speedUp(double time, double factor, double ramp) {
        program_.speedupStart = time, program_.speedup = factor, program_.speedupRamp = ramp;
    }
    const Drive& program() const { return program_; }
    std::vector<double> state() const { return {program_.speedupStart}; }
    void setState(const std::vector<double>& s) { program_.speedupStart = s.at(0); }

private:
    Drive program_;
};

}  // namespace ldem
