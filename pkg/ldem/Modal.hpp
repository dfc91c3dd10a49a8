// Extreme natural frequencies of the undamaged lattice under its boundary
// conditions: omega_1 sets the damping D_f = 2 zeta omega_1, omega_max the
// stable time step 2 / omega_max. Both come from one Lanczos run on
// M^-1/2 K M^-1/2 restricted to the free DOFs (matrix-free: K x is one pass
// over the bars), so no stiffness matrix is ever stored.
#pragma once
#include <cstdint>
#include <vector>

#include "ldem/Lattice.hpp"

namespace ldem {

struct Frequencies {
    double omega1 = 0;    // fundamental circular frequency [rad/s]
    double omegaMax = 0;  // largest circular frequency [rad/s]
    int iterations = 0;
};

// mask: per node, bit d set if DOF d is prescribed (held in the modal problem).
// tolerance: Lanczos residual / eigenvalue; the frequency error is at most half of it.
Frequencies latticeFrequencies(const Lattice& lat, const std::vector<std::uint8_t>& mask,
                               int maxIterations = 20000, double tolerance = 1e-4);

// Throws std::invalid_argument when the constraints leave a mechanism (a motion
// that stretches no bar, omega_1 = 0): no damping (D_f = 2 zeta omega_1), an
// infinite smooth start, NaN at once.
void refuseMechanism(const Frequencies& f);

}  // namespace ldem
