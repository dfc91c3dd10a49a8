#include "ldem/Loading.hpp"

#include <algorithm>
#include <cmath>

namespace ldem {

void LoadingParams::validate() const { LDEM_LOADING_PARAMETERS(LDEM_CHECK_MEMBER) }

namespace {
// Integral over [0, t] of a velocity that rises from 0 to 1 as (1 - cos(pi t/t_r))/2.
double smoothRampIntegral(double t, double tr) {
    constexpr double pi = 3.14159265358979323846;
    if (t <= 0) return 0;
    if (t < tr) return 0.5 * (t - tr / pi * std::sin(pi * t / tr));
    return t - 0.5 * tr;
}
// Its derivative: the velocity (1 - cos(pi t/t_r))/2, then 1.
double smoothRampVelocity(double t, double tr) {
    constexpr double pi = 3.14159265358979323846;
    if (t <= 0) return 0;
    return t < tr ? 0.5 * (1 - std::cos(pi * t / tr)) : 1.0;
}
}  // namespace

double Drive::displacement(double t) const {
    const double U = v0 * smoothRampIntegral(t, rampTime);
    return t <= speedupStart ? U : U + (speedup - 1) * v0 * smoothRampIntegral(t - speedupStart, rampTime);
}

double Drive::velocityFactor(double t) const { return smoothRampVelocity(t, rampTime); }

double AdaptiveDrive::target(double floor, double ceiling, double load, bool softening, double faceLoad) {
    if (softening || !(faceLoad < load)) return floor;  // NaN: the floor too
    return faceLoad > 0 ? std::clamp(floor * load / faceLoad, floor, ceiling) : ceiling;
}

double AdaptiveDrive::next(double s, bool softening, double faceLoad) const {
    return std::clamp(target(floor_, ceiling_, load_, softening, faceLoad), s / step_, s * step_);
}

void AdaptiveDrive::start(double U0, double Uprev0, double factor, double fracture) {
    active_ = true, U = U0, Uprev = Uprev0, S0_ = S1_ = factor, fracture_ = fracture;
}

void AdaptiveDrive::record(double fracture, double stressSupport, double stressLoaded, double peakStress) {
    const bool softening = fracture > fracture_;
    const double faceLoad = std::max(std::abs(stressSupport), std::abs(stressLoaded)) / peakStress;
    fracture_ = fracture;
    S0_ = S1_, S1_ = next(S0_, softening, faceLoad);
}

void AdaptiveDrive::setState(const std::vector<double>& s) {
    active_ = s.at(0) != 0, U = s.at(1), Uprev = s.at(2), S0_ = s.at(3), S1_ = s.at(4), fracture_ = s.at(5);
}

double Servo::velocity(double t, double opening, const Drive& program) const {
    const double ramp = smoothRampVelocity(t, program.rampTime);
    const double demand = rate * ramp + gain * (rate * smoothRampIntegral(t, program.rampTime) - opening);
    const double a = U > 0 && opening > 0 ? opening / U : 0.0;
    const double limit = program.v0 * ramp;
    return a > 0 ? std::clamp(demand / a, -limit, limit) : std::copysign(limit, demand);
}

}  // namespace ldem
