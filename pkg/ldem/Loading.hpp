// The loading of the cube tests (LDEM_SPEC section 6): its parameters and the
// drive, a displacement that grows smoothly from rest (the specimen says which
// DOFs follow it and with which weights, Specimen.hpp).
//
// Every prescribed degree of freedom follows u = weight * U(t), with U(t) the
// displacement of the most-pulled point:
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

}  // namespace ldem
