// Internal forces of the lattice: every bar pushes/pulls its two end nodes.
//
// The scatter walks the lattice colour by colour (no two bars of a colour
// share a node), so each colour runs in parallel without atomics and each node
// sums its bars in a fixed order: bit-identical results for any thread count.
#pragma once
#include <cstdint>
#include <vector>

#include "ldem/HillerborgLaw.hpp"
#include "ldem/Lattice.hpp"

namespace ldem {

// Three components in structure-of-arrays form (displacements, velocities, forces).
struct Field3 {
    std::vector<double> x, y, z;
    explicit Field3(std::int64_t n = 0) : x(n, 0.0), y(n, 0.0), z(n, 0.0) {}
    void setZero();
};

// Per-bar state of the softening law.
struct BarState {
    double epsP = 0;             // critical strain (same for all bars)
    std::vector<double> epsR;    // limit strain of each bar
    std::vector<double> kappa;   // damage: largest strain reached
};

// Axial strain of a bar from its reference vector d0 (length L) and the
// relative displacement du of its ends, without cancellation:
//   l^2 - L^2 = 2 d0.du + du.du   =>   eps = (l - L)/L = (2 d0.du + du.du) / ((l + L) L)
inline double barStrain(const double d0[3], double L, double dux, double duy, double duz, double l) {
    return (2 * (d0[0] * dux + d0[1] * duy + d0[2] * duz) + dux * dux + duy * duy + duz * duz) / ((l + L) * L);
}

// f = forces of all bars on the nodes at displacement u (large displacements:
// the current bar direction is used); updates the damage kappa of every bar.
void computeInternalForces(const Lattice& lat, const Field3& u, BarState& bars, Field3& f);

// y = K x for the undamaged, small-displacement stiffness K (K x = -internal force).
void linearStiffnessProduct(const Lattice& lat, const Field3& x, Field3& y);

struct BarEnergies {
    double elastic = 0;    // stored on the secants [J]
    double fracture = 0;   // dissipated by damage [J]
    std::int64_t damaged = 0, broken = 0;
};
BarEnergies barEnergies(const Lattice& lat, const Field3& u, const BarState& bars);

// Current strain of every bar.
std::vector<double> barStrains(const Lattice& lat, const Field3& u);

}  // namespace ldem
