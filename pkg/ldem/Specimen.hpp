// A specimen is data: its lattice, named groups of nodes, the degrees of
// freedom it prescribes and what a run measures on it. Small functions build
// one (cubeTestSpecimen: the study's cube, LDEM_SPEC section 6); Simulation
// runs any of them, reading stress, strain and separation from the groups the
// measures name.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ldem/Lattice.hpp"
#include "ldem/Loading.hpp"
#include "ldem/Material.hpp"

namespace ldem {

// Prescribed DOFs: u[node][dim] = weight * U(t), U the drive's displacement.
struct Prescribed {
    std::vector<std::uint8_t> mask;  // per node: bit d set if DOF d is prescribed
    std::vector<std::int32_t> node;
    std::vector<std::uint8_t> dim;
    std::vector<double> weight;
    void add(std::int32_t n, int d, double w);
};

struct Measures {
    std::string support;        // group whose reactions along dim, over area, are the stress
    std::string loaded;         // the driven group: the same reactions, negated (their counterpart)
    int dim = 2;                // direction of the reactions and of the drive
    double area = 0;            // [m^2]
    double gaugeLength = 0;     // [m]: drive velocity = strain rate x gauge length
    double meanDriveWeight = 0; // mean weight of the loaded group's DOFs along dim:
                                // mean strain = U(t) x meanDriveWeight / gaugeLength
    // The specimen is split when no chain of intact bars joins support and loaded.
};

struct Specimen {
    Lattice lattice;
    std::map<std::string, std::vector<std::int32_t>> groups;
    Prescribed prescribed;
    Measures measures;
};

// The cube of nx x ny x nz modules (LDEM_SPEC section 6): groups "bottom" (the
// support: z held; x, y held, or on rollers with only the rigid motion pinned)
// and "top" (loaded: z driven with weight 1, uniform, or x/width, triangular;
// x, y free or held).
Specimen cubeTestSpecimen(int nx, int ny, int nz, double L0, const Material& m, const LoadingParams& p);

}  // namespace ldem
