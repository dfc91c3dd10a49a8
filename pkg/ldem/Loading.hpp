// The loading of the cube tests (LDEM_SPEC section 6): its parameters and the
// drive, a displacement that grows smoothly from rest (the specimen says which
// DOFs follow it and with which weights, Specimen.hpp).
//
// Every prescribed degree of freedom follows u = weight * U(t), with U(t) the
// displacement of the most-pulled point:
//   U(t) = v0 (t - (t_r/pi) sin(pi t / t_r)) / 2   for t < t_r  (velocity ramps
//          v0 (t - t_r / 2)                        for t >= t_r  up as 1 - cos)
// so velocity and acceleration start at zero. v0 = strain rate x height.
// Once the load is lost the specimen hangs on mechanisms that carry almost no
// force, and separation needs strains far beyond the peak; a faster drive
// reaches them in fewer steps. Two ways (tail_drive):
// - fixed: the drive speeds up by a factor S (loss_speedup), with the same
//   smooth ramp starting at t_s:  U(t) + (S - 1) U(t - t_s);
// - adaptive (AdaptiveDrive, below): U is state from the load loss on, and its
//   velocity factor follows a quasi-static criterion, record by record.
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
enum class TailDrive { Fixed, Adaptive };

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
    // The program's velocity over v0 at t before the load loss (the smooth start's 0 to 1).
    double velocityFactor(double t) const;
};

// The adaptive drive after the load loss (tail_drive adaptive). Between the
// load loss and separation the specimen is mostly chains straightening; what
// loads them beyond their static share is the drag of the mass-proportional
// damping (on absolute velocity) and inertia, both in proportion to the
// drive's speed (results/separation/speedup_sweep.md). The criterion, at each
// record, from state n:
//   softening  = the fracture energy grew since the last record (some bar's damage moved);
//   face load  = max(|s_support|, |s_loaded|) / peak: the force the chains
//                carry (support) and that the drive must apply (loaded: the
//                chains' plus the drag and inertia of all the mass between),
//                against the specimen's strength;
//   target     = floor                                        while softening,
//                clamp(floor x load / face load, floor, ceiling)  otherwise,
// with floor = loss_speedup (the fixed drive's rate, the study's reference
// tail), ceiling = tail_max_speedup, load = tail_load. So the drive is at the
// reference rate whenever a bar softens or the faces carry tail_load x peak,
// and goes faster only in proportion as the chains are slack and the
// dynamic forces small. The factor S moves towards the target by at most the
// ratio `step` per record, and within a record interval of R steps the
// velocity ramps linearly from S_0 (the factor at the record) to S_1:
//   v_k = v0 (S_0 + (S_1 - S_0)(k + 1)/R),   k = 0..R-1 the step in the interval,
// so that the velocity never jumps by more than (step - 1) S_0 v0 / R in a
// step; U is state, U(n+1) = U(n) + dt v_k.
class AdaptiveDrive {
public:
    AdaptiveDrive() = default;
    AdaptiveDrive(double floor, double ceiling, double load, double step)
        : floor_(floor), ceiling_(ceiling), load_(load), step_(step) {}
    // The criterion (a pure function): the factor the drive heads for.
    static double target(double floor, double ceiling, double load, bool softening, double faceLoad);
    // The factor at the end of the next record interval, from the factor s now: target clamped to [s/step, s step].
    double next(double s, bool softening, double faceLoad) const;
    // At the load-loss record: U(n), U(n-1) of the program, its velocity factor there and the fracture energy.
    void start(double U, double Uprev, double factor, double fracture);
    bool active() const { return active_; }
    // At each record from the load-loss one on (state n): picks S_1 of the interval starting at this step.
    void record(double fracture, double stressSupport, double stressLoaded, double peakStress);
    // Velocity factor of step k (0..R-1) of the interval, and U(n+1) from U(n) with it.
    double factor(int k, int R) const { return S0_ + (S1_ - S0_) * (k + 1) / R; }
    void advance(double dt, double v0, int k, int R) { Uprev = U, U += dt * v0 * factor(k, R); }
    double speedFactor() const { return S1_; }  // the factor the current interval ends at
    double U = 0, Uprev = 0;                    // drive displacement at t_n and t_n-1 [m]
    // Its state, for a checkpoint, and back.
    std::vector<double> state() const { return {double(active_), U, Uprev, S0_, S1_, fracture_}; }
    void setState(const std::vector<double>& s);

private:
    double floor_ = 1, ceiling_ = 1, load_ = 0.05, step_ = 1.2;
    bool active_ = false;
    double S0_ = 1, S1_ = 1;  // factor at the start and the end of the current record interval
    double fracture_ = 0;     // fracture energy at the last record [J]
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
