// Opening control: the drive moves so that an opening c (a probe, e.g. the CMOD)
// follows c*(t) = r S(t), S the smooth ramp. U is state, advanced from state n:
//   U(n+1) = U(n) + dt clamp((r S'(t) + g (c*(t) - c)) / a, -v_max S'(t), v_max S'(t)),  t = t_n + dt/2,
// a = c / U the secant ratio, v_max the displacement program's v0 (the actuator's
// limit). g = D_f / 2: with mass-proportional damping every mode has 2 zeta_i
// omega_i = D_f, and the loop U' = (g/a)(c* - c) around a mode crosses -180
// degrees with the gain (g/a) a_t / D_f, below 1 while the tangent ratio a_t < 2a.
#pragma once
#include <stdexcept>
#include <vector>

#include "ldem/Parameters.hpp"
#include "ldem/dynamics/ConstantRateDrive.hpp"
#include "ldem/dynamics/Part.hpp"

// Its parameters.
#define LDEM_SERVO_PARAMETERS(X)                                                                             \
    X(double, openingRate, "opening_rate", 0.0, "m/s", Domain::atLeast(0),                                   \
      "opening control: the rate of the specimen's controlled probe (0: displacement control at strain_rate)")

namespace ldem {

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


// The drive part: U follows the servo from the start.
class ServoDrive {
public:
    static constexpr const char* name = "servo";
    static constexpr const char* doc = "opening control: the controlled probe opens at opening_rate";
    static constexpr bool kChoice = false;  // the drive of every specimen with a controlled probe
    struct Params {
        LDEM_SERVO_PARAMETERS(LDEM_DECLARE_MEMBER)
    };
    // The servo at opening_rate with the gain g = D_f / 2 (above), on the fixed drive's program.
    ServoDrive(const Params& p, const ConstantRateDrive& fixed, double Df) : program_(fixed.program()) {
        servo_.rate = p.openingRate, servo_.gain = 0.5 * Df;
    }
    ServoDrive(const Params& p, const DriveSetup& s) : ServoDrive(p, ConstantRateDrive(ConstantRateDrive::Params{}, s), s.Df) {}
    // Refuses opening control without opening_rate, and opening_rate without opening control.
    static const char* select(const Params& p, const DriveSetup& s, bool) {
        if (s.openingControl != (p.openingRate > 0))
            throw std::invalid_argument(s.openingControl ? "opening control (a controlled probe) needs opening_rate > 0"
                                                         : "opening_rate needs a controlled probe (measure.control)");
        return name;
    }
    void setUp(const RunSetup&) {}
    double now(double, double) const { return servo_.U; }
    double before(double, double) const { return servo_.Uprev; }
    double next(const DriveStep& c) {
        servo_.advance(c.dt, c.time, c.opening, program_);
        return servo_.U;
    }
    void record(const DriveRecord&) {}
    const Drive& program() const { return program_; }
    const Servo& servo() const { return servo_; }
    std::vector<double> state() const { return {servo_.U, servo_.Uprev}; }
    void setState(const std::vector<double>& s) { servo_.U = s.at(0), servo_.Uprev = s.at(1); }

private:
    Drive program_;
    Servo servo_;
};

}  // namespace ldem
