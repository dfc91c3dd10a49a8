#include "ldem/dynamics/ServoDrive.hpp"

#include <algorithm>
#include <cmath>

namespace ldem {

double Servo::velocity(double t, double opening, const Drive& program) const {
    const double ramp = smoothRampVelocity(t, program.rampTime);
    const double demand = rate * ramp + gain * (rate * smoothRampIntegral(t, program.rampTime) - opening);
    const double a = U > 0 && opening > 0 ? opening / U : 0.0;
    const double limit = program.v0 * ramp;
    return a > 0 ? std::clamp(demand / a, -limit, limit) : std::copysign(limit, demand);
}

}  // namespace ldem
