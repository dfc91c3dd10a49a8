// Extreme natural frequencies of the undamaged lattice under its boundary
// conditions: omega_1 sets the damping D_f = 2 zeta omega_1, omega_max the
// stable time step 2 / omega_max. Both come from one Lanczos run on
// M^-1/2 K M^-1/2 restricted to the free DOFs (matrix-free: K x is one pass
// over the bars), so no stiffness matrix is ever stored. omega_d, the drive's
// own frequency, times the drive (driveFrequency).
#pragma once
#include <cstdint>
#include <vector>

#include "ldem/Field3.hpp"
#include "ldem/Lattice.hpp"

namespace ldem {

struct Frequencies {
    double omega1 = 0;    // fundamental circular frequency [rad/s]
    double omegaMax = 0;  // largest circular frequency [rad/s]
    int iterations = 0;
    double omegaDrive = 0;  // omega_d, the drive's (driveFrequency) [rad/s]
    int driveIterations = 0;
};

// mask: per node, bit d set if DOF d is prescribed (held in the modal problem).
// tolerance: Lanczos residual / eigenvalue; the frequency error is at most half of it.
Frequencies latticeFrequencies(const Lattice& lat, const std::vector<std::uint8_t>& mask,
                               int maxIterations = 20000, double tolerance = 1e-4);

// omega_d = sqrt(u'K u / u'M u), the Rayleigh quotient of u, the elastic field
// of a unit drive: u = drive on the prescribed DOFs (mask), K_ff u_f = -K_fp u_p
// on the free ones. A beam's roller held along z only lets omega_1 be a sideways
// swing that the drive never excites; omega_d is the mode the drive moves
// (near the bending mode; sqrt(3 E/rho)/H for a column pulled at its end).
// u_f by conjugate gradients on the matrix-free K, Jacobi-preconditioned, to
// |r| <= tolerance |r_0|; iterations (out): those taken. 0 if the drive moves nothing.
double driveFrequency(const Lattice& lat, const std::vector<std::uint8_t>& mask, const Field3& drive,
                      int* iterations = nullptr, int maxIterations = 20000, double tolerance = 1e-10);

// Throws std::invalid_argument when the constraints leave a mechanism (a motion
// that stretches no bar, omega_1 = 0): no damping (D_f = 2 zeta omega_1), an
// infinite smooth start, NaN at once.
void refuseMechanism(const Frequencies& f);

}  // namespace ldem
