// Is the loading quasi-static? Two guards every run gets (Simulation::run;
// README, Outputs).
// - The drive's step, as a fraction of the critical strain: r = strain_rate dt
//   / eps_p (the drive moves at most strain_rate x gauge). At r >= 1 the
//   most-pulled bars pass their elastic branch within one step, before any
//   force has done work on them: the run measures nothing and is refused.
// - Beyond that, inertia shows at the peak as kinetic energy. Measured on the
//   0.12 m cube (README): K/W at the peak 0.06% at the default 0.02/s, 0.2% at
//   0.2/s (peak 0.6% above the default's), 1.4% at 2/s (peak 8.5% above, its
//   strain 48% further): above 1% the run is flagged not quasi-static.
#pragma once
#include <cmath>
#include <limits>

#include "ldem/dynamics/Record.hpp"

namespace ldem {

constexpr double kDriveStepLimit = 1.0;
// The other end: a drive so slow that it takes more than a million steps to
// strain eps_p is refused too. The default runs take ~10^3 (0.02/s at L0 = 0.02 m,
// r ~ 1e-3), 0.2% of their work is kinetic at the peak: slower changes no
// result, and such a run would take hours to reach its peak.
constexpr double kDriveStepFloor = 1e-6;
constexpr double kKineticAtPeakLimit = 0.01;
// Rule (c) (results/dynamics/criteria.md): the drive strains the gauge by eps_p
// in no fewer than N = 3 fundamental periods,
//   N = eps_p / (strain_rate T1) >= kRatePeriods,   T1 = 2 pi / omega_1,
// so that the peak comes many periods after the smooth start (2 T1). Measured
// at a quarter of the rate, the same drive: the D50 notched beam's peak moved
// by 1.7 % at N = 0.74 (no pace, 0.4 of the step limit), 0.83 % and 3.9 % (paced
// on K, on K_own), and by 0.67 % and 0.39 % at N = 3 (paced), the eccentric-notch
// beam's by 1.2 % at N = 0.31, the 0.48 m cubes' by 0.4-1.1 % at N = 3.2. It is
// not always needed (the coarse notched beam of examples/beam_3pb.toml moved by
// 0.78 % at N = 0.12), and not always enough (below): a run below it is warned, not refused.
constexpr double kRatePeriods = 3.0;
// The rate of a specimen whose file gives none (ParameterTable.hpp,
// specimenOwnDefaults): eps_p in 12 periods. Seed 1 against a quarter of the
// rate, peak (fracture energy): N = 3 moved the compression cube of
// examples/compression.toml by +3.5 % (+1.1 %), the dog-bone's energy at its load
// loss by -59 % (an early loss), the L-panel by +1.9 to +2.7 %; N = 12 moved the
// dog-bone by +0.06 % (+0.18 %), the Brazilian disc by -0.04 % (+0.18 %), the
// compression cube by +0.27 % (its collapse's energy by +30 %), the L-panel by
// -0.56 % (its energy to 1 mm +3.0 %: its bursts): results/dynamics/criteria.md.
constexpr double kSpecimenRatePeriods = 12.0;

// N, the fundamental periods the drive takes to strain eps_p.
inline double periodsToEpsP(double strainRate, double epsP, double omega1) {
    return epsP * omega1 / (2 * 3.14159265358979323846 * strainRate);
}

// Its inverse, the setting rate_periods: the strain rate whose drive strains eps_p in N periods. The
// relation N x strain_rate = eps_p omega_1 / (2 pi) is symmetric: the same expression with N for the rate.
inline double rateForPeriods(double periods, double epsP, double omega1) {
    return periodsToEpsP(periods, epsP, omega1);
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
