// Natural frequencies of the lattice (LDEM_SPEC section 5): the matrix-free
// Lanczos estimates of omega_1 and omega_max against (i) a dense eigensolver on
// a stiffness matrix assembled bar by bar (Assembled.hpp), independently of the library,
// (ii) the Rayleigh quotient of smooth trial shapes (upper bound on omega_1^2)
// and (iii) the Gershgorin bound (upper bound on omega_max^2).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "Assembled.hpp"
#include "ldem/InternalForces.hpp"
#include "ldem/Lattice.hpp"
#include "ldem/laws/Hillerborg.hpp"
#include "ldem/Loading.hpp"
#include "ldem/Modal.hpp"
#include "ldem/Specimen.hpp"
#include "ldem/RandomField.hpp"
#include "ldem/Simulation.hpp"

using namespace ldem;

namespace {

struct Reduced {
    std::vector<Eigen::Index> dofs;  // free DOFs, as 3 node + d
    Eigen::MatrixXd K, A;            // stiffness and M^-1/2 K M^-1/2 on them
    Eigen::VectorXd m;               // masses of the free DOFs
};

Reduced reduce(const Lattice& lat, const std::vector<std::uint8_t>& mask) {
    const Eigen::MatrixXd K = assembleStiffness(lat);
    Reduced r;
    for (std::int64_t i = 0; i < lat.numNodes(); ++i)
        for (int d = 0; d < 3; ++d)
            if (!(mask[i] & (1u << d))) r.dofs.push_back(3 * i + d);
    const Eigen::Index n = Eigen::Index(r.dofs.size());
    r.K.resize(n, n), r.A.resize(n, n), r.m.resize(n);
    for (Eigen::Index a = 0; a < n; ++a) r.m(a) = lat.mass[r.dofs[a] / 3];
    for (Eigen::Index a = 0; a < n; ++a)
        for (Eigen::Index c = 0; c < n; ++c) {
            r.K(a, c) = K(r.dofs[a], r.dofs[c]);
            r.A(a, c) = r.K(a, c) / std::sqrt(r.m(a) * r.m(c));
        }
    return r;
}

// Rayleigh quotient of a trial displacement u(x, y, z) on the free DOFs.
template <class Shape>
double rayleigh(const Lattice& lat, const Reduced& r, Shape shape) {
    Eigen::VectorXd u(r.dofs.size());
    const auto x0 = nodePositions(lat);
    for (Eigen::Index a = 0; a < u.size(); ++a) {
        const auto node = r.dofs[a] / 3;
        u(a) = shape(x0[0][node], x0[1][node], x0[2][node], int(r.dofs[a] % 3));
    }
    return u.dot(r.K * u) / u.dot(r.m.asDiagonal() * u);
}

void checkFrequencies(int n, bool rollers) {
    SCOPED_TRACE(testing::Message() << n << "^3, bottom rollers " << rollers);
    Material m;
    const double L0 = 0.02, H = n * L0;
    LoadingParams lp;
    lp.bottomLateralFree = rollers;
    const Specimen spec = cubeTestSpecimen(n, n, n, L0, m, lp);
    const Lattice& lat = spec.lattice;
    const Prescribed& con = spec.prescribed;
    const Frequencies f = latticeFrequencies(lat, con.mask);
    const Reduced r = reduce(lat, con.mask);

    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(r.A, Eigen::EigenvaluesOnly);
    const double lmin = es.eigenvalues()(0), lmax = es.eigenvalues()(es.eigenvalues().size() - 1);
    ASSERT_GT(lmin, 0.0) << "constraints must remove every rigid motion";

    // Rayleigh quotients of smooth shapes that respect the constraints (bottom
    // held, top vertical DOF held): lateral sway sin(pi z / 2H), and vertical
    // sin(pi z / H) (zero on both faces).
    const double pi = M_PI;
    const double Rsway =
        rayleigh(lat, r, [&](double, double, double z, int d) { return d == 0 ? std::sin(pi * z / (2 * H)) : 0.0; });
    const double Rvert =
        rayleigh(lat, r, [&](double, double, double z, int d) { return d == 2 ? std::sin(pi * z / H) : 0.0; });
    // Rigid slide in x: every free x DOF moves by 1. Admissible (the pinned DOFs
    // stay put); only the bars at pinned nodes strain. Under rollers this is
    // close to the fundamental mode: a nearly rigid motion held by two pins.
    const double Rslide = rayleigh(lat, r, [&](double, double, double, int d) { return d == 0 ? 1.0 : 0.0; });
    const double Rbest = std::min({Rsway, Rvert, Rslide});
    // Gershgorin: every eigenvalue of A lies below max_i sum_j |A_ij|; and the
    // largest diagonal entry is a Rayleigh quotient, hence below lambda_max.
    double gersh = 0, diagMax = 0;
    for (Eigen::Index a = 0; a < r.A.rows(); ++a) {
        gersh = std::max(gersh, r.A.row(a).cwiseAbs().sum());
        diagMax = std::max(diagMax, r.A(a, a));
    }
    std::printf(
        "[ modal ] %d^3 %s: omega_1 Lanczos %.6e dense %.6e sqrt(R_sway) %.4e sqrt(R_vert) %.4e sqrt(R_slide) %.4e | "
        "omega_max Lanczos %.6e dense %.6e sqrt(Gershgorin) %.4e | %d iterations\n",
        n, rollers ? "rollers" : "clamped", f.omega1, std::sqrt(lmin), std::sqrt(Rsway), std::sqrt(Rvert),
        std::sqrt(Rslide), f.omegaMax, std::sqrt(lmax), std::sqrt(gersh), f.iterations);

    // The required inequalities.
    EXPECT_LE(f.omega1 * f.omega1, Rsway * (1 + 1e-9));
    EXPECT_LE(f.omega1 * f.omega1, Rvert * (1 + 1e-9));
    EXPECT_LE(f.omega1 * f.omega1, Rslide * (1 + 1e-9));
    EXPECT_LE(f.omegaMax * f.omegaMax, gersh * (1 + 1e-12));
    EXPECT_GE(f.omegaMax * f.omegaMax, diagMax * (1 - 1e-9));
    // Within reasonable factors of the bounds: a smooth trial shape is close to
    // the fundamental mode; the Gershgorin bound overestimates by a bounded factor.
    EXPECT_GT(f.omega1, 0.5 * std::sqrt(Rbest));
    EXPECT_GT(f.omegaMax, 0.5 * std::sqrt(gersh));
    // And Lanczos agrees with the dense eigensolver. Ritz values lie inside the
    // spectrum, so omega_max is never overestimated (the time step is not
    // made unsafe by the estimate) and omega_1 never underestimated.
    EXPECT_NEAR(f.omega1, std::sqrt(lmin), 1e-5 * std::sqrt(lmin));
    EXPECT_NEAR(f.omegaMax, std::sqrt(lmax), 1e-6 * std::sqrt(lmax));
    EXPECT_LE(f.omegaMax, std::sqrt(lmax) * (1 + 1e-12));
}

}  // namespace

// The smallest cubes: the Krylov space is exhausted within a few iterations
// (11 free DOFs for one module); Lanczos must stop there, not add ghosts.
TEST(Modal, LanczosAgainstDenseTwoModulesRollers) { checkFrequencies(2, true); }

// One module with a laterally free upper face is a mechanism: the upper face
// turns about the vertical axis without stretching a bar (edges rigid, the
// corner-centre bars perpendicular to the motion). Lanczos finds omega_1 = 0
// (the dense solver 6e-3 rad/s, rounding) and omega_max exactly; a Simulation
// refuses it with a message instead of running into NaN (D_f = 0, ramp time inf).
TEST(Modal, OneModuleIsAMechanismAndIsRefused) {
    Material m;
    const Specimen spec = cubeTestSpecimen(1, 1, 1, 0.02, m, LoadingParams{});
    const Lattice& lat = spec.lattice;
    const Prescribed& con = spec.prescribed;
    const Frequencies f = latticeFrequencies(lat, con.mask);
    const Reduced r = reduce(lat, con.mask);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(r.A, Eigen::EigenvaluesOnly);
    const double lmax = es.eigenvalues().maxCoeff();
    EXPECT_EQ(r.A.rows(), 11);
    EXPECT_LT(es.eigenvalues()(0), 1e-12 * lmax);
    EXPECT_LT(f.omega1, 1e-6 * f.omegaMax);
    EXPECT_NEAR(f.omegaMax, std::sqrt(lmax), 1e-9 * std::sqrt(lmax));
    EXPECT_LE(f.iterations, 11);
    try {
        Simulation sim(cubeTestSpecimen(1, 1, 1, 0.02, m, LoadingParams{}), m, LoadingParams{}, RunParams{});
        ADD_FAILURE() << "a mechanism was accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("mechanism"), std::string::npos) << e.what();
    }
    // Held laterally at the top, the same module is stable and runs.
    LoadingParams held;
    held.topLateralFree = false;
    Simulation sim(cubeTestSpecimen(1, 1, 1, 0.02, m, held), m, held, RunParams{});
    EXPECT_GT(sim.frequencies().omega1, 0.1 * sim.frequencies().omegaMax);
}
// Clamped bottom (default): omega_1 is a lateral sway, 0.81 x sqrt(R_sway).
TEST(Modal, LanczosAgainstDenseRayleighAndGershgorin3) { checkFrequencies(3, false); }
// Bottom on rollers: omega_1 (7.9e3 rad/s on 4^3) is not a deformation mode
// but a nearly rigid slide/rotation of the whole cube held only by the two
// pinned corner nodes (0.60 x sqrt(R_slide); the sway is 4.7e4). So under
// rollers D_f = 2 zeta omega_1 damps the deformation modes far less than zeta.
TEST(Modal, LanczosAgainstDenseRayleighAndGershgorin4Rollers) { checkFrequencies(4, true); }

// The matrix-free product used by Lanczos is the assembled stiffness.
TEST(Modal, MatrixFreeProductIsAssembledStiffness) {
    Material m;
    const Lattice lat = buildCubicLattice(2, 3, 2, 0.02, m);
    const Eigen::MatrixXd K = assembleStiffness(lat);
    // Symmetric, positive semi-definite, six rigid-body modes.
    EXPECT_LT((K - K.transpose()).cwiseAbs().maxCoeff(), 1e-6);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(K, Eigen::EigenvaluesOnly);
    const double top = es.eigenvalues().maxCoeff();
    int zero = 0;
    for (Eigen::Index i = 0; i < es.eigenvalues().size(); ++i) {
        EXPECT_GT(es.eigenvalues()(i), -1e-9 * top);
        zero += std::abs(es.eigenvalues()(i)) < 1e-9 * top;
    }
    EXPECT_EQ(zero, 6);

    Field3 x(lat.numNodes()), y(lat.numNodes());
    Eigen::VectorXd xv(3 * lat.numNodes());
    for (std::int64_t i = 0; i < lat.numNodes(); ++i) {
        x.x[i] = xv(3 * i) = hashedUniform(9, i, 0) - 0.5;
        x.y[i] = xv(3 * i + 1) = hashedUniform(9, i, 1) - 0.5;
        x.z[i] = xv(3 * i + 2) = hashedUniform(9, i, 2) - 0.5;
    }
    BarForceBuffers g;
    linearStiffnessProduct(lat, x, g, y);
    const Eigen::VectorXd yv = K * xv;
    const double scale = yv.cwiseAbs().maxCoeff();
    for (std::int64_t i = 0; i < lat.numNodes(); ++i) {
        EXPECT_NEAR(y.x[i], yv(3 * i), 1e-12 * scale);
        EXPECT_NEAR(y.y[i], yv(3 * i + 1), 1e-12 * scale);
        EXPECT_NEAR(y.z[i], yv(3 * i + 2), 1e-12 * scale);
    }
    // Small displacements through the nonlinear force loop give -K x too.
    HillerborgLaw bars(lat, 1.0, std::vector<double>(lat.numBars(), 1.0));
    Field3 small(lat.numNodes()), f(lat.numNodes());
    const double a = 1e-9;  // displacement amplitude [m]: geometric nonlinearity ~ a / L0 = 5e-8
    for (std::int64_t i = 0; i < lat.numNodes(); ++i)
        small.x[i] = a * x.x[i], small.y[i] = a * x.y[i], small.z[i] = a * x.z[i];
    computeInternalForces(lat, small, bars, g, f);
    for (std::int64_t i = 0; i < lat.numNodes(); ++i) {
        EXPECT_NEAR(f.x[i], -a * yv(3 * i), 1e-6 * a * scale);
        EXPECT_NEAR(f.y[i], -a * yv(3 * i + 1), 1e-6 * a * scale);
        EXPECT_NEAR(f.z[i], -a * yv(3 * i + 2), 1e-6 * a * scale);
    }
}

namespace {
// The unit drive of a specimen: each prescribed DOF at its weight (U = 1), and the dense u_f of K_ff u_f = -K_fp u_p.
Field3 unitDrive(const Specimen& s) {
    Field3 w(s.lattice.numNodes());
    for (std::size_t k = 0; k < s.prescribed.node.size(); ++k)
        w[s.prescribed.dim[k]][s.prescribed.node[k]] = s.prescribed.weight[k];
    return w;
}

double denseDriveFrequency(const Specimen& s) {
    const Lattice& lat = s.lattice;
    const Eigen::MatrixXd K = assembleStiffness(lat);
    const Field3 w = unitDrive(s);
    const Eigen::Index N = 3 * lat.numNodes();
    Eigen::VectorXd u(N), m(N);
    std::vector<Eigen::Index> freeDofs;
    for (std::int64_t i = 0; i < lat.numNodes(); ++i)
        for (int d = 0; d < 3; ++d) {
            u(3 * i + d) = w[d][i], m(3 * i + d) = lat.mass[i];
            if (!(s.prescribed.mask[i] & (1u << d))) freeDofs.push_back(3 * i + d);
        }
    const Eigen::Index f = Eigen::Index(freeDofs.size());
    Eigen::MatrixXd Kff(f, f);
    Eigen::VectorXd rhs = -(K * u);  // u is zero on the free DOFs: -K_fp u_p there
    Eigen::VectorXd b(f);
    for (Eigen::Index a = 0; a < f; ++a) {
        b(a) = rhs(freeDofs[a]);
        for (Eigen::Index c = 0; c < f; ++c) Kff(a, c) = K(freeDofs[a], freeDofs[c]);
    }
    const Eigen::VectorXd uf = Kff.ldlt().solve(b);
    for (Eigen::Index a = 0; a < f; ++a) u(freeDofs[a]) = uf(a);
    return std::sqrt(u.dot(K * u) / u.dot(m.asDiagonal() * u));
}
}  // namespace

// omega_d (driveFrequency): the matrix-free CG's Rayleigh quotient is the dense one, for
// the uniform and the triangular drive, clamped and on rollers.
TEST(Modal, DriveFrequencyIsTheDenseRayleighQuotient) {
    Material m;
    for (bool rollers : {false, true})
        for (LoadShape load : {LoadShape::Uniform, LoadShape::Triangular}) {
            LoadingParams lp;
            lp.bottomLateralFree = rollers, lp.shape = load;
            const Specimen s = cubeTestSpecimen(3, 3, 3, 0.02, m, lp);
            int iterations = 0;
            const double cg = driveFrequency(s.lattice, s.prescribed.mask, unitDrive(s), &iterations);
            const double dense = denseDriveFrequency(s);
            SCOPED_TRACE(testing::Message() << "rollers " << rollers << ", load " << int(load));
            EXPECT_NEAR(cg, dense, 1e-9 * dense);
            EXPECT_GT(iterations, 0);
            EXPECT_LT(iterations, 300);  // (220 free DOFs at most: CG converges within them, bar rounding)
        }
}

// A one-module-wide column of n modules, every node held laterally, its lower end held and its
// upper end pulled along z, the end centre nodes (one centre-centre bar each) moved with the
// linear field u = z/H e_z: that field is then the elastic solution (every free node's bars
// pull up and down alike), so omega_d is its Rayleigh quotient, by hand. With
// k = EA/L, u'Ku = sum k (n_z dz/H)^2 = sum EA L n_z^4 / H^2: the 4 vertical edges of each of
// the n levels (a quarter each: E A_n L0), the n - 1 centre-centre bars (E A_n L0) and the 8n
// diagonals (n_z^2 = 1/3, L = sqrt(3)/2 L0, A_d = 2 delta/sqrt(3) A_n: 8 delta/9 E A_n L0 each level):
//   u'Ku H^2 = E phi L0^3 (2n - 1 + 8 delta n/9)     (= E phi L0^3 (3n - 1) at nu = 0.25).
// The masses (rho L0^3 a module: half to its centre, 1/16 to each corner):
//   u'Mu H^2 = rho L0^5 [ sum_{k<n} k^2/2 + n^2/4 + sum_{k<n} (k + 1/2)^2/2 ].
// For large n, omega_d -> sqrt(3 E'/rho)/H, E' = 3 E phi = 1.2 E the modulus of uniaxial strain.
TEST(DirectModal, DriveFrequencyOfALaterallyHeldColumnIsItsLinearField) {
    Material m;
    const int n = 7;
    const double L0 = 0.02, H = n * L0;
    LoadingParams lp;
    lp.topLateralFree = false;
    Specimen s = cubeTestSpecimen(1, 1, n, L0, m, lp);
    for (std::int32_t i = 0; i < std::int32_t(s.lattice.numNodes()); ++i)
        for (int d : {0, 1})
            if (!(s.prescribed.mask[i] & (1u << d))) s.prescribed.add(i, d, 0.0);
    s.prescribed.add(s.lattice.centreId(0, 0, 0), 2, 0.5 / n);
    s.prescribed.add(s.lattice.centreId(0, 0, n - 1), 2, (n - 0.5) / n);
    const double phi = nayfehPhi(m.nu), delta = nayfehDelta(m.nu);
    const double uKu = m.E * phi * std::pow(L0, 3) * (2 * n - 1 + 8 * delta * n / 9) / (H * H);
    double levels = n * n / 4.0;  // the upper corners, 4 x 1/16
    for (int k = 0; k < n; ++k) levels += k * k / 2.0 + (k + 0.5) * (k + 0.5) / 2.0;
    const double uMu = m.rho * std::pow(L0, 5) * levels / (H * H);
    const double want = std::sqrt(uKu / uMu);
    int iterations = 0;
    const double got = driveFrequency(s.lattice, s.prescribed.mask, unitDrive(s), &iterations);
    EXPECT_NEAR(got, want, 1e-9 * want);
    EXPECT_LT(iterations, 100);
    std::printf("[ modal ] column 1x1x%d held laterally: omega_d %.6e rad/s, by hand %.6e, sqrt(3.6 E/rho)/H %.4e\n",
                n, got, want, std::sqrt(3 * 1.2 * m.E / m.rho) / H);
}
