// Mass-proportional damping (LDEM_SPEC section 5): the force -D_f m v on every
// node, D_f = 2 zeta omega_1 (or 2 zeta damping_omega), in the node update of
// central differences (Integrator.hpp). tail_damping relative: from the record of
// the load loss on, -D_f m (v - vbar), vbar each node's velocity low-passed,
//   vbar' = (v - vbar) / tau,   tau = damping_filter_periods x 2 pi/omega_1,
// so that a part that moves with the drive is not dragged; a vibration at omega
// keeps the share (omega tau)^2 / (1 + (omega tau)^2) of its damping (0.9937 at
// omega_1, tau = 2 T_1), and a speed-up of acceleration a is dragged by at most
// D_f tau m a (AdaptiveDrive.hpp). Its state: whether it switched, and vbar
// (node-local: a rank moves the vbar of the nodes it advances).
#pragma once
#include <functional>
#include <stdexcept>
#include <vector>

#include "ldem/BarDashpot.hpp"
#include "ldem/Integrator.hpp"
#include "ldem/Lattice.hpp"
#include "ldem/Parameters.hpp"
#include "ldem/dynamics/Part.hpp"

// Its parameters.
#define LDEM_MASS_DAMPING_PARAMETERS(X)                                                                      \
    X(double, zeta, "zeta", 0.02, "", Domain::closed(0, 10),                                                 \
      "damping ratio on the fundamental mode (D_f = 2 zeta omega_1); at most 10: above, the damping forces, "\
      "not the bars, carry the load (at 10 they take 5% of the work by the peak, the peak 3% lower than at 0.02)")\
    X(double, dampingOmega, "damping_omega", 0.0, "rad/s", Domain::atLeast(0),                              \
      "the circular frequency zeta is stated on: D_f = 2 zeta damping_omega (0: omega_1, the fundamental "    \
      "mode; another mode's, or one D_f for specimens of every size)")                                       \
    X(bool, tailDampingRelative, "tail_damping", false, "", Domain::choices({"absolute", "relative"}),        \
      "the mass-proportional damping from the load loss on: on each node's absolute velocity, or relative "  \
      "to its mean velocity (low-passed over damping_filter_periods): a part that moves with the drive is "  \
      "then not dragged, a vibration at omega_1 damped by zeta x 0.994 (2 periods)")                          \
    X(double, dampingFilterPeriods, "damping_filter_periods", 2.0, "", Domain::closed(0.5, 100),             \
      "tail_damping relative: the time constant of each node's mean velocity, in fundamental periods "       \
      "2 pi/omega_1; a vibration at omega keeps the ratio (omega tau)^2 / (1 + (omega tau)^2) of its damping")

namespace ldem {

// D_f = 2 zeta omega_1: damping ratio zeta on the fundamental mode.
inline double massDampingCoefficient(double zeta, double omega1) { return 2.0 * zeta * omega1; }

// The share of the damping ratio that relative damping keeps at omega (filter time tau).
inline double relativeDampingShare(double omega, double tau) {
    const double x = omega * tau;
    return x * x / (1 + x * x);
}

class MassDamping {
public:
    static constexpr const char* name = "mass";
    static constexpr const char* doc = "-D_f m v on every node, D_f = 2 zeta omega_1; tail_damping relative: on v "
                                       "less its mean velocity from the load loss on";
    struct Params {
        LDEM_MASS_DAMPING_PARAMETERS(LDEM_DECLARE_MEMBER)
    };
    MassDamping() = default;  // none: D_f = 0
    MassDamping(const Params& p, double omega1)
        : Df_(massDampingCoefficient(p.zeta, p.dampingOmega > 0 ? p.dampingOmega : omega1)),
          relative_(p.tailDampingRelative),
          tau_(p.dampingFilterPeriods * 2 * 3.14159265358979323846 / omega1) {}
    MassDamping(const Params& p, const DampingSetup& s) : MassDamping(p, s.omega1) {}
    double coefficient() const { return Df_; }  // D_f [1/s]
    double lag() const { return relative_ ? tau_ : 0.0; }  // the filter time of the relative tail, else 0 [s]
    bool relative() const { return relative_; }  // tail_damping relative
    double filterTime() const { return tau_; }   // tau [s]
    bool switched() const { return switched_; }  // relative from here on
    // Implicit in the node update (the mean of v(n-1/2) and v(n+1/2)): no bound on the time step.
    double stepFactor() const { return 1.0; }
    CentralDifference nodeUpdate(const CentralDifference& cd) {
        CentralDifference out(cd.dt, cd.Df + Df_);
        if (switched_) out.mean = &mean_, out.filter = cd.dt / tau_;
        return out;
    }
    // At each record: from the load loss on (relative), vbar starts at v(n-1/2).
    void record(const DampingRecord& r) {
        if (relative_ && !switched_ && r.summary.loadLoss.reached()) switched_ = true, mean_ = r.v;
    }
    DashpotPass barPass(const Field3&) const { return {}; }  // no bar forces
    bool deferred() const { return false; }
    bool waits(int) const { return false; }
    void followLayer(int, const Lattice&, const std::vector<std::uint8_t>&, const Field3&, const Field3&, Field3&,
                     const std::function<void(int)>&) {}
    void afterForces(const Lattice&, const std::vector<std::uint8_t>&, const Field3&, const Field3&, Field3&,
                     const std::function<void(int)>&, bool) {}
    double stepWork(int) const { return 0.0; }
    double closingWork(int) const { return 0.0; }
    double openingWork(int) const { return 0.0; }
    // Absolute: none. Relative: whether it switched, then vbar (x, y, z of every node) once it did.
    std::vector<double> state() const {
        if (!relative_) return {};
        std::vector<double> s{double(switched_)};
        for (const std::vector<double>* c : {&mean_.x, &mean_.y, &mean_.z}) s.insert(s.end(), c->begin(), c->end());
        return s;
    }
    void setState(const std::vector<double>& s) {
        if (relative_ ? s.empty() || (s.size() - 1) % 3 != 0 : !s.empty())
            throw std::invalid_argument("the checkpoint's mass damping is of another run (tail_damping)");
        if (!relative_) return;
        switched_ = s[0] != 0;
        const std::size_t n = (s.size() - 1) / 3;
        const auto from = [&](std::size_t c) { return s.begin() + std::ptrdiff_t(1 + c * n); };
        mean_.x.assign(from(0), from(1)), mean_.y.assign(from(1), from(2)), mean_.z.assign(from(2), from(3));
    }

private:
    double Df_ = 0;
    bool relative_ = false;
    double tau_ = 0;  // filter time [s]
    bool switched_ = false;
    Field3 mean_;  // vbar(n-1/2) of every node [m/s]
};

}  // namespace ldem
