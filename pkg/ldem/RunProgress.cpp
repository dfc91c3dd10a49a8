#include "ldem/RunProgress.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace ldem {

void RunProgress::begin() {
    if (!started) {
        *this = RunProgress();
        started = true;
    } else if (!pendingAdvance) {
        throw std::invalid_argument("this specimen has already run: build a new one (or restore a checkpoint)");
    }
}

void RunProgress::record(const CurvePoint& p, double edgeStrain, double dt, double dtLimit) {
    const double total = p.kinetic + p.elastic + p.fracture + p.damping;
    // Energy from nothing (kinetic above all the work put in) or NaN: the
    // integration is unstable; stop before it writes garbage.
    if (!std::isfinite(total) || !std::isfinite(p.stress) ||
        p.kinetic > 1.5 * p.externalWork + 1e-9 * (1 + maxEnergy)) {
        std::ostringstream msg;
        msg << "numerical instability at step " << p.step << " (t = " << p.time << " s): kinetic energy "
            << p.kinetic << " J against external work " << p.externalWork << " J; dt = " << dt
            << " s, stability limit " << dtLimit << " s";
        throw InstabilityError(msg.str());
    }
    // The peak: the largest record (a load cell's mean over its interval), at the
    // drive's displacement at the record; an unstable record is no peak.
    RunSummary& s = summary;
    if (p.stress > s.peakStress)
        s.peakStress = p.stress, s.strainAtPeak = p.meanStrain, s.edgeStrainAtPeak = edgeStrain;
    // The balance is measured against the largest energy in play, not the
    // work alone: energy that appears without work (a drive that jumps
    // past the bars' elastic branch in a step, before any force did work)
    // is then an error of 1, not 0/0.
    maxEnergy = std::max({maxEnergy, p.externalWork, total});
    maxResidual = std::max(maxResidual, std::abs(p.balanceResidual()));
    s.fractureEnergy = p.fracture;
    s.steps = p.step;
}

void RunProgress::finish(double energyTolerance) {
    summary.energyBalanceError = maxEnergy > 0 ? maxResidual / maxEnergy : 0.0;  // 0: nothing moved
    summary.energyError = summary.energyBalanceError > energyTolerance;
}

void checkSizes(const Checkpoint& c, const Lattice& lat) {
    const std::size_t n = std::size_t(lat.numNodes()), b = std::size_t(lat.numBars());
    bool sizesMatch = c.u.x.size() == n && c.v.x.size() == n && c.f.x.size() == n &&
                      c.softening.size() == lat.barRows.size();
    for (const auto& [name, values] : c.bars) sizesMatch = sizesMatch && values.size() == b;
    if (!sizesMatch) throw std::invalid_argument("the checkpoint is of another specimen (its sizes differ)");
}

}  // namespace ldem
