// Boundary conditions of the cube tests (LDEM_SPEC section 6): lower face
// fixed, upper face pulled vertically by a displacement that grows smoothly
// from rest, uniform or triangular across the face.
//
// Every prescribed degree of freedom follows u = weight * U(t), with U(t) the
// displacement of the most-pulled point of the upper face:
//   U(t) = v0 (t - (t_r/pi) sin(pi t / t_r)) / 2   for t < t_r  (velocity ramps
//          v0 (t - t_r / 2)                        for t >= t_r  up as 1 - cos)
// so velocity and acceleration start at zero. v0 = strain rate x height.
// Once the load is lost the drive can speed up by a factor S, with the same
// smooth ramp starting at t_s:  U(t) + (S - 1) U(t - t_s). The specimen then
// hangs on mechanisms that carry almost no force, and separation needs strains
// far beyond the peak; a faster drive reaches them in fewer steps.
#pragma once
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "ldem/Lattice.hpp"
#include "ldem/Parameters.hpp"

namespace ldem {

enum class LoadShape { Uniform, Triangular };

// LDEM_LOADING_PARAMETERS (Parameters.hpp): load shape, strain rate, smooth
// start, lateral DOFs of the faces, speed-up after load loss.
struct LoadingParams {
    LDEM_LOADING_PARAMETERS(LDEM_DECLARE_MEMBER)
    void validate() const;
};

struct Drive {
    double v0 = 0;        // final velocity of the most-pulled point [m/s]
    double rampTime = 0;  // [s]
    double speedup = 1;   // velocity factor after speedupStart
    double speedupStart = std::numeric_limits<double>::infinity();  // [s]; never, until the load is lost
    double displacement(double t) const;
};

struct Constraints {
    std::vector<std::uint8_t> mask;  // per node: bit d set if DOF d is prescribed
    // Prescribed DOFs: u[node][dim] = weight * U(t).
    std::vector<std::int32_t> node;
    std::vector<std::uint8_t> dim;
    std::vector<double> weight;
    std::vector<std::int32_t> bottomNodes, topNodes;
    double meanTopWeight = 0;  // mean weight of the upper face's vertical DOFs
    double faceArea = 0;       // area of the loaded faces [m^2]
    double height = 0;         // specimen height [m]
};

Constraints cubeTestConstraints(const Lattice& lat, const LoadingParams& p);

}  // namespace ldem
