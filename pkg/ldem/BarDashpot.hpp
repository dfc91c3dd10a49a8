// A dashpot beside a bar, in the force loop (InternalForces.hpp): its force
// and its work, for the damping part dynamics/BarDashpots.hpp (the why, the
// ratios and the time step are there).
//   F_d = beta (EA/L) r de/dt,   de/dt = s = d.(v_B - v_A) / L,
// d the current bar vector (a rigid rotation stretches no dashpot), r the
// law's ratio of the bar's dashpot (dashpotRatio in laws/BarLaw.hpp: 1 while
// a bar that has left its elastic branch is in compression, else 0), v the
// velocities v(n-1/2).
//
// The work: F_k, the dashpot of step k, works over the centred increment
// (x(k+1) - x(k-1))/2 = dt (v(k-1/2) + v(k+1/2))/2, so the bar dissipates
// F_k (s_k + s_k+1) dt/2: step k's bar loop adds
//   closing = s_k F_k-1 dt/2  (the rest of step k-1's work)  and  opening = s_k F_k dt/2,
// with F_k-1 kept per bar (0 while the bar has none). Exact up to the change
// of d over a step (checked against the nodes' f_d.(x(k+1) - x(k-1))/2 on the
// 0.24 m cube on rollers: the two agree to 3e-4 of the work).
// Read at the predicted velocity (dashpot_velocity predicted), F_k = beta (EA/L) r
// d.(v~_B - v~_A)/L, v~ = v(n-1/2) + dt/2 f*/m: the force pass keeps each bar's
// coefficient beta (EA/L) r and adds the closing work (deferDashpot); once every
// node has f*, predictedDashpots (InternalForces.hpp) adds F_k to the nodes, each
// node's in a fixed order (by bar layer, then bar), and the opening work
// s_k F_k dt/2 (s_k still from v(n-1/2): the same bookkeeping).
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

#include "ldem/Field3.hpp"
#include "ldem/LayerSweep.hpp"

namespace ldem {

struct ActingBar {
    std::int32_t row, p;
};

// The dashpots' state the force loop reads and writes.
struct DashpotState {
    double beta = 0;              // [s]: dashpot over stiffness
    double halfDt = 0;            // dt / 2 [s]
    std::vector<double> force;    // F of each bar's dashpot at the last step [N]
    std::vector<double> closing;  // per bar layer: the sum of s_k F_k-1 dt/2 in this step [J]
    std::vector<double> opening;  // per bar layer: the sum of s_k F_k dt/2 in this step [J]
    bool predicted = false;       // read at the predicted velocity: the forces in a second pass
    std::vector<double> coefficient;  // predicted: per bar, beta (EA/L) r of this step [N s/m]
    std::vector<std::uint8_t> rows;   // predicted: per bar row, whether some bar of it has a dashpot now
    std::vector<std::uint8_t> layers; // predicted: per bar layer, whether some row of it has a dashpot now
    bool slab = false;                // predicted: a slab's halo takes v~ from its owner, so every layer waits
    Field3 velocity;                  // predicted, a slab: v~ of its nodes at this step [m/s]
    BarForceBuffers forces;           // predicted: per bar layer, each acting bar's dashpot force on its A node [N]
    // predicted: per bar layer, its acting bars (coefficient > 0) in row order: row and place in it.
    std::vector<std::vector<ActingBar>> acting;
    // Whether a dashpot acts in bar layers m-2..m, which pull node layer m (a bar of layer k pulls
    // node layers k..k+2).
    bool pulled(int m) const {
        return layers[std::size_t(m)] || (m >= 1 && layers[std::size_t(m - 1)]) ||
               (m >= 2 && layers[std::size_t(m - 2)]);
    }
    // Whether node layer m waits for the dashpots' forces: while it is pulled, or always in a slab.
    // The others move as soon as they have f*.
    bool waits(int m) const { return slab || pulled(m); }
};

// Their state for a lattice of `bars` bars in `rows` rows and `layers` layers, `nodes` nodes (slab: a part of a
// lattice split over ranks), before the first step.
inline DashpotState dashpotState(double beta, std::int64_t bars, int layers, std::int64_t rows, std::int64_t nodes,
                                 bool predicted, bool slab = false) {
    DashpotState d;
    d.beta = beta;
    d.force.assign(std::size_t(bars), 0.0), d.closing.assign(std::size_t(layers), 0.0);
    d.opening.assign(std::size_t(layers), 0.0);
    if (predicted)
        d.predicted = true, d.coefficient.assign(std::size_t(bars), 0.0), d.rows.assign(std::size_t(rows), 0),
        d.layers.assign(std::size_t(layers), 0), d.slab = slab, d.velocity = Field3(slab ? nodes : 0),
        d.acting.resize(std::size_t(layers));
    return d;
}

// One DOF's predicted velocity v~ = v(n-1/2) + dt/2 f*/m, or v on a held DOF: the one formula
// wherever v~ is read (the same bits on one slab and on many). Its fused multiply-add is
// spelled out, as the compiler fused it before, so that no caller's context fuses it otherwise.
inline double predictedVelocity(bool held, double v, double f, double halfDt, double invMass) {
    return held ? v : std::fma(halfDt * f, invMass, v);
}

// What the force pass needs of them: their state and v(n-1/2); none while state is null.
struct DashpotPass {
    DashpotState* state = nullptr;
    const Field3* v = nullptr;
};

// One bar: adds its dashpot's force on node A to g (bar vector d, velocity
// difference dv = v_B - v_A, EA, 1/L, the law's ratio r), keeps F in `force`
// and adds to the two work sums (without dt/2).
inline void addDashpot(double beta, double EA, double invL, double r, double dx, double dy, double dz, double dvx,
                       double dvy, double dvz, double& force, double& closing, double& opening, double& gx,
                       double& gy, double& gz) {
    const double s = (dx * dvx + dy * dvy + dz * dvz) * invL;  // de/dt [m/s]
    const double F = beta * EA * invL * r * s;
    closing += s * force;
    opening += s * F;
    force = F;
    const double Fl = F * invL;  // tension pulls A towards B, along +d
    gx += Fl * dx, gy += Fl * dy, gz += Fl * dz;
}

// The same bar, read at the predicted velocity: its closing work (without dt/2) from
// v(n-1/2) and its coefficient beta (EA/L) r; its force is predictedDashpots' (0 till then).
inline void deferDashpot(double beta, double EA, double invL, double r, double dx, double dy, double dz, double dvx,
                         double dvy, double dvz, double& force, double& coefficient, double& closing) {
    closing += (dx * dvx + dy * dvy + dz * dvz) * invL * force;
    force = 0.0;
    coefficient = beta * EA * invL * r;
}

}  // namespace ldem
