#include "ldem/Loading.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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

double AdaptiveDrive::target(const Limits& l, bool softening, double chainLoad) {
    if (softening || std::isnan(chainLoad)) return l.floor;
    return chainLoad > 0 ? std::clamp(l.floor * l.load / chainLoad, l.floor, l.ceiling) : l.ceiling;
}

double AdaptiveDrive::next(double s, bool softening, double chainLoad, double peakStress) const {
    double lo = s / lim_.step, hi = s * lim_.step;
    if (lim_.column > 0) {
        const double B = lim_.drag * peakStress / lim_.column;
        lo = std::max(lo, s - B), hi = std::min(hi, (B + s) / (1 + lim_.dampingT));
    }
    hi = std::max(hi, lo);  // drag alone above the budget: slow down as fast as inertia allows
    return std::max(std::clamp(target(lim_, softening, chainLoad), lo, hi), lim_.floor);
}

void AdaptiveDrive::start(double U0, double Uprev0, double fracture) {
    active_ = true, U = U0, Uprev = Uprev0, S0_ = S1_ = lim_.floor, fracture_ = fracture;
    time_ = std::numeric_limits<double>::quiet_NaN();  // the first record starts the average
}

void AdaptiveDrive::record(double time, double fracture, double stressSupport, double peakStress) {
    const bool softening = fracture > fracture_;
    if (std::isnan(time_) || !(lim_.tau > 0)) support_ = stressSupport;
    else support_ += -std::expm1(-(time - time_) / lim_.tau) * (stressSupport - support_);  // weight 1 - exp(-dt/tau)
    fracture_ = fracture, time_ = time;
    S0_ = S1_;
    S1_ = next(S0_, softening, std::abs(support_) / peakStress, peakStress);
}

void AdaptiveDrive::setState(const std::vector<double>& s) {
    active_ = s.at(0) != 0, U = s.at(1), Uprev = s.at(2), S0_ = s.at(3), S1_ = s.at(4), fracture_ = s.at(5);
    time_ = s.at(6), support_ = s.at(7);
}

double Servo::velocity(double t, double opening, const Drive& program) const {
    const double ramp = smoothRampVelocity(t, program.rampTime);
    const double demand = rate * ramp + gain * (rate * smoothRampIntegral(t, program.rampTime) - opening);
    const double a = U > 0 && opening > 0 ? opening / U : 0.0;
    const double limit = program.v0 * ramp;
    return a > 0 ? std::clamp(demand / a, -limit, limit) : std::copysign(limit, demand);
}

}  // namespace ldem
