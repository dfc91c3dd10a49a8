#include "ldem/Modal.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "ldem/InternalForces.hpp"
#include "ldem/Interrupt.hpp"
#include "ldem/Slab.hpp"
#include "ldem/RandomField.hpp"

namespace ldem {

namespace {
// a . b over the owned nodes, the same bits for any number of ranks (Slab.hpp).
double dot(const Lattice& lat, const Field3& a, const Field3& b) {
    return nodeSum<1>(lat, [&](std::int32_t i, std::array<double, 1>& s) {
        s[0] += a.x[i] * b.x[i] + a.y[i] * b.y[i] + a.z[i] * b.z[i];
    })[0];
}

// The diagonal of K: a bar of stiffness k = EA/L along n adds k n_d^2 to DOF d of both its nodes.
Field3 stiffnessDiagonal(const Lattice& lat) {
    Field3 k(lat.numNodes());
    for (const BarRow& row : lat.barRows) {
        const BarFamily& fam = lat.families[row.family];
        const double n[3] = {fam.d0[0] / fam.L, fam.d0[1] / fam.L, fam.d0[2] / fam.L};
        for (int p = 0; p < row.count; ++p) {
            const double kb = fam.EA * row.shareAt(p) / fam.L;
            for (const std::int32_t i : {row.nodeA + p, row.nodeB + p})
                k.x[i] += kb * n[0] * n[0], k.y[i] += kb * n[1] * n[1], k.z[i] += kb * n[2] * n[2];
        }
    }
    return k;
}

// Number of eigenvalues below x of the symmetric tridiagonal matrix with
// diagonal a and off-diagonal b (Sturm sequence of the LDL^T pivots).
int eigenvaluesBelow(const std::vector<double>& a, const std::vector<double>& b, double x) {
    int count = 0;
    double d = 1.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        d = a[i] - x - (i > 0 ? b[i - 1] * b[i - 1] / d : 0.0);
        if (d == 0.0) d = -1e-300;
        count += d < 0;
    }
    return count;
}

// The j-th smallest eigenvalue (j = 0, 1, ...) by bisection between Gershgorin bounds.
double tridiagonalEigenvalue(const std::vector<double>& a, const std::vector<double>& b, int j) {
    double lo = a[0], hi = a[0];
    for (std::size_t i = 0; i < a.size(); ++i) {
        const double r = (i > 0 ? std::abs(b[i - 1]) : 0.0) + (i + 1 < a.size() ? std::abs(b[i]) : 0.0);
        lo = std::min(lo, a[i] - r), hi = std::max(hi, a[i] + r);
    }
    for (int it = 0; it < 200 && hi - lo > 1e-15 * std::max(std::abs(lo), std::abs(hi)); ++it) {
        const double mid = 0.5 * (lo + hi);
        (eigenvaluesBelow(a, b, mid) > j ? hi : lo) = mid;
    }
    return 0.5 * (lo + hi);
}

// Last component of the unit eigenvector of the tridiagonal matrix for the
// eigenvalue theta, by two steps of inverse iteration (Thomas algorithm).
double lastEigenvectorComponent(const std::vector<double>& a, const std::vector<double>& b, double theta) {
    const std::size_t k = a.size();
    const double shift = theta + 1e-10 * std::abs(theta);  // keeps T - shift I invertible
    std::vector<double> x(k, 1.0), c(k), d(k);
    for (int step = 0; step < 2; ++step) {
        // Solve (T - shift I) y = x, forward elimination then back substitution.
        double piv = a[0] - shift;
        c[0] = k > 1 ? b[0] / piv : 0.0, d[0] = x[0] / piv;
        for (std::size_t i = 1; i < k; ++i) {
            piv = a[i] - shift - b[i - 1] * c[i - 1];
            if (piv == 0.0) piv = 1e-300;
            c[i] = i + 1 < k ? b[i] / piv : 0.0;
            d[i] = (x[i] - b[i - 1] * d[i - 1]) / piv;
        }
        x[k - 1] = d[k - 1];
        for (std::size_t i = k - 1; i-- > 0;) x[i] = d[i] - c[i] * x[i + 1];
        double norm = 0;
        for (double v : x) norm += v * v;
        norm = std::sqrt(norm);
        for (double& v : x) v /= norm;
    }
    return x[k - 1];
}
}  // namespace

Frequencies latticeFrequencies(const Lattice& lat, const std::vector<std::uint8_t>& mask, int maxIterations,
                               double tolerance) {
    const std::int64_t n = lat.numNodes();
    // s = M^-1/2 on free DOFs, 0 on prescribed ones: A = S K S. A node of mass 0
    // (of no present module of a masked lattice: no bars) is removed like a prescribed one.
    Field3 s(n);
    std::int64_t freeDofs = 0;
    InterruptCheck heard;  // the two passes over the nodes below grow with the lattice
    for (std::int64_t i = 0; i < n; ++i) {
        heard();
        const bool removed = !(lat.mass[i] > 0);
        const double r = removed ? 0.0 : 1.0 / std::sqrt(lat.mass[i]);
        s.x[i] = (mask[i] & 1) ? 0 : r, s.y[i] = (mask[i] & 2) ? 0 : r, s.z[i] = (mask[i] & 4) ? 0 : r;
        if (!removed && lat.owns(lat.layerOfNode(std::int32_t(i))))
            freeDofs += !(mask[i] & 1) + !(mask[i] & 2) + !(mask[i] & 4);
    }
    freeDofs = commOf(lat).sum(freeDofs);
    Field3 q(n), qPrev(n), w(n), tmp(n);
    BarForceBuffers barWork;
    for (std::int64_t i = 0; i < n; ++i) {  // deterministic start vector, a function of the node
        heard();
        const std::uint64_t id = lat.globalNode(std::int32_t(i));
        q.x[i] = s.x[i] * (hashedUniform(7, id, 0) - 0.5);
        q.y[i] = s.y[i] * (hashedUniform(7, id, 1) - 0.5);
        q.z[i] = s.z[i] * (hashedUniform(7, id, 2) - 0.5);
    }
    const double q0 = std::sqrt(dot(lat, q, q));
    if (q0 == 0) throw std::invalid_argument("every degree of freedom is prescribed: nothing moves");
    auto axpy = [n](Field3& y, double a, const Field3& x, double b) {  // y = a y + b x
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i)
            y.x[i] = a * y.x[i] + b * x.x[i], y.y[i] = a * y.y[i] + b * x.y[i], y.z[i] = a * y.z[i] + b * x.z[i];
    };
    axpy(q, 1.0 / q0, q, 0.0);

    std::vector<double> alpha, beta;
    double betaPrev = 0;
    int nextCheck = 10;
    Frequencies out;
    InterruptCheck interruptPoint;
    for (int it = 1; it <= maxIterations; ++it) {
        interruptPoint();
        // w = S K S q - beta_{j-1} q_{j-1}
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i)
            tmp.x[i] = s.x[i] * q.x[i], tmp.y[i] = s.y[i] * q.y[i], tmp.z[i] = s.z[i] * q.z[i];
        exchangeHalo(lat, tmp);  // the product at the owned nodes needs the halo's
        linearStiffnessProduct(lat, tmp, barWork, w);
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i)
            w.x[i] = s.x[i] * w.x[i] - betaPrev * qPrev.x[i], w.y[i] = s.y[i] * w.y[i] - betaPrev * qPrev.y[i],
            w.z[i] = s.z[i] * w.z[i] - betaPrev * qPrev.z[i];
        const double a = dot(lat, w, q);
        axpy(w, 1.0, q, -a);
        const double b = std::sqrt(dot(lat, w, w));
        alpha.push_back(a);
        // Krylov space exhausted (tiny lattices): the Ritz values are exact. Its
        // dimension is at most the number of free DOFs; going on past it (b is
        // then rounding noise, not always below the threshold) adds spurious
        // Ritz values: a 1-module cube found omega_1 = 0 and ran into NaN.
        const bool exhausted = b <= 1e-12 * std::abs(a) || it >= freeDofs;
        if (it == nextCheck || exhausted || it == maxIterations) {
            // A Ritz pair (theta, s) has residual |beta_k s_k| and an eigenvalue
            // lies within it: converged when both extremes are that close.
            const double lmin = tridiagonalEigenvalue(alpha, beta, 0);
            const double lmax = tridiagonalEigenvalue(alpha, beta, int(alpha.size()) - 1);
            const double rmin = std::abs(b * lastEigenvectorComponent(alpha, beta, lmin));
            const double rmax = std::abs(b * lastEigenvectorComponent(alpha, beta, lmax));
            out = {std::sqrt(std::max(lmin, 0.0)), std::sqrt(lmax), it};
            if (exhausted || (rmin <= tolerance * lmin && rmax <= tolerance * lmax)) return out;
            nextCheck = it + std::max(10, it / 10);
        }
        beta.push_back(b);
        std::swap(qPrev, q);  // q_{j-1} <- q_j
        axpy(q, 0.0, w, 1.0 / b);
        betaPrev = b;
    }
    return out;
}

double driveFrequency(const Lattice& lat, const std::vector<std::uint8_t>& mask, const Field3& drive,
                      int* iterations, int maxIterations, double tolerance) {
    const std::int64_t n = lat.numNodes();
    // P = 1/K_ii on the unknowns (the free DOFs of nodes with bars), 0 elsewhere.
    Field3 P = stiffnessDiagonal(lat);
    for (std::int64_t i = 0; i < n; ++i) {
        const bool removed = !(lat.mass[i] > 0);
        auto inverse = [&](unsigned bit, double& k) { k = (mask[i] & bit) || removed || !(k > 0) ? 0.0 : 1.0 / k; };
        inverse(1, P.x[i]), inverse(2, P.y[i]), inverse(4, P.z[i]);
    }
    BarForceBuffers barWork;
    auto product = [&](Field3& x, Field3& y) {  // y = K x at the owned nodes
        exchangeHalo(lat, x);
        linearStiffnessProduct(lat, x, barWork, y);
    };
    auto onUnknowns = [&](Field3& y, double a) {  // y = a y on the unknowns, 0 elsewhere
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i)
            y.x[i] = P.x[i] > 0 ? a * y.x[i] : 0.0, y.y[i] = P.y[i] > 0 ? a * y.y[i] : 0.0,
            y.z[i] = P.z[i] > 0 ? a * y.z[i] : 0.0;
    };
    auto precondition = [&](const Field3& r, Field3& z) {
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i) z.x[i] = P.x[i] * r.x[i], z.y[i] = P.y[i] * r.y[i], z.z[i] = P.z[i] * r.z[i];
    };
    Field3 u = drive, r(n), z(n), p(n), q(n);
    product(u, r);
    onUnknowns(r, -1.0);  // r = -K_fp u_p, the residual of u_f = 0
    precondition(r, z);
    p = z;
    double rz = dot(lat, r, z);
    const double r0 = std::sqrt(dot(lat, r, r));
    int it = 0;
    InterruptCheck interruptPoint;
    for (; it < maxIterations && std::sqrt(dot(lat, r, r)) > tolerance * r0; ++it) {
        interruptPoint();
        product(p, q);
        onUnknowns(q, 1.0);
        const double alpha = rz / dot(lat, p, q);
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i)
            u.x[i] += alpha * p.x[i], u.y[i] += alpha * p.y[i], u.z[i] += alpha * p.z[i],
            r.x[i] -= alpha * q.x[i], r.y[i] -= alpha * q.y[i], r.z[i] -= alpha * q.z[i];
        precondition(r, z);
        const double rzNext = dot(lat, r, z), b = rzNext / rz;
        rz = rzNext;
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i)
            p.x[i] = z.x[i] + b * p.x[i], p.y[i] = z.y[i] + b * p.y[i], p.z[i] = z.z[i] + b * p.z[i];
    }
    if (iterations) *iterations = it;
    product(u, q);
    const double uKu = dot(lat, u, q);
    const double uMu = nodeSum<1>(lat, [&](std::int32_t i, std::array<double, 1>& s) {
        s[0] += lat.mass[i] * (u.x[i] * u.x[i] + u.y[i] * u.y[i] + u.z[i] * u.z[i]);
    })[0];
    return uMu > 0 ? std::sqrt(uKu / uMu) : 0.0;
}

void refuseMechanism(const Frequencies& f) {
    if (f.omega1 > 1e-6 * f.omegaMax) return;
    std::ostringstream msg;
    msg << "the constraints leave a mechanism: omega_1 = " << f.omega1 << " rad/s (omega_max = " << f.omegaMax
        << " rad/s); e.g. one module with a laterally free upper face turns about the "
        << "vertical axis: use at least 2 modules a side or hold the upper face laterally";
    throw std::invalid_argument(msg.str());
}

}  // namespace ldem
