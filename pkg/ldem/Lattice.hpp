// The cubic lattice with centre nodes (LDEM_SPEC section 1).
//
// Nodes: (nx+1)(ny+1)(nz+1) corner nodes, then nx ny nz centre nodes.
// Bars are stored in structure-of-arrays form and grouped into 14 families
// (3 edge directions, 3 centre-centre directions, 8 diagonals); every bar of a
// family has the same reference vector, length, full area and fracture area,
// so only the end nodes and the share k/4 of surface edge bars are per bar.
// Families are split into "colours": contiguous bar ranges in which no two
// bars share a node, so a colour can scatter forces in parallel without races
// and every node sums its bars in the same order whatever the thread count.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "ldem/Material.hpp"

namespace ldem {

enum class BarKind : unsigned char { Edge = 0, CentreCentre = 1, Diagonal = 2 };

struct BarFamily {
    BarKind kind;
    std::array<double, 3> d0;  // reference vector from first to second node [m]
    double L;                  // initial length [m]
    double EA;                 // axial stiffness of a full (interior) bar [N]
    double Af;                 // fracture area of a full bar [m^2]
};

struct BarRange {
    std::int64_t begin, end;
};

struct Lattice {
    int nx = 0, ny = 0, nz = 0;
    double L0 = 0.0;

    // Nodes, structure of arrays.
    std::vector<double> x0, y0, z0;  // reference positions [m]
    std::vector<double> mass;        // lumped masses [kg]

    // Bars, structure of arrays.
    std::vector<std::int32_t> n1, n2;  // end nodes; d0 of the family points n1 -> n2
    std::vector<std::uint8_t> family;  // index into families
    std::vector<float> share;          // k/4 for edge bars shared by k modules, else 1

    std::vector<BarFamily> families;
    std::vector<BarRange> colours;

    std::int64_t numNodes() const { return static_cast<std::int64_t>(mass.size()); }
    std::int64_t numBars() const { return static_cast<std::int64_t>(n1.size()); }
    std::int32_t cornerId(int i, int j, int k) const { return i + (nx + 1) * (j + (ny + 1) * k); }
    std::int32_t centreId(int i, int j, int k) const {
        return (nx + 1) * (ny + 1) * (nz + 1) + i + nx * (j + ny * k);
    }
    double barEA(std::int64_t b) const { return families[family[b]].EA * share[b]; }
    double barAf(std::int64_t b) const { return families[family[b]].Af * share[b]; }
    double barLength(std::int64_t b) const { return families[family[b]].L; }
};

// Node and bar counts of an nx x ny x nz lattice (spec section 1).
std::int64_t expectedNodeCount(int nx, int ny, int nz);
std::int64_t expectedBarCount(int nx, int ny, int nz);

// Builds the lattice of nx x ny x nz modules of side L0 with the bar areas of
// the Nayfeh-Hefzy equivalence for material m and lumped masses rho L0^3
// (half to the centre node, 1/16 to each corner).
Lattice buildCubicLattice(int nx, int ny, int nz, double L0, const Material& m);

}  // namespace ldem
