#include "ldem/dynamics/QuasiStatic.hpp"

#include <cstdio>
#include <stdexcept>
#include <string>

namespace ldem {

void refuseDriveJump(double strainRate, double dt, double epsP) {
    const double r = driveStep(strainRate, dt, epsP);
    if (r < kDriveStepLimit) return;
    char msg[400];
    std::snprintf(msg, sizeof msg,
                  "strain_rate %g 1/s moves the drive by %.3g x eps_p of the gauge in one step of %.3g s: the bars "
                  "break before the lattice can respond; quasi-static loading needs a strain rate far below %.3g 1/s",
                  strainRate, r, dt, kDriveStepLimit * epsP / dt);
    throw std::invalid_argument(msg);
}

void refuseDriveCrawl(double strainRate, double dt, double epsP) {
    const double r = driveStep(strainRate, dt, epsP);
    if (r >= kDriveStepFloor) return;
    char msg[400];
    std::snprintf(msg, sizeof msg,
                  "strain_rate %g 1/s takes %.3g steps of %.3g s to strain eps_p: more than %.0f before any bar can "
                  "crack; quasi-static loading needs no strain rate below %.3g 1/s here",
                  strainRate, 1 / r, dt, 1 / kDriveStepFloor, kDriveStepFloor * epsP / dt);
    throw std::invalid_argument(msg);
}

}  // namespace ldem
