// Random fracture energy (LDEM_SPEC section 4): the Weibull marginal from
// (mean, CV), the hashed uniforms, and the correlated field.
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <cstdint>
#include <vector>

#include "ldem/Lattice.hpp"
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

// Correlated field: l_c = 0.06 m on a 0.24 m cube (12^3 modules, L0 = 0.02).
// Bars whose midpoints are closer than l_c/4 have a Gaussian correlation
// exp(-(r/l_c)^2) >= exp(-1/16) = 0.94 between their normal scores; bars
// farther than 3 l_c have exp(-9) ~ 1e-4. With 512 Fourier modes one
// realisation's empirical covariance has noise of order 1/sqrt(512) ~ 0.04.
TEST(FractureEnergyField, CorrelationLengthMakesNearBarsAlike) {
    Material m;
    m.corrLength = 0.06;
    const double L0 = 0.02;
    const Lattice lat = buildCubicLattice(12, 12, 12, L0, m);
    const std::uint64_t seed = 77;
    const auto gf = fractureEnergyField(lat, m, seed);
    const Weibull w = weibullFromMeanCV(m.GfMean, m.GfCV);
    const std::int64_t nb = lat.numBars();
    const BarTable t = listBars(lat);
    const auto x0 = nodePositions(lat);
    std::vector<double> mx(nb), my(nb), mz(nb), score(nb);
    for (std::int64_t b = 0; b < nb; ++b) {
        const auto i = t.n1[b], j = t.n2[b];
        mx[b] = 0.5 * (x0[0][i] + x0[0][j]), my[b] = 0.5 * (x0[1][i] + x0[1][j]),
        mz[b] = 0.5 * (x0[2][i] + x0[2][j]);
        ASSERT_GT(gf[b], 0.0);
        score[b] = normalScore(w, gf[b]);
    }
    auto dist = [&](std::int64_t a, std::int64_t b) {
        return std::sqrt((mx[a] - mx[b]) * (mx[a] - mx[b]) + (my[a] - my[b]) * (my[a] - my[b]) +
                         (mz[a] - mz[b]) * (mz[a] - mz[b]));
    };
    // Near pairs: bars sharing a node (midpoints at most L0 apart), kept if < l_c/4.
    std::vector<std::vector<std::int64_t>> barsAt(lat.numNodes());
    for (std::int64_t b = 0; b < nb; ++b) barsAt[t.n1[b]].push_back(b), barsAt[t.n2[b]].push_back(b);
    std::vector<double> na, nbv;
    for (const auto& list : barsAt)
        for (std::size_t p = 0; p < list.size(); ++p)
            for (std::size_t q = p + 1; q < list.size(); ++q)
                if (dist(list[p], list[q]) < m.corrLength / 4)
                    na.push_back(score[list[p]]), nbv.push_back(score[list[q]]);
    // Far pairs: hashed random pairs, kept if farther than 3 l_c.
    std::vector<double> fa, fb;
    for (std::uint64_t t = 0; fa.size() < 20000 && t < 2000000; ++t) {
        const auto a = std::int64_t(hashedUniform(5, t, 0) * nb), b = std::int64_t(hashedUniform(5, t, 1) * nb);
        if (dist(a, b) > 3 * m.corrLength) fa.push_back(score[a]), fb.push_back(score[b]);
    }
    ASSERT_GT(na.size(), 10000u);
    ASSERT_EQ(fa.size(), 20000u);
    const double rNear = pearson(na, nbv), rFar = pearson(fa, fb);
    std::printf(
        "[ field ] l_c = %.3f m: normal-score correlation near (< l_c/4, %zu pairs) = %.3f, "
        "far (> 3 l_c, %zu pairs) = %.3f\n",
        m.corrLength, na.size(), rNear, fa.size(), rFar);
    EXPECT_GT(rNear, 0.85);
    EXPECT_LT(std::abs(rFar), 0.25);

    // Same seed: identical field; another seed: a different field.
    EXPECT_EQ(fractureEnergyField(lat, m, seed), gf);
    const auto other = fractureEnergyField(lat, m, seed + 1);
    std::int64_t same = 0;
    for (std::int64_t b = 0; b < nb; ++b) same += other[b] == gf[b];
    EXPECT_LT(same, nb / 100);
}

// Marginal of the correlated field. One realisation of a field with
// correlation length l_c on a cube of side S holds only about
// S^3 / (pi^1.5 l_c^3) independent values, so the spatial mean of one
// specimen is itself random. Take 40 independent seeds and test the grand mean
// against 4 standard errors estimated from the spread of the 40 specimen means
// (t-test, 39 d.o.f.); the pooled CV of G_f and the pooled variance of the
// normal scores must also match the request.
TEST(FractureEnergyField, CorrelatedFieldHasRequestedMarginal) {
    Material m;
    m.corrLength = 0.02;
    const Lattice lat = buildCubicLattice(8, 8, 8, 0.02, m);  // 0.16 m: ~90 correlation volumes
    const Weibull w = weibullFromMeanCV(m.GfMean, m.GfCV);
    const int seeds = 40;
    std::vector<double> specimenMean;
    double s1 = 0, s2 = 0, z1 = 0, z2 = 0, n = 0;
    for (int s = 0; s < seeds; ++s) {
        const auto gf = fractureEnergyField(lat, m, 1000 + s);
        double sm = 0;
        for (double g : gf) {
            sm += g, s1 += g, s2 += g * g, n += 1;
            const double z = normalScore(w, g);
            z1 += z, z2 += z * z;
        }
        specimenMean.push_back(sm / gf.size());
    }
    double mm = 0, vm = 0;
    for (double x : specimenMean) mm += x;
    mm /= seeds;
    for (double x : specimenMean) vm += (x - mm) * (x - mm);
    const double se = std::sqrt(vm / (seeds - 1) / seeds);
    const double poolMean = s1 / n, poolCV = std::sqrt(s2 / n - poolMean * poolMean) / poolMean;
    const double zMean = z1 / n, zVar = z2 / n - zMean * zMean;
    std::printf(
        "[ field ] l_c = %.3f m, %d seeds: mean G_f = %.2f (SE %.2f), pooled CV = %.3f, "
        "normal scores mean %.3f var %.3f\n",
        m.corrLength, seeds, mm, se, poolCV, zMean, zVar);
    EXPECT_NEAR(mm, m.GfMean, 4 * se);
    EXPECT_LT(se, 0.05 * m.GfMean);     // the spatial correlation is real but the test keeps its teeth
    EXPECT_GT(se, 100 / std::sqrt(n));  // and the specimens are correlated: more spread than iid draws
    EXPECT_NEAR(poolCV, m.GfCV, 0.1);
    EXPECT_NEAR(zMean, 0.0, 0.1);
    EXPECT_NEAR(zVar, 1.0, 0.1);
}
