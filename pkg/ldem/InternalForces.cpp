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

namespace {
// d.w with its fused multiply-adds spelled out: left to the compiler, they were fused one way in
// dashpotLayer's loop on one slab and the other way on many (the order the one loop had before).
double dot(double dx, double dy, double dz, double wx, double wy, double wz) {
    return std::fma(dz, wz, std::fma(dx, wx, dy * wy));
}
}  // namespace

void predictedVelocities(const Lattice& lat, const std::vector<std::uint8_t>& mask, const Field3& v, const Field3& f,
                         DashpotState& d) {
    // The components by pointer: Field3's [c] selects its vector by a branch at every use.
    const double* vc[3] = {v.x.data(), v.y.data(), v.z.data()};
    const double* fc[3] = {f.x.data(), f.y.data(), f.z.data()};
    double* wc[3] = {d.velocity.x.data(), d.velocity.y.data(), d.velocity.z.data()};
    const double* invMass = lat.invMass.data();
#pragma omp parallel for schedule(static)
    for (int m = lat.ownBegin; m < lat.ownEnd; ++m) {
        const auto [first, count] = lat.layerNodes(m);
        for (int c = 0; c < 3; ++c)
            for (std::int32_t i = first; i < first + count; ++i)
                wc[c][i] = predictedVelocity((mask[i] >> c) & 1, vc[c][i], fc[c][i], d.halfDt, invMass[i]);
    }
    exchangeHalo(lat, d.velocity);
}

void dashpotLayer(const Lattice& lat, int k, const std::vector<std::uint8_t>& mask, const Field3& u, const Field3& v,
                  const Field3& f, DashpotState& d) {
    std::vector<ActingBar>& acting = d.acting[std::size_t(k)];
    acting.clear();
    if (!d.layers[std::size_t(k)]) return;
    // v~ of node i: a slab's from its exchange, else from v and f* here (only the acting bars' ends).
    const double* vc[3] = {v.x.data(), v.y.data(), v.z.data()};
    const double* fc[3] = {f.x.data(), f.y.data(), f.z.data()};
    const double* wc[3] = {d.velocity.x.data(), d.velocity.y.data(), d.velocity.z.data()};
    const double* invMass = lat.invMass.data();
    const auto vTilde = [&](int c, std::int32_t i) {
        return d.slab ? wc[c][i] : predictedVelocity((mask[i] >> c) & 1, vc[c][i], fc[c][i], d.halfDt, invMass[i]);
    };
    double opening = 0;
    for (std::int32_t r = lat.barLayerStart[k]; r < lat.barLayerStart[k + 1]; ++r) {
        if (!d.rows[std::size_t(r)]) continue;
        const BarRow& row = lat.barRows[r];
        const BarFamily fam = lat.families[row.family];
        const std::int32_t A = row.nodeA, B = row.nodeB;
        const double* c = &d.coefficient[std::size_t(row.first)];
        double* force = &d.force[std::size_t(row.first)];
        double *gx = d.forces.x(k) + row.inLayer, *gy = d.forces.y(k) + row.inLayer, *gz = d.forces.z(k) + row.inLayer;
        double sF = 0;  // sum of s F over the row (its opening work, without dt/2L)
        for (std::int32_t p = 0; p < row.count; ++p) {
            if (c[p] == 0) continue;  // (most bars of a row whose dashpots act have none: force 0 since lawBars)
            acting.push_back({r, p});
            const std::int32_t a = A + p, b = B + p;
            const double dx = fam.d0[0] + u.x[b] - u.x[a], dy = fam.d0[1] + u.y[b] - u.y[a],
                         dz = fam.d0[2] + u.z[b] - u.z[a];
            const double s = dot(dx, dy, dz, v.x[b] - v.x[a], v.y[b] - v.y[a], v.z[b] - v.z[a]);
            const double sp = dot(dx, dy, dz, vTilde(0, b) - vTilde(0, a), vTilde(1, b) - vTilde(1, a),
                                  vTilde(2, b) - vTilde(2, a));
            const double F = c[p] * sp * fam.invL;
            force[p] = F;
            sF += s * F;
            const double Fl = F * fam.invL;  // tension pulls A towards B, along +d
            gx[p] = Fl * dx, gy[p] = Fl * dy, gz[p] = Fl * dz;
        }
        opening += sF * fam.invL;
    }
    d.opening[std::size_t(k)] += opening * d.halfDt;
}

void addDashpotForces(const Lattice& lat, int m, const DashpotState& d, Field3& f) {
    // The acting bars of bar layers m-2, m-1, m, row by row: a row's A ends lie in one node layer,
    // its B ends in one, so a row adds to node layer m at one end, both or neither; all its A ends
    // first, then its B ends (a node may be the B end of one bar and the A end of the next).
    for (int k = std::max(0, m - 2); k <= m; ++k) {
        const std::vector<ActingBar>& acting = d.acting[std::size_t(k)];
        const double *gx = d.forces.x(k), *gy = d.forces.y(k), *gz = d.forces.z(k);
        for (std::size_t i = 0, j; i < acting.size(); i = j) {
            const BarRow& row = lat.barRows[acting[i].row];
            for (j = i; j < acting.size() && acting[j].row == acting[i].row; ++j) {}
            const auto addEnds = [&](std::int32_t end, double sign) {
                if (lat.layerOfNode(end) != m) return;
                for (std::size_t q = i; q < j; ++q) {
                    const std::int32_t p = acting[q].p, b = row.inLayer + p;
                    f.x[end + p] += sign * gx[b], f.y[end + p] += sign * gy[b], f.z[end + p] += sign * gz[b];
                }
            };
            addEnds(row.nodeA, 1.0), addEnds(row.nodeB, -1.0);
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
