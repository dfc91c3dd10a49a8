#include "ldem/dynamics/ConstantRateDrive.hpp"

namespace ldem {

double Drive::displacement(double t) const {
    const double U = v0 * smoothRampIntegral(t, rampTime);
    return t <= speedupStart ? U : U + (speedup - 1) * v0 * smoothRampIntegral(t - speedupStart, speedupRamp);
}

}  // namespace ldem
