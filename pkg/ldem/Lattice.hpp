// The cubic lattice with centre nodes (LDEM_SPEC section 1).
//
// Nodes: (nx+1)(ny+1)(nz+1) corner nodes (id = i + (nx+1)(j + (ny+1)k)), then
// nx ny nz centre nodes. Node ids grow by one along x, so a row of nodes is a
// contiguous range.
//
// Bars are never listed: the lattice is regular, so they form 14 families
// (3 edge directions, 3 centre-centre directions, 8 diagonals), each a box of
// bars indexed (p, q, r) that joins node A = (p, q, r) of one kind to node
// B = (p, q, r) + offset of another. A row of bars (fixed q, r) joins two
// contiguous rows of nodes, so the hot loops stream through plain arrays
// with no index arrays at all (see InternalForces).
//
// Layers: node layer m = 2k is the corner plane z = k L0, m = 2k+1 the centre
// plane z = (k + 1/2) L0. A bar belongs to the lower layer of its two ends.
// Rows are stored layer by layer, and bars are numbered in that order, so the
// bars of a few consecutive layers are close together in memory.
//
// Module mask: a lattice may keep only some modules of its nx x ny x nz box
// (a notched or non-prismatic specimen). Node ids stay those of the box, so
// positions and ids still follow from (i, j, k); nodes of no present module
// get mass 0 and no bars. A family's row then becomes one or more BarRows
// (segments), one per run of bars that exist and whose shares fit the row's
// (share, endShare) pattern; a full box keeps one BarRow per row.
//
// Slabs (MPI, Slab.hpp): a process may hold only the module layers
// [k0, k1) of an nz-layer lattice and one halo module layer on each side.
// Such a lattice is the box of its modules (nz = its own layers, ids and
// layers local), placed at global module layer kOffset; the mask, the shares
// and the random field see the whole lattice (globalNode, position), so every
// bar it owns is the bar of the whole lattice, bit for bit.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "ldem/Interrupt.hpp"
#include "ldem/Material.hpp"

namespace ldem {

enum class BarKind : unsigned char { Edge = 0, CentreCentre = 1, Diagonal = 2 };
enum class NodeKind : unsigned char { Corner = 0, Centre = 1 };

struct BarFamily {
    BarKind kind;
    NodeKind kindA, kindB;
    std::array<int, 3> offsetB;  // B = A's box index + offsetB, in B's node grid
    std::array<int, 3> box;      // number of bars along x, y, z
    int axis;                    // edge families: the bar's direction (0, 1, 2); else -1
    std::array<double, 3> d0;    // reference vector A -> B [m]
    double L;                    // initial length [m]
    double invL, invL2;          // 1/L, 1/L^2 (the elastic fast path: laws/BarLaw.hpp)
    double EA;                   // axial stiffness of a full (interior) bar [N]
    double Af;                   // fracture area of a full bar [m^2]
};

// A row of bars of one family (or, in a masked lattice, a segment of one):
// bars first .. first+count-1 join nodes nodeA+p and nodeB+p (p = 0 .. count-1).
struct BarRow {
    std::int64_t first;
    std::int32_t inLayer;  // first - (number of the first bar of the row's layer)
    std::int32_t nodeA, nodeB, count;
    std::uint8_t family;
    double share;     // k/4 of the row's bars (edge bars on the surface), 1 otherwise
    double endShare;  // share of the row's first and last bar (surface edges along x ends)
    double shareAt(int p) const { return (p == 0 || p == count - 1) ? endShare : share; }
};

// The bars meeting a row of nodes from one family: node first+i (i in [begin, end))
// is end A (sign +1) or end B (sign -1) of the bar numbered inLayerAtZero + i
// within bar layer `layer`.
struct Incidence {
    std::int32_t layer, inLayerAtZero, begin, end;
    double sign;
};

struct NodeRow {
    std::int32_t first, count;
    std::vector<Incidence> incidences;  // in a fixed order: the summation order of a node's bars
    // The nodes [bulkBegin, bulkEnd) meet a bar of every incidence (all but the
    // row's end nodes, in a full box); empty if the row's segments leave no such node.
    std::int32_t bulkBegin = 0, bulkEnd = 0;
};

struct Lattice {
    int nx = 0, ny = 0, nz = 0;
    double L0 = 0.0;
    std::vector<double> mass;     // lumped masses [kg]
    std::vector<double> invMass;  // 1 / mass, for the integrator
    std::vector<BarFamily> families;
    std::vector<BarRow> barRows;    // by layer; bar numbers increase along them
    std::vector<NodeRow> nodeRows;  // by layer
    std::vector<std::int32_t> barLayerStart, nodeLayerStart;  // rows of layer m: [start[m], start[m+1])
    std::int32_t maxBarsInLayer = 0;
    std::vector<std::uint8_t> moduleMask;  // module (i, j, k) at i + nx (j + ny k), nonzero = present; empty = all
                                           // (of the whole lattice: k global)
    int kOffset = 0;  // global module layer of local layer k = 0 (0 unless a slab)
    int nzTotal = 0;  // module layers of the whole lattice (nz unless a slab)
    int ownBegin = 0, ownEnd = 0;  // the node and bar layers this process owns: computes, reports, sums

    // Whether module (i, j, k) of this box (k local) is present in the whole lattice.
    bool present(int i, int j, int k) const {
        k += kOffset;
        if (i < 0 || i >= nx || j < 0 || j >= ny || k < 0 || k >= nzTotal) return false;
        return moduleMask.empty() || moduleMask[i + std::size_t(nx) * (j + std::size_t(ny) * k)] != 0;
    }
    bool owns(int layer) const { return layer >= ownBegin && layer < ownEnd; }
    // The layers the force pass covers, [0, forceLayers()): the owned ones and
    // the halo below, whose bars reach the owned nodes (the halo above is its owner's).
    int forceLayers() const { return ownEnd; }
    bool isSlab() const { return ownBegin > 0 || ownEnd < numLayers(); }  // a part of a lattice split over ranks
    // Node id in the whole lattice of local node n, and back (-1: not in this box).
    std::int64_t globalNode(std::int32_t n) const;
    std::int32_t localNode(std::int64_t global) const;
    // Node layer (local) of node n: 2k for corners of plane k, 2k + 1 for centres.
    int layerOfNode(std::int32_t n) const {
        return n < numCorners() ? 2 * (n / ((nx + 1) * (ny + 1))) : 2 * ((n - numCorners()) / (nx * ny)) + 1;
    }
    // Nodes of layer m: the contiguous ids [first, first + count).
    std::pair<std::int32_t, std::int32_t> layerNodes(int m) const {
        return m % 2 ? std::pair{centreId(0, 0, m / 2), nx * ny} : std::pair{cornerId(0, 0, m / 2), (nx + 1) * (ny + 1)};
    }
    // The bars of the owned layers: [first, end) (bars are numbered layer by layer).
    std::pair<std::int64_t, std::int64_t> ownedBars() const;

    std::int64_t numNodes() const { return std::int64_t(mass.size()); }
    std::int64_t numBars() const { return barRows.back().first + barRows.back().count; }
    int numLayers() const { return 2 * nz + 1; }
    std::int32_t numCorners() const { return (nx + 1) * (ny + 1) * (nz + 1); }
    std::int32_t cornerId(int i, int j, int k) const { return i + (nx + 1) * (j + (ny + 1) * k); }
    std::int32_t centreId(int i, int j, int k) const { return numCorners() + i + nx * (j + ny * k); }
    std::int32_t nodeId(NodeKind kind, int i, int j, int k) const {
        return kind == NodeKind::Corner ? cornerId(i, j, k) : centreId(i, j, k);
    }
    std::array<double, 3> position(std::int32_t node) const;  // reference position in the whole lattice [m]

    // Per-bar query (not for hot loops): the row of a bar.
    const BarRow& rowOf(std::int64_t bar) const;
};

// Calls fn(bar, nodeA, nodeB, row, p) for every bar (p: position in its row),
// rows split between threads, hearing signals (interruptibleFor: fn must
// write only bar's own elements).
template <class Fn>
void forEachBar(const Lattice& lat, Fn fn) {
    interruptibleFor(0, std::int64_t(lat.barRows.size()), [&](std::int64_t r) {
        const BarRow& row = lat.barRows[r];
        for (int p = 0; p < row.count; ++p) fn(row.first + p, row.nodeA + p, row.nodeB + p, row, p);
    });
}

// Every bar listed explicitly, by bar number: for output, tests and the YADE
// bridge (the hot loops never use it).
struct BarTable {
    std::vector<std::int32_t> n1, n2;  // nodes A and B
    std::vector<std::uint8_t> family;
    std::vector<double> share, EA, Af, L;  // share k/4 (or 1), stiffness [N], fracture area [m^2], length [m]
};
BarTable listBars(const Lattice& lat);

// Reference coordinates of every node [m].
std::array<std::vector<double>, 3> nodePositions(const Lattice& lat);

// Node and bar counts of an nx x ny x nz lattice (spec section 1); for a
// masked lattice, the bar count is an upper bound.
std::int64_t expectedNodeCount(int nx, int ny, int nz);
std::int64_t expectedBarCount(int nx, int ny, int nz);
// Memory a run of such a lattice takes: ldem-bench's peak resident size per bar
// is 63 B at 24^3 and 38 B at 48^3 (lattice, state, Lanczos); with a margin.
constexpr std::int64_t kBytesPerBar = 100;
std::int64_t memoryEstimate(int nx, int ny, int nz);
// The memory a lattice must fit: the smallest of the machine's available
// memory, the cgroup's limit less its usage and the address-space limit
// (ulimit -v) less the process's size; bytes 0 if unknown.
struct MemoryLimit {
    double bytes;
    const char* what;  // which: "this machine has available", "the address-space limit (ulimit -v) leaves", ...
};
MemoryLimit memoryLimit();
// Why the slab of module layers [k0, k1) of an nx x ny x nz lattice (its box:
// with a halo layer each side) does not fit one process of memory `have`:
// its estimate above it, or, only when it fits, node ids past 32 bits (then
// MPI ranks on this machine could hold it); "" if it fits.
std::string latticeMisfit(int nx, int ny, int nz, int k0, int k1, const MemoryLimit& have);
// Throws std::invalid_argument with latticeMisfit's message: every builder
// calls it before anything is allocated (buildSlab; a specimen file's shape).
void checkFits(int nx, int ny, int nz, int k0, int k1);

// Builds the lattice of nx x ny x nz modules of side L0 with the bar areas of
// the Nayfeh-Hefzy equivalence for material m and lumped masses rho L0^3
// (half to the centre node, 1/16 to each corner).
Lattice buildCubicLattice(int nx, int ny, int nz, double L0, const Material& m);

// The same lattice clipped to the modules of moduleMask (nx ny nz entries,
// module (i, j, k) at i + nx (j + ny k), nonzero = present; empty = all present).
// A present module brings its mass, its 8 diagonals and its share of the
// edges: an edge bar exists if a module around it is present and carries k/4
// of a full bar, k = present modules around it; a centre-centre bar exists if
// both its modules are present. Nodes of no present module keep their id but
// have mass 0, invMass 0 and no bars. A full mask gives buildCubicLattice's
// lattice, bar numbers included.
Lattice buildLattice(int nx, int ny, int nz, double L0, const Material& m,
                     const std::vector<std::uint8_t>& moduleMask);

// The slab of that lattice that owns module layers [k0, k1), with one halo
// module layer below and above (where the lattice has them): owned bars and
// owned nodes' masses are those of the whole lattice; halo nodes are moved by
// their owner (Slab.hpp exchanges them).
Lattice buildSlab(int nx, int ny, int nz, double L0, const Material& m, const std::vector<std::uint8_t>& moduleMask,
                  int k0, int k1);

}  // namespace ldem
