// What a run has found at its records (the peak, the energy balance), the
// check that its integration is stable, and its whole state at a record (a
// checkpoint): with the specimen's parameters, enough to go on bit-identically.
#pragma once
#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "ldem/Field3.hpp"
#include "ldem/Lattice.hpp"
#include "ldem/dynamics/Parts.hpp"
#include "ldem/dynamics/Record.hpp"

namespace ldem {

// Thrown when the integration blows up (NaN, or energy created from nothing).
class InstabilityError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct RunProgress {
    RunSummary summary;
    double maxEnergy = 0, maxResidual = 0;  // the largest of W and K + E + F + D, and of |W - (K + E + F + D)|
    bool started = false;
    bool pendingAdvance = false;  // state n is recorded: the run goes on with its advance()

    // A record of state n (edgeStrain: the most-pulled point's U / the gauge length): an unstable
    // integration throws (dt and the stability limit 2/omega_max name it); else its peak and balance.
    void begin();  // run()'s: fresh the first time, else restored at a record (a specimen that ran refuses)
    void record(const CurvePoint& p, double edgeStrain, double dt, double dtLimit);
    void finish(double energyTolerance);  // the balance error of the whole run, flagged above the tolerance
};

// The record interval by default [steps]: a record per eps_p/50 of mean strain at the drive's initial
// speed (meanSpeed = v0 |w|, the mean of the loaded face), about 100 before the peak; 1e9 steps for a
// drive that moves nothing.
inline int defaultRecordEvery(double epsP, double gaugeLength, double meanSpeed, double dt) {
    const double rowTime = epsP / 50 * gaugeLength / meanSpeed;
    return std::max(1, int(std::min(rowTime / dt, 1e9)));
}

struct Checkpoint {
    Field3 u, v, f;
    std::vector<std::pair<std::string, std::vector<double>>> bars;  // the law's per-bar state, by name
    std::vector<std::uint8_t> softening;                             // the law's softening rows
    double time = 0, externalWork = 0, dampingWork = 0;
    std::int64_t step = 0;
    RunProgress progress;
    PartStates parts;  // each dynamic part's, by role and name (Parts::states)
};

// Throws std::invalid_argument unless c is of a specimen of lat's sizes: its nodes, bars and softening rows.
void checkSizes(const Checkpoint& c, const Lattice& lat);

}  // namespace ldem
