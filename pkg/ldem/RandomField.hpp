// Random fracture energy G_f (LDEM_SPEC section 4): Weibull marginal (minimum,
// type III) with a given mean and CV, and a location (lower bound, Gf_min) that
// is 0 by default, either one independent draw per bar or a Gaussian field with
// correlation length l_c mapped to that marginal.
// Every draw is a pure function of (seed, bar end nodes, bar position), so the
// specimen does not depend on the thread count or on the order bars are stored in.
#pragma once
#include <cstdint>
#include <vector>

#include "ldem/Lattice.hpp"

namespace ldem {

struct Weibull {
    double shape;          // k (infinite for CV = 0: deterministic)
    double scale;          // lambda
    double location = 0;   // a, the lower bound
    double quantile(double u) const;  // inverse CDF: a + lambda (-ln(1-u))^(1/k)
    double mean() const;
    double cv() const;
};

// With location a: G = a + W, W a two-parameter Weibull of mean m - a and standard
// deviation CV m, so that G keeps the mean m and the CV. W's shape from
// CV_W^2 = Gamma(1+2/k)/Gamma(1+1/k)^2 - 1, CV_W = CV m / (m - a) (solved
// numerically), its scale from m - a = lambda Gamma(1+1/k). CV = 1, a = 0 gives
// k = 1 (exponential); a > 0 needs k < 1 for the same CV.
Weibull weibullFromMeanCV(double mean, double cv, double location = 0);

// Uniform (0,1) number that depends only on (seed, a, b): splitmix64 hashing.
double hashedUniform(std::uint64_t seed, std::uint64_t a, std::uint64_t b);

// G_f for every bar of the lattice [N/m].
//   corrLength == 0: independent draws keyed by (seed, n1, n2);
//   corrLength > 0: g(x) = sqrt(2/N) sum_n cos(k_n.x + phi_n), k_n ~ N(0, 2/l_c^2),
//     a Gaussian field with covariance exp(-(r/l_c)^2) (random Fourier modes),
//     evaluated at bar midpoints and mapped by G = F_W^-1(Phi(g)).
// m.GfPerModule: every bar takes the value of the module that holds its
//   midpoint (drawn keyed by the module, or the field at the module's centre);
//   a bar on a face or edge shared by modules takes the one at higher indices.
std::vector<double> fractureEnergyField(const Lattice& lat, const Material& m, std::uint64_t seed,
                                        int fourierModes = 512);

}  // namespace ldem
