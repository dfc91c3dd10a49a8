// The adaptive drive after the load loss (tail_drive adaptive), and before it the
// pace of CrackPace.hpp. Past its load loss a specimen hangs from the drive on its
// chains; the drive's drag and inertia load them, so that from the load loss on
//   rho H v0 (dS/dt + D_f S) <= tail_drag x peak          (1)
// (S the velocity factor, H the gauge length). From the load loss S ramps as the
// fixed drive's smooth ramp to the floor S_f = clamp(S_d/2, 1, loss_speedup),
// S_d = tail_drag peak / (rho H v0 D_f), over the shortest time within (1),
// t_q = max(t_r, pi (S_f - 1) / (2 D_f sqrt((S_d - S_f)(S_d - 1)))); then, record
// by record, S heads for S_f while a bar softens, else S_f tail_load / c (c: the
// support's stress over the peak, averaged over the split window), within the
// ratio tail_step, (1) over the record (S_1 <= (B + S_0)/(1 + D_f T), S_1 >= S_0 - B,
// B = tail_drag peak T / (rho H v0)), and never below S_f, ramped linearly over the
// record's steps. Relative tail damping (MassDamping.hpp): D_f T = 0, the column
// x (1 + D_f tau). Measured: results/dynamics/README.md.
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
