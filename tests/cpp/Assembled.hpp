// The lattice's linear stiffness assembled bar by bar, independently of the
// library's matrix-free product: a bar of direction n and stiffness k = EA/L
// adds k n n^T to the (i,i) and (j,j) blocks and -k n n^T to (i,j), (j,i).
// For the dense checks of tests/cpp (test_modal.cpp, test_dashpots.cpp).
#pragma once
#include <Eigen/Dense>
#include <cmath>

#include "ldem/Lattice.hpp"

inline Eigen::MatrixXd assembleStiffness(const ldem::Lattice& lat) {
    const Eigen::Index N = 3 * lat.numNodes();
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(N, N);
    const ldem::BarTable t = ldem::listBars(lat);
    const auto x0 = ldem::nodePositions(lat);
    for (std::int64_t b = 0; b < lat.numBars(); ++b) {
        const auto i = t.n1[b], j = t.n2[b];
        const double dx = x0[0][j] - x0[0][i], dy = x0[1][j] - x0[1][i], dz = x0[2][j] - x0[2][i];
        const double L = std::sqrt(dx * dx + dy * dy + dz * dz);
        const double n[3] = {dx / L, dy / L, dz / L};
        const double k = t.EA[b] / L;
        for (int a = 0; a < 3; ++a)
            for (int c = 0; c < 3; ++c) {
                const double v = k * n[a] * n[c];
                K(3 * i + a, 3 * i + c) += v;
                K(3 * j + a, 3 * j + c) += v;
                K(3 * i + a, 3 * j + c) -= v;
                K(3 * j + a, 3 * i + c) -= v;
            }
    }
    return K;
}
