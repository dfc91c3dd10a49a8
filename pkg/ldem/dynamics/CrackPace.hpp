// The drive's pace before the load loss (tail_drive adaptive): slow while the
// lattice moves by itself (a crack runs, a burst rings), at the given rate
// where nothing happens (issue 41, item 3).
// Parameters: crack_pace, crack_kinetic, crack_secant, crack_band (LDEM_ADAPTIVE_DRIVE_PARAMETERS); the
// brake's bound is the adaptive drive's inertia budget (tail_drag), its release
// the ratio tail_step.
//
// Why. At and past its peak a large specimen releases elastic energy into its
// cracks faster than the drive loads it; a drive that keeps its rate feeds the
// running crack as well, and what it feeds depends on the rate. Measured on
// the 0.48 m uniform cube, seed 1 (results/dynamics/criteria.md): the fracture
// energy at the load loss is 23.21 J at 0.02 /s, 21.80 J at a quarter and
// 21.47 J at a sixteenth of that rate, while the peak moves by 0.5 % and 0.07 %.
// A whole test at a sixteenth costs 11 times the steps; slowing the drive only
// while the lattice moves by itself takes 1.8 times the steps to the load loss
// (9,077 against 5,162), and the quarter rate's energy moves by +1.5 % from it.
//
// The drive's program U(tau) (ConstantRateDrive.hpp) runs on its own clock tau,
//   d tau / dt = P,
// the pace P in [crack_pace, 1]. At each record (K_own the kinetic energy less
// the drive's quasi-static motion, W the external work, U_f the fracture
// energy, at that state):
//   U_f grew since the last record, K_own > crack_kinetic x W, the load not lost:  target crack_pace
//   near the peak (below), the load not lost:                                      target crack_pace
//   else                                                                           target 1
// K_own = sum 1/2 m |v - (U'/U) u|^2 (Integrator.hpp, ownKineticEnergy): a
// specimen the drive leads quasi-statically moves as u = U phi, and K_own
// counts only what is not that motion: a running crack turns stored energy
// into it. K itself would count the specimen's own motion under the drive:
// on the coarse notched beam of examples/beam_3pb.toml at 0.1 D/s that is near
// 1e-3 of W, the pace braked and released in turn, and the peak rose by 11 %;
// on K_own it stays within 0.05 % of the unpaced peak, and the quarter rate's
// peak within 0.83 % (results/dynamics/criteria.md, "The pace on K_own").
// (While no bar softens there is no crack to follow: the smooth start is left alone.)
//
// Near the peak (crack_secant > 0). A large cube snaps back at its peak: it stores
// more elastic energy than the rest of its fracture takes, and the load falls to
// nothing within half a fundamental period at any rate. What the rate adds to the
// fracture energy is the drive's work during that snap (0.96 m uniform cube, seed 1:
// 129.6 J at 0.02 /s, 104.4 J at 0.000625 /s), while the energy before the peak does
// not move with the rate (within 1.5 %; results/dynamics/cube_rate.md). K_own rises
// only once the snap runs, too late for the brake, so the drive must already be slow
// at the peak. With S = sigma / eps the curve's secant at a record and E_0 its largest
// value while no bar had softened (the elastic secant),
//   near the peak:  S < crack_secant x E_0  and  sigma >= crack_band x peak so far.
// Below the band the snap is over (a triangular cube falls to 0.2-0.35 of its peak
// and softens slowly from there to its load loss: that stretch is not slowed for
// its secant); while the snap rings, the K_own rule above holds the pace.
// After the load loss the adaptive tail takes over (AdaptiveDrive.hpp) and the
// pace returns to 1.
// The pace moves towards its target within the adaptive drive's bounds: down
// by at most B = tail_drag peak T / (rho H v0) per record (the drive's
// deceleration puts at most tail_drag x peak on a column of the specimen's
// height), up by at most the ratio tail_step. Within a record interval of R
// steps it ramps linearly from P_0 to P_1, as the tail's factor does:
//   tau(n+1) = tau(n) + dt (P_0 + (P_1 - P_0)(k + 1)/R),   k = 0..R-1.
// crack_pace = 1 (the default): tau = t, the constant-rate program, bit for bit.
#pragma once
#include <vector>

namespace ldem {

class CrackPace {
public:
    struct Limits {
        double slowest = 1;     // crack_pace
        double kinetic = 1e-3;  // crack_kinetic
        double brake = 0;       // B per unit peak stress: tail_drag T / (rho H v0) [1/Pa]; 0: at once
        double step = 1.1;      // tail_step
        double secant = 0;      // crack_secant (0: off)
        double band = 0.5;      // crack_band
    };
    CrackPace() = default;
    explicit CrackPace(const Limits& l) : lim_(l) {}
    bool on() const { return lim_.slowest < 1; }
    // The criterion (a pure function): the pace the drive heads for.
    static double target(const Limits& l, double kinetic, double work, bool cracking, bool nearPeak, bool lost);
    // Near the peak (a pure function): secant S, elastic secant E_0, stress and the peak so far.
    static bool nearPeak(const Limits& l, double secant, double elasticSecant, double stress, double peakStress);
    // The pace at the end of the next record interval from P0, towards target.
    static double next(const Limits& l, double P0, double target, double peakStress);
    // At a record (state n): K_own, W, U_f, the load lost, the peak so far, the stress and mean strain.
    void record(double kinetic, double work, double fracture, bool lost, double peakStress, double stress,
                double strain);
    // tau(n+1) from tau(n), step k (0..R-1) of the interval.
    void advance(double dt, int k, int R) { tauBefore = tau, tau += dt * (P0_ + (P1_ - P0_) * (k + 1) / R); }
    double pace() const { return P1_; }  // the pace the current interval ends at
    double tau = 0, tauBefore = 0;       // the program's clock at t_n and t_n-1 [s]
    std::vector<double> state() const { return {tau, tauBefore, P0_, P1_, fracture_, elasticSecant_}; }
    void setState(const std::vector<double>& s);
    static constexpr int kStateSize = 6;

private:
    Limits lim_;
    double P0_ = 1, P1_ = 1;
    double fracture_ = 0;  // U_f at the last record [J]
    double elasticSecant_ = 0;  // E_0: the largest sigma / eps while U_f = 0 [Pa]
};

}  // namespace ldem
