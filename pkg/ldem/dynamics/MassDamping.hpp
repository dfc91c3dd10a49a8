// Mass-proportional damping (LDEM_SPEC section 5): the force -D_f m v on
// every node, D_f = 2 zeta omega_1, the damping ratio zeta on the fundamental
// mode (every mode i has 2 zeta_i omega_i = D_f). It enters the node update of
// central differences (Integrator.hpp) through the coefficients a and b of
// CentralDifference; its work is the integrator's. It adds no bar force.
// Parameters: LDEM_MASS_DAMPING_PARAMETERS (zeta).
#pragma once
#include <vector>

#include "ldem/BarDashpot.hpp"
#include "ldem/Integrator.hpp"
#include "ldem/Parameters.hpp"
#include "ldem/RunParams.hpp"
#include "ldem/dynamics/Part.hpp"

namespace ldem {

// D_f = 2 zeta omega_1: damping ratio zeta on the fundamental mode.
inline double massDampingCoefficient(double zeta, double omega1) { return 2.0 * zeta * omega1; }

class MassDamping {
public:
    static constexpr const char* name = "mass";
    struct Params {
        LDEM_MASS_DAMPING_PARAMETERS(LDEM_DECLARE_MEMBER)
    };
    MassDamping() = default;  // none: D_f = 0
    MassDamping(const Params& p, double omega1) : Df_(massDampingCoefficient(p.zeta, omega1)) {}
    // Every damping is built from the run's parameters and its set-up (Registry.hpp: makeDampings).
    MassDamping(const RunParams& run, const DampingSetup& s)
        : MassDamping(LDEM_PART_PARAMS(Params, LDEM_MASS_DAMPING_PARAMETERS, run), s.omega1) {}
    double coefficient() const { return Df_; }  // D_f [1/s]
    // Implicit in the node update (the mean of v(n-1/2) and v(n+1/2)): no bound on the time step.
    double stepFactor() const { return 1.0; }
    CentralDifference nodeUpdate(const CentralDifference& cd) const { return CentralDifference(cd.dt, cd.Df + Df_); }
    DashpotPass barPass(const Field3&) const { return {}; }  // no bar forces
    double stepWork(int) const { return 0.0; }
    double closingWork(int) const { return 0.0; }
    double openingWork(int) const { return 0.0; }
    std::vector<double> state() const { return {}; }
    void setState(const std::vector<double>&) {}

private:
    double Df_ = 0;
};

}  // namespace ldem
