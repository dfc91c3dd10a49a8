#include "ldem/Modal.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>

#include "ldem/InternalForces.hpp"
#include "ldem/Parallel.hpp"
#include "ldem/RandomField.hpp"

namespace ldem {

namespace {
double dot(const Field3& a, const Field3& b) {
    return blockSum<1>(std::int64_t(a.x.size()), [&](std::int64_t i, std::array<double, 1>& s) {
        s[0] += a.x[i] * b.x[i] + a.y[i] * b.y[i] + a.z[i] * b.z[i];
    })[0];
}

// Smallest and largest eigenvalues of the tridiagonal Lanczos matrix.
std::pair<double, double> ritzExtremes(const std::vector<double>& alpha, const std::vector<double>& beta) {
    const Eigen::Index k = Eigen::Index(alpha.size());
    Eigen::VectorXd diag = Eigen::Map<const Eigen::VectorXd>(alpha.data(), k);
    Eigen::VectorXd sub = Eigen::Map<const Eigen::VectorXd>(beta.data(), k - 1);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es;
    es.computeFromTridiagonal(diag, sub, Eigen::EigenvaluesOnly);
    return {es.eigenvalues()(0), es.eigenvalues()(k - 1)};
}
}  // namespace

Frequencies latticeFrequencies(const Lattice& lat, const std::vector<std::uint8_t>& mask, int maxIterations,
                               double tolerance) {
    const std::int64_t n = lat.numNodes();
    // s = M^-1/2 on free DOFs, 0 on prescribed ones: A = S K S.
    Field3 s(n);
    for (std::int64_t i = 0; i < n; ++i) {
        const double r = 1.0 / std::sqrt(lat.mass[i]);
        s.x[i] = (mask[i] & 1) ? 0 : r, s.y[i] = (mask[i] & 2) ? 0 : r, s.z[i] = (mask[i] & 4) ? 0 : r;
    }
    Field3 q(n), qPrev(n), w(n), tmp(n);
    for (std::int64_t i = 0; i < n; ++i) {  // deterministic start vector
        q.x[i] = s.x[i] * (hashedUniform(7, i, 0) - 0.5);
        q.y[i] = s.y[i] * (hashedUniform(7, i, 1) - 0.5);
        q.z[i] = s.z[i] * (hashedUniform(7, i, 2) - 0.5);
    }
    const double q0 = std::sqrt(dot(q, q));
    if (q0 == 0) throw std::invalid_argument("every degree of freedom is prescribed: nothing moves");
    auto axpy = [n](Field3& y, double a, const Field3& x, double b) {  // y = a y + b x
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i)
            y.x[i] = a * y.x[i] + b * x.x[i], y.y[i] = a * y.y[i] + b * x.y[i], y.z[i] = a * y.z[i] + b * x.z[i];
    };
    axpy(q, 1.0 / q0, q, 0.0);

    std::vector<double> alpha, beta;
    double prevMin = 0, prevMax = 0, betaPrev = 0;
    int nextCheck = 10;
    Frequencies out;
    for (int it = 1; it <= maxIterations; ++it) {
        // w = S K S q - beta_{j-1} q_{j-1}
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i)
            tmp.x[i] = s.x[i] * q.x[i], tmp.y[i] = s.y[i] * q.y[i], tmp.z[i] = s.z[i] * q.z[i];
        linearStiffnessProduct(lat, tmp, w);
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i)
            w.x[i] = s.x[i] * w.x[i] - betaPrev * qPrev.x[i], w.y[i] = s.y[i] * w.y[i] - betaPrev * qPrev.y[i],
            w.z[i] = s.z[i] * w.z[i] - betaPrev * qPrev.z[i];
        const double a = dot(w, q);
        axpy(w, 1.0, q, -a);
        const double b = std::sqrt(dot(w, w));
        alpha.push_back(a);
        const bool exhausted = b <= 1e-12 * std::abs(a);  // Krylov space exhausted: exact
        if (it == nextCheck || exhausted || it == maxIterations) {
            const auto [lmin, lmax] = ritzExtremes(alpha, beta);
            const bool converged = std::abs(lmin - prevMin) <= tolerance * lmin &&
                                   std::abs(lmax - prevMax) <= tolerance * lmax;
            prevMin = lmin, prevMax = lmax;
            out = {std::sqrt(std::max(lmin, 0.0)), std::sqrt(lmax), it};
            if (converged || exhausted) return out;
            nextCheck = it + std::max(10, it / 8);
        }
        beta.push_back(b);
        std::swap(qPrev, q);  // q_{j-1} <- q_j
        axpy(q, 0.0, w, 1.0 / b);
        betaPrev = b;
    }
    return out;
}

}  // namespace ldem
