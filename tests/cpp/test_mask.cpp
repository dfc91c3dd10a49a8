// A lattice clipped by a module mask (buildLattice): a full mask is the box
// itself, field for field; a block of modules inside a larger masked box is
// the box of that block, shifted (bars, masses, stiffness, frequencies);
// every bar of an irregular mask reaches both its ends exactly once, and its
// share is the k/4 of the present modules around it, counted here by walking
// the modules.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <tuple>
#include <utility>
#include <vector>

#include "ldem/InternalForces.hpp"
#include "ldem/Lattice.hpp"
#include "ldem/Modal.hpp"

using namespace ldem;

namespace {

const Material kMat{};
constexpr double kL0 = 0.02;

std::vector<std::uint8_t> fullMask(int nx, int ny, int nz) { return std::vector<std::uint8_t>(nx * ny * nz, 1); }

// Modules [i0, i1) x [j0, j1) x [k0, k1) of an nx x ny x nz mask.
std::vector<std::uint8_t> blockMask(int nx, int ny, int nz, std::array<int, 6> b) {
    std::vector<std::uint8_t> mask(nx * ny * nz, 0);
    for (int k = b[4]; k < b[5]; ++k)
        for (int j = b[2]; j < b[3]; ++j)
            for (int i = b[0]; i < b[1]; ++i) mask[i + nx * (j + ny * k)] = 1;
    return mask;
}

// A node's position in units of L0/2, shifted by (si, sj, sk) modules.
using Grid = std::array<long, 3>;
Grid gridOf(const Lattice& lat, std::int32_t node, std::array<int, 3> shift = {0, 0, 0}) {
    const auto x = lat.position(node);
    Grid g;
    for (int d = 0; d < 3; ++d) g[d] = std::lround(2 * x[d] / lat.L0) - 2 * shift[d];
    return g;
}

void expectSameLattice(const Lattice& a, const Lattice& b) {
    EXPECT_EQ(a.mass, b.mass);
    EXPECT_EQ(a.invMass, b.invMass);
    EXPECT_EQ(a.barLayerStart, b.barLayerStart);
    EXPECT_EQ(a.nodeLayerStart, b.nodeLayerStart);
    EXPECT_EQ(a.maxBarsInLayer, b.maxBarsInLayer);
    EXPECT_EQ(a.numBars(), b.numBars());
    ASSERT_EQ(a.barRows.size(), b.barRows.size());
    for (std::size_t r = 0; r < a.barRows.size(); ++r) {
        const BarRow &x = a.barRows[r], &y = b.barRows[r];
        EXPECT_EQ(std::tie(x.first, x.inLayer, x.nodeA, x.nodeB, x.count, x.family, x.share, x.endShare),
                  std::tie(y.first, y.inLayer, y.nodeA, y.nodeB, y.count, y.family, y.share, y.endShare))
            << "bar row " << r;
    }
    ASSERT_EQ(a.nodeRows.size(), b.nodeRows.size());
    for (std::size_t r = 0; r < a.nodeRows.size(); ++r) {
        const NodeRow &x = a.nodeRows[r], &y = b.nodeRows[r];
        EXPECT_EQ(x.first, y.first);
        EXPECT_EQ(x.count, y.count);
        ASSERT_EQ(x.incidences.size(), y.incidences.size()) << "node row " << r;
        for (std::size_t i = 0; i < x.incidences.size(); ++i) {
            const Incidence &p = x.incidences[i], &q = y.incidences[i];
            EXPECT_EQ(std::tie(p.layer, p.inLayerAtZero, p.begin, p.end, p.sign),
                      std::tie(q.layer, q.inLayerAtZero, q.begin, q.end, q.sign))
                << "node row " << r << " incidence " << i;
        }
    }
    const BarTable s = listBars(a), t = listBars(b);
    EXPECT_EQ(s.n1, t.n1);
    EXPECT_EQ(s.n2, t.n2);
    EXPECT_EQ(s.family, t.family);
    EXPECT_EQ(s.share, t.share);
    EXPECT_EQ(s.EA, t.EA);
    EXPECT_EQ(s.Af, t.Af);
    EXPECT_EQ(s.L, t.L);
}

// Structure of the rows and incidences, and every bar against a walk over
// the present modules:
//   - bars numbered without holes, layer by layer, row after row (inLayer,
//     barLayerStart, maxBarsInLayer consistent);
//   - every bar once at its A end with sign +1 and once at its B end with -1,
//     a node's incidences in family order (the order of the full box);
//   - the bars are those of the present modules: an edge bar with share k/4
//     (k = present modules around it, >= 1), a centre link iff both its
//     modules are present, a diagonal iff its module is; masses rho L0^3
//     shared 1/2 and 8 x 1/16, invMass 0 on nodes of no present module.
void checkMaskedLattice(const Lattice& lat) {
    const BarTable t = listBars(lat);
    const std::int64_t nb = lat.numBars();
    const int layers = lat.numLayers();
    ASSERT_EQ(lat.barLayerStart.back(), std::int32_t(lat.barRows.size()));
    std::vector<std::int64_t> layerFirst(layers + 1);
    std::int64_t next = 0, maxInLayer = 0;
    for (int m = 0; m < layers; ++m) {
        layerFirst[m] = next;
        for (std::int32_t r = lat.barLayerStart[m]; r < lat.barLayerStart[m + 1]; ++r) {
            const BarRow& row = lat.barRows[r];
            ASSERT_EQ(row.first, next) << "bar row " << r;
            ASSERT_GT(row.count, 0);
            ASSERT_EQ(row.inLayer, next - layerFirst[m]);
            for (int p = 0; p < row.count; ++p) {
                const auto a = lat.position(row.nodeA + p), b = lat.position(row.nodeB + p);
                EXPECT_EQ(std::lround(2 * std::min(a[2], b[2]) / lat.L0), m) << "bar " << row.first + p;
            }
            next += row.count;
        }
        maxInLayer = std::max(maxInLayer, next - layerFirst[m]);
    }
    layerFirst[layers] = next;
    ASSERT_EQ(next, nb);
    EXPECT_EQ(lat.maxBarsInLayer, maxInLayer);

    // Incidences: (bar, sign) met by each node, in incidence order.
    std::vector<std::vector<std::pair<std::int64_t, double>>> found(lat.numNodes());
    for (const NodeRow& row : lat.nodeRows)
        for (const Incidence& in : row.incidences) {
            ASSERT_LE(0, in.begin);
            ASSERT_LT(in.begin, in.end);
            ASSERT_LE(in.end, row.count);
            for (int i = in.begin; i < in.end; ++i) {
                const std::int64_t b = layerFirst[in.layer] + in.inLayerAtZero + i;
                ASSERT_GE(b, layerFirst[in.layer]);
                ASSERT_LT(b, layerFirst[in.layer + 1]);
                found[row.first + i].push_back({b, in.sign});
            }
        }
    std::vector<int> atA(nb, 0), atB(nb, 0);
    for (std::int32_t n = 0; n < lat.numNodes(); ++n) {
        int lastFamily = -1;
        for (const auto& [b, sign] : found[n]) {
            EXPECT_EQ(sign > 0 ? t.n1[b] : t.n2[b], n) << "bar " << b << " sign " << sign;
            ++(sign > 0 ? atA : atB)[b];
            EXPECT_LE(lastFamily, int(t.family[b])) << "node " << n << ": incidences out of family order";
            lastFamily = t.family[b];
        }
    }
    for (std::int64_t b = 0; b < nb; ++b) {
        EXPECT_EQ(atA[b], 1) << "bar " << b;
        EXPECT_EQ(atB[b], 1) << "bar " << b;
    }

    // The bars and masses of the present modules, from a walk over them.
    std::map<std::pair<Grid, Grid>, int> edges;  // -> present modules around
    std::map<std::pair<Grid, Grid>, int> others;  // centre links and diagonals: 1
    std::vector<double> mass(lat.numNodes(), 0.0);
    const double mm = kMat.rho * lat.L0 * lat.L0 * lat.L0;
    for (int k = 0; k < lat.nz; ++k)
        for (int j = 0; j < lat.ny; ++j)
            for (int i = 0; i < lat.nx; ++i) {
                if (!lat.present(i, j, k)) continue;
                const std::int32_t c = lat.centreId(i, j, k);
                mass[c] += mm / 2;
                for (int v = 0; v < 8; ++v) {
                    const std::int32_t corner = lat.cornerId(i + (v & 1), j + (v >> 1 & 1), k + (v >> 2));
                    mass[corner] += mm / 16;
                    ++others[{gridOf(lat, c), gridOf(lat, corner)}];
                    for (int d = 0; d < 3; ++d)  // the edge from this corner along +d, if in the module
                        if (!(v >> d & 1)) {
                            const int w = v | (1 << d);
                            const std::int32_t end = lat.cornerId(i + (w & 1), j + (w >> 1 & 1), k + (w >> 2));
                            ++edges[{gridOf(lat, corner), gridOf(lat, end)}];
                        }
                }
                for (int d = 0; d < 3; ++d) {
                    std::array<int, 3> nb3{i, j, k};
                    ++nb3[d];
                    if (lat.present(nb3[0], nb3[1], nb3[2]))
                        ++others[{gridOf(lat, c), gridOf(lat, lat.centreId(nb3[0], nb3[1], nb3[2]))}];
                }
            }
    ASSERT_EQ(std::size_t(nb), edges.size() + others.size());
    for (std::int64_t b = 0; b < nb; ++b) {
        const auto key = std::make_pair(gridOf(lat, t.n1[b]), gridOf(lat, t.n2[b]));
        const BarFamily& fam = lat.families[t.family[b]];
        if (fam.kind == BarKind::Edge) {
            ASSERT_TRUE(edges.count(key)) << "bar " << b;
            EXPECT_EQ(t.share[b], edges[key] / 4.0) << "bar " << b;
            edges[key] = -100;  // seen
        } else {
            ASSERT_EQ(others[key], 1) << "bar " << b;
            EXPECT_EQ(t.share[b], 1.0);
            others[key] = -100;
        }
    }
    for (std::int32_t n = 0; n < lat.numNodes(); ++n) {
        EXPECT_NEAR(lat.mass[n], mass[n], 1e-12 * mm) << "node " << n;
        EXPECT_EQ(lat.invMass[n], mass[n] > 0 ? 1.0 / lat.mass[n] : 0.0) << "node " << n;
    }
}

}  // namespace

TEST(ModuleMask, FullMaskIsTheBox) {
    for (const auto& [nx, ny, nz] : {std::array<int, 3>{1, 1, 1}, {2, 3, 4}, {5, 4, 3}, {1, 3, 2}, {2, 1, 1}}) {
        SCOPED_TRACE(testing::Message() << nx << "x" << ny << "x" << nz);
        const Lattice box = buildCubicLattice(nx, ny, nz, kL0, kMat);
        expectSameLattice(buildLattice(nx, ny, nz, kL0, kMat, fullMask(nx, ny, nz)), box);
        expectSameLattice(buildLattice(nx, ny, nz, kL0, kMat, {}), box);
        // One BarRow per row of a family, as the hot loop wants.
        std::size_t rows = 0;
        for (const BarFamily& fam : box.families)
            if (fam.box[0] > 0) rows += std::size_t(fam.box[1]) * fam.box[2];
        EXPECT_EQ(box.barRows.size(), rows);
    }
}

// Modules 1..3 x 1..2 x 0..3 of a 5 x 4 x 4 box: the 3 x 2 x 4 box, shifted.
TEST(ModuleMask, ClippedBlockIsTheBox) {
    const Lattice box = buildCubicLattice(3, 2, 4, kL0, kMat);
    const Lattice lat = buildLattice(5, 4, 4, kL0, kMat, blockMask(5, 4, 4, {1, 4, 1, 3, 0, 4}));
    const std::array<int, 3> shift{1, 1, 0};
    checkMaskedLattice(lat);

    using Bar = std::tuple<Grid, Grid, double, double, double>;
    auto bars = [](const Lattice& l, std::array<int, 3> s) {
        const BarTable t = listBars(l);
        std::vector<Bar> out;
        for (std::size_t b = 0; b < t.n1.size(); ++b)
            out.emplace_back(gridOf(l, t.n1[b], s), gridOf(l, t.n2[b], s), t.EA[b], t.Af[b], t.L[b]);
        std::sort(out.begin(), out.end());
        return out;
    };
    EXPECT_EQ(bars(lat, shift), bars(box, {0, 0, 0}));

    // Masses: the box's at the same place, 0 (and invMass 0) elsewhere.
    std::map<Grid, std::int32_t> boxNode;
    for (std::int32_t n = 0; n < box.numNodes(); ++n) boxNode[gridOf(box, n)] = n;
    int matched = 0;
    for (std::int32_t n = 0; n < lat.numNodes(); ++n) {
        const auto it = boxNode.find(gridOf(lat, n, shift));
        if (it == boxNode.end()) {
            EXPECT_EQ(lat.mass[n], 0.0) << "node " << n;
            EXPECT_EQ(lat.invMass[n], 0.0) << "node " << n;
            continue;
        }
        ++matched;
        EXPECT_EQ(lat.mass[n], box.mass[it->second]) << "node " << n;
        EXPECT_EQ(lat.invMass[n], box.invMass[it->second]) << "node " << n;
    }
    EXPECT_EQ(matched, box.numNodes());
}

TEST(ModuleMask, IncidencesAndSharesOfIrregularMasks) {
    {
        SCOPED_TRACE("L shape");
        const int nx = 4, ny = 3, nz = 4;
        std::vector<std::uint8_t> mask(nx * ny * nz, 0);
        for (int k = 0; k < nz; ++k)
            for (int j = 0; j < ny; ++j)
                for (int i = 0; i < nx; ++i) mask[i + nx * (j + ny * k)] = k < 2 || i < 2;
        checkMaskedLattice(buildLattice(nx, ny, nz, kL0, kMat, mask));
    }
    for (unsigned seed : {1u, 2u, 3u}) {
        SCOPED_TRACE(testing::Message() << "random mask, seed " << seed);
        const int nx = 6, ny = 4, nz = 5;
        std::mt19937 rng(seed);
        std::vector<std::uint8_t> mask(nx * ny * nz);
        for (auto& v : mask) v = rng() % 3 != 0;
        checkMaskedLattice(buildLattice(nx, ny, nz, kL0, kMat, mask));
    }
    {
        SCOPED_TRACE("single module in a 3 x 3 x 3 box");
        checkMaskedLattice(buildLattice(3, 3, 3, kL0, kMat, blockMask(3, 3, 3, {1, 2, 1, 2, 1, 2})));
    }
}

TEST(ModuleMask, RejectsBadMasks) {
    EXPECT_THROW(buildLattice(2, 2, 2, kL0, kMat, std::vector<std::uint8_t>(7, 1)), std::invalid_argument);
    EXPECT_THROW(buildLattice(2, 2, 2, kL0, kMat, std::vector<std::uint8_t>(8, 0)), std::invalid_argument);
}

// Clipping changes no stiffness: under u_z = eps z on every node, the block's
// K u equals the box's node by node, and is zero on nodes of no present module.
TEST(ModuleMask, ClippedBlockHasTheStiffnessOfTheBox) {
    const Lattice box = buildCubicLattice(3, 2, 4, kL0, kMat);
    const Lattice lat = buildLattice(5, 4, 4, kL0, kMat, blockMask(5, 4, 4, {1, 4, 1, 3, 0, 4}));
    const std::array<int, 3> shift{1, 1, 0};
    const double eps = 1e-4;
    auto stiffness = [eps](const Lattice& l) {
        Field3 u(l.numNodes()), f(l.numNodes());
        for (std::int32_t n = 0; n < l.numNodes(); ++n) u.z[n] = eps * l.position(n)[2];
        BarForceBuffers g;
        linearStiffnessProduct(l, u, g, f);
        return f;
    };
    const Field3 fb = stiffness(box), fl = stiffness(lat);
    std::map<Grid, std::int32_t> boxNode;
    for (std::int32_t n = 0; n < box.numNodes(); ++n) boxNode[gridOf(box, n)] = n;
    double scale = 0;
    for (double v : fb.z) scale = std::max(scale, std::abs(v));
    ASSERT_GT(scale, 0);
    for (std::int32_t n = 0; n < lat.numNodes(); ++n) {
        const auto it = boxNode.find(gridOf(lat, n, shift));
        if (it == boxNode.end()) {
            EXPECT_EQ(fl.x[n], 0.0) << "node " << n;
            EXPECT_EQ(fl.y[n], 0.0) << "node " << n;
            EXPECT_EQ(fl.z[n], 0.0) << "node " << n;
            continue;
        }
        const std::int32_t m = it->second;
        EXPECT_NEAR(fl.x[n], fb.x[m], 1e-12 * scale) << "node " << n;
        EXPECT_NEAR(fl.y[n], fb.y[m], 1e-12 * scale) << "node " << n;
        EXPECT_NEAR(fl.z[n], fb.z[m], 1e-12 * scale) << "node " << n;
    }
}

// Nodes of mass 0 are no degrees of freedom of the modal problem: the block
// has the frequencies of the box (both on a fixed base z = 0).
TEST(ModuleMask, ClippedBlockHasTheFrequenciesOfTheBox) {
    const Lattice box = buildCubicLattice(3, 2, 4, kL0, kMat);
    const Lattice lat = buildLattice(5, 4, 4, kL0, kMat, blockMask(5, 4, 4, {1, 4, 1, 3, 0, 4}));
    auto frequencies = [](const Lattice& l) {
        std::vector<std::uint8_t> held(l.numNodes(), 0);
        for (std::int32_t n = 0; n < l.numNodes(); ++n) held[n] = l.position(n)[2] == 0.0 ? 7 : 0;
        return latticeFrequencies(l, held, 20000, 1e-8);
    };
    const Frequencies a = frequencies(lat), b = frequencies(box);
    EXPECT_GT(b.omega1, 0.0);
    EXPECT_NEAR(a.omega1, b.omega1, 1e-6 * b.omega1);
    EXPECT_NEAR(a.omegaMax, b.omegaMax, 1e-6 * b.omegaMax);
}
