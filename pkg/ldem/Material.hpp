// Material constants of the study (LDEM_SPEC section 6, Table 2) and the
// Nayfeh-Hefzy elastic equivalence of the cubic module (section 2).
#pragma once
#include <cmath>
#include <stdexcept>
#include <string>

#include "ldem/Parameters.hpp"

namespace ldem {

// LDEM_MATERIAL_PARAMETERS (Parameters.hpp): E, nu, rho, G_f (mean, CV,
// correlation length, per bar or per module), eps_p, c_a,
// the softening law (a BarLawId: laws/Registry.hpp) and the laws' constants.
struct Material {
    LDEM_MATERIAL_PARAMETERS(LDEM_DECLARE_MEMBER)
    // Throws std::invalid_argument with a one-line message on bad input.
    void validate() const;
};

// delta = 9 nu / (4 - 8 nu)
inline double nayfehDelta(double nu) { return 9.0 * nu / (4.0 - 8.0 * nu); }
// phi = (9 + 8 delta) / (18 + 24 delta):  A_n = phi L0^2
inline double nayfehPhi(double nu) {
    const double d = nayfehDelta(nu);
    return (9.0 + 8.0 * d) / (18.0 + 24.0 * d);
}
// A_n = phi L0^2
inline double normalBarArea(double nu, double L0) { return nayfehPhi(nu) * L0 * L0; }
// A_d = (2 delta / sqrt 3) A_n
inline double diagonalBarArea(double nu, double L0) {
    return 2.0 * nayfehDelta(nu) / std::sqrt(3.0) * normalBarArea(nu, L0);
}
// Fracture areas: A_f = c_a L0^2 (normal), c_a (1.15 L0)^2 (diagonal).
inline double normalFractureArea(double ca, double L0) { return ca * L0 * L0; }
inline double diagonalFractureArea(double ca, double L0) { return ca * (1.15 * L0) * (1.15 * L0); }

}  // namespace ldem
