// Random fracture energy (LDEM_SPEC section 4): the Weibull marginal from
// (mean, CV), the hashed uniforms, and the correlated field.
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <cstdint>
#include <thread>
#include <vector>

#include "ldem/Interrupt.hpp"
#include "ldem/Lattice.hpp"
#include "ldem/Parallel.hpp"
#include "ldem/RandomField.hpp"

using namespace ldem;

namespace {

// Raw moment E[X^n] of a Weibull(k, lambda).
double rawMoment(const Weibull& w, int n) { return std::pow(w.scale, n) * std::tgamma(1 + n / w.shape); }

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
    const double n = double(a.size());
    double ma = 0, mb = 0;
    for (std::size_t i = 0; i < a.size(); ++i) ma += a[i], mb += b[i];
    ma /= n, mb /= n;
    double sab = 0, saa = 0, sbb = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        sab += (a[i] - ma) * (b[i] - mb);
        saa += (a[i] - ma) * (a[i] - ma);
        sbb += (b[i] - mb) * (b[i] - mb);
    }
    return sab / std::sqrt(saa * sbb);
}

// Normal score of a Weibull value: Phi^-1(F_W(x)), F_W(x) = 1 - exp(-(x/lambda)^k).
double normalScore(const Weibull& w, double x) {
    static const boost::math::normal N01;
    const double u = -std::expm1(-std::pow(x / w.scale, w.shape));
    return boost::math::quantile(N01, std::min(std::max(u, 1e-300), 1 - 1e-16));
}

}  // namespace

TEST(Weibull, CV100PercentIsExponential) {
    const Weibull w = weibullFromMeanCV(100.0, 1.0);
    EXPECT_NEAR(w.shape, 1.0, 1e-9);
    EXPECT_NEAR(w.scale, 100.0, 1e-9 * 100);
    EXPECT_NEAR(w.mean(), 100.0, 1e-9 * 100);
    EXPECT_NEAR(w.cv(), 1.0, 1e-9);
    // Exponential quantile: -100 ln(1 - u).
    EXPECT_NEAR(w.quantile(0.5), 100 * std::log(2.0), 1e-9);
}

TEST(Weibull, MeanAndCVAreReproduced) {
    for (double mean : {1.0, 100.0, 250.0})
        for (double cv : {0.2, 0.5, 1.0, 2.0}) {
            const Weibull w = weibullFromMeanCV(mean, cv);
            EXPECT_NEAR(w.mean(), mean, 1e-9 * mean) << mean << " " << cv;
            EXPECT_NEAR(w.cv(), cv, 1e-9) << mean << " " << cv;
            // Independently, from the raw moments.
            const double m1 = rawMoment(w, 1), m2 = rawMoment(w, 2);
            EXPECT_NEAR(m1, mean, 1e-9 * mean);
            EXPECT_NEAR(std::sqrt(m2 - m1 * m1) / m1, cv, 1e-8);
        }
    // Larger CV = smaller shape; CV(k = 2, Rayleigh) = sqrt(4/pi - 1).
    EXPECT_GT(weibullFromMeanCV(1, 0.2).shape, weibullFromMeanCV(1, 0.5).shape);
    EXPECT_NEAR(weibullFromMeanCV(1, std::sqrt(4 / M_PI - 1)).shape, 2.0, 1e-9);
    // CV = 0: deterministic G_f = mean.
    const Weibull d = weibullFromMeanCV(100, 0.0);
    EXPECT_EQ(d.quantile(0.01), 100.0);
    EXPECT_EQ(d.quantile(0.99), 100.0);
    EXPECT_EQ(d.cv(), 0.0);
    EXPECT_THROW(weibullFromMeanCV(-1, 1), std::invalid_argument);
    EXPECT_THROW(weibullFromMeanCV(1, -1), std::invalid_argument);
}

// A lower bound a (Gf_min): G = a + W keeps the mean and the CV, W's moments
// from its own shape and scale; no draw below a; a >= mean refused.
TEST(Weibull, LocationKeepsMeanAndCVAboveItsBound) {
    for (double a : {4.0, 20.0, 50.0}) {
        const Weibull w = weibullFromMeanCV(100.0, 1.0, a);
        EXPECT_EQ(w.location, a);
        EXPECT_LT(w.shape, 1.0) << a;  // the same CV over a smaller variable part
        EXPECT_NEAR(w.mean(), 100.0, 1e-9 * 100) << a;
        EXPECT_NEAR(w.cv(), 1.0, 1e-9) << a;
        const Weibull W{w.shape, w.scale, 0.0};
        const double m1 = rawMoment(W, 1), m2 = rawMoment(W, 2);
        EXPECT_NEAR(a + m1, 100.0, 1e-8 * 100) << a;
        EXPECT_NEAR(std::sqrt(m2 - m1 * m1) / 100.0, 1.0, 1e-8) << a;
        EXPECT_GE(w.quantile(1e-15), a);
        EXPECT_NEAR(w.quantile(1e-15), a, 1e-3 * a);
    }
    EXPECT_THROW(weibullFromMeanCV(100, 1, 100), std::invalid_argument);
    EXPECT_THROW(weibullFromMeanCV(100, 1, -1), std::invalid_argument);
}

// The field of a material with Gf_min: every bar at or above it, the mean kept
// (SE 100/sqrt n), and the bars below the brittle threshold (4 N/m) gone.
TEST(FractureEnergyField, LowerBoundHoldsInEveryBar) {
    Material m;
    m.GfMin = 20.0;
    const Lattice lat = buildCubicLattice(8, 8, 8, 0.02, m);
    const auto g = fractureEnergyField(lat, m, 3);
    double s = 0;
    for (double x : g) {
        ASSERT_GE(x, 20.0);
        s += x;
    }
    EXPECT_NEAR(s / g.size(), 100.0, 4 * 100 / std::sqrt(double(g.size())));
    Material zero;  // location 0: 3-4 % of the bars below 4 N/m
    const auto g0 = fractureEnergyField(lat, zero, 3);
    EXPECT_GT(std::count_if(g0.begin(), g0.end(), [](double x) { return x < 4.0; }), 100);
}

// 200000 draws. Standard errors from the Weibull's own moments:
//   SE(mean) = sigma / sqrt(n);   Var(s^2) ~ (mu4 - sigma^4) / n, SE(s) ~ SE(s^2) / (2 sigma).
// The CV estimate s/xbar is checked against 4 x (relative SE of s + relative SE
// of xbar), which bounds its SE whatever the correlation of s and xbar: a
// false failure has probability below ~1e-4 per check.
TEST(Weibull, SamplingReproducesMeanAndCV) {
    const int n = 200000;
    for (double cv : {0.2, 0.5, 1.0}) {
        const double mean = 100.0;
        const Weibull w = weibullFromMeanCV(mean, cv);
        double s1 = 0, s2 = 0;
        for (int i = 0; i < n; ++i) {
            const double x = w.quantile(hashedUniform(2024, i, 0));
            ASSERT_GT(x, 0.0);
            s1 += x, s2 += x * x;
        }
        const double xbar = s1 / n, sd = std::sqrt((s2 - n * xbar * xbar) / (n - 1));
        const double m1 = rawMoment(w, 1), m2 = rawMoment(w, 2), m3 = rawMoment(w, 3), m4 = rawMoment(w, 4);
        const double var = m2 - m1 * m1;
        const double mu4 = m4 - 4 * m1 * m3 + 6 * m1 * m1 * m2 - 3 * m1 * m1 * m1 * m1;
        const double seMean = std::sqrt(var / n);
        const double seSd = std::sqrt((mu4 - var * var) / n) / (2 * std::sqrt(var));
        EXPECT_NEAR(xbar, mean, 4 * seMean) << "cv " << cv;
        const double relTol = 4 * (seSd / std::sqrt(var) + seMean / mean);
        EXPECT_NEAR(sd / xbar, cv, relTol * cv) << "cv " << cv;
        EXPECT_LT(relTol, 0.03);  // the check has teeth: a few % at most
    }
}

TEST(HashedUniform, RangeMomentsAndIndependenceOfStreams) {
    const int n = 200000;
    double s1 = 0, s2 = 0, sab = 0, mn = 1, mx = 0;
    for (int i = 0; i < n; ++i) {
        const double u = hashedUniform(1, i, 0), v = hashedUniform(1, i, 1);
        ASSERT_GT(u, 0.0);
        ASSERT_LT(u, 1.0);
        s1 += u, s2 += u * u, sab += (u - 0.5) * (v - 0.5);
        mn = std::min(mn, u), mx = std::max(mx, u);
    }
    // Uniform(0,1): mean 1/2 (SE 0.289/sqrt n), E[u^2] = 1/3 (SE 0.298/sqrt n),
    // covariance of independent streams 0 (SE (1/12)/sqrt n); 5 SE tolerances.
    const double rn = std::sqrt(double(n));
    EXPECT_NEAR(s1 / n, 0.5, 5 * 0.2887 / rn);
    EXPECT_NEAR(s2 / n, 1.0 / 3, 5 * 0.2982 / rn);
    EXPECT_NEAR(sab / n, 0.0, 5 * (1.0 / 12) / rn);
    EXPECT_LT(mn, 1e-4);
    EXPECT_GT(mx, 1 - 1e-4);
    // Pure function of its arguments; every argument matters.
    EXPECT_EQ(hashedUniform(5, 6, 7), hashedUniform(5, 6, 7));
    EXPECT_NE(hashedUniform(5, 6, 7), hashedUniform(4, 6, 7));
    EXPECT_NE(hashedUniform(5, 6, 7), hashedUniform(5, 7, 7));
    EXPECT_NE(hashedUniform(5, 6, 7), hashedUniform(5, 6, 8));
}

TEST(FractureEnergyField, IndependentDrawsPerBar) {
    Material m;  // GfMean 100, CV 1, corrLength 0
    const Lattice lat = buildCubicLattice(8, 8, 8, 0.02, m);
    const auto a = fractureEnergyField(lat, m, 11), b = fractureEnergyField(lat, m, 11),
               c = fractureEnergyField(lat, m, 12);
    ASSERT_EQ(std::int64_t(a.size()), lat.numBars());
    EXPECT_EQ(a, b);
    std::int64_t same = 0;
    for (std::size_t i = 0; i < a.size(); ++i) same += a[i] == c[i];
    EXPECT_EQ(same, 0);
    // Marginal: exponential of mean 100 (SE 100/sqrt n with n = 7384 bars).
    double s = 0;
    for (double g : a) s += g;
    EXPECT_NEAR(s / a.size(), 100.0, 4 * 100 / std::sqrt(double(a.size())));
    // Bars sharing a node are uncorrelated (consecutive bars in each node's list).
    const BarTable t = listBars(lat);
    std::vector<std::vector<std::int64_t>> barsAt(lat.numNodes());
    for (std::int64_t b = 0; b < lat.numBars(); ++b) barsAt[t.n1[b]].push_back(b), barsAt[t.n2[b]].push_back(b);
    std::vector<double> p, q;
    for (const auto& list : barsAt)
        for (std::size_t k = 0; k + 1 < list.size(); ++k) p.push_back(a[list[k]]), q.push_back(a[list[k + 1]]);
    ASSERT_GT(p.size(), 10000u);
    EXPECT_LT(std::abs(pearson(p, q)), 4 / std::sqrt(double(p.size())) + 0.01);
}

// One draw per module: the bars whose midpoints lie inside a module share its
// G_f; distinct modules draw independently from the same Weibull marginal.
TEST(FractureEnergyField, PerModuleDrawsShareTheModulesValue) {
    Material m;
    m.GfPerModule = true;
    const int n = 12;
    const double L0 = 0.02;
    const Lattice lat = buildCubicLattice(n, n, n, L0, m);
    const auto gf = fractureEnergyField(lat, m, 5);
    EXPECT_EQ(gf, fractureEnergyField(lat, m, 5));
    const BarTable t = listBars(lat);
    const auto x0 = nodePositions(lat);
    std::vector<double> moduleValue(n * n * n, -1.0);
    std::vector<int> barsIn(n * n * n, 0);
    for (std::int64_t b = 0; b < lat.numBars(); ++b) {
        int ijk[3];
        for (int d = 0; d < 3; ++d)  // module of the midpoint, shared faces to the higher index
            ijk[d] = std::min(int(std::floor((x0[d][t.n1[b]] + x0[d][t.n2[b]]) / (2 * L0) + 1e-9)), n - 1);
        const int mod = (ijk[2] * n + ijk[1]) * n + ijk[0];
        if (moduleValue[mod] < 0) moduleValue[mod] = gf[b];
        EXPECT_EQ(gf[b], moduleValue[mod]) << "bar " << b;
        ++barsIn[mod];
    }
    // Every module holds its 8 diagonals at least, and the marginal is the
    // exponential of mean 100 over the 1728 modules (SE 100/sqrt 1728).
    EXPECT_GE(*std::min_element(barsIn.begin(), barsIn.end()), 8);
    double s = 0, s2 = 0;
    for (double g : moduleValue) s += g, s2 += g * g;
    const double N = double(moduleValue.size()), mean = s / N;
    EXPECT_NEAR(mean, 100.0, 4 * 100 / std::sqrt(N));
    EXPECT_NEAR(std::sqrt(s2 / N - mean * mean) / mean, 1.0, 0.12);
    // Per module differs from per bar for the same seed.
    m.GfPerModule = false;
    EXPECT_NE(gf, fractureEnergyField(lat, m, 5));
}

// Correlated field: its correlation function against the analytic one, at
// seven distances from 0.35 l_c to 3 l_c. The normal score of G_f at a bar,
// Phi^-1(F_W(G_f)), is the Gaussian field g at the bar's midpoint (the Weibull
// map is monotone). For the random-Fourier construction, over realisations
// (seeds), E[g(x)] = 0, E[g^2] = 1 and
//   E[g(x) g(y)] = E[cos(k.(x - y))] = exp(-(|x - y| / l_c)^2),  k ~ N(0, 2/l_c^2 I),
// exactly, at every pair of points, whatever the specimen's size. The estimator
// is the variogram: E[(z_a - z_b)^2 / 2] = 1 - rho(r_ab), unbiased and blind to
// the spatial mean of one specimen (the plain product z_a z_b was 7-30 times
// noisier at short distances, and a correlation centred on one specimen's mean
// is biased: a specimen holds few correlation volumes). So the mean of
// (z_a - z_b)^2/2 - 1 + rho(r_ab) over the pairs of a distance class, averaged
// over 40 seeds, must be zero within 4.5 standard errors, the standard error
// from the spread of the 40 per-seed means. l_c is also fitted per seed (the l
// at which the pairs closer than 0.9 l_c have a mean (z_a - z_b)^2/2 - 1 +
// exp(-(r/l)^2) of zero) and its mean tested likewise. Measured (l_c = L0 on an
// 8^3 lattice): the classes within 0.7-1.4 SE, SE 0.0017 at 0.35-0.6 l_c to
// 0.014 at 2.2-3 l_c; l_c 1.0060 +- 0.0060 of the request (60 other seeds,
// twice: 1.0010 +- 0.0065, 0.9915 +- 0.0055). So a correlation off by 0.008 at
// short distances, or l_c off by 3 %, fails; the old check (near pairs > 0.85,
// far |r| < 0.25) also passed an l_c twice the request.
TEST(FractureEnergyField, CorrelationMatchesGaussianFunctionAtSeveralDistances) {
    Material m;
    m.corrLength = 0.02;
    const double L0 = 0.02, lc = m.corrLength;
    const Lattice lat = buildCubicLattice(8, 8, 8, L0, m);
    const Weibull w = weibullFromMeanCV(m.GfMean, m.GfCV);
    const std::int64_t nb = lat.numBars();
    const BarTable t = listBars(lat);
    const auto x0 = nodePositions(lat);
    // Midpoints on the grid of L0/4, in grid units: squared distances are integers.
    std::vector<std::int64_t> gx(nb), gy(nb), gz(nb);
    const double g = L0 / 4;
    for (std::int64_t b = 0; b < nb; ++b) {
        const auto i = t.n1[b], j = t.n2[b];
        gx[b] = std::llround((x0[0][i] + x0[0][j]) / (2 * g)), gy[b] = std::llround((x0[1][i] + x0[1][j]) / (2 * g)),
        gz[b] = std::llround((x0[2][i] + x0[2][j]) / (2 * g));
    }
    // Pairs up to 3 l_c, counted by squared distance.
    const std::vector<double> edges = {0.3, 0.6, 0.9, 1.2, 1.6, 2.2, 3.0};
    const int nbin = int(edges.size()) - 1;
    const std::int64_t maxKey = std::int64_t(std::pow(3.0 * lc / g, 2)) + 1;
    std::vector<std::int64_t> pa, pb, pk;
    std::vector<double> nKey(maxKey + 1, 0.0);
    // Every pair closer than 0.9 l_c; beyond, 400 anchor bars (hashed) with every other bar.
    const std::int64_t shortKey = std::int64_t(std::pow(0.9 * lc / g, 2));
    std::vector<char> anchor(nb, 0);
    for (int k = 0; k < 400; ++k) anchor[std::int64_t(hashedUniform(9, k, 0) * nb)] = 1;
    for (std::int64_t a = 0; a < nb; ++a)
        for (std::int64_t b = a + 1; b < nb; ++b) {
            const std::int64_t key = (gx[a] - gx[b]) * (gx[a] - gx[b]) + (gy[a] - gy[b]) * (gy[a] - gy[b]) +
                                     (gz[a] - gz[b]) * (gz[a] - gz[b]);
            if (key > maxKey || (key > shortKey && !anchor[a])) continue;
            pa.push_back(a), pb.push_back(b), pk.push_back(key), nKey[key] += 1;
        }
    auto rOf = [&](std::int64_t key) { return g * std::sqrt(double(key)); };
    auto binOf = [&](std::int64_t key) {
        for (int q = 0; q < nbin; ++q)
            if (rOf(key) / lc >= edges[q] && rOf(key) / lc < edges[q + 1]) return q;
        return -1;
    };
    std::vector<double> rhoBin(nbin, 0.0), nBin(nbin, 0.0);
    for (std::int64_t key = 1; key <= maxKey; ++key)
        if (nKey[key] > 0 && binOf(key) >= 0)
            rhoBin[binOf(key)] += nKey[key] * std::exp(-std::pow(rOf(key) / lc, 2)), nBin[binOf(key)] += nKey[key];
    const int seeds = 40;
    std::vector<std::vector<double>> dev(nbin);  // per class, per seed: mean of (z_a - z_b)^2/2 - 1 + rho(r)
    std::vector<double> lcSeed;
    for (int s = 0; s < seeds; ++s) {
        const auto gf = fractureEnergyField(lat, m, 3000 + s);
        std::vector<double> z(nb);
        for (std::int64_t b = 0; b < nb; ++b) z[b] = normalScore(w, gf[b]);
        std::vector<double> semi(maxKey + 1, 0.0);  // per squared distance: sum of (z_a - z_b)^2 / 2
        for (std::size_t p = 0; p < pa.size(); ++p) semi[pk[p]] += 0.5 * (z[pa[p]] - z[pb[p]]) * (z[pa[p]] - z[pb[p]]);
        std::vector<double> sum(nbin, 0.0);
        for (std::int64_t key = 1; key <= maxKey; ++key)
            if (nKey[key] > 0 && binOf(key) >= 0)
                sum[binOf(key)] += semi[key] - nKey[key] * (1 - std::exp(-std::pow(rOf(key) / lc, 2)));
        for (int q = 0; q < nbin; ++q) dev[q].push_back(sum[q] / nBin[q]);
        double lo = 0.2 * lc, hi = 5 * lc;  // the band's sum is increasing in l: bisection
        for (int it = 0; it < 60; ++it) {
            const double l = 0.5 * (lo + hi);
            double f = 0;
            for (std::int64_t key = 1; key <= maxKey; ++key)
                if (nKey[key] > 0 && rOf(key) < 0.9 * lc)
                    f += semi[key] - nKey[key] * (1 - std::exp(-std::pow(rOf(key) / l, 2)));
            (f > 0 ? hi : lo) = l;
        }
        lcSeed.push_back(0.5 * (lo + hi));
    }
    auto meanSe = [&](const std::vector<double>& v) {
        double mean = 0, var = 0;
        for (double x : v) mean += x;
        mean /= v.size();
        for (double x : v) var += (x - mean) * (x - mean);
        return std::pair<double, double>{mean, std::sqrt(var / (v.size() - 1) / v.size())};
    };
    for (int q = 0; q < nbin; ++q) {
        const auto [d, se] = meanSe(dev[q]);
        std::printf("[ field ] r/l_c in [%.1f, %.1f): %8.0f pairs, analytic %.4f, measured %.4f (SE %.4f)\n",
                    edges[q], edges[q + 1], nBin[q], rhoBin[q] / nBin[q], rhoBin[q] / nBin[q] - d, se);
        EXPECT_NEAR(d, 0.0, 4.5 * se) << "class " << q;
    }
    const auto [lcMean, lcSe] = meanSe(lcSeed);
    std::printf("[ field ] l_c fitted over %d seeds: %.5f m (SE %.5f), requested %.5f m\n", seeds, lcMean, lcSe, lc);
    EXPECT_NEAR(lcMean, lc, 4.5 * lcSe);
    EXPECT_LT(lcSe, 0.01 * lc);  // the test keeps its teeth (measured 0.6 %)

    // Same seed: identical field; another seed: a different field.
    const auto gf = fractureEnergyField(lat, m, 77);
    EXPECT_EQ(fractureEnergyField(lat, m, 77), gf);
    const auto other = fractureEnergyField(lat, m, 78);
    std::int64_t same = 0;
    for (std::int64_t b = 0; b < nb; ++b) same += other[b] == gf[b];
    EXPECT_LT(same, nb / 100);
}

// Marginal of the correlated field. One realisation of a field with
// correlation length l_c on a cube of side S holds only about
// S^3 / (pi^1.5 l_c^3) independent values, so the spatial mean of one
// specimen is itself random. Take 40 independent seeds and test each statistic
// against 4.5 standard errors estimated from the spread over the 40 specimens
// (t-test, 39 d.o.f.): the grand mean of G_f, its pooled CV (jackknife over the
// specimens), the mean of the normal scores (0) and of their squares (1: the
// field's variance, uncentred). Measured: G_f mean 99.53 (SE 1.27), CV 0.9928
// (SE 0.0082), scores -0.0024 (SE 0.0135) and 0.9945 (SE 0.0126); formerly
// CV and scores were only required within 0.1 of the request. (The marginal
// itself, the same Weibull quantile, is tested to 4 SE of 200000 iid draws above.)
TEST(FractureEnergyField, CorrelatedFieldHasRequestedMarginal) {
    Material m;
    m.corrLength = 0.02;
    const Lattice lat = buildCubicLattice(8, 8, 8, 0.02, m);  // 0.16 m: ~90 correlation volumes
    const Weibull w = weibullFromMeanCV(m.GfMean, m.GfCV);
    const int seeds = 40;
    std::vector<double> s1(seeds), s2(seeds), z1(seeds), z2(seeds);
    double n = 0;
    for (int s = 0; s < seeds; ++s) {
        const auto gf = fractureEnergyField(lat, m, 1000 + s);
        for (double g : gf) {
            s1[s] += g, s2[s] += g * g;
            const double z = normalScore(w, g);
            z1[s] += z, z2[s] += z * z;
        }
        n = double(gf.size());  // bars per specimen
    }
    auto meanSe = [&](const std::vector<double>& sums) {  // per-specimen means: grand mean and its SE
        double mean = 0, var = 0;
        for (double x : sums) mean += x / n;
        mean /= seeds;
        for (double x : sums) var += (x / n - mean) * (x / n - mean);
        return std::pair<double, double>{mean, std::sqrt(var / (seeds - 1) / seeds)};
    };
    auto pooledCV = [&](int skip) {
        double a = 0, b = 0, k = 0;
        for (int s = 0; s < seeds; ++s)
            if (s != skip) a += s1[s], b += s2[s], k += n;
        return std::sqrt(b / k - (a / k) * (a / k)) / (a / k);
    };
    const auto [mm, se] = meanSe(s1);
    const double cv = pooledCV(-1);
    double jm = 0, jv = 0;
    for (int s = 0; s < seeds; ++s) jm += pooledCV(s) / seeds;
    for (int s = 0; s < seeds; ++s) jv += (pooledCV(s) - jm) * (pooledCV(s) - jm);
    const double cvSe = std::sqrt((seeds - 1.0) / seeds * jv);
    const auto [zMean, zSe] = meanSe(z1);
    const auto [z2Mean, z2Se] = meanSe(z2);
    std::printf(
        "[ field ] l_c = %.3f m, %d seeds: mean G_f = %.2f (SE %.2f), pooled CV = %.4f (SE %.4f), "
        "normal scores mean %.4f (SE %.4f), mean square %.4f (SE %.4f)\n",
        m.corrLength, seeds, mm, se, cv, cvSe, zMean, zSe, z2Mean, z2Se);
    EXPECT_NEAR(mm, m.GfMean, 4.5 * se);
    EXPECT_LT(se, 0.02 * m.GfMean);         // the spatial correlation is real but the test keeps its teeth
    EXPECT_GT(se, 100 / std::sqrt(seeds * n));  // and the specimens are correlated: more spread than iid draws
    EXPECT_NEAR(cv, m.GfCV, 4.5 * cvSe);
    EXPECT_LT(cvSe, 0.02);
    EXPECT_NEAR(zMean, 0.0, 4.5 * zSe);
    EXPECT_NEAR(z2Mean, 1.0, 4.5 * z2Se);
    EXPECT_LT(z2Se, 0.02);
}

namespace {
struct Stop {};
int polls = 0;
// A poll installed for one test (the bindings install Python's), removed after it.
struct PollInstalled {
    explicit PollInstalled(InterruptPoll poll) {
        setInterruptPoll(poll);
        std::this_thread::sleep_for(kInterruptPollPeriod);  // this thread's last poll a period behind: one is due
    }
    ~PollInstalled() { setInterruptPoll(nullptr); }
};
}  // namespace

// The field is one loop over the bars (the correlated one took 43.6 s at 0.96 m
// and heard no signal): with a poll installed, it runs in chunks with polls
// between, the same field to the bit on any number of threads, and a poll
// that throws (a signal heard) stops it.
TEST(FractureEnergyField, HearsASignalAndIsTheSameToTheBit) {
    Material m;
    m.corrLength = 0.02;
    const Lattice lat = buildCubicLattice(8, 8, 8, 0.02, m);
    const auto alone = fractureEnergyField(lat, m, 5);
    const int threads = maxThreads();
    {
        PollInstalled counting([] { ++polls; });
        polls = 0;
        for (int t : {1, 2}) {
            setThreads(t);
            EXPECT_EQ(fractureEnergyField(lat, m, 5), alone) << t << " threads";
        }
        EXPECT_GE(polls, 1);
    }
    setThreads(threads);
    PollInstalled stopping([] { throw Stop(); });
    EXPECT_THROW(fractureEnergyField(lat, m, 5), Stop);
}
