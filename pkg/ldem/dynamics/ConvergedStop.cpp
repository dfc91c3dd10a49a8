#include "ldem/dynamics/ConvergedStop.hpp"

namespace ldem {

bool EnergyConvergence::update(double meanStrain, double fracture, bool loadLost) {
    if (rungStrain_ == 0) {  // the load-loss record: the first rung
        rungStrain_ = meanStrain, rungFracture_ = fracture;
        return false;
    }
    if (meanStrain < 2 * rungStrain_) return false;
    const bool quiet = loadLost && fracture - rungFracture_ < growth_ * fracture;
    quiet_ = quiet ? quiet_ + 1 : 0;
    rungStrain_ = meanStrain, rungFracture_ = fracture;
    return quiet_ >= quietRungs;
}

void ConvergedStop::record(StopRecord& r) {
    RunSummary& s = r.summary;
    if (s.loadLoss.reached() && !s.converged.reached() &&
        convergence_.update(r.point.meanStrain, r.point.fracture, r.lost))
        s.converged = RunEvent::at(r.point);
}

}  // namespace ldem
