// Lattice geometry (LDEM_SPEC section 1): node and bar counts, families,
// surface shares k/4, lumped masses and the colouring used by the parallel
// force scatter. Every expectation is derived here from the module picture
// (a brute-force enumeration of the modules' bars), not from the library's
// own counting helpers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include "ldem/Lattice.hpp"

using namespace ldem;

namespace {

using Pair = std::pair<std::int32_t, std::int32_t>;
Pair unordered(std::int32_t a, std::int32_t b) { return a < b ? Pair{a, b} : Pair{b, a}; }

// Closed-form counts, written from the spec's description:
//   edges along x: nx segments on each of the (ny+1)(nz+1) lattice lines, etc.;
//   centre-centre along x: (nx-1) links per row of ny nz rows, etc.;
//   8 diagonals per module.
struct Counts {
    std::int64_t nodes, edge[3], cc[3], diag;
    std::int64_t bars() const { return edge[0] + edge[1] + edge[2] + cc[0] + cc[1] + cc[2] + diag; }
};
Counts closedForm(std::int64_t nx, std::int64_t ny, std::int64_t nz) {
    Counts c;
    c.nodes = (nx + 1) * (ny + 1) * (nz + 1) + nx * ny * nz;
    c.edge[0] = nx * (ny + 1) * (nz + 1);
    c.edge[1] = ny * (nx + 1) * (nz + 1);
    c.edge[2] = nz * (nx + 1) * (ny + 1);
    c.cc[0] = (nx - 1) * ny * nz;
    c.cc[1] = nx * (ny - 1) * nz;
    c.cc[2] = nx * ny * (nz - 1);
    c.diag = 8 * nx * ny * nz;
    return c;
}

// Brute force: walk every module, list its 12 edges, its 8 diagonals and the
// links of its centre to the centres of its face neighbours; count how many
// modules claim each edge (k), deduplicating shared bars by their node pair.
struct BruteForce {
    std::map<Pair, int> edgeModules;  // edge -> number of modules sharing it
    std::set<Pair> centreLinks, diagonals;
};
BruteForce enumerateModules(const Lattice& lat) {
    BruteForce bf;
    const int nx = lat.nx, ny = lat.ny, nz = lat.nz;
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const auto c = lat.centreId(i, j, k);
                // 12 edges: for each pair of corners that differ in exactly one index.
                for (int a = 0; a < 8; ++a)
                    for (int b = a + 1; b < 8; ++b) {
                        const int diff = a ^ b;
                        if (diff != 1 && diff != 2 && diff != 4) continue;
                        const auto na = lat.cornerId(i + (a & 1), j + ((a >> 1) & 1), k + ((a >> 2) & 1));
                        const auto nb = lat.cornerId(i + (b & 1), j + ((b >> 1) & 1), k + ((b >> 2) & 1));
                        ++bf.edgeModules[unordered(na, nb)];
                    }
                for (int a = 0; a < 8; ++a)
                    bf.diagonals.insert(
                        unordered(c, lat.cornerId(i + (a & 1), j + ((a >> 1) & 1), k + ((a >> 2) & 1))));
                const int nb[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
                for (const auto& d : nb) {
                    const int ii = i + d[0], jj = j + d[1], kk = k + d[2];
                    if (ii < 0 || jj < 0 || kk < 0 || ii >= nx || jj >= ny || kk >= nz) continue;
                    bf.centreLinks.insert(unordered(c, lat.centreId(ii, jj, kk)));
                }
            }
    return bf;
}

const Material kMat{};  // Table 2 of the study

void checkCountsAndTopology(int nx, int ny, int nz) {
    SCOPED_TRACE(testing::Message() << nx << "x" << ny << "x" << nz);
    const double L0 = 0.02;
    const Lattice lat = buildCubicLattice(nx, ny, nz, L0, kMat);
    const Counts c = closedForm(nx, ny, nz);
    ASSERT_EQ(lat.numNodes(), c.nodes);
    ASSERT_EQ(lat.numBars(), c.bars());
    ASSERT_EQ(std::int64_t(lat.n2.size()), lat.numBars());
    ASSERT_EQ(std::int64_t(lat.family.size()), lat.numBars());
    ASSERT_EQ(std::int64_t(lat.share.size()), lat.numBars());

    // Brute-force enumeration must give the same numbers as the closed form.
    const BruteForce bf = enumerateModules(lat);
    EXPECT_EQ(std::int64_t(bf.edgeModules.size()), c.edge[0] + c.edge[1] + c.edge[2]);
    EXPECT_EQ(std::int64_t(bf.centreLinks.size()), c.cc[0] + c.cc[1] + c.cc[2]);
    EXPECT_EQ(std::int64_t(bf.diagonals.size()), c.diag);

    // Per-family counts and the kind/length/area of each family.
    ASSERT_EQ(lat.families.size(), 14u);
    std::vector<std::int64_t> perFamily(lat.families.size(), 0);
    for (auto f : lat.family) ++perFamily.at(f);
    int edgeFam = 0, ccFam = 0, diagFam = 0;
    const double An = 0.4 * L0 * L0, Ad = 2 * 1.125 / std::sqrt(3.0) * An;  // nu = 0.25
    for (std::size_t f = 0; f < lat.families.size(); ++f) {
        const BarFamily& fam = lat.families[f];
        int axis = -1;
        for (int a = 0; a < 3; ++a)
            if (std::abs(fam.d0[a]) > 0.5 * L0) axis = a;
        switch (fam.kind) {
            case BarKind::Edge:
                ++edgeFam;
                ASSERT_GE(axis, 0);
                EXPECT_EQ(perFamily[f], c.edge[axis]);
                EXPECT_NEAR(fam.L, L0, 1e-15);
                EXPECT_NEAR(fam.EA, kMat.E * An, 1e-9 * kMat.E * An);
                EXPECT_NEAR(fam.Af, kMat.ca * L0 * L0, 1e-18);
                break;
            case BarKind::CentreCentre:
                ++ccFam;
                ASSERT_GE(axis, 0);
                EXPECT_EQ(perFamily[f], c.cc[axis]);
                EXPECT_NEAR(fam.L, L0, 1e-15);
                EXPECT_NEAR(fam.EA, kMat.E * An, 1e-9 * kMat.E * An);
                break;
            case BarKind::Diagonal:
                ++diagFam;
                EXPECT_EQ(perFamily[f], std::int64_t(nx) * ny * nz);
                EXPECT_NEAR(fam.L, std::sqrt(3.0) / 2 * L0, 1e-15);
                EXPECT_NEAR(fam.EA, kMat.E * Ad, 1e-9 * kMat.E * Ad);
                EXPECT_NEAR(fam.Af, kMat.ca * 1.15 * 1.15 * L0 * L0, 1e-18);
                break;
        }
    }
    EXPECT_EQ(edgeFam, 3);
    EXPECT_EQ(ccFam, 3);
    EXPECT_EQ(diagFam, 8);

    // Every stored bar is one of the enumerated bars, none twice, its reference
    // vector is its family's d0, and its share is k/4 of the modules sharing it.
    std::set<Pair> seen;
    for (std::int64_t b = 0; b < lat.numBars(); ++b) {
        const auto i = lat.n1[b], j = lat.n2[b];
        const Pair p = unordered(i, j);
        ASSERT_TRUE(seen.insert(p).second) << "bar " << b << " duplicated";
        const BarFamily& fam = lat.families[lat.family[b]];
        EXPECT_NEAR(lat.x0[j] - lat.x0[i], fam.d0[0], 1e-12);
        EXPECT_NEAR(lat.y0[j] - lat.y0[i], fam.d0[1], 1e-12);
        EXPECT_NEAR(lat.z0[j] - lat.z0[i], fam.d0[2], 1e-12);
        if (fam.kind == BarKind::Edge) {
            const auto it = bf.edgeModules.find(p);
            ASSERT_NE(it, bf.edgeModules.end());
            EXPECT_TRUE(it->second == 1 || it->second == 2 || it->second == 4);
            EXPECT_EQ(lat.share[b], float(it->second) / 4.0f);
            EXPECT_DOUBLE_EQ(lat.barEA(b), fam.EA * it->second / 4.0);
            EXPECT_DOUBLE_EQ(lat.barAf(b), fam.Af * it->second / 4.0);
        } else {
            EXPECT_EQ(lat.share[b], 1.0f);
            EXPECT_TRUE(fam.kind == BarKind::Diagonal ? bf.diagonals.count(p) : bf.centreLinks.count(p));
        }
    }

    // Colours: contiguous ranges covering every bar exactly once, one family
    // each (the scatter reads the family of the first bar), no shared node.
    std::vector<BarRange> colours = lat.colours;
    std::sort(colours.begin(), colours.end(), [](auto& a, auto& b) { return a.begin < b.begin; });
    std::int64_t next = 0;
    for (const BarRange& r : colours) {
        EXPECT_EQ(r.begin, next);
        EXPECT_LT(r.begin, r.end);
        next = r.end;
        std::vector<char> used(lat.numNodes(), 0);
        for (std::int64_t b = r.begin; b < r.end; ++b) {
            EXPECT_EQ(lat.family[b], lat.family[r.begin]);
            EXPECT_FALSE(used[lat.n1[b]]) << "node " << lat.n1[b] << " twice in a colour";
            EXPECT_FALSE(used[lat.n2[b]]) << "node " << lat.n2[b] << " twice in a colour";
            used[lat.n1[b]] = used[lat.n2[b]] = 1;
        }
    }
    EXPECT_EQ(next, lat.numBars());

    // Masses: the whole specimen, rho V.
    double total = 0;
    for (double m : lat.mass) total += m;
    const double V = nx * ny * nz * L0 * L0 * L0;
    EXPECT_NEAR(total, kMat.rho * V, 1e-12 * kMat.rho * V);
}

}  // namespace

TEST(Lattice, ClosedFormCountsOfSmallCubes) {
    // Hand-counted: one module has 8 + 1 nodes, 12 edges, no centre links, 8 diagonals.
    EXPECT_EQ(closedForm(1, 1, 1).nodes, 9);
    EXPECT_EQ(closedForm(1, 1, 1).bars(), 20);
    // 2x2x2: 27 + 8 nodes; 3 x 2 x 9 = 54 edges, 3 x 4 = 12 centre links, 64 diagonals.
    EXPECT_EQ(closedForm(2, 2, 2).nodes, 35);
    EXPECT_EQ(closedForm(2, 2, 2).bars(), 54 + 12 + 64);
    // And the library agrees on these hand counts.
    EXPECT_EQ(expectedNodeCount(2, 2, 2), 35);
    EXPECT_EQ(expectedBarCount(2, 2, 2), 130);
    EXPECT_EQ(expectedBarCount(2, 3, 4), closedForm(2, 3, 4).bars());
}

TEST(Lattice, CountsFamiliesSharesColoursCube1) { checkCountsAndTopology(1, 1, 1); }
TEST(Lattice, CountsFamiliesSharesColoursCube2) { checkCountsAndTopology(2, 2, 2); }
TEST(Lattice, CountsFamiliesSharesColoursCube3) { checkCountsAndTopology(3, 3, 3); }
TEST(Lattice, CountsFamiliesSharesColoursCube5) { checkCountsAndTopology(5, 5, 5); }
TEST(Lattice, CountsFamiliesSharesColoursNonCubic2x3x4) { checkCountsAndTopology(2, 3, 4); }

TEST(Lattice, EdgeSharesOfVerticalColumnsInA3Cube) {
    const Lattice lat = buildCubicLattice(3, 3, 3, 0.02, kMat);
    // Vertical edge bars on lattice line (i, j), all heights k.
    auto shareOfColumn = [&](int i, int j) {
        std::vector<float> s;
        for (std::int64_t b = 0; b < lat.numBars(); ++b) {
            const BarFamily& fam = lat.families[lat.family[b]];
            if (fam.kind != BarKind::Edge || fam.d0[2] == 0) continue;
            for (int k = 0; k < 3; ++k)
                if (lat.n1[b] == lat.cornerId(i, j, k) && lat.n2[b] == lat.cornerId(i, j, k + 1))
                    s.push_back(lat.share[b]);
        }
        return s;
    };
    for (auto [i, j] : {std::pair{0, 0}, std::pair{3, 0}, std::pair{0, 3}, std::pair{3, 3}}) {
        const auto s = shareOfColumn(i, j);  // the 4 vertical edges of the cube: 1 module
        ASSERT_EQ(s.size(), 3u);
        for (float v : s) EXPECT_EQ(v, 0.25f);
    }
    for (auto [i, j] : {std::pair{1, 0}, std::pair{0, 2}, std::pair{3, 1}, std::pair{2, 3}}) {
        const auto s = shareOfColumn(i, j);  // on a face, not an edge: 2 modules
        ASSERT_EQ(s.size(), 3u);
        for (float v : s) EXPECT_EQ(v, 0.5f);
    }
    for (auto [i, j] : {std::pair{1, 1}, std::pair{2, 1}, std::pair{1, 2}, std::pair{2, 2}}) {
        const auto s = shareOfColumn(i, j);  // interior: 4 modules
        ASSERT_EQ(s.size(), 3u);
        for (float v : s) EXPECT_EQ(v, 1.0f);
    }
}

TEST(Lattice, NodeMassesAndPositions) {
    const double L0 = 0.02;
    const Lattice lat = buildCubicLattice(3, 3, 3, L0, kMat);
    const double mm = kMat.rho * L0 * L0 * L0;                          // mass of a module
    EXPECT_NEAR(lat.mass[lat.cornerId(1, 1, 1)], mm / 2, 1e-12 * mm);   // interior corner: 8 x 1/16
    EXPECT_NEAR(lat.mass[lat.centreId(1, 1, 1)], mm / 2, 1e-12 * mm);   // centre: 1/2
    EXPECT_NEAR(lat.mass[lat.centreId(0, 0, 0)], mm / 2, 1e-12 * mm);   // every centre
    EXPECT_NEAR(lat.mass[lat.cornerId(0, 0, 0)], mm / 16, 1e-12 * mm);  // cube corner: 1 module
    EXPECT_NEAR(lat.mass[lat.cornerId(3, 3, 3)], mm / 16, 1e-12 * mm);
    EXPECT_NEAR(lat.mass[lat.cornerId(1, 0, 0)], mm / 8, 1e-12 * mm);  // on a cube edge: 2 modules
    EXPECT_NEAR(lat.mass[lat.cornerId(1, 2, 0)], mm / 4, 1e-12 * mm);  // on a face: 4 modules
    // Positions: corners on the L0 grid, centres in the middle of their module.
    EXPECT_DOUBLE_EQ(lat.x0[lat.cornerId(3, 1, 2)], 3 * L0);
    EXPECT_DOUBLE_EQ(lat.y0[lat.cornerId(3, 1, 2)], 1 * L0);
    EXPECT_DOUBLE_EQ(lat.z0[lat.cornerId(3, 1, 2)], 2 * L0);
    EXPECT_DOUBLE_EQ(lat.x0[lat.centreId(2, 0, 1)], 2.5 * L0);
    EXPECT_DOUBLE_EQ(lat.y0[lat.centreId(2, 0, 1)], 0.5 * L0);
    EXPECT_DOUBLE_EQ(lat.z0[lat.centreId(2, 0, 1)], 1.5 * L0);
}

TEST(Lattice, RejectsBadInput) {
    EXPECT_THROW(buildCubicLattice(0, 2, 2, 0.02, kMat), std::invalid_argument);
    EXPECT_THROW(buildCubicLattice(2, 2, 2, 0.0, kMat), std::invalid_argument);
    Material bad;
    bad.nu = 0.5;
    EXPECT_THROW(buildCubicLattice(2, 2, 2, 0.02, bad), std::invalid_argument);
}
