// Internal forces of the lattice, in two steps that share no writes:
//   1. bars: every bar computes the force g it exerts on its A node (its B
//      node gets -g) and updates its damage;
//   2. nodes: every node sums the +-g of its bars in a fixed order.
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

#include "ldem/HillerborgLaw.hpp"
#include "ldem/Lattice.hpp"
#include "ldem/Parallel.hpp"

namespace ldem {

// Three components in structure-of-arrays form (per node or per bar).
struct Field3 {
    std::vector<double> x, y, z;
    explicit Field3(std::int64_t n = 0) : x(n, 0.0), y(n, 0.0), z(n, 0.0) {}
};

// Per-bar state of the softening law. Kept in double precision: the damaged
// regime is chaotic, and rounding kappa or eps_r to float moved the peak of the
// 0.24 m cube by 3e-4 (measured), far above rounding.
struct BarState {
    double epsP = 0;            // critical strain (same for all bars)
    std::vector<double> epsR;   // limit strain of each bar
    std::vector<double> kappa;  // damage: largest strain reached
};

// Axial strain of a bar from its reference vector d0 (length L) and the
// relative displacement du of its ends, without cancellation:
//   l^2 - L^2 = 2 d0.du + du.du   =>   eps = (l - L)/L = (2 d0.du + du.du) / ((l + L) L)
inline double barStrain(const double d0[3], double L, double dux, double duy, double duz, double l) {
    return (2 * (d0[0] * dux + d0[1] * duy + d0[2] * duz) + dux * dux + duy * duy + duz * duz) / ((l + L) * L);
}

// Layers [first, second) of thread t out of T.
inline std::pair<int, int> layerRange(int layers, int t, int T) {
    return {int(std::int64_t(layers) * t / T), int(std::int64_t(layers) * (t + 1) / T)};
}

// g, the force of each bar on its A node, for the bar layers in use. Bar layer
// m is needed until node layer m + 2 is summed, so each thread cycles its
// layers through three buffers; the two lowest and two highest layers of its
// range keep their own, because the neighbouring range reads them after the barrier.
class BarForceBuffers {
public:
    // Assigns buffers to layers for `threads` threads (no-op if unchanged).
    void prepare(const Lattice& lat, int threads);
    double* x(int m) const { return base_[m]; }
    double* y(int m) const { return base_[m] + stride_; }
    double* z(int m) const { return base_[m] + 2 * stride_; }

private:
    int threads_ = 0;
    std::size_t stride_ = 0;
    std::vector<double> storage_;
    std::vector<double*> base_;  // per layer
};

// The Hillerborg law as a bar functor: at relative displacement du of a bar's
// ends, updates its damage and writes in g the force on its A node (large
// displacements: the current bar direction d = d0 + du is used).
struct HillerborgBars {
    double* kappa;
    const double* epsR;
    double epsP;
    void operator()(std::int64_t b, const BarFamily& fam, double EA, double dux, double duy, double duz, double& gx,
                    double& gy, double& gz) const {
        const double d[3] = {fam.d0[0] + dux, fam.d0[1] + duy, fam.d0[2] + duz};
        const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        const double eps = barStrain(fam.d0.data(), fam.L, dux, duy, duz, l);
        const double k = updateDamage(kappa[b], eps);
        kappa[b] = k;
        // Tension (F > 0) pulls node A towards node B: along +d.
        const double s = hillerborgForce(eps, k, EA, epsP, epsR[b]) / l;
        gx = s * d[0], gy = s * d[1], gz = s * d[2];
    }
};

// Calls law(b, fam, EA, dux, duy, duz, gx, gy, gz) for every bar b of layer
// m; du = u(B) - u(A) and law writes the force on A into gx, gy, gz.
template <class Law>
void barLayer(const Lattice& lat, int m, const Field3& u, const BarForceBuffers& g, const Law& law) {
    for (std::int32_t r = lat.barLayerStart[m]; r < lat.barLayerStart[m + 1]; ++r) {
        const BarRow& row = lat.barRows[r];
        const BarFamily& fam = lat.families[row.family];
        const double *ax = &u.x[row.nodeA], *ay = &u.y[row.nodeA], *az = &u.z[row.nodeA];
        const double *bx = &u.x[row.nodeB], *by = &u.y[row.nodeB], *bz = &u.z[row.nodeB];
        double *gx = g.x(m) + row.inLayer, *gy = g.y(m) + row.inLayer, *gz = g.z(m) + row.inLayer;
        const int n = row.count;
        const double EA = fam.EA * row.share, EAend = fam.EA * row.endShare;
#pragma omp simd
        for (int p = 0; p < n; ++p)
            law(row.first + p, fam, (p == 0 || p == n - 1) ? EAend : EA, bx[p] - ax[p], by[p] - ay[p],
                bz[p] - az[p], gx[p], gy[p], gz[p]);
    }
}

// f of every node of layer m: the sum of +-g over its bars, in incidence order.
void nodeLayer(const Lattice& lat, int m, const BarForceBuffers& g, Field3& f);

// Bars then nodes, layer by layer (see above), inside one parallel region:
// afterLayer(m) runs once node layer m has its forces and no bar still to be
// computed reads node layer m, so it may move those nodes. A node layer needs
// the bars of layers m-2 .. m (bars belong to the layer of their lower end).
template <class Law, class AfterLayer>
void layeredForces(const Lattice& lat, const Field3& u, BarForceBuffers& g, Field3& f, const Law& law,
                   AfterLayer afterLayer) {
#pragma omp parallel
    {
#pragma omp single
        g.prepare(lat, threadCount());
        const auto [m0, m1] = layerRange(lat.numLayers(), threadIndex(), threadCount());
        for (int m = m0; m < m1; ++m) {
            barLayer(lat, m, u, g, law);
            if (m0 == 0 || m >= m0 + 2) nodeLayer(lat, m, g, f), afterLayer(m);
        }
        // The two lowest layers of a range need (and their nodes are read by)
        // bars of the range below.
#pragma omp barrier
        if (m0 > 0)
            for (int m = m0; m < std::min(m0 + 2, m1); ++m) nodeLayer(lat, m, g, f), afterLayer(m);
    }
}

// f = forces of all bars on the nodes at displacement u with the Hillerborg
// law; updates the damage kappa of every bar.
void computeInternalForces(const Lattice& lat, const Field3& u, BarState& bars, BarForceBuffers& g, Field3& f);

// y = K x for the undamaged, small-displacement stiffness K (K x = -internal force).
void linearStiffnessProduct(const Lattice& lat, const Field3& x, BarForceBuffers& g, Field3& y);

struct BarEnergies {
    double elastic = 0;    // stored on the secants [J]
    double fracture = 0;   // dissipated by damage [J]
    std::int64_t damaged = 0, broken = 0;
};
BarEnergies barEnergies(const Lattice& lat, const Field3& u, const BarState& bars);

// Current strain of every bar.
std::vector<double> barStrains(const Lattice& lat, const Field3& u);

}  // namespace ldem
