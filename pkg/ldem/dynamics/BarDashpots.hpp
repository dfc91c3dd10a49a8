// Dashpots in the bars that have left their elastic branch, acting while such a
// bar is in compression: numerical damping of the modes that clap across closing
// cracks, where the explicit scheme pumps energy into its highest modes (the
// model's damping is MassDamping.hpp). Its force (BarDashpot.hpp):
//   F_d = beta (EA/L) r de/dt,   beta = 2 zeta_high / omega_max,   r = 1 in compression, 0 in tension,
// stiffness-proportional where it acts: zeta_i = zeta_high omega_i / omega_max. Read
// at v(n-1/2) (lagged), for one mode the scheme is stable iff
//   dt <= (2/omega) (sqrt(1 + zeta^2) - zeta),
// which holds as well for dashpots on some bars only (M - (dt^2/4) K - (dt/2) C >= 0).
// Read at v~(n) = v(n-1/2) + dt/2 f*(n)/m (predicted; f* the bars' forces), one mode,
// h = omega dt, x_n, w_n = dt v(n-1/2):
//   w_n+1 = (1 - 2 zeta h) w_n - h^2 (1 - zeta h) x_n,   x_n+1 = x_n + w_n+1:
// det 1 - 2 zeta h, trace 2 - 2 zeta h - h^2 (1 - zeta h), stable iff h <= 2 and
// zeta h <= 1: the undamped limit while zeta_high omega_max dt <= 1. Its force waits
// for every node's f*: a second sweep over the layers whose dashpots act, which moves
// the nodes they pull (BarDashpot.hpp, InternalForces.hpp: predictedDashpots).
// Measured: results/dynamics/README.md.
#pragma once
#include <cmath>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <vector>

#include "ldem/BarDashpot.hpp"
#include "ldem/Integrator.hpp"
#include "ldem/InternalForces.hpp"
#include "ldem/Parameters.hpp"
#include "ldem/dynamics/Part.hpp"

// Its parameters.
#define LDEM_BAR_DASHPOT_PARAMETERS(X)                                                                       \
    X(double, zetaHigh, "zeta_high", 0.5, "", Domain::closedOpen(0, 1),                                      \
      "numerical damping: the ratio, on the highest mode omega_max, of dashpots in the bars that have left "   \
      "their elastic branch, acting while such a bar is in compression (zeta_high omega/omega_max on mode "    \
      "omega); they damp the modes that clap across closing cracks; 0: none (then keep dt_safety at 0.4); "    \
      "the stable time step shrinks by the factor sqrt(1 + zeta_high^2) - zeta_high (dashpot_velocity lagged)") \
    X(bool, dashpotPredicted, "dashpot_velocity", true, "", Domain::choices({"lagged", "predicted"}),        \
      "the velocity the bar dashpots read: lagged, v(n-1/2); predicted, v(n-1/2) + dt/2 f/m with f the "        \
      "bars' forces at n, stable up to the undamped 2/omega_max while zeta_high omega_max dt <= 1, at the "     \
      "cost of a second pass over the bars whose dashpots act")

namespace ldem {

// beta [s]: dashpot over stiffness for the ratio zeta_high at omega_max.
inline double dashpotBeta(double zetaHigh, double omegaMax) { return 2.0 * zetaHigh / omegaMax; }

// The stability limit of central differences with an explicit damping ratio
// zeta on the highest mode, as a fraction of the undamped 2/omega_max.
inline double dampedStepFactor(double zeta) { return std::sqrt(1.0 + zeta * zeta) - zeta; }
// The same for the dashpot read at the predicted velocity: h <= 2 and zeta h <= 1.
inline double predictedStepFactor(double zeta) { return zeta > 0.5 ? 0.5 / zeta : 1.0; }

class BarDashpots {
public:
    static constexpr const char* name = "bar_dashpots";
    static constexpr const char* doc = "dashpots in the bars past their elastic branch while in compression, "
                                       "zeta_high on the highest mode";
    struct Params {
        LDEM_BAR_DASHPOT_PARAMETERS(LDEM_DECLARE_MEMBER)
    };
    BarDashpots() = default;  // none
    BarDashpots(const Params& p, const DampingSetup& s) : zeta_(p.zetaHigh) {
        const double beta = dashpotBeta(p.zetaHigh, s.omegaMax);
        if (beta > 0) d_ = dashpotState(beta, s.bars, s.layers, s.rows, s.nodes, p.dashpotPredicted, s.slab);
    }
    bool on() const { return d_.beta > 0; }
    double coefficient() const { return 0.0; }  // no mass-proportional term
    double lag() const { return 0.0; }
    double beta() const { return d_.beta; }  // [s]
    double stepFactor() const { return d_.predicted ? predictedStepFactor(zeta_) : dampedStepFactor(zeta_); }
    // Predicted: the nodes the acting dashpots pull wait for their forces, which wait for every node's f*.
    bool deferred() const { return d_.predicted; }
    bool waits(int m) const { return d_.predicted && d_.waits(m); }
    // One thread on one rank: the force sweep's node layer m has its f* (InternalForces.hpp: followLayer).
    void followLayer(int m, const Lattice& lat, const std::vector<std::uint8_t>& mask, const Field3& u,
                     const Field3& v, Field3& f, const std::function<void(int)>& move) {
        if (d_.predicted) ldem::followLayer(lat, m, mask, u, v, d_, f, move);
    }
    void afterForces(const Lattice& lat, const std::vector<std::uint8_t>& mask, const Field3& u, const Field3& v,
                     Field3& f, const std::function<void(int)>& moveWaiting, bool followed) {
        if (!d_.predicted) return;
        if (followed) followedDashpots(lat, mask, u, v, d_, f, moveWaiting);
        else predictedDashpots(lat, mask, u, v, d_, f, moveWaiting);
    }
    CentralDifference nodeUpdate(const CentralDifference& cd) {
        d_.halfDt = 0.5 * cd.dt;
        return cd;
    }
    DashpotPass barPass(const Field3& v) { return on() ? DashpotPass{&d_, &v} : DashpotPass{}; }
    void record(const DampingRecord&) {}
    // The work of bar layer m's dashpots in this step, whole (closing + opening), and its parts [J].
    double stepWork(int m) const { return on() ? d_.closing[m] + d_.opening[m] : 0.0; }
    double closingWork(int m) const { return on() ? d_.closing[m] : 0.0; }
    double openingWork(int m) const { return on() ? d_.opening[m] : 0.0; }
    // Each bar's last force, then the current step's work sums of each bar layer
    // (a checkpoint is taken between a record's forces and the rest of its step).
    std::vector<double> state() const {
        std::vector<double> s = d_.force;
        s.insert(s.end(), d_.closing.begin(), d_.closing.end());
        s.insert(s.end(), d_.opening.begin(), d_.opening.end());
        return s;
    }
    void setState(const std::vector<double>& s) {
        const std::size_t bars = d_.force.size(), layers = d_.closing.size();
        if (s.size() != bars + 2 * layers)
            throw std::invalid_argument("the checkpoint's bar dashpots are of another run (zeta_high)");
        d_.force.assign(s.begin(), s.begin() + bars);
        d_.closing.assign(s.begin() + bars, s.begin() + bars + layers);
        d_.opening.assign(s.begin() + bars + layers, s.end());
    }

private:
    double zeta_ = 0;
    DashpotState d_;
};

}  // namespace ldem
