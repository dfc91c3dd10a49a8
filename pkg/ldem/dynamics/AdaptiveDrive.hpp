// The adaptive drive after the load loss (tail_drive adaptive): the engine
// (AdaptiveDrive) and the drive part that uses it (AdaptiveTailDrive).
// Parameters: LDEM_ADAPTIVE_DRIVE_PARAMETERS (tail_max_speedup, tail_load, tail_drag, tail_step);
// its floor is the fixed drive's loss_speedup.
//
// Between the load loss and separation the specimen is mostly chains straightening; what
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
// Undamped (zeta 0) the drive stays fixed (Registry.cpp: makeDrive).
// Within a record interval of R steps the velocity ramps linearly from S_0
// (the factor at the record) to S_1:
//   v_k = v0 (S_0 + (S_1 - S_0)(k + 1)/R),   k = 0..R-1 the step in the interval,
// so that it never jumps by more than |S_1 - S_0| v0 / R <= (tail_step - 1)
// max(S_0, S_1) v0 / R in a step; U(n+1) = U(n) + dt v_k.
#pragma once
#include <vector>

#include "ldem/Parameters.hpp"
#include "ldem/dynamics/ConstantRateDrive.hpp"
#include "ldem/dynamics/Part.hpp"

namespace ldem {

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

// The drive part: the fixed drive (the same bits) until the end of its ramp to
// the floor after the load loss, then the adaptive drive.
class AdaptiveTailDrive {
public:
    static constexpr const char* name = "adaptive";
    struct Params {
        LDEM_ADAPTIVE_DRIVE_PARAMETERS(LDEM_DECLARE_MEMBER)
    };
    AdaptiveTailDrive(const ConstantRateDrive& fixed, const AdaptiveDrive::Limits& l) : fixed_(fixed), tail_(l) {}
    double now(double t, double dt) const { return tail_.active() ? tail_.U : fixed_.now(t, dt); }
    double before(double t, double dt) const { return tail_.active() ? tail_.Uprev : fixed_.before(t, dt); }
    double next(const DriveStep& c) {
        if (!tail_.active()) return fixed_.next(c);
        tail_.advance(c.dt, fixed_.program().v0, c.k, c.R);
        return tail_.U;
    }
    void record(const DriveRecord& r);
    const Drive& program() const { return fixed_.program(); }
    const AdaptiveDrive& adaptive() const { return tail_; }
    // The fixed drive's state, then the adaptive one's once it started.
    std::vector<double> state() const;
    void setState(const std::vector<double>& s);

private:
    ConstantRateDrive fixed_;
    AdaptiveDrive tail_;
};

}  // namespace ldem
