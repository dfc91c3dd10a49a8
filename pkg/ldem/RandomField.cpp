#include "ldem/RandomField.hpp"

#include <algorithm>
#include <array>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace ldem {

namespace {
constexpr double kPi = 3.14159265358979323846;

std::uint64_t splitmix64(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

// CV^2 of a Weibull of shape k, computed without cancellation for large k.
double weibullCV2(double k) { return std::expm1(std::lgamma(1 + 2 / k) - 2 * std::lgamma(1 + 1 / k)); }

// Standard normal from two uniforms (Box-Muller), portable across libraries.
double normalDraw(std::uint64_t seed, std::uint64_t a, std::uint64_t b) {
    const double u1 = hashedUniform(seed, a, 2 * b), u2 = hashedUniform(seed, a, 2 * b + 1);
    return std::sqrt(-2 * std::log(u1)) * std::cos(2 * kPi * u2);
}
}  // namespace

double hashedUniform(std::uint64_t seed, std::uint64_t a, std::uint64_t b) {
    const std::uint64_t h = splitmix64(splitmix64(splitmix64(seed) ^ a) ^ b);
    return ((h >> 11) + 0.5) * 0x1.0p-53;  // in (0, 1), never 0 or 1
}

double Weibull::quantile(double u) const {
    if (std::isinf(shape)) return location + scale;
    return location + scale * std::pow(-std::log1p(-u), 1 / shape);
}
double Weibull::mean() const { return location + (std::isinf(shape) ? scale : scale * std::tgamma(1 + 1 / shape)); }
double Weibull::cv() const {
    return std::isinf(shape) ? 0.0 : std::sqrt(weibullCV2(shape)) * (mean() - location) / mean();
}

Weibull weibullFromMeanCV(double mean, double cv, double location) {
    if (!(mean > 0)) throw std::invalid_argument("Weibull mean must be positive");
    if (!(cv >= 0)) throw std::invalid_argument("Weibull CV must be >= 0");
    if (cv == 0) return {std::numeric_limits<double>::infinity(), mean, 0.0};
    if (!(location >= 0 && location < mean)) throw std::invalid_argument("Weibull location must be in [0, mean)");
    const double cvW = cv * mean / (mean - location);
    // CV decreases monotonically with k; solve in log k on a bracket that spans
    // CV from about 1e-6 to far above 10.
    const auto f = [cvW](double logk) { return weibullCV2(std::exp(logk)) - cvW * cvW; };
    boost::uintmax_t iters = 200;
    const auto r = boost::math::tools::toms748_solve(f, std::log(0.05), std::log(2e6),
                                                     boost::math::tools::eps_tolerance<double>(52), iters);
    const double k = std::exp(0.5 * (r.first + r.second));
    return {k, (mean - location) / std::tgamma(1 + 1 / k), location};
}

namespace {
std::array<double, 3> midpoint(const Lattice& lat, std::int32_t a, std::int32_t b) {
    const auto pa = lat.position(a), pb = lat.position(b);
    return {0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1]), 0.5 * (pa[2] + pb[2])};
}

// (i, j, k) of the module holding point x, clamped into the lattice.
std::array<int, 3> moduleOf(const Lattice& lat, const std::array<double, 3>& x) {
    const int n[3] = {lat.nx, lat.ny, lat.nzTotal};
    std::array<int, 3> ijk{};
    for (int d = 0; d < 3; ++d)
        ijk[d] = std::min(std::max(int(std::floor(x[d] / lat.L0 + 1e-9)), 0), n[d] - 1);
    return ijk;
}

// Where a bar samples the random field: its midpoint, or its module's centre.
std::array<double, 3> samplePoint(const Lattice& lat, bool perModule, std::int32_t a, std::int32_t b) {
    const auto x = midpoint(lat, a, b);
    if (!perModule) return x;
    const auto ijk = moduleOf(lat, x);
    return {(ijk[0] + 0.5) * lat.L0, (ijk[1] + 0.5) * lat.L0, (ijk[2] + 0.5) * lat.L0};
}
}  // namespace

std::vector<double> fractureEnergyField(const Lattice& lat, const Material& m, std::uint64_t seed,
                                        int fourierModes) {
    const Weibull w = weibullFromMeanCV(m.GfMean, m.GfCV, m.GfMin);
    const std::int64_t nb = lat.numBars();
    std::vector<double> gf(nb);
    if (m.corrLength <= 0) {
        forEachBar(lat, [&](std::int64_t b, std::int32_t a, std::int32_t c, const BarRow&, int) {
            if (!m.GfPerModule) {
                gf[b] = w.quantile(hashedUniform(seed, lat.globalNode(a), lat.globalNode(c)));
                return;
            }
            // Key (module number, ~0): no (node, node) key of a bar can collide with it.
            const auto ijk = moduleOf(lat, midpoint(lat, a, c));
            const std::uint64_t module = (std::uint64_t(ijk[2]) * lat.ny + ijk[1]) * lat.nx + ijk[0];
            gf[b] = w.quantile(hashedUniform(seed, module, ~std::uint64_t(0)));
        });
        return gf;
    }
    // Random Fourier modes: wave vectors k ~ N(0, sigma^2 I) with sigma^2 = 2 / l_c^2
    // give E[cos(k.r)] = exp(-sigma^2 r^2 / 2) = exp(-(r/l_c)^2).
    const int N = fourierModes;
    const double sigma = std::sqrt(2.0) / m.corrLength;
    const std::uint64_t fieldSeed = splitmix64(seed ^ 0x5eedf1e1dULL);
    std::vector<double> kx(N), ky(N), kz(N), phase(N);
    for (int n = 0; n < N; ++n) {
        kx[n] = sigma * normalDraw(fieldSeed, n, 0);
        ky[n] = sigma * normalDraw(fieldSeed, n, 1);
        kz[n] = sigma * normalDraw(fieldSeed, n, 2);
        phase[n] = 2 * kPi * hashedUniform(fieldSeed, n, 7);
    }
    const double amp = std::sqrt(2.0 / N);
    forEachBar(lat, [&](std::int64_t b, std::int32_t nodeA, std::int32_t nodeB, const BarRow&, int) {
        const auto [x, y, z] = samplePoint(lat, m.GfPerModule, nodeA, nodeB);
        double g = 0;
        for (int n = 0; n < N; ++n) g += std::cos(kx[n] * x + ky[n] * y + kz[n] * z + phase[n]);
        g *= amp;
        const double u = 0.5 * std::erfc(-g / std::sqrt(2.0));
        gf[b] = w.quantile(std::min(std::max(u, 1e-16), 1 - 1e-16));
    });
    return gf;
}

}  // namespace ldem
