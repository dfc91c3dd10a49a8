// Mass-proportional damping (LDEM_SPEC section 5): the force -D_f m v on
// every node, D_f = 2 zeta omega_1, the damping ratio zeta on the fundamental
// mode (every mode i has 2 zeta_i omega_i = D_f). It enters the node update of
// central differences (Integrator.hpp) through the coefficients a and b of
// CentralDifference; its work is the integrator's. It adds no bar force.
// Parameters: LDEM_MASS_DAMPING_PARAMETERS (zeta).
#pragma once
#include <vector>

#include "ldem/Integrator.hpp"
#include "ldem/Parameters.hpp"
#include "ldem/RunParams.hpp"

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
    // Every damping is built from the run's parameters and omega_1 (Registry.hpp: makeDampings).
    MassDamping(const RunParams& run, double omega1) : MassDamping(params(run), omega1) {}
    double coefficient() const { return Df_; }  // D_f [1/s]
    CentralDifference nodeUpdate(const CentralDifference& cd) const { return CentralDifference(cd.dt, cd.Df + Df_); }
    template <class Rows>
    Rows barRows(Rows rows) const { return rows; }
    std::vector<double> state() const { return {}; }
    void setState(const std::vector<double>&) {}

private:
    static Params params(const RunParams& from) {
        Params to;
        LDEM_MASS_DAMPING_PARAMETERS(LDEM_COPY_MEMBER)
        return to;
    }
    double Df_ = 0;
};

}  // namespace ldem
