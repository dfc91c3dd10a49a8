// A drive at a constant velocity: the loaded face moves at drive_velocity [m/s]
// after the smooth start, U(t) = v (t - (t_r/pi) sin(pi t/t_r)) / 2 for t < t_r,
// v (t - t_r/2) after (ConstantRateDrive.hpp, the same program with v0 = v), and
// is never sped up: a test at a given crosshead speed, whatever the specimen's size.
#pragma once
#include <vector>

#include "ldem/Parameters.hpp"
#include "ldem/dynamics/ConstantRateDrive.hpp"
#include "ldem/dynamics/Part.hpp"

// Its parameters.
#define LDEM_CONSTANT_VELOCITY_PARAMETERS(X)                                                                 \
    X(double, driveVelocity, "drive_velocity", 2.4e-3, "m/s", Domain::openClosed(0, 10),                     \
      "tail_drive constant_velocity: the velocity of the most-pulled point after the smooth start (2.4e-3: "  \
      "strain_rate's default on the 0.12 m cube)")

namespace ldem {

class ConstantVelocityDrive {
public:
    static constexpr const char* name = "constant_velocity";
    static constexpr const char* doc = "drive_velocity from the smooth start on, never sped up";
    static constexpr bool kChoice = true;
    struct Params {
        LDEM_CONSTANT_VELOCITY_PARAMETERS(LDEM_DECLARE_MEMBER)
    };
    ConstantVelocityDrive(const Params& p, const DriveSetup& s)
        : program_{p.driveVelocity, s.program.rampTime > 0 ? s.program.rampTime : 4 * 3.14159265358979323846 / s.omegaDrive} {
        program_.strainRate = p.driveVelocity / s.gaugeLength;
    }
    static const char* select(const Params&, const DriveSetup&, bool) { return name; }
    void setUp(const RunSetup&) {}
    double now(double t, double) const { return program_.displacement(t); }
    double before(double t, double dt) const { return program_.displacement(t - dt); }
    double next(const DriveStep& c) const { return program_.displacement(c.time + c.dt); }
    void record(const DriveRecord&) {}
    const Drive& program() const { return program_; }
    std::vector<double> state() const { return {}; }
    void setState(const std::vector<double>&) {}

private:
    Drive program_;
};

}  // namespace ldem
