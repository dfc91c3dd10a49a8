// Is the loading quasi-static? The guards every Simulation gets (dynamics/Parts.cpp).
// - The drive's step over the critical strain, r = strain_rate dt / eps_p: at r >= 1
//   the most-pulled bars pass their elastic branch within one step, before any
//   force has done work on them, and below 1e-6 the run would take hours to its
//   peak: both are refused when the Simulation is built.
// - Inertia shows at the peak as kinetic energy: K/W above 1 % there is flagged.
// - Rule (c): the drive strains the gauge by eps_p in no fewer than N periods
//   of the mode it drives, N = eps_p / (strain_rate T_d), T_d = 2 pi / omega_d
//   (Modal.hpp: driveFrequency; omega_1 may be a mode the drive never moves, a
//   beam's sideways swing); a run below it is warned, not refused. N = 12 at a
//   constant drive: at 3 the D50 beam's peak moves by 2 % and the L-panel's by
//   9 % at a quarter of the rate, at 12 by less than 1 % (results/criteria/).
//   N = 3 under the crack pace, which slows the drive near the peak: the study's
//   cubes pass the quarter-rate test at 3.4 (results/dynamics/predicted_step/).
#pragma once
#include <cmath>
#include <limits>

#include "ldem/dynamics/Record.hpp"

namespace ldem {

constexpr double kDriveStepLimit = 1.0;
constexpr double kDriveStepFloor = 1e-6;
constexpr double kKineticAtPeakLimit = 0.01;
constexpr double kRatePeriods = 12.0;  // also the rate of a specimen whose file gives none (specimenOwnDefaults)
constexpr double kPacedRatePeriods = 3.0;

// N, the drive's periods 2 pi / omega_d it takes to strain eps_p.
inline double periodsToEpsP(double strainRate, double epsP, double omegaDrive) {
    return epsP * omegaDrive / (2 * 3.14159265358979323846 * strainRate);
}

// Its inverse, the setting rate_periods: the strain rate whose drive strains eps_p in N periods. The
// relation N x strain_rate = eps_p omega_d / (2 pi) is symmetric: the same expression with N for the rate.
inline double rateForPeriods(double periods, double epsP, double omegaDrive) {
    return periodsToEpsP(periods, epsP, omegaDrive);
}

// The drive's displacement in one step over eps_p x the gauge length.
inline double driveStep(double strainRate, double dt, double epsP) { return strainRate * dt / epsP; }

// Throws std::invalid_argument (saying the strain rate to stay far below) when driveStep >= kDriveStepLimit.
void refuseDriveJump(double strainRate, double dt, double epsP);
// Throws std::invalid_argument when driveStep < kDriveStepFloor.
void refuseDriveCrawl(double strainRate, double dt, double epsP);

// K / W at the record of the largest stress (the first such record; 0 while W <= 0), fed record by
// record. The stress is compared in MPa, as the curve's stress_MPa column is (bit for bit the same choice of row).
class KineticAtPeak {
public:
    void record(const CurvePoint& p) {
        const double stressMPa = p.stress * 1e-6;
        if (!(stressMPa > peakMPa_)) return;
        peakMPa_ = stressMPa;
        ratio_ = p.externalWork > 0 ? p.kinetic / p.externalWork : 0.0;
    }
    double ratio() const { return ratio_; }
    bool flagged() const { return ratio_ > kKineticAtPeakLimit; }
    std::vector<double> state() const { return {peakMPa_, ratio_}; }
    void setState(const std::vector<double>& s) { peakMPa_ = s.at(0), ratio_ = s.at(1); }

private:
    double peakMPa_ = -std::numeric_limits<double>::infinity(), ratio_ = 0;
};

}  // namespace ldem
