// The adaptive drive after the load loss (tail_drive adaptive): the engine
// (AdaptiveDrive) and the drive part that uses it (AdaptiveTailDrive), which
// before the load loss slows while the cracks run (CrackPace.hpp).
// Parameters: LDEM_ADAPTIVE_DRIVE_PARAMETERS (tail_max_speedup, tail_load, tail_drag, tail_step; the pace's
// crack_pace, crack_kinetic);
// loss_speedup caps its floor.
//
// Between the load loss and separation the specimen is mostly chains straightening; what
// loads them beyond their static share is the drag of the mass-proportional
// damping (on absolute velocity) and inertia, both in proportion to the
// drive's speed (results/separation/speedup_sweep.md). Past its load loss a
// specimen hangs from the drive on its chains (or a triangular cube on its
// hinge), and the part above them moves with it (0.48 m, seed 2: the whole
// cube, K = M v^2 / 2). The stress that the drive's own motion puts on that
// part's face is rho H (a + D_f v) at most (H the gauge length, v = S v0 the
// most-pulled point's velocity); from the load loss on, at every instant,
//   rho H v0 (dS/dt + D_f S) <= tail_drag x peak.                        (1)
// Its steady form is S <= S_d = tail_drag peak / (rho H v0 D_f).
//
// The ramp. From the load loss the drive speeds up to the floor
//   S_f = clamp(S_d / 2, 1, loss_speedup)
// (half of the budget left to drag once there) along the fixed drive's smooth
// ramp, S(t) = 1 + (S_f - 1)(1 - cos(pi t / t_q)) / 2, over
//   t_q = max(t_r, pi (S_f - 1) / (2 D_f sqrt((S_d - S_f)(S_d - 1)))),
// the shortest such ramp within (1): the largest of (1)'s left side over the
// ramp is rho H v0 D_f [(S_f + 1)/2 + sqrt(A^2 + (S_f - 1)^2 / 4)],
// A = pi (S_f - 1) / (2 D_f t_q), and it equals the budget rho H v0 D_f S_d at
// that t_q. Where (1) allows the fixed drive's ramp (S_f = loss_speedup,
// t_q = t_r), it is that ramp, bit for bit. (Measured without it: the fixed
// ramp to 20, a = 145 m/s^2 at every size, broke bars in the hanging
// triangular cubes, +3.7 % of U_min at 0.48 m by mean strain 4e-3, +12 % at
// 0.72 m, +22 % at 0.96 m; results/separation/study_in_an_hour.md.)
//
// From the end of the ramp on, U is state and its velocity factor S >= S_f
// follows, record by record, a quasi-static criterion on state n:
//   softening    the fracture energy grew since the last record (some bar's damage moved);
//   chain load   c = |<s_support>| / peak: what the chains carry to the fixed
//                face, against the specimen's strength; it rises as a chain
//                straightens, before its bars soften. <.> is an exponential
//                average over tau (the split window, two fundamental periods):
//                a specimen rings after its load loss, a free vibration the
//                drive neither makes nor feeds;
//   target       S_f while softening, else clamp(S_f tail_load / c, S_f, tail_max_speedup):
// back at the floor whenever a bar softens or the chains carry
// tail_load x peak, faster in inverse proportion to their load while slack.
// The speed then moves towards the target within three bounds per record:
// - the ratio tail_step;
// - (1) over the record interval T = R dt, a = (S_1 - S_0) v0 / T over it:
//       S_1 <= (B + S_0) / (1 + D_f T),   S_1 >= S_0 - B,   B = tail_drag peak T / (rho H v0)
//   (measured without it, 0.48 m seed 2: a factor of 1.1 per record from 20
//   to 60 broke bars in the hanging cube and doubled U);
// - never below S_f.
// Undamped (zeta 0) the drive stays fixed (Registry.cpp: makeDrive).
// With tail_damping relative (MassDamping.hpp) the damping acts, from the load
// loss on, on v - vbar: a part that moves with the drive at a steady speed has
// no drag, and D_f S leaves (1); a speed-up's mean lags by at most tau dv/dt, so
//   rho H v0 (1 + D_f tau) dS/dt <= tail_drag x peak:
// column carries the factor 1 + D_f tau and dampingT is 0 (S_d infinite: the
// floor is loss_speedup, its ramp the shortest within inertia's bound, and
// the record-wise bound S_1 <= S_0 + B).
// Within a record interval of R steps the velocity ramps linearly from S_0
// (the factor at the record) to S_1:
//   v_k = v0 (S_0 + (S_1 - S_0)(k + 1)/R),   k = 0..R-1 the step in the interval,
// so that it never jumps by more than |S_1 - S_0| v0 / R <= (tail_step - 1)
// max(S_0, S_1) v0 / R in a step; U(n+1) = U(n) + dt v_k.
#pragma once
#include <vector>

#include "ldem/Parameters.hpp"
#include "ldem/dynamics/ConstantRateDrive.hpp"
#include "ldem/dynamics/CrackPace.hpp"
#include "ldem/dynamics/Part.hpp"

// Its parameters.
#define LDEM_ADAPTIVE_DRIVE_PARAMETERS(X)                                                                    \
    X(double, tailMaxSpeedup, "tail_max_speedup", 2000.0, "", Domain::atLeast(1),                            \
      "tail_drive adaptive: the largest velocity factor (over strain_rate) once the load is lost")           \
    X(double, tailLoad, "tail_load", 0.005, "", Domain::open(0, 1),                                          \
      "tail_drive adaptive: the support's stress, over the peak, at which the drive is back at its floor "   \
      "(the chains are taut); below, at most floor x tail_load / (support stress / peak)")                   \
    X(double, tailDrag, "tail_drag", 0.03, "", Domain::open(0, 1),                                           \
      "tail_drive adaptive: the largest stress, over the peak, that the drive's drag and inertia may put on "\
      "the part of the specimen that hangs from it, rho H (a + D_f v) with H the height, at every instant "  \
      "from the load loss on")                                                                               \
    X(double, tailStep, "tail_step", 1.1, "", Domain::openClosed(1, 2),                                      \
      "tail_drive adaptive: the velocity factor changes by at most this ratio per record, ramped linearly "  \
      "over the record's steps")                                                                             \
    X(double, crackPace, "crack_pace", 1.0, "", Domain::openClosed(0, 1),                                    \
      "tail_drive adaptive: the drive's velocity factor (over strain_rate) before the load loss while the "  \
      "lattice moves by itself (crack_kinetic; 1: never slowed, a file's default; 0.0625: the cube's, "       \
      "cubeOwnDefaults in ParameterTable.hpp; dynamics/CrackPace.hpp)")                                     \
    X(double, crackKinetic, "crack_kinetic", 1e-3, "", Domain::open(0, 1),                                   \
      "tail_drive adaptive: the kinetic energy less the drive's quasi-static motion, over the external "     \
      "work, above which the drive slows to crack_pace (a tenth of the quasi-static flag's 1 % at the peak)") \
    X(double, crackSecant, "crack_secant", 0.0, "", Domain::closed(0, 1),                                    \
      "tail_drive adaptive: the drive also slows to crack_pace near the peak, while the curve's secant "      \
      "stress / strain is below crack_secant x its elastic value and the stress above crack_band x the "     \
      "peak so far (0: off, a file's default; 0.9: the cube's; dynamics/CrackPace.hpp)")                     \
    X(double, crackBand, "crack_band", 0.5, "", Domain::open(0, 1),                                          \
      "tail_drive adaptive: crack_secant's band: the stress, over the peak so far, below which the curve "    \
      "is past its snap and the drive is no longer slowed for its secant")

namespace ldem {

class AdaptiveDrive {
public:
    struct Limits {
        double floor = 20, ceiling = 2000;  // S_f (loss_speedup until the load loss), tail_max_speedup
        double load = 0.005, drag = 0.1;    // tail_load, tail_drag
        double step = 1.1;                  // tail_step
        double tau = 0;                     // averaging time of the support's stress [s] (0: none)
        double column = 0;                  // rho H v0 / T: face stress of a unit change of S over a record [Pa] (0: no bound)
        double dampingT = 0;                // D_f T
        double interval = 0;                // T, the record interval [s]
    };
    // The ramp after the load loss: to the factor floor over time [s].
    struct Ramp {
        double floor = 1, time = 0;
    };
    AdaptiveDrive() = default;
    explicit AdaptiveDrive(const Limits& l) : lim_(l) {}
    // The criterion (a pure function): the factor the drive heads for.
    static double target(const Limits& l, bool softening, double chainLoad);
    // (1)'s steady bound S_d = tail_drag peak / (rho H v0 D_f) (infinite without the bound).
    static double steadyBound(const Limits& l, double peakStress);
    // The ramp from 1 to S_f = clamp(S_d / 2, 1, l.floor) within (1), at least as long as rampTime.
    static Ramp rampAfterLoss(const Limits& l, double peakStress, double rampTime);
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

// The drive part: the fixed drive's program on the pace's clock until the load
// loss (CrackPace.hpp; crack_pace 1: the fixed drive, bit for bit), from there
// its ramp to the floor (rampAfterLoss), then the adaptive drive.
class AdaptiveTailDrive {
public:
    static constexpr const char* name = "adaptive";
    static constexpr const char* doc =
        "ramped in to loss_speedup the same way, then faster while no bar softens and the chains are slack, "
        "within bounds of drag and inertia: tail_max_speedup, tail_load, tail_drag, tail_step";
    static constexpr bool kChoice = true;
    struct Params {
        LDEM_ADAPTIVE_DRIVE_PARAMETERS(LDEM_DECLARE_MEMBER)
    };
    AdaptiveTailDrive(const ConstantRateDrive& fixed, const AdaptiveDrive::Limits& l, const CrackPace::Limits& pace = {})
        : fixed_(fixed), tail_(l), lim_(l), pace_(pace) {}
    // Its bounds are set once the record interval is known (setUp).
    AdaptiveTailDrive(const Params& p, const DriveSetup& s)
        : AdaptiveTailDrive(ConstantRateDrive(ConstantRateDrive::Params{}, s), AdaptiveDrive::Limits{}) {
        p_ = p, setup_ = s;
    }
    // Refuses tail_max_speedup below loss_speedup; undamped (D_f = 0) the fixed drive stands in.
    static const char* select(const Params& p, const DriveSetup& s, bool chosen);
    void setUp(const RunSetup& r);
    double now(double t, double dt) const {
        if (tail_.active()) return tail_.U;
        return pace_.on() ? program().displacement(pace_.tau) : fixed_.now(t, dt);
    }
    double before(double t, double dt) const {
        if (tail_.active()) return tail_.Uprev;
        return pace_.on() ? program().displacement(pace_.tauBefore) : fixed_.before(t, dt);
    }
    double next(const DriveStep& c) {
        if (tail_.active()) {
            tail_.advance(c.dt, fixed_.program().v0, c.k, c.R);
            return tail_.U;
        }
        if (!pace_.on()) return fixed_.next(c);
        pace_.advance(c.dt, c.k, c.R);
        return program().displacement(pace_.tau);
    }
    void record(const DriveRecord& r);
    const Drive& program() const { return fixed_.program(); }
    const AdaptiveDrive& adaptive() const { return tail_; }
    const CrackPace& pace() const { return pace_; }
    // The ramp's start, floor and time, the pace's state (when on), then the adaptive drive's once it started.
    std::vector<double> state() const;
    void setState(const std::vector<double>& s);

private:
    // The adaptive drive at the ramp's floor.
    AdaptiveDrive atFloor() const {
        AdaptiveDrive::Limits l = lim_;
        l.floor = program().speedup;
        return AdaptiveDrive(l);
    }
    // The program's time at time t: the pace's clock, or t.
    double clock(double t) const { return pace_.on() ? pace_.tau : t; }
    ConstantRateDrive fixed_;
    AdaptiveDrive tail_;
    AdaptiveDrive::Limits lim_;  // floor: loss_speedup
    CrackPace pace_;
    Params p_;
    DriveSetup setup_;
};

}  // namespace ldem
