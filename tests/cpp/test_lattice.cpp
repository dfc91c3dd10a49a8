// Lattice geometry (LDEM_SPEC section 1): node and bar counts, families,
// surface shares k/4, lumped masses, and the implicit structure the force loop
// streams through (rows of bars by layer, rows of nodes with their bar
// incidences). Every expectation is derived here from the module picture
// (a brute-force enumeration of the modules' bars and the nodes' reference
// positions), not from the library's own counting helpers.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
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

// Node layer from the reference height: corner plane z = k L0 is layer 2k,
// centre plane z = (k + 1/2) L0 is layer 2k + 1.
int layerOfNode(const std::array<std::vector<double>, 3>& x, std::int32_t node, double L0) {
    return int(std::lround(2 * x[2][node] / L0));
}

// The structure the force loop streams through, checked against the explicit
// bar listing and the node positions:
//   - bar rows partition the bars [0, numBars) into contiguous runs, in bar
//     order, layer by layer (bars belong to the lower layer of their ends);
//   - barLayerStart / inLayer / maxBarsInLayer locate a bar inside its layer;
//   - node rows partition the nodes, layer by layer, each a run along x;
//   - a node's incidences name exactly the bars that touch it, each once, with
//     sign +1 at end A (n1) and -1 at end B (n2), from bar layers m-2 .. m.
// This replaces the old "colours" (bar groups with no shared node): the
// node-wise gather needs no colouring, but it is only correct if every bar
// force reaches both its ends exactly once with the right sign.
void checkRowsAndIncidences(const Lattice& lat, const BarTable& t, const std::array<std::vector<double>, 3>& x) {
    const double L0 = lat.L0;
    const std::int64_t nb = lat.numBars();
    const int layers = lat.numLayers();
    ASSERT_EQ(layers, 2 * lat.nz + 1);
    ASSERT_EQ(lat.barLayerStart.size(), std::size_t(layers + 1));
    ASSERT_EQ(lat.nodeLayerStart.size(), std::size_t(layers + 1));
    EXPECT_EQ(lat.barLayerStart.front(), 0);
    EXPECT_EQ(lat.barLayerStart.back(), std::int32_t(lat.barRows.size()));
    EXPECT_EQ(lat.nodeLayerStart.front(), 0);
    EXPECT_EQ(lat.nodeLayerStart.back(), std::int32_t(lat.nodeRows.size()));

    // Layer of every bar from its end nodes' heights.
    std::vector<int> barLayer(nb);
    for (std::int64_t b = 0; b < nb; ++b)
        barLayer[b] = std::min(layerOfNode(x, t.n1[b], L0), layerOfNode(x, t.n2[b], L0));
    // Bars are numbered layer by layer.
    for (std::int64_t b = 1; b < nb; ++b) ASSERT_LE(barLayer[b - 1], barLayer[b]) << "bar " << b;

    // Bar rows: every bar in exactly one row, rows in bar order, one layer each.
    std::vector<int> rowsOfBar(nb, 0);
    std::vector<std::int64_t> layerFirst(layers + 1, -1), layerCount(layers, 0);
    std::int64_t next = 0;
    for (int m = 0; m < layers; ++m) {
        ASSERT_LE(lat.barLayerStart[m], lat.barLayerStart[m + 1]);
        layerFirst[m] = next;
        for (std::int32_t r = lat.barLayerStart[m]; r < lat.barLayerStart[m + 1]; ++r) {
            const BarRow& row = lat.barRows[r];
            EXPECT_EQ(row.first, next) << "row " << r;
            EXPECT_GT(row.count, 0) << "row " << r;
            EXPECT_EQ(row.inLayer, row.first - layerFirst[m]) << "row " << r;
            ASSERT_LT(row.family, lat.families.size());
            for (int p = 0; p < row.count; ++p) {
                const std::int64_t b = row.first + p;
                ASSERT_LT(b, nb);
                ++rowsOfBar[b];
                EXPECT_EQ(barLayer[b], m) << "bar " << b << " in a row of layer " << m;
                EXPECT_EQ(t.family[b], row.family);
                EXPECT_EQ(t.n1[b], row.nodeA + p);
                EXPECT_EQ(t.n2[b], row.nodeB + p);
                EXPECT_EQ(&lat.rowOf(b), &row) << "bar " << b;
            }
            next += row.count;
        }
        layerCount[m] = next - layerFirst[m];
    }
    layerFirst[layers] = next;
    EXPECT_EQ(next, nb);
    for (std::int64_t b = 0; b < nb; ++b) ASSERT_EQ(rowsOfBar[b], 1) << "bar " << b << " rows";
    // The per-layer force buffers are maxBarsInLayer long.
    EXPECT_EQ(lat.maxBarsInLayer, *std::max_element(layerCount.begin(), layerCount.end()));

    // Expected incidences of every node, from the explicit listing: (bar, sign).
    using Inc = std::pair<std::int64_t, double>;
    std::vector<std::vector<Inc>> expected(lat.numNodes()), found(lat.numNodes());
    for (std::int64_t b = 0; b < nb; ++b)
        expected[t.n1[b]].push_back({b, +1.0}), expected[t.n2[b]].push_back({b, -1.0});

    // Node rows: every node in exactly one row, in the row's layer, a run along x.
    std::vector<int> rowsOfNode(lat.numNodes(), 0);
    for (int m = 0; m < layers; ++m) {
        ASSERT_LE(lat.nodeLayerStart[m], lat.nodeLayerStart[m + 1]);
        for (std::int32_t r = lat.nodeLayerStart[m]; r < lat.nodeLayerStart[m + 1]; ++r) {
            const NodeRow& row = lat.nodeRows[r];
            ASSERT_GT(row.count, 0);
            ASSERT_LE(std::int64_t(row.first) + row.count, lat.numNodes());
            for (int i = 0; i < row.count; ++i) {
                const std::int32_t node = row.first + i;
                ++rowsOfNode[node];
                EXPECT_EQ(layerOfNode(x, node, L0), m) << "node " << node;
                EXPECT_NEAR(x[0][node] - x[0][row.first], i * L0, 1e-12) << "node " << node;
                EXPECT_EQ(x[1][node], x[1][row.first]) << "node " << node;
                EXPECT_EQ(x[2][node], x[2][row.first]) << "node " << node;
            }
            for (const Incidence& in : row.incidences) {
                EXPECT_TRUE(in.sign == 1.0 || in.sign == -1.0);
                // A node layer is summed from the bars of layers m-2 .. m only.
                EXPECT_GE(in.layer, std::max(0, m - 2));
                EXPECT_LE(in.layer, m);
                ASSERT_GE(in.begin, 0);
                ASSERT_LT(in.begin, in.end);
                ASSERT_LE(in.end, row.count);
                for (int i = in.begin; i < in.end; ++i) {
                    const std::int64_t inLayer = std::int64_t(in.inLayerAtZero) + i;
                    ASSERT_GE(inLayer, 0);
                    ASSERT_LT(inLayer, layerCount[in.layer]);
                    found[row.first + i].push_back({layerFirst[in.layer] + inLayer, in.sign});
                }
            }
        }
    }
    for (std::int64_t n = 0; n < lat.numNodes(); ++n) {
        ASSERT_EQ(rowsOfNode[n], 1) << "node " << n << " rows";
        std::sort(expected[n].begin(), expected[n].end());
        std::sort(found[n].begin(), found[n].end());
        ASSERT_EQ(found[n], expected[n]) << "incidences of node " << n;
    }
}

void checkCountsAndTopology(int nx, int ny, int nz) {
    SCOPED_TRACE(testing::Message() << nx << "x" << ny << "x" << nz);
    const double L0 = 0.02;
    const Lattice lat = buildCubicLattice(nx, ny, nz, L0, kMat);
    const Counts c = closedForm(nx, ny, nz);
    ASSERT_EQ(lat.numNodes(), c.nodes);
    ASSERT_EQ(lat.numBars(), c.bars());
    ASSERT_EQ(std::int64_t(lat.mass.size()), lat.numNodes());
    ASSERT_EQ(std::int64_t(lat.invMass.size()), lat.numNodes());
    const BarTable t = listBars(lat);
    const auto x = nodePositions(lat);
    for (const auto* v : {&t.n1, &t.n2}) ASSERT_EQ(std::int64_t(v->size()), lat.numBars());
    ASSERT_EQ(std::int64_t(t.family.size()), lat.numBars());
    for (const auto* v : {&t.share, &t.EA, &t.Af, &t.L}) ASSERT_EQ(std::int64_t(v->size()), lat.numBars());
    for (const auto& v : x) ASSERT_EQ(std::int64_t(v.size()), lat.numNodes());

    // Brute-force enumeration must give the same numbers as the closed form.
    const BruteForce bf = enumerateModules(lat);
    EXPECT_EQ(std::int64_t(bf.edgeModules.size()), c.edge[0] + c.edge[1] + c.edge[2]);
    EXPECT_EQ(std::int64_t(bf.centreLinks.size()), c.cc[0] + c.cc[1] + c.cc[2]);
    EXPECT_EQ(std::int64_t(bf.diagonals.size()), c.diag);

    // Per-family counts and the kind/length/area of each family.
    ASSERT_EQ(lat.families.size(), 14u);
    std::vector<std::int64_t> perFamily(lat.families.size(), 0);
    for (auto f : t.family) ++perFamily.at(f);
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
                EXPECT_EQ(fam.axis, axis);
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

    // Every listed bar is one of the enumerated bars, none twice, its reference
    // vector is its family's d0 (and its length the family's L), its ends are
    // of the family's node kinds, and its share is k/4 of the modules sharing it.
    std::set<Pair> seen;
    const std::int32_t nc = lat.numCorners();
    for (std::int64_t b = 0; b < lat.numBars(); ++b) {
        const auto i = t.n1[b], j = t.n2[b];
        ASSERT_GE(i, 0);
        ASSERT_LT(i, lat.numNodes());
        ASSERT_GE(j, 0);
        ASSERT_LT(j, lat.numNodes());
        const Pair p = unordered(i, j);
        ASSERT_TRUE(seen.insert(p).second) << "bar " << b << " duplicated";
        const BarFamily& fam = lat.families[t.family[b]];
        const double d[3] = {x[0][j] - x[0][i], x[1][j] - x[1][i], x[2][j] - x[2][i]};
        EXPECT_NEAR(d[0], fam.d0[0], 1e-12);
        EXPECT_NEAR(d[1], fam.d0[1], 1e-12);
        EXPECT_NEAR(d[2], fam.d0[2], 1e-12);
        EXPECT_NEAR(t.L[b], std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), 1e-15);
        EXPECT_EQ(i < nc, fam.kindA == NodeKind::Corner) << "bar " << b;
        EXPECT_EQ(j < nc, fam.kindB == NodeKind::Corner) << "bar " << b;
        if (fam.kind == BarKind::Edge) {
            const auto it = bf.edgeModules.find(p);
            ASSERT_NE(it, bf.edgeModules.end());
            EXPECT_TRUE(it->second == 1 || it->second == 2 || it->second == 4);
            EXPECT_EQ(t.share[b], it->second / 4.0);
            EXPECT_DOUBLE_EQ(t.EA[b], fam.EA * it->second / 4.0);
            EXPECT_DOUBLE_EQ(t.Af[b], fam.Af * it->second / 4.0);
        } else {
            EXPECT_EQ(t.share[b], 1.0);
            EXPECT_EQ(t.EA[b], fam.EA);
            EXPECT_EQ(t.Af[b], fam.Af);
            EXPECT_TRUE(fam.kind == BarKind::Diagonal ? bf.diagonals.count(p) : bf.centreLinks.count(p));
        }
    }

    // Rows of bars and nodes, layers and incidences (replaces the colours).
    checkRowsAndIncidences(lat, t, x);

    // Masses: the whole specimen, rho V; invMass is their inverse.
    double total = 0;
    for (double m : lat.mass) total += m;
    const double V = nx * ny * nz * L0 * L0 * L0;
    EXPECT_NEAR(total, kMat.rho * V, 1e-12 * kMat.rho * V);
    for (std::int64_t n = 0; n < lat.numNodes(); ++n) EXPECT_EQ(lat.invMass[n], 1.0 / lat.mass[n]);
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

TEST(Lattice, CountsFamiliesSharesRowsCube1) { checkCountsAndTopology(1, 1, 1); }
TEST(Lattice, CountsFamiliesSharesRowsCube2) { checkCountsAndTopology(2, 2, 2); }
TEST(Lattice, CountsFamiliesSharesRowsCube3) { checkCountsAndTopology(3, 3, 3); }
TEST(Lattice, CountsFamiliesSharesRowsCube5) { checkCountsAndTopology(5, 5, 5); }
TEST(Lattice, CountsFamiliesSharesRowsNonCubic2x3x4) { checkCountsAndTopology(2, 3, 4); }
// Shapes where a row of bars along x has a single bar (its share is endShare)
// or where nx differs from ny and nz.
TEST(Lattice, CountsFamiliesSharesRowsThinSlabs) {
    checkCountsAndTopology(1, 3, 2);
    checkCountsAndTopology(4, 1, 1);
    checkCountsAndTopology(2, 1, 3);
}

TEST(Lattice, EdgeSharesOfVerticalColumnsInA3Cube) {
    const Lattice lat = buildCubicLattice(3, 3, 3, 0.02, kMat);
    const BarTable t = listBars(lat);
    // Vertical edge bars on lattice line (i, j), all heights k.
    auto shareOfColumn = [&](int i, int j) {
        std::vector<double> s;
        for (std::int64_t b = 0; b < lat.numBars(); ++b) {
            const BarFamily& fam = lat.families[t.family[b]];
            if (fam.kind != BarKind::Edge || fam.d0[2] == 0) continue;
            for (int k = 0; k < 3; ++k)
                if (t.n1[b] == lat.cornerId(i, j, k) && t.n2[b] == lat.cornerId(i, j, k + 1))
                    s.push_back(t.share[b]);
        }
        return s;
    };
    for (auto [i, j] : {std::pair{0, 0}, std::pair{3, 0}, std::pair{0, 3}, std::pair{3, 3}}) {
        const auto s = shareOfColumn(i, j);  // the 4 vertical edges of the cube: 1 module
        ASSERT_EQ(s.size(), 3u);
        for (double v : s) EXPECT_EQ(v, 0.25);
    }
    for (auto [i, j] : {std::pair{1, 0}, std::pair{0, 2}, std::pair{3, 1}, std::pair{2, 3}}) {
        const auto s = shareOfColumn(i, j);  // on a face, not an edge: 2 modules
        ASSERT_EQ(s.size(), 3u);
        for (double v : s) EXPECT_EQ(v, 0.5);
    }
    for (auto [i, j] : {std::pair{1, 1}, std::pair{2, 1}, std::pair{1, 2}, std::pair{2, 2}}) {
        const auto s = shareOfColumn(i, j);  // interior: 4 modules
        ASSERT_EQ(s.size(), 3u);
        for (double v : s) EXPECT_EQ(v, 1.0);
    }
}

// Direct check (run first by tests/mutation/run.py): the lumped mass of every
// node of a 3 x 2 x 4 box, by its kind. A module of mass m = rho L0^3 gives
// half to its centre node and 1/16 to each of its 8 corners, so a corner node
// touched by c modules has c m/16: c = 1 at a box corner, 2 on a box edge, 4
// on a face, 8 inside; every centre node has m/2; the total is rho V.
// Exact to round-off (1e-14 relative).
TEST(DirectLattice, LumpedMassOfEveryNodeKind) {
    const double L0 = 0.02;
    const int nx = 3, ny = 2, nz = 4;
    const Lattice lat = buildCubicLattice(nx, ny, nz, L0, kMat);
    const double mm = kMat.rho * L0 * L0 * L0;
    auto inside = [](int i, int n) { return i > 0 && i < n; };  // not on the box's boundary along that axis
    std::map<int, int> kinds;  // modules touching a corner node -> how many such nodes
    for (int k = 0; k <= nz; ++k)
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i) {
                const int c = (inside(i, nx) ? 2 : 1) * (inside(j, ny) ? 2 : 1) * (inside(k, nz) ? 2 : 1);
                ++kinds[c];
                EXPECT_NEAR(lat.mass[lat.cornerId(i, j, k)], c * mm / 16, 1e-14 * mm) << i << j << k;
            }
    EXPECT_EQ(kinds, (std::map<int, int>{{1, 8}, {2, 4 * (nx - 1 + ny - 1 + nz - 1)},
                                         {4, 2 * ((nx - 1) * (ny - 1) + (ny - 1) * (nz - 1) + (nz - 1) * (nx - 1))},
                                         {8, (nx - 1) * (ny - 1) * (nz - 1)}}));
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i)
                EXPECT_NEAR(lat.mass[lat.centreId(i, j, k)], mm / 2, 1e-14 * mm) << i << j << k;
    double total = 0;
    for (double x : lat.mass) total += x;
    EXPECT_NEAR(total, nx * ny * nz * mm, 1e-13 * nx * ny * nz * mm);
}

TEST(Lattice, NodePositions) {
    const double L0 = 0.02;
    const Lattice lat = buildCubicLattice(3, 3, 3, L0, kMat);
    // Positions: corners on the L0 grid, centres in the middle of their module.
    const auto x = nodePositions(lat);
    EXPECT_DOUBLE_EQ(x[0][lat.cornerId(3, 1, 2)], 3 * L0);
    EXPECT_DOUBLE_EQ(x[1][lat.cornerId(3, 1, 2)], 1 * L0);
    EXPECT_DOUBLE_EQ(x[2][lat.cornerId(3, 1, 2)], 2 * L0);
    EXPECT_DOUBLE_EQ(x[0][lat.centreId(2, 0, 1)], 2.5 * L0);
    EXPECT_DOUBLE_EQ(x[1][lat.centreId(2, 0, 1)], 0.5 * L0);
    EXPECT_DOUBLE_EQ(x[2][lat.centreId(2, 0, 1)], 1.5 * L0);
    // And lat.position agrees for every node.
    for (std::int32_t n = 0; n < lat.numNodes(); ++n) {
        const auto p = lat.position(n);
        EXPECT_EQ(p[0], x[0][n]);
        EXPECT_EQ(p[1], x[1][n]);
        EXPECT_EQ(p[2], x[2][n]);
    }
}

TEST(Lattice, RejectsBadInput) {
    EXPECT_THROW(buildCubicLattice(0, 2, 2, 0.02, kMat), std::invalid_argument);
    EXPECT_THROW(buildCubicLattice(2, 2, 2, 0.0, kMat), std::invalid_argument);
    Material bad;
    bad.nu = 0.5;
    EXPECT_THROW(buildCubicLattice(2, 2, 2, 0.02, bad), std::invalid_argument);
}
