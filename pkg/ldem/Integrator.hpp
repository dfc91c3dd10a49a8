// Explicit central differences with mass-proportional damping (LDEM_SPEC section 5;
// the damping is a dynamic part, dynamics/MassDamping.hpp, that sets D_f here):
//   M x'' + D_f M x' + F_int(x) = P(t)
//   v(n+1/2) = [ (1 - D_f dt/2) v(n-1/2) + dt (P - F_int)/m ] / (1 + D_f dt/2)
//   x(n+1)   = x(n) + dt v(n+1/2)
// Here f is the force of the bars on the nodes (f = -F_int) and P is the
// free DOFs' weight, m g_z along z (none unless the run asks for gravity); the
// specimen is otherwise loaded only through its prescribed degrees of freedom,
// which the integrator leaves alone (Loading sets them).
#pragma once
#include <cstdint>
#include <vector>

#include "ldem/Field3.hpp"
#include "ldem/Lattice.hpp"

namespace ldem {

// Stability limit of central differences: dt_crit = 2 / omega_max.
inline double stableTimeStep(double omegaMax) { return 2.0 / omegaMax; }

// The update  v <- a v + b f/m,  x <- x + dt v,  with
//   a = (1 - D_f dt/2) / (1 + D_f dt/2),  b = dt / (1 + D_f dt/2).
// With a mean velocity (relative damping, dynamics/MassDamping.hpp) the
// damping force is -D_f m (v - vbar), vbar(n-1/2) known at the step:
//   v(n+1/2) = a v(n-1/2) + b (f/m + D_f vbar(n-1/2)),
//   vbar(n+1/2) = vbar(n-1/2) + (v(n+1/2) - vbar(n-1/2)) dt/tau   (filter = dt/tau).
struct CentralDifference {
    double dt, Df, a, b;
    Field3* mean = nullptr;  // vbar per node, or none (the damping on absolute velocity)
    double filter = 0;       // dt/tau
    double gz = 0;           // the body force per unit mass along z [m/s^2]: -g under gravity (Weight.hpp)
    CentralDifference(double dt_, double Df_)
        : dt(dt_), Df(Df_), a((1 - 0.5 * Df_ * dt_) / (1 + 0.5 * Df_ * dt_)), b(dt_ / (1 + 0.5 * Df_ * dt_)) {}
};

// Advances every DOF of nodes [first, end) whose bit is not set in mask;
// returns the damping work (see advanceLayer).
double advanceNodes(std::int32_t first, std::int32_t end, const std::vector<double>& mass,
                    const std::vector<double>& invMass, const std::vector<std::uint8_t>& mask,
                    const CentralDifference& cd, const Field3& f, Field3& u, Field3& v);

// Advances every DOF of the nodes of layer m whose bit is not set in mask;
// returns the work of the damping forces over the step, sum D_f m vbar^2 dt
// with vbar the mean of v(n-1/2) and v(n+1/2). This choice makes the discrete
// energy balance exact: 1/2 m (v+^2 - v-^2) = f (x(n+1) - x(n-1))/2 - D_f m vbar^2 dt.
// Relative to a mean velocity w = cd.mean's vbar(n-1/2) the update gives
// v+ - v- = dt (f/m - D_f (vbar - w)), so the work of the force actually applied is
// sum D_f m (vbar - w) vbar dt (of either sign: the mean may move faster than the node).
double advanceLayer(const Lattice& lat, int m, const CentralDifference& cd, const std::vector<std::uint8_t>& mask,
                    const Field3& f, Field3& u, Field3& v);

// sum m g_z (x(n) + x(n-1))/2 = sum m g_z (u - dt v/2) over the free z DOFs,
// u = x(n), v = v(n-1/2): the work a constant weight g_z did from rest (its
// share of f (x(n+1) - x(n-1))/2 telescopes). While the weight changes,
// RisingWeight::stepTo (Weight.hpp) adds the rest of the sum by parts.
double weightWork(const Lattice& lat, const std::vector<std::uint8_t>& mask, double gz, double dt, const Field3& u,
                  const Field3& v);

// Sum of 1/2 m v^2 over the DOFs not set in mask, of the owned nodes (Slab.hpp).
double kineticEnergy(const Lattice& lat, const std::vector<std::uint8_t>& mask, const Field3& v);

// The kinetic energy of the motion that is not the drive's quasi-static one,
//   K_own = sum 1/2 m |v - s u|^2,   s = U'/U,
// over the same DOFs (U the drive's displacement, U' its velocity). A linear
// specimen led from rest follows its drive as u = U phi, so v = U' phi = s u:
// K_own is zero for it at any rate, and a running crack or a ringing mode is
// what it counts (dynamics/CrackPace.hpp). s = 0 (the drive at rest) gives K.
double ownKineticEnergy(const Lattice& lat, const std::vector<std::uint8_t>& mask, const Field3& u, const Field3& v,
                        double s);

}  // namespace ldem
