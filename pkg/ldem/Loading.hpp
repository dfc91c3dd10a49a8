// The loading of the cube tests (LDEM_SPEC section 6): its parameters and the
// drive, a displacement that grows smoothly from rest (the specimen says which
// DOFs follow it and with which weights, Specimen.hpp).
//
// Every prescribed degree of freedom follows u = weight * U(t), with U(t) the
// displacement of the most-pulled point:
//   U(t) = v0 (t - (t_r/pi) sin(pi t / t_r)) / 2   for t < t_r  (velocity ramps
//          v0 (t - t_r / 2)                        for t >= t_r  up as 1 - cos)
// so velocity and acceleration start at zero. v0 = strain rate x height.
// Once the load is lost the drive can speed up by a factor S, with the same
// smooth ramp starting at t_s:  U(t) + (S - 1) U(t - t_s). The specimen then
// hangs on mechanisms that carry almost no force, and separation needs strains
// far beyond the peak; a faster drive reaches them in fewer steps.
//
// Or the drive is a servo (Servo, below) that holds an opening to a program,
// as laboratories run notched beams past their peak under CMOD control.
#pragma once
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "ldem/Lattice.hpp"
#include "ldem/Parameters.hpp"

namespace ldem {

enum class LoadShape { Uniform, Triangular };

// LDEM_LOADING_PARAMETERS (Parameters.hpp): load shape, strain rate, smooth
// start, lateral DOFs of the faces, speed-up after load loss.
struct LoadingParams {
    LDEM_LOADING_PARAMETERS(LDEM_DECLARE_MEMBER)
    void validate() const;
};

struct Drive {
    double v0 = 0;        // final velocity of the most-pulled point [m/s]
    double rampTime = 0;  // [s]
    double speedup = 1;   // velocity factor after speedupStart
    double speedupStart = std::numeric_limits<double>::infinity();  // [s]; never, until the load is lost
    double displacement(double t) const;
};

// Opening control: the drive moves so that an opening c (a probe, e.g. the
// CMOD) follows the program c*(t) = r S(t), S the smooth ramp above. The drive
// displacement U is state, advanced once per step from state n:
//   U(n+1) = U(n) + dt clamp((r S'(t) + g (c*(t) - c)) / a, -v_max S'(t), v_max S'(t)),  t = t_n + dt/2,
// with a = c / U the secant ratio of opening to drive displacement (unknown,
// and the velocity v_max S'(t), until both have moved): the velocity that
// opens the mouth at the program's rate, plus a correction of the lag at the
// rate g [1/s]. v_max (Drive::v0, displacement control's rate) is the actuator's
// speed limit, reached smoothly. Why g = D_f / 2: with mass-proportional
// damping every mode has 2 zeta_i omega_i = D_f, and the integral loop
// U' = (g/a) (c* - c) around a mode that opens the mouth as c = a_t U crosses
// -180 degrees at omega_i with the gain (g/a) a_t / D_f; below 1, stable, as
// long as the tangent ratio a_t < 2a. Past the peak a crack that runs on its
// own opens the mouth ahead of the program (c > c*), and the drive backs off.
struct Servo {
    double rate = 0;      // r [m/s]
    double gain = 0;      // g [1/s]
    double U = 0, Uprev = 0;  // drive displacement at t_n and t_n-1 [m]
    // Drive velocity at time t, from the opening c at t_n; the actuator's
    // speed limit v_max and the ramp are those of the displacement program.
    double velocity(double t, double opening, const Drive& program) const;
    // U(n+1) from U(n) with the velocity at the middle of [t_n, t_n+1] (the program's ramp, there, to O(dt^3)).
    void advance(double dt, double t, double opening, const Drive& program) {
        Uprev = U, U += dt * velocity(t + 0.5 * dt, opening, program);
    }
};

}  // namespace ldem
