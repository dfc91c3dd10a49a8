// The drive's pace before the load loss (tail_drive adaptive): the program U(tau)
// runs on its own clock, d tau/dt = P, P in [crack_pace, 1], slow while the lattice
// moves by itself, so that the drive does not feed a running crack. At a record
// the target is crack_pace if the load is not lost and either U_f grew with
// K_own > crack_kinetic x W (K_own: the kinetic energy less the drive's
// quasi-static motion, Integrator.hpp) or the curve is near its peak (its secant
// sigma/eps < crack_secant x the elastic one, sigma >= crack_band x the peak so far);
// else 1. P moves towards it down by at most tail_drag peak T / (rho H v0), up by
// the ratio tail_step, and either way by at most T / t_r, the smooth start's mean
// slope (t_r: two periods of the mode the drive moves): a change of the drive's
// speed within a period would set that mode ringing (a force of m omega_d dv), and the
// ringing rides on the peak. Linearly over the record's R steps:
//   tau(n+1) = tau(n) + dt (P_0 + (P_1 - P_0)(k + 1)/R).
// crack_pace 1: tau = t, bit for bit. Measured: results/dynamics/README.md.
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
        double glide = 0;       // the largest change of P over a record: T / t_r (0: no bound)
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
