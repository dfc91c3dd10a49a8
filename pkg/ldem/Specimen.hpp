// A specimen is data: its lattice, named groups of nodes, the degrees of
// freedom it prescribes and what a run measures on it. Small functions build
// one (cubeTestSpecimen: the study's cube, LDEM_SPEC section 6); Simulation
// runs any of them, reading stress, strain and separation from the groups the
// measures name.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "ldem/Field3.hpp"
#include "ldem/Lattice.hpp"
#include "ldem/Loading.hpp"
#include "ldem/Material.hpp"
#include "ldem/Modal.hpp"
#include "ldem/ParameterTable.hpp"

namespace ldem {

// Prescribed DOFs: u[node][dim] = weight * U(t), U the drive's displacement.
struct Prescribed {
    std::vector<std::uint8_t> mask;  // per node: bit d set if DOF d is prescribed
    std::vector<std::int32_t> node;
    std::vector<std::uint8_t> dim;
    std::vector<double> weight;
    void add(std::int32_t n, int d, double w);
    // Each DOF at weight x U, its velocity weight x (U - Ustart) / dt: the drive's over the step from Ustart.
    void follow(double U, double Ustart, double dt, Field3& u, Field3& v) const;
};

// omega_1 and omega_max of the lattice under its prescribed DOFs (refused if they leave a mechanism), and
// omega_d of its drive (Modal.hpp), omega_1 for a drive that moves nothing (a held specimen's weight).
Frequencies specimenFrequencies(const Lattice& lat, const Prescribed& pre);

// A displacement read at every record: u_dim[b] - u_dim[a] (a < 0: u_dim[b] alone),
// e.g. the crack mouth opening between two nodes across a notch.
struct Probe {
    std::string name;
    std::int32_t a = -1, b = 0;
    int dim = 0;
};

// Stress and strain are positive in the sense the specimen is driven: for a
// drive that pushes (mean weight < 0, compression, bending from above) both
// are reported with the sign turned (sense() = -1), so a peak is a maximum.
struct Measures {
    std::string support;        // group whose reactions along dim, over area, are the stress
    std::string loaded;         // the driven group: the same reactions, negated (their counterpart)
    int dim = 2;                // direction of the reactions and of the drive
    double area = 0;            // [m^2]
    double gaugeLength = 0;     // [m]: drive velocity = strain rate x gauge length
    double meanDriveWeight = 0; // mean weight of the loaded group's DOFs along dim:
                                // mean strain = U(t) x |meanDriveWeight| / gaugeLength
    std::vector<Probe> probes;  // extra displacements in every record
    int control = -1;           // the probe a servo holds to LoadingParams::openingRate (-1: none; Loading.hpp)
    double ligament = 0;        // [m^2]: the section the specimen is meant to break through (a notched
                                // beam's b (D - a0), a cube's face); U_min = E[G_f] x ligament; 0: none declared
    // The specimen is split when no chain of intact bars joins support and loaded.
    double sense() const { return meanDriveWeight < 0 ? -1.0 : 1.0; }
};

// The readings of the measures, summed over the ranks that own the nodes (a
// slab's node held elsewhere is -1, Slab.hpp): a probe's u_dim[b] - u_dim[a],
// and a force component summed over a group's nodes.
double probeReading(const Lattice& lat, const Field3& u, const Probe& q);
double groupSum(const Lattice& lat, const std::vector<double>& f, const std::vector<std::int32_t>& nodes);

struct Specimen {
    Lattice lattice;
    std::map<std::string, std::vector<std::int32_t>> groups;
    Prescribed prescribed;
    Measures measures;
};

// Prescribed DOFs u[node[k]][dim[k]] = weight[k] U(t); throws std::invalid_argument
// on a node out of range, a direction not 0-2, a DOF listed twice.
Prescribed makePrescribed(std::int64_t numNodes, const std::vector<std::int32_t>& node,
                          const std::vector<std::uint8_t>& dim, const std::vector<double>& weight);

// Throws std::invalid_argument naming what is wrong: a node id out of range,
// a direction not 0-2, a prescribed DOF listed twice, measures without an
// area, a gauge length or a driven DOF, a probe on no node, a measured group
// the specimen does not have, a whole lattice under mpirun (not this rank's slab).
void validate(const Specimen& s);

// The group of nodes by its name; throws std::invalid_argument on a name the specimen does not have.
const std::vector<std::int32_t>& nodeGroup(const std::map<std::string, std::vector<std::int32_t>>& groups,
                                           const std::string& name);

// The cube of nx x ny x nz modules (LDEM_SPEC section 6): groups "bottom" (the
// support: z held; x, y held, or on rollers with only the rigid motion pinned)
// and "top" (loaded: z driven with weight 1, uniform, or x/width, triangular;
// x, y free or held).
// With moduleMask (buildLattice), the prism of those modules pulled the same
// way: a face is its nodes of some module, the area its modules' (a prism's
// lower and upper faces must have the same nodes). Rollers need the face's
// two corners (0, 0) and (nx, 0).
// slab: the module layers [k0, k1) this process owns (Slab.hpp); {0, -1}: all.
Specimen cubeTestSpecimen(int nx, int ny, int nz, double L0, const Material& m, const LoadingParams& p,
                          const std::vector<std::uint8_t>& moduleMask = {}, std::pair<int, int> slab = {0, -1});
// The cube test of p (p.geometry.modules() a side): under mpirun this rank's
// slab (Slab.hpp), the whole cube otherwise. Run it with
// Simulation(cubeTestSpecimen(p), p.material, p.loading, p.run).
Specimen cubeTestSpecimen(const CubeTestParams& p);

// A specimen described on the whole nx x ny x nz lattice (moduleMask as
// buildLattice; groups, prescribed DOFs and probes by the whole lattice's node
// ids), built as the slab [k0, k1) of it (Slab.hpp; {0, -1}: all of it): the
// groups and DOFs keep their nodes in the slab's box, with its local ids; a
// probe's node that is not there becomes -1 (its owner reads it). Throws
// std::invalid_argument on a node id outside the whole lattice.
Specimen specimenSlab(int nx, int ny, int nz, double L0, const Material& m,
                      const std::vector<std::uint8_t>& moduleMask,
                      const std::map<std::string, std::vector<std::int32_t>>& groups,
                      const std::vector<std::int32_t>& node, const std::vector<std::uint8_t>& dim,
                      const std::vector<double>& weight, const Measures& measures,
                      std::pair<int, int> slab = {0, -1});

}  // namespace ldem
