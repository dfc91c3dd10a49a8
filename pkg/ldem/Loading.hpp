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
};

// The adaptive drive after the load loss (tail_drive adaptive). Between the
// load loss and separation the specimen is mostly chains straightening; what
// loads them beyond their static share is the drag of the mass-proportional
// damping (on absolute velocity) and inertia, both in proportion to the
// drive's speed (results/separation/speedup_sweep.md). From the load loss the
// drive first speeds up to the floor S_f = loss_speedup exactly as the fixed
// one does (the same ramp, the same bits); from the end of that ramp on, U is
// state and its velocity factor S >= S_f follows, record by record, a
// quasi-static criterion on state n:
//   softening    the fracture energy grew since the last record (some bar's damage moved);
//   chain load   c = |<s_support>| / peak: what the chains carry to the fixed
//                face, against the specimen's strength; it rises as a chain
//                straightens, before its bars soften. <.> is an exponential
//                average over tau (the split window, two fundamental periods):
//                a specimen rings after its load loss, a free vibration the
//                drive neither makes nor feeds;
//   target       S_f while softening, else clamp(S_f tail_load / c, S_f, tail_max_speedup):
// back at the reference rate whenever a bar softens or the chains carry
// tail_load x peak, faster in inverse proportion to their load while slack.
// The speed then moves towards the target within three bounds per record:
// - the ratio tail_step;
// - drag and inertia: past its load loss a specimen hangs from the drive on
//   its chains, and the part above them moves with it (0.48 m, seed 2, at
//   S_f: the whole cube, K = M v^2 / 2). The stress that the drive's own
//   motion puts on that part's face is rho H (a + D_f v) at most (H the
//   gauge length); it is kept below tail_drag x peak:
//       S_1 <= (B + S_0) / (1 + D_f T),   S_1 >= S_0 - B,   B = tail_drag peak T / (rho H v0),
//   T = R dt the record interval, a = (S_1 - S_0) v0 / T over it (measured
//   without it, 0.48 m seed 2: a factor of 1.1 per record from 20 to 60
//   broke bars in the hanging cube and doubled U);
// - never below S_f (the fixed drive's own rate is always allowed).
// Undamped (zeta 0) the drive stays fixed (Simulation::run).
// Within a record interval of R steps the velocity ramps linearly from S_0
// (the factor at the record) to S_1:
//   v_k = v0 (S_0 + (S_1 - S_0)(k + 1)/R),   k = 0..R-1 the step in the interval,
// so that it never jumps by more than |S_1 - S_0| v0 / R <= (tail_step - 1)
// max(S_0, S_1) v0 / R in a step; U(n+1) = U(n) + dt v_k.
class AdaptiveDrive {
public:
    struct Limits {
        double floor = 20, ceiling = 2000;  // S_f = loss_speedup, tail_max_speedup
        double load = 0.005, drag = 0.1;    // tail_load, tail_drag
        double step = 1.1;                  // tail_step
        double tau = 0;                     // averaging time of the support's stress [s] (0: none)
        double column = 0;                  // rho H v0 / T: face stress of a unit change of S over a record [Pa] (0: no bound)
        double dampingT = 0;                // D_f T
    };
    AdaptiveDrive() = default;
    explicit AdaptiveDrive(const Limits& l) : lim_(l) {}
    // The criterion (a pure function): the factor the drive heads for.
    static double target(const Limits& l, bool softening, double chainLoad);
    // The factor at the end of the next record interval from the factor s now:
    // the target within the bounds of tail_step and of drag and inertia.
    double next(double s, bool softening, double chainLoad, double peakStress) const;
    // At the record that ends the fixed ramp to the floor: U(n), U(n-1), the fracture energy.
    void start(double U, double Uprev, double fracture);
    bool active() const { return active_; }
    // At each record from then on (state n): picks S_1 of the interval starting at this step.
    void record(double time, double fracture, double stressSupport, double peakStress);
    // Velocity factor of step k (0..R-1) of the interval, and U(n+1) from U(n) with it.
    double factor(int k, int R) const { return S0_ + (S1_ - S0_) * (k + 1) / R; }
    void advance(double dt, double v0, int k, int R) { Uprev = U, U += dt * v0 * factor(k, R); }
    double speedFactor() const { return S1_; }  // the factor the current interval ends at
    const Limits& limits() const { return lim_; }
    double U = 0, Uprev = 0;                    // drive displacement at t_n and t_n-1 [m]
    // Its state, for a checkpoint, and back.
    std::vector<double> state() const { return {double(active_), U, Uprev, S0_, S1_, fracture_, time_, support_}; }
    void setState(const std::vector<double>& s);

private:
    Limits lim_;
    bool active_ = false;
    double S0_ = 1, S1_ = 1;  // factor at the start and the end of the current record interval
    double fracture_ = 0;     // fracture energy at the last record [J]
    double time_ = 0;         // time of the last record [s] (NaN: none yet)
    double support_ = 0;      // average of s_support [Pa]
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
