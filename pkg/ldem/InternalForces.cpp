#include "ldem/InternalForces.hpp"

#include <cmath>

#include "ldem/Block.hpp"
#include "ldem/Parallel.hpp"
#include "ldem/Slab.hpp"

namespace ldem {

namespace {

// Calls perBar(b, fam, EA, eps) for every bar of row r.
template <class PerBar>
void forEachBarStrainInRow(const Lattice& lat, const Field3& u, std::int64_t r, PerBar perBar) {
    const BarRow& row = lat.barRows[r];
    const BarFamily& fam = lat.families[row.family];
    for (int p = 0; p < row.count; ++p) {
        const auto a = row.nodeA + p, b = row.nodeB + p;
        const BarStretch s = barStretch(fam, u.x[b] - u.x[a], u.y[b] - u.y[a], u.z[b] - u.z[a]);
        perBar(row.first + p, fam, fam.EA * row.shareAt(p), s.strain());
    }
}

// Instantiated here for each law of the registry, with forEachBarStrainInRow
// local to this file: the compiler then inlines the whole bar loop, and its
// sums keep the fused multiply-adds they had (as a template in the header
// instead, elastic_J changed in its last bits: tests/golden).
template <class Law>
BarEnergies lawEnergies(const Lattice& lat, const Field3& u, const Law& law) {
    auto addBar = [&](std::int64_t b, const BarFamily& fam, double EA, double eps, std::array<double, 4>& acc) {
        acc[0] += law.stored(b, EA, fam.L, eps);
        acc[1] += law.dissipated(b, EA, fam.L, eps);
        const DamageState s = law.damage(b, eps);
        acc[2] += s == DamageState::Damaged;
        acc[3] += s == DamageState::Broken;
    };
    // Owned layers only, each summed in bar order, added in layer order: the
    // same sums for any number of ranks and threads (Slab.hpp).
    const auto sums = layerSum<4>(lat, [&](int m, std::array<double, 4>& acc) {
        for (std::int32_t r = lat.barLayerStart[m]; r < lat.barLayerStart[m + 1]; ++r)
            forEachBarStrainInRow(lat, u, r, [&](std::int64_t b, const BarFamily& fam, double EA, double eps) {
                addBar(b, fam, EA, eps, acc);
            });
    });
    return {sums[0], sums[1], std::int64_t(sums[2]), std::int64_t(sums[3])};
}

}  // namespace


void BarForceBuffers::prepare(const Lattice& lat, int threads) {
    if (threads == threads_ && base_.size() == std::size_t(lat.numLayers())) return;
    threads_ = threads;
    stride_ = std::size_t(lat.maxBarsInLayer);
    // Buffer index of every layer: own ones at the ends of each range, a ring of three inside.
    std::vector<int> buffer(lat.numLayers(), 0);
    int count = 0;
    for (int t = 0; t < threads; ++t) {
        const auto [m0, m1] = layerRange(lat.forceLayers(), t, threads);
        const int ring = count;
        if (m1 - m0 > 4) count += 3;
        for (int m = m0; m < m1; ++m)
            buffer[m] = (m < m0 + 2 || m >= m1 - 2) ? count++ : ring + (m - m0) % 3;
    }
    storage_.assign(std::size_t(count) * 3 * stride_, 0.0);
    base_.resize(lat.numLayers());
    for (int m = 0; m < lat.numLayers(); ++m) base_[m] = storage_.data() + std::size_t(buffer[m]) * 3 * stride_;
}

// Every node's sum runs over its incidences in their order, from 0: the same
// additions, in the same order, in the bulk (a block of nodes at a time, its
// sums in registers: a loop over f in memory, incidence after incidence, was
// bound by the stores and their reloads) and at the row's ends.
void nodeLayer(const Lattice& lat, int m, const BarForceBuffers& g, Field3& f) {
    for (std::int32_t r = lat.nodeLayerStart[m]; r < lat.nodeLayerStart[m + 1]; ++r) {
        const NodeRow& row = lat.nodeRows[r];
        double *fx = &f.x[row.first], *fy = &f.y[row.first], *fz = &f.z[row.first];
        // Blocks over the bulk, the last one shifted back to end with it
        // (its nodes computed twice, the same sums): no partial block.
        const bool blocks = row.bulkEnd - row.bulkBegin >= kBlock;
        for (int i0 = row.bulkBegin; blocks && i0 < row.bulkEnd; i0 += kBlock) {
            i0 = std::min(i0, row.bulkEnd - kBlock);
            Block sx = {}, sy = {}, sz = {};
            for (const Incidence& in : row.incidences) {
                const std::int32_t b = in.inLayerAtZero + i0;
                sx += in.sign * loadBlock(g.x(in.layer) + b), sy += in.sign * loadBlock(g.y(in.layer) + b),
                    sz += in.sign * loadBlock(g.z(in.layer) + b);
            }
            storeBlock(sx, fx + i0), storeBlock(sy, fy + i0), storeBlock(sz, fz + i0);
        }
        auto ends = [&](int begin, int end) {
            for (int i = begin; i < end; ++i) {
                double sx = 0, sy = 0, sz = 0;
                for (const Incidence& in : row.incidences) {
                    if (i < in.begin || i >= in.end) continue;
                    const std::int32_t b = in.inLayerAtZero + i;
                    sx += in.sign * g.x(in.layer)[b], sy += in.sign * g.y(in.layer)[b], sz += in.sign * g.z(in.layer)[b];
                }
                fx[i] = sx, fy[i] = sy, fz[i] = sz;
            }
        };
        if (blocks) ends(0, row.bulkBegin), ends(row.bulkEnd, row.count);
        else ends(0, row.count);
    }
}

namespace {
// The undamaged, small-displacement stiffness as a bar law (never inelastic):
// force on node A of a bar of stiffness EA/L, negated for K x: -(EA/L)(n.du)n.
struct LinearBars {
    static constexpr bool kElasticOnly = true;  // barLayer never takes the law's paths
    LinearBars forRow(std::int32_t, std::int64_t) const { return *this; }
    std::uint8_t path() const { return kElasticPath; }
    double elastic(std::int64_t, const BarFamily& fam, double EA, double dux, double duy, double duz, double& gx,
                   double& gy, double& gz) const {
        const double n[3] = {fam.d0[0] / fam.L, fam.d0[1] / fam.L, fam.d0[2] / fam.L};
        const double s = -EA / fam.L * (n[0] * dux + n[1] * duy + n[2] * duz);
        gx = s * n[0], gy = s * n[1], gz = s * n[2];
        return -1;
    }
};
}  // namespace

void linearStiffnessProduct(const Lattice& lat, const Field3& x, BarForceBuffers& g, Field3& y) {
    layeredForces(lat, x, g, y, LinearBars{}, [](int) {});
}

void predictedDashpots(const Lattice& lat, const std::vector<std::uint8_t>& mask, const Field3& u, const Field3& v,
                       DashpotState& d, Field3& f) {
    // The components by pointer: Field3's [c] selects its vector by a branch at every use.
    const double* vc[3] = {v.x.data(), v.y.data(), v.z.data()};
    double* fc[3] = {f.x.data(), f.y.data(), f.z.data()};
    double* wc[3] = {d.velocity.x.data(), d.velocity.y.data(), d.velocity.z.data()};
    const double* invMass = lat.invMass.data();
    // v~ of the owned nodes that wait (an acting bar's ends do), then of the halo's from their
    // owners (a slab's halo masses are partial: MPI)
#pragma omp parallel for schedule(static)
    for (int m = lat.ownBegin; m < lat.ownEnd; ++m) {
        if (!d.waits(m)) continue;
        const auto [first, count] = lat.layerNodes(m);
        for (int c = 0; c < 3; ++c)
            for (std::int32_t i = first; i < first + count; ++i)
                wc[c][i] = (mask[i] >> c) & 1 ? vc[c][i] : vc[c][i] + d.halfDt * fc[c][i] * invMass[i];
    }
    exchangeHalo(lat, d.velocity);
    // One pass over the acting bars: each force from v~ (which f no longer moves), then onto the nodes.
    for (int m = 0; m < lat.forceLayers(); ++m)
        for (std::int32_t r = lat.barLayerStart[m]; r < lat.barLayerStart[m + 1]; ++r) {
            if (!d.rows[std::size_t(r)]) continue;
            const BarRow& row = lat.barRows[r];
            const BarFamily& fam = lat.families[row.family];
            for (int p = 0; p < row.count; ++p) {
                const std::int64_t b = row.first + p;
                if (d.coefficient[std::size_t(b)] == 0) continue;
                const std::int32_t A = row.nodeA + p, B = row.nodeB + p;
                const double dvec[3] = {fam.d0[0] + u.x[B] - u.x[A], fam.d0[1] + u.y[B] - u.y[A],
                                        fam.d0[2] + u.z[B] - u.z[A]};
                double s = 0, sp = 0;
                for (int c = 0; c < 3; ++c)
                    s += dvec[c] * (vc[c][B] - vc[c][A]), sp += dvec[c] * (wc[c][B] - wc[c][A]);
                const double F = d.coefficient[std::size_t(b)] * sp * fam.invL;
                d.force[std::size_t(b)] = F;
                d.opening[m] += s * fam.invL * F * d.halfDt;
                const double Fl = F * fam.invL;  // tension pulls A towards B, along +d
                for (int c = 0; c < 3; ++c) fc[c][A] += Fl * dvec[c], fc[c][B] -= Fl * dvec[c];
            }
        }
}

BarEnergies barEnergies(const Lattice& lat, const Field3& u, const BarLaws& law) {
    return std::visit([&](const auto& l) { return lawEnergies(lat, u, l); }, law);
}

std::vector<double> barStrains(const Lattice& lat, const Field3& u) {
    std::vector<double> eps(lat.numBars());
#pragma omp parallel for schedule(static)
    for (std::int64_t r = 0; r < std::int64_t(lat.barRows.size()); ++r)
        forEachBarStrainInRow(lat, u, r, [&](std::int64_t b, const BarFamily&, double, double e) { eps[b] = e; });
    return eps;
}

}  // namespace ldem
