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

double Servo::velocity(double t, double opening, const Drive& program) const {
    const double ramp = smoothRampVelocity(t, program.rampTime);
    const double demand = rate * ramp + gain * (rate * smoothRampIntegral(t, program.rampTime) - opening);
    const double a = U > 0 && opening > 0 ? opening / U : 0.0;
    const double limit = program.v0 * ramp;
    return a > 0 ? std::clamp(demand / a, -limit, limit) : std::copysign(limit, demand);
}

}  // namespace ldem
