#include "ldem/Integrator.hpp"

#include "ldem/Parallel.hpp"

namespace ldem {

namespace {
// One DOF: returns its damping work.
inline double advanceDof(double m, double f, double dt, double c, double Df, double& u, double& v) {
    const double vNew = ((1.0 - c) * v + dt * f / m) / (1.0 + c);
    const double vBar = 0.5 * (v + vNew);
    v = vNew;
    u += dt * vNew;
    return Df * m * vBar * vBar * dt;
}
}  // namespace

double centralDifferenceStep(const std::vector<double>& mass, const std::vector<std::uint8_t>& mask,
                             const Field3& f, double dt, double Df, Field3& u, Field3& v) {
    const double c = 0.5 * Df * dt;
    return blockSum<1>(std::int64_t(mass.size()), [&](std::int64_t i, std::array<double, 1>& damping) {
        const unsigned held = mask[i];
        const double m = mass[i];
        if (!(held & 1)) damping[0] += advanceDof(m, f.x[i], dt, c, Df, u.x[i], v.x[i]);
        if (!(held & 2)) damping[0] += advanceDof(m, f.y[i], dt, c, Df, u.y[i], v.y[i]);
        if (!(held & 4)) damping[0] += advanceDof(m, f.z[i], dt, c, Df, u.z[i], v.z[i]);
    })[0];
}

double kineticEnergy(const std::vector<double>& mass, const std::vector<std::uint8_t>& mask, const Field3& v) {
    return blockSum<1>(std::int64_t(mass.size()), [&](std::int64_t i, std::array<double, 1>& e) {
        const unsigned held = mask[i];
        const double vx = (held & 1) ? 0 : v.x[i], vy = (held & 2) ? 0 : v.y[i], vz = (held & 4) ? 0 : v.z[i];
        e[0] += 0.5 * mass[i] * (vx * vx + vy * vy + vz * vz);
    })[0];
}

}  // namespace ldem
