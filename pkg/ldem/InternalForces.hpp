// Internal forces of the lattice, in two steps that share no writes:
//   1. bars: every bar computes the force g it exerts on its A node (its B
//      node gets -g) and updates its damage; rows of bars that are all
//      elastic take a fast path without the law's state, square root or
//      division (the row functor of laws/BarLaw.hpp: elasticBarForce);
//   2. nodes: every node sums the +-g of its bars in a fixed order, a block
//      of nodes at a time in registers (InternalForces.cpp, Block.hpp).
// Both stream along rows of the regular lattice (see Lattice.hpp), so the
// inner loops are plain vectorizable loops over contiguous arrays. They are
// interleaved layer by layer along z: a node layer is summed right after the
// bars of its layer, so a bar layer's g is needed only briefly and lives in a
// small ring of layer buffers that stays in cache (BarForceBuffers). Each
// thread takes a range of layers; the two layers at the bottom of a range need
// bars of the range below and are summed after one barrier. No sum depends on
// the thread count: results are bit-identical for any number of threads.
#pragma once
#include <cmath>
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "ldem/BarDashpot.hpp"
#include "ldem/Field3.hpp"
#include "ldem/Lattice.hpp"
#include "ldem/LayerSweep.hpp"
#include "ldem/laws/BarLaw.hpp"
#include "ldem/laws/Registry.hpp"

namespace ldem {

// The law, and the dashpots if there are (BarDashpot.hpp), for the n bars of a
// row, each from its stretch(p) (a SeriesStretch or a BarStretch): the same
// loop for both paths; m the row's bar layer. The law and stretch(p) come by
// value, and stretch(p) holds its family and pointers by value: the loop's
// stores to g, kappa and the dashpots' force are doubles, which the compiler
// must assume may alias doubles reached through a reference, so it re-read
// them every iteration (as vector gathers and broadcasts). Returns whether a
// dashpot read at the predicted velocity acts in the row (its force then waits:
// predictedDashpots).
template <class Law, class StretchOf>
bool lawBars(const Law rowLaw, const BarRow& row, int m, double EA, double EAend, double invL, StretchOf stretch,
             const DashpotPass& dash, double* gx, double* gy, double* gz) {
    const std::int64_t n = row.count;
    if (!dash.state) {
#pragma omp simd
        for (std::int64_t p = 0; p < n; ++p)
            rowLaw(p, (p == 0 || p == n - 1) ? EAend : EA, stretch(p), gx[p], gy[p], gz[p]);
        return false;
    }
    const Field3& v = *dash.v;
    const double *ax = &v.x[row.nodeA], *ay = &v.y[row.nodeA], *az = &v.z[row.nodeA];
    const double *bx = &v.x[row.nodeB], *by = &v.y[row.nodeB], *bz = &v.z[row.nodeB];
    double* force = &dash.state->force[row.first];
    const double beta = dash.state->beta;
    double closing = 0, opening = 0;
    if (dash.state->predicted) {
        double* coefficient = &dash.state->coefficient[row.first];
        double acting = 0;
#pragma omp simd reduction(+ : closing) reduction(max : acting)
        for (std::int64_t p = 0; p < n; ++p) {
            const double EAp = (p == 0 || p == n - 1) ? EAend : EA;
            const auto s = stretch(p);
            const double r = rowLaw(p, EAp, s, gx[p], gy[p], gz[p]);
            deferDashpot(beta, EAp, invL, r, s.dx, s.dy, s.dz, bx[p] - ax[p], by[p] - ay[p], bz[p] - az[p], force[p],
                         coefficient[p], closing);
            acting = std::max(acting, coefficient[p]);
        }
        dash.state->closing[m] += closing * dash.state->halfDt;
        return acting > 0;
    }
#pragma omp simd reduction(+ : closing, opening)
    for (std::int64_t p = 0; p < n; ++p) {
        const double EAp = (p == 0 || p == n - 1) ? EAend : EA;
        const auto s = stretch(p);
        const double r = rowLaw(p, EAp, s, gx[p], gy[p], gz[p]);
        addDashpot(beta, EAp, invL, r, s.dx, s.dy, s.dz, bx[p] - ax[p], by[p] - ay[p], bz[p] - az[p], force[p],
                   closing, opening, gx[p], gy[p], gz[p]);
    }
    dash.state->closing[m] += closing * dash.state->halfDt;
    dash.state->opening[m] += opening * dash.state->halfDt;
    return false;
}

// The bars of a row whose path is the law's (laws/BarLaw.hpp: RowPath), from
// the displacements at their ends; the row moves on to the exact path once a
// bar is beyond the series. Returns lawBars' answer.
template <class Law>
bool lawRow(const Law& rowLaw, std::uint8_t path, const BarFamily fam, const BarRow& row, int m, double EA,
            double EAend, const double* ax, const double* ay, const double* az, const double* bx, const double* by,
            const double* bz, const DashpotPass& dash, double* gx, double* gy, double* gz) {
    const std::int64_t n = row.count;
    if (path == kSeriesPath) {  // still within the series? (reads u only: the law's state is not touched twice)
        double xMax = 0;
#pragma omp simd reduction(max : xMax)
        for (std::int64_t p = 0; p < n; ++p)
            xMax = std::max(xMax, std::abs(stretchN(fam, bx[p] - ax[p], by[p] - ay[p], bz[p] - az[p]) * fam.invL2));
        if (xMax > kElasticSeriesLimit) path = kExactPath;
    }
    rowLaw.setPath(path);
    if (path == kSeriesPath)
        return lawBars(rowLaw, row, m, EA, EAend, fam.invL, [=](std::int64_t p) {
            return seriesStretch(fam, bx[p] - ax[p], by[p] - ay[p], bz[p] - az[p]);
        }, dash, gx, gy, gz);
    return lawBars(rowLaw, row, m, EA, EAend, fam.invL, [=](std::int64_t p) {
        return barStretch(fam, bx[p] - ax[p], by[p] - ay[p], bz[p] - az[p]);
    }, dash, gx, gy, gz);
}

// Calls the bar law's row functor (laws/BarLaw.hpp) for every bar of layer m, writing the force
// on its A node into the layer's g.
template <class Law>
void barLayer(const Lattice& lat, int m, const Field3& u, const BarForceBuffers& g, const Law& law,
              const DashpotPass& dash) {
    if (dash.state) dash.state->closing[m] = dash.state->opening[m] = 0.0;
    std::uint8_t* actingRows = dash.state && dash.state->predicted ? dash.state->rows.data() : nullptr;
    std::uint8_t acting = 0;
    for (std::int32_t r = lat.barLayerStart[m]; r < lat.barLayerStart[m + 1]; ++r) {
        if (actingRows) actingRows[r] = 0;
        const BarRow& row = lat.barRows[r];
        const BarFamily fam = lat.families[row.family];  // a copy: the stores to g cannot alias it
        const double *ax = &u.x[row.nodeA], *ay = &u.y[row.nodeA], *az = &u.z[row.nodeA];
        const double *bx = &u.x[row.nodeB], *by = &u.y[row.nodeB], *bz = &u.z[row.nodeB];
        double *gx = g.x(m) + row.inLayer, *gy = g.y(m) + row.inLayer, *gz = g.z(m) + row.inLayer;
        const int n = row.count;
        const double EA = fam.EA * row.share, EAend = fam.EA * row.endShare;
        const Law rowLaw = law.forRow(r, row.first);
        std::uint8_t path = rowLaw.path();
        if (path == kElasticPath) {
            // (a max reduction over doubles: measured faster than an int | reduction;
            // a 64-bit index: one vector of doubles per iteration, where an int index
            // made the compiler take 16 bars at once and rows of 12 to 25 bars
            // fell mostly into its scalar remainder)
            double excess = -1;
#pragma omp simd reduction(max : excess)
            for (std::int64_t p = 0; p < n; ++p)
                excess = std::max(excess, rowLaw.elastic(p, fam, (p == 0 || p == n - 1) ? EAend : EA, bx[p] - ax[p],
                                                         by[p] - ay[p], bz[p] - az[p], gx[p], gy[p], gz[p]));
            if (excess <= 0) continue;
            path = kSeriesPath;
        }
        if constexpr (!Law::kElasticOnly) {
            const bool deferred = lawRow(rowLaw, path, fam, row, m, EA, EAend, ax, ay, az, bx, by, bz, dash, gx, gy, gz);
            if (actingRows) actingRows[r] = deferred, acting |= deferred;
        }
    }
    if (actingRows) dash.state->layers[std::size_t(m)] = acting;
}

// f of every node of layer m: the sum of +-g over its bars, in incidence order.
void nodeLayer(const Lattice& lat, int m, const BarForceBuffers& g, Field3& f);

// Bars then nodes, layer by layer (see the top of this file, and LayerSweep.hpp):
// afterLayer(m) runs once node layer m has its forces and no bar still to be
// computed reads node layer m, so it may move those nodes. A node layer needs
// the bars of layers m-2 .. m (bars belong to the layer of their lower end).
template <class Law, class AfterLayer>
void layeredForces(const Lattice& lat, const Field3& u, BarForceBuffers& g, Field3& f, const Law& law,
                   AfterLayer afterLayer, const DashpotPass& dash = {}) {
    layerSweep(lat, g, [&](int m) { barLayer(lat, m, u, g, law, dash); },
               [&](int m) { nodeLayer(lat, m, g, f), afterLayer(m); });
}

// The dashpots read at the predicted velocity (BarDashpot.hpp), once f holds every node's f*
// (the bars' forces; the weight, the same on both ends of a bar, and the mass damping,
// D_f dt/2 ~ 1e-6, are left out). On one slab, v~ of an acting bar's ends is read from v and
// f* as the bar is read. A slab's halo masses are partial, so there v~ comes from d.velocity:
// its owned nodes' v~, then the halo's from their owners (predictedVelocities).
void predictedVelocities(const Lattice& lat, const std::vector<std::uint8_t>& mask, const Field3& v, const Field3& f,
                         DashpotState& d);
// Bar layer k's dashpots: F = coefficient d.(v~_B - v~_A)/L of each acting bar, kept, its
// opening work added, its force on node A into d.forces, the bar into d.acting[k].
void dashpotLayer(const Lattice& lat, int k, const std::vector<std::uint8_t>& mask, const Field3& u, const Field3& v,
                  const Field3& f, DashpotState& d);
// f of node layer m += the forces of the acting dashpots of bar layers m-2 .. m, in that
// order: each node's sum in a fixed order.
void addDashpotForces(const Lattice& lat, int m, const DashpotState& d, Field3& f);

// Then in one layered sweep: the acting bars' forces, each waiting node layer's sum added to
// f, then afterNodes(m) (which may move it). Every sum in a fixed order, per bar layer and
// per node: the same bits for any number of threads and ranks.
template <class AfterNodes>
void settleLayer(const Lattice& lat, int m, const DashpotState& d, Field3& f, AfterNodes afterNodes) {
    if (!d.waits(m)) return;
    if (d.pulled(m)) addDashpotForces(lat, m, d, f);
    afterNodes(m);
}
template <class AfterNodes>
void predictedDashpots(const Lattice& lat, const std::vector<std::uint8_t>& mask, const Field3& u, const Field3& v,
                       DashpotState& d, Field3& f, AfterNodes afterNodes) {
    if (d.slab) predictedVelocities(lat, mask, v, f, d);
    layerSweep(lat, d.forces, [&](int k) { dashpotLayer(lat, k, mask, u, v, f, d); },
               [&](int m) { settleLayer(lat, m, d, f, afterNodes); });
}

// On one thread and one rank they follow the force sweep instead, two layers behind: node
// layer m has its f* (afterLayer): it moves, unless it waits; then bar layer m-2's dashpots
// (their ends, node layers m-2 .. m, have f*), and node layer m-2 settles (it has bar layers
// m-4 .. m-2's). No layer waits for a second sweep; the last two settle after it
// (followedDashpots). The same sums in the same order as predictedDashpots: the same bits.
template <class AfterNodes>
void followLayer(const Lattice& lat, int m, const std::vector<std::uint8_t>& mask, const Field3& u, const Field3& v,
                 DashpotState& d, Field3& f, AfterNodes afterNodes) {
    if (m == 0) d.forces.prepare(lat, 1);
    if (!d.waits(m)) afterNodes(m);
    if (m < 2) return;
    dashpotLayer(lat, m - 2, mask, u, v, f, d);
    settleLayer(lat, m - 2, d, f, afterNodes);
}
template <class AfterNodes>
void followedDashpots(const Lattice& lat, const std::vector<std::uint8_t>& mask, const Field3& u, const Field3& v,
                      DashpotState& d, Field3& f, AfterNodes afterNodes) {
    for (int k = std::max(0, lat.forceLayers() - 2); k < lat.forceLayers(); ++k)
        dashpotLayer(lat, k, mask, u, v, f, d), settleLayer(lat, k, d, f, afterNodes);
}

// f = forces of all bars on the nodes at displacement u with the bar law
// (laws/BarLaw.hpp); updates the law's state (damage) of every bar.
template <class Law>
void computeInternalForces(const Lattice& lat, const Field3& u, Law& law, BarForceBuffers& g, Field3& f) {
    layeredForces(lat, u, g, f, law.rows(), [](int) {});
}

// y = K x for the undamaged, small-displacement stiffness K (K x = -internal force).
void linearStiffnessProduct(const Lattice& lat, const Field3& x, BarForceBuffers& g, Field3& y);

struct BarEnergies {
    double elastic = 0;    // stored on the secants [J]
    double fracture = 0;   // dissipated by damage [J]
    std::int64_t damaged = 0, broken = 0;
};

// The sums of the law's energies and damage states over the bars at displacement u.
BarEnergies barEnergies(const Lattice& lat, const Field3& u, const BarLaws& law);

// Current strain of every bar.
std::vector<double> barStrains(const Lattice& lat, const Field3& u);

}  // namespace ldem
