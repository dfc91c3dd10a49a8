#include "ldem/dynamics/SeparationStop.hpp"

namespace ldem {

void SeparationStop::record(StopRecord& r) {
    const CurvePoint& p = r.point;
    if (p.broken > 0 && p.stress < 0.5 * r.summary.peakStress && p.step - lastCheck_ >= checkSteps) {
        lastCheck_ = p.step;
        if (!r.facesJoined()) r.summary.separation = RunEvent::at(p);
    }
}

}  // namespace ldem
