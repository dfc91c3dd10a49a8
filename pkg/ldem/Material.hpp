// Material constants of the study (LDEM_SPEC section 6, Table 2) and the
// Nayfeh-Hefzy elastic equivalence of the cubic module (section 2).
#pragma once
#include <cmath>
#include <stdexcept>
#include <string>

namespace ldem {

struct Material {
    double E = 3.5e10;          // Young's modulus [Pa]
    double nu = 0.25;           // Poisson's ratio [-]
    double rho = 2400.0;        // density [kg/m^3]
    double GfMean = 100.0;      // mean specific fracture energy E[G_f] [N/m]
    double GfCV = 1.0;          // coefficient of variation of G_f [-]
    double corrLength = 0.0;    // correlation length of the G_f field [m]; 0 = one draw per bar
    bool GfPerModule = false;   // one G_f per module (its bars alike) instead of one per bar
    double epsP = 6.3e-5;       // critical (peak) strain of a bar [-]
    double ca = 0.1385;         // fracture-area coefficient c_a [-]

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
