#include "ldem/InternalForces.hpp"

#include <cmath>

#include "ldem/Parallel.hpp"

namespace ldem {

void Field3::setZero() {
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < std::int64_t(x.size()); ++i) x[i] = y[i] = z[i] = 0.0;
}

namespace {

// Calls force(b, family, dux, duy, duz, g) for every bar, colour by colour;
// force writes in g[3] the force on the bar's first node, the second gets -g.
template <class BarForce>
void scatterBarForces(const Lattice& lat, const Field3& u, Field3& f, BarForce force) {
    f.setZero();
    const auto* n1 = lat.n1.data();
    const auto* n2 = lat.n2.data();
    for (const BarRange& c : lat.colours) {
        const BarFamily& fam = lat.families[lat.family[c.begin]];
#pragma omp parallel for schedule(static)
        for (std::int64_t b = c.begin; b < c.end; ++b) {
            const auto i = n1[b], j = n2[b];
            double g[3];
            force(b, fam, u.x[j] - u.x[i], u.y[j] - u.y[i], u.z[j] - u.z[i], g);
            f.x[i] += g[0], f.y[i] += g[1], f.z[i] += g[2];
            f.x[j] -= g[0], f.y[j] -= g[1], f.z[j] -= g[2];
        }
    }
}

}  // namespace

void computeInternalForces(const Lattice& lat, const Field3& u, BarState& bars, Field3& f) {
    double* kappa = bars.kappa.data();
    const double* epsR = bars.epsR.data();
    const double epsP = bars.epsP;
    const float* share = lat.share.data();
    scatterBarForces(lat, u, f, [&](std::int64_t b, const BarFamily& fam, double dux, double duy, double duz,
                                    double* g) {
        const double d[3] = {fam.d0[0] + dux, fam.d0[1] + duy, fam.d0[2] + duz};
        const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        const double eps = barStrain(fam.d0.data(), fam.L, dux, duy, duz, l);
        const double k = updateDamage(kappa[b], eps);
        kappa[b] = k;
        // Tension (F > 0) pulls the first node towards the second: along +d.
        const double s = hillerborgForce(eps, k, fam.EA * share[b], epsP, epsR[b]) / l;
        g[0] = s * d[0], g[1] = s * d[1], g[2] = s * d[2];
    });
}

void linearStiffnessProduct(const Lattice& lat, const Field3& x, Field3& y) {
    const float* share = lat.share.data();
    scatterBarForces(lat, x, y, [&](std::int64_t b, const BarFamily& fam, double dux, double duy, double duz,
                                    double* g) {
        // Force on the first node of a bar of stiffness EA/L: -(EA/L)(n.du)n for K x.
        const double n[3] = {fam.d0[0] / fam.L, fam.d0[1] / fam.L, fam.d0[2] / fam.L};
        const double s = -fam.EA * share[b] / fam.L * (n[0] * dux + n[1] * duy + n[2] * duz);
        g[0] = s * n[0], g[1] = s * n[1], g[2] = s * n[2];
    });
}

namespace {
template <class PerBar>
void forEachBarStrain(const Lattice& lat, const Field3& u, std::int64_t b, PerBar perBar) {
    const auto i = lat.n1[b], j = lat.n2[b];
    const BarFamily& fam = lat.families[lat.family[b]];
    const double dux = u.x[j] - u.x[i], duy = u.y[j] - u.y[i], duz = u.z[j] - u.z[i];
    const double d[3] = {fam.d0[0] + dux, fam.d0[1] + duy, fam.d0[2] + duz};
    const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    perBar(fam, barStrain(fam.d0.data(), fam.L, dux, duy, duz, l));
}
}  // namespace

BarEnergies barEnergies(const Lattice& lat, const Field3& u, const BarState& bars) {
    const auto sums = blockSum<4>(lat.numBars(), [&](std::int64_t b, std::array<double, 4>& acc) {
        forEachBarStrain(lat, u, b, [&](const BarFamily& fam, double eps) {
            const double EA = fam.EA * lat.share[b], epsR = bars.epsR[b];
            // kappa is the damage reached at the last force evaluation; the bar
            // can only have gone further since, so take the larger.
            const double kappa = updateDamage(bars.kappa[b], eps);
            acc[0] += storedEnergy(eps, kappa, EA, bars.epsP, epsR, fam.L);
            acc[1] += dissipatedEnergy(kappa, EA, bars.epsP, epsR, fam.L);
            const DamageState s = damageState(kappa, bars.epsP, epsR);
            acc[2] += s == DamageState::Damaged;
            acc[3] += s == DamageState::Broken;
        });
    });
    return {sums[0], sums[1], std::int64_t(sums[2]), std::int64_t(sums[3])};
}

std::vector<double> barStrains(const Lattice& lat, const Field3& u) {
    std::vector<double> eps(lat.numBars());
#pragma omp parallel for schedule(static)
    for (std::int64_t b = 0; b < lat.numBars(); ++b)
        forEachBarStrain(lat, u, b, [&](const BarFamily&, double e) { eps[b] = e; });
    return eps;
}

}  // namespace ldem
