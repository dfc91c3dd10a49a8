// The specimen's weight (gravity): a body force m g_z along -z on every free
// DOF, rising over the drive's smooth start t_r as g_z(n) = -g (1 - cos(pi t/t_r))/2,
// t = n dt. Laid on its supports at once, a specimen would ring in its
// fundamental by its whole static sag (a beam's load by +-100 N on a 1 kN peak,
// decaying as 1/(zeta omega_1)); risen over t_r, the ringing left in a mode omega
// is about 1/((omega t_r/pi)^2 - 1) of its share of the sag (7 % at two periods).
// Its work, sum_n m g_n (x(n+1) - x(n-1))/2, is summed by parts:
// g_N Y_N - sum_n (g_{n+1} - g_n) Y_n with Y_n = sum m (x(n+1) + x(n))/2, the
// last step's term being weightWork (Integrator.hpp); each change of g puts its
// term into the external work when the step is about to be taken, where
// u - dt v/2 is (x(n+1) + x(n))/2.
#pragma once
#include <cstdint>
#include <vector>

#include "ldem/Field3.hpp"
#include "ldem/Integrator.hpp"
#include "ldem/Lattice.hpp"
#include "ldem/dynamics/ConstantRateDrive.hpp"

namespace ldem {

class RisingWeight {
public:
    RisingWeight() = default;
    RisingWeight(double gravity, double riseTime, double dt) : g_(gravity), rise_(riseTime), dt_(dt) {}
    double gz() const { return gz_; }  // of the last step [m/s^2]
    // g_z for step n, about to be taken: the work its change takes from the external work [J].
    double stepTo(std::int64_t n, const Lattice& lat, const std::vector<std::uint8_t>& mask, const Field3& u,
                  const Field3& v) {
        const double gz = at(n);
        if (gz == gz_) return 0.0;
        const double work = weightWork(lat, mask, gz - gz_, dt_, u, v);
        gz_ = gz;
        return work;
    }
    // Its work up to state n, the last step's term (weightWork).
    double work(const Lattice& lat, const std::vector<std::uint8_t>& mask, const Field3& u, const Field3& v) const {
        return weightWork(lat, mask, gz_, dt_, u, v);
    }
    void restoreAt(std::int64_t n) { gz_ = n > 0 ? at(n - 1) : 0.0; }  // a run set back to state n

private:
    double at(std::int64_t n) const { return -g_ * smoothRampVelocity(double(n) * dt_, rise_); }
    double g_ = 0, rise_ = 0, dt_ = 0, gz_ = 0;
};

}  // namespace ldem
