#include "ldem/Integrator.hpp"

#include "ldem/Slab.hpp"

namespace ldem {

namespace {
// One DOF, unless held; returns its damping work. Selects instead of branches,
// so the node loop vectorizes.
inline double advanceDof(bool held, double m, double invM, double f, const CentralDifference& cd, double& u,
                         double& v) {
    const double vNew = cd.a * v + cd.b * f * invM;
    const double vBar = 0.5 * (v + vNew);
    u = held ? u : u + cd.dt * vNew;
    v = held ? v : vNew;
    return held ? 0.0 : cd.Df * m * vBar * vBar * cd.dt;
}
}  // namespace

double advanceNodes(std::int32_t first, std::int32_t end, const std::vector<double>& mass,
                    const std::vector<double>& invMass, const std::vector<std::uint8_t>& mask,
                    const CentralDifference& cd, const Field3& f, Field3& u, Field3& v) {
    double damping = 0.0;
#pragma omp simd reduction(+ : damping)
    for (std::int32_t i = first; i < end; ++i) {
        const unsigned h = mask[i];
        const double m = mass[i], invM = invMass[i];
        damping += advanceDof(h & 1, m, invM, f.x[i], cd, u.x[i], v.x[i]) +
                   advanceDof(h & 2, m, invM, f.y[i], cd, u.y[i], v.y[i]) +
                   advanceDof(h & 4, m, invM, f.z[i], cd, u.z[i], v.z[i]);
    }
    return damping;
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

double kineticEnergy(const Lattice& lat, const std::vector<std::uint8_t>& mask, const Field3& v) {
    return nodeSum<1>(lat, [&](std::int32_t i, std::array<double, 1>& e) {
        const unsigned held = mask[i];
        const double vx = (held & 1) ? 0 : v.x[i], vy = (held & 2) ? 0 : v.y[i], vz = (held & 4) ? 0 : v.z[i];
        e[0] += 0.5 * lat.mass[i] * (vx * vx + vy * vy + vz * vz);
    })[0];
}

}  // namespace ldem
