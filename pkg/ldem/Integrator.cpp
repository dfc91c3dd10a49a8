#include "ldem/Integrator.hpp"

#include "ldem/Block.hpp"
#include "ldem/Slab.hpp"

namespace ldem {

namespace {
// One DOF, unless held; returns its damping work. Selects instead of
// branches; the same source for one DOF (T double, M bool) and for the DOFs of
// a block of nodes (T Block, M BlockMask: -1 in the lanes that are held).
template <class T, class M>
inline T advanceDof(M held, T m, T invM, T f, const CentralDifference& cd, T& u, T& v) {
    const T vNew = cd.a * v + cd.b * f * invM;
    const T vBar = 0.5 * (v + vNew);
    u = held ? u : u + cd.dt * vNew;
    v = held ? v : vNew;
    return held ? T{} : cd.Df * m * vBar * vBar * cd.dt;
}

// The same, damped relative to the DOF's mean velocity w (Integrator.hpp), which it moves on.
template <class T, class M>
inline T advanceDof(M held, T m, T invM, T f, const CentralDifference& cd, T& u, T& v, T& w) {
    const T vNew = cd.a * v + cd.b * (f * invM + cd.Df * w);
    const T vBar = 0.5 * (v + vNew);
    const T work = cd.Df * m * (vBar - w) * vBar * cd.dt;
    u = held ? u : u + cd.dt * vNew;
    v = held ? v : vNew;
    w = held ? w : w + (vNew - w) * cd.filter;
    return held ? T{} : work;
}

// The mask bit `bit` of kBlock nodes from p, as lanes.
inline BlockMask heldLanes(const std::uint8_t* p, unsigned bit) {
    BlockMask h;
    for (int k = 0; k < kBlock; ++k) h[k] = p[k] & bit;
    return h != 0;
}


// kBlock nodes at a time, the rest one by one. The damping work adds up in
// kBlock lanes (node first + k + kBlock j in lane k), then lane after lane: the
// same sum on any machine and for any thread count. Mean: whether the damping
// is relative to cd.mean (the DOF's extra argument, w); Weight: whether the z
// DOFs carry their weight m g_z (cd.gz) beside the bars' force.
template <bool Mean, bool Weight>
double advanceNodesOf(std::int32_t first, std::int32_t end, const std::vector<double>& mass,
                      const std::vector<double>& invMass, const std::vector<std::uint8_t>& mask,
                      const CentralDifference& cd, const Field3& f, Field3& u, Field3& v) {
    Field3& w = Mean ? *cd.mean : v;  // (unused without a mean)
    auto dof = [&](auto held, auto m, auto invM, auto fi, auto& ui, auto& vi, auto& wi) {
        if constexpr (Mean) return advanceDof(held, m, invM, fi, cd, ui, vi, wi);
        else return advanceDof(held, m, invM, fi, cd, ui, vi);
    };
    auto weighed = [&](auto fz, auto m) {  // f_z + m g_z, or f_z untouched (the same bits without gravity)
        if constexpr (Weight) return fz + m * cd.gz;
        else return fz;
    };
    Block damping = {};
    std::int32_t i = first;
    for (; i + kBlock <= end; i += kBlock) {
        const Block m = loadBlock(&mass[i]), invM = loadBlock(&invMass[i]);
        Block ux = loadBlock(&u.x[i]), uy = loadBlock(&u.y[i]), uz = loadBlock(&u.z[i]);
        Block vx = loadBlock(&v.x[i]), vy = loadBlock(&v.y[i]), vz = loadBlock(&v.z[i]);
        Block wx = {}, wy = {}, wz = {};
        if constexpr (Mean) wx = loadBlock(&w.x[i]), wy = loadBlock(&w.y[i]), wz = loadBlock(&w.z[i]);
        damping += dof(heldLanes(&mask[i], 1), m, invM, loadBlock(&f.x[i]), ux, vx, wx) +
                   dof(heldLanes(&mask[i], 2), m, invM, loadBlock(&f.y[i]), uy, vy, wy) +
                   dof(heldLanes(&mask[i], 4), m, invM, weighed(loadBlock(&f.z[i]), m), uz, vz, wz);
        storeBlock(ux, &u.x[i]), storeBlock(uy, &u.y[i]), storeBlock(uz, &u.z[i]);
        storeBlock(vx, &v.x[i]), storeBlock(vy, &v.y[i]), storeBlock(vz, &v.z[i]);
        if constexpr (Mean) storeBlock(wx, &w.x[i]), storeBlock(wy, &w.y[i]), storeBlock(wz, &w.z[i]);
    }
    for (; i < end; ++i) {
        const unsigned held = mask[i];
        const double m = mass[i], invM = invMass[i];
        damping[(i - first) % kBlock] += dof(bool(held & 1), m, invM, f.x[i], u.x[i], v.x[i], w.x[i]) +
                                         dof(bool(held & 2), m, invM, f.y[i], u.y[i], v.y[i], w.y[i]) +
                                         dof(bool(held & 4), m, invM, weighed(f.z[i], m), u.z[i], v.z[i], w.z[i]);
    }
    double sum = 0.0;
    for (int k = 0; k < kBlock; ++k) sum += damping[k];
    return sum;
}
}  // namespace

double advanceNodes(std::int32_t first, std::int32_t end, const std::vector<double>& mass,
                    const std::vector<double>& invMass, const std::vector<std::uint8_t>& mask,
                    const CentralDifference& cd, const Field3& f, Field3& u, Field3& v) {
    if (cd.gz != 0)
        return cd.mean ? advanceNodesOf<true, true>(first, end, mass, invMass, mask, cd, f, u, v)
                       : advanceNodesOf<false, true>(first, end, mass, invMass, mask, cd, f, u, v);
    return cd.mean ? advanceNodesOf<true, false>(first, end, mass, invMass, mask, cd, f, u, v)
                   : advanceNodesOf<false, false>(first, end, mass, invMass, mask, cd, f, u, v);
}

double advanceLayer(const Lattice& lat, int m, const CentralDifference& cd, const std::vector<std::uint8_t>& mask,
                    const Field3& f, Field3& u, Field3& v) {
    double damping = 0.0;
    for (std::int32_t r = lat.nodeLayerStart[m]; r < lat.nodeLayerStart[m + 1]; ++r) {
        const NodeRow& row = lat.nodeRows[r];
        damping += advanceNodes(row.first, row.first + row.count, lat.mass, lat.invMass, mask, cd, f, u, v);
    }
    return damping;
}

double weightWork(const Lattice& lat, const std::vector<std::uint8_t>& mask, double gz, double dt, const Field3& u,
                  const Field3& v) {
    if (gz == 0) return 0.0;
    return nodeSum<1>(lat, [&](std::int32_t i, std::array<double, 1>& e) {
        if (!(mask[i] & 4)) e[0] += lat.mass[i] * gz * (u.z[i] - 0.5 * dt * v.z[i]);
    })[0];
}

double kineticEnergy(const Lattice& lat, const std::vector<std::uint8_t>& mask, const Field3& v) {
    return nodeSum<1>(lat, [&](std::int32_t i, std::array<double, 1>& e) {
        const unsigned held = mask[i];
        const double vx = (held & 1) ? 0 : v.x[i], vy = (held & 2) ? 0 : v.y[i], vz = (held & 4) ? 0 : v.z[i];
        e[0] += 0.5 * lat.mass[i] * (vx * vx + vy * vy + vz * vz);
    })[0];
}

double ownKineticEnergy(const Lattice& lat, const std::vector<std::uint8_t>& mask, const Field3& u, const Field3& v,
                        double s) {
    return nodeSum<1>(lat, [&](std::int32_t i, std::array<double, 1>& e) {
        const unsigned held = mask[i];
        const double wx = (held & 1) ? 0 : v.x[i] - s * u.x[i], wy = (held & 2) ? 0 : v.y[i] - s * u.y[i],
                     wz = (held & 4) ? 0 : v.z[i] - s * u.z[i];
        e[0] += 0.5 * lat.mass[i] * (wx * wx + wy * wy + wz * wz);
    })[0];
}

}  // namespace ldem
