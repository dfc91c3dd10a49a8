#include "ldem/dynamics/AdaptiveDrive.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace ldem {

double AdaptiveDrive::target(const Limits& l, bool softening, double chainLoad) {
    if (softening || std::isnan(chainLoad)) return l.floor;
    return chainLoad > 0 ? std::clamp(l.floor * l.load / chainLoad, l.floor, l.ceiling) : l.ceiling;
}

double AdaptiveDrive::steadyBound(const Limits& l, double peakStress) {
    if (!(l.column > 0 && l.dampingT > 0)) return std::numeric_limits<double>::infinity();
    return l.drag * peakStress / (l.column * l.dampingT);  // column dampingT = rho H v0 D_f
}

AdaptiveDrive::Ramp AdaptiveDrive::rampAfterLoss(const Limits& l, double peakStress, double rampTime) {
    constexpr double pi = 3.14159265358979323846;
    const double Sd = steadyBound(l, peakStress), Sf = std::clamp(Sd / 2, 1.0, l.floor);
    if (!(l.column > 0) || !(Sf > 1)) return {Sf, rampTime};
    // pi (S_f - 1) / (2 D_f sqrt((S_d - S_f)(S_d - 1))), D_f = dampingT / T; S_d >= 2 S_f > 2. Without
    // drag (D_f T = 0, S_d infinite): inertia alone, rho H v0 pi (S_f - 1) / (2 t_q) <= tail_drag peak.
    const double shortest = std::isfinite(Sd)
                                ? pi * (Sf - 1) * l.interval / (2 * l.dampingT * std::sqrt((Sd - Sf) * (Sd - 1)))
                                : pi * (Sf - 1) * l.column * l.interval / (2 * l.drag * peakStress);
    return {Sf, std::max(rampTime, shortest)};
}

double AdaptiveDrive::next(double s, bool softening, double chainLoad, double peakStress) const {
    double lo = s / lim_.step, hi = s * lim_.step;
    if (lim_.column > 0) {
        const double B = lim_.drag * peakStress / lim_.column;
        lo = std::max(lo, s - B), hi = std::min(hi, (B + s) / (1 + lim_.dampingT));
    }
    hi = std::max(hi, lo);  // drag alone above the budget: slow down as fast as inertia allows
    return std::max(std::clamp(target(lim_, softening, chainLoad), lo, hi), lim_.floor);
}

void AdaptiveDrive::start(double U0, double Uprev0, double fracture) {
    active_ = true, U = U0, Uprev = Uprev0, S0_ = S1_ = lim_.floor, fracture_ = fracture;
    time_ = std::numeric_limits<double>::quiet_NaN();  // the first record starts the average
}

void AdaptiveDrive::record(double time, double fracture, double stressSupport, double peakStress) {
    const bool softening = fracture > fracture_;
    if (std::isnan(time_) || !(lim_.tau > 0)) support_ = stressSupport;
    else support_ += -std::expm1(-(time - time_) / lim_.tau) * (stressSupport - support_);  // weight 1 - exp(-dt/tau)
    fracture_ = fracture, time_ = time;
    S0_ = S1_;
    S1_ = next(S0_, softening, std::abs(support_) / peakStress, peakStress);
}

void AdaptiveDrive::setState(const std::vector<double>& s) {
    active_ = s.at(0) != 0, U = s.at(1), Uprev = s.at(2), S0_ = s.at(3), S1_ = s.at(4), fracture_ = s.at(5);
    time_ = s.at(6), support_ = s.at(7);
}

const char* AdaptiveTailDrive::select(const Params& p, const DriveSetup& s, bool chosen) {
    if (chosen && p.tailMaxSpeedup < s.program.lossSpeedup)
        throw std::invalid_argument("tail_max_speedup (" + formatNumber(p.tailMaxSpeedup) +
                                    ") must be at least loss_speedup (" + formatNumber(s.program.lossSpeedup) +
                                    ") for the adaptive drive");
    // Undamped, nothing would damp the ringing its changes of speed set off (measured, 0.08 m on
    // rollers, zeta 0: balance error 0.015 against 0.008 fixed, and another path to separation).
    return s.Df > 0 ? name : ConstantRateDrive::name;
}

// rho H v0 / T: the face stress of a unit change of S over a record, were a column of the
// specimen's height to follow the drive; D_f T its drag's share. Damped relative to the mean
// velocity (from the load loss on, as this bound) a steady motion has no drag: the bound is
// inertia's and the lag of the mean behind a speed-up, D_f tau m a (MassDamping.hpp):
// rho H v0 (1 + D_f tau) / T, D_f T = 0. The pace's brake acts before the load loss, where
// the damping is of the absolute velocity: the plain column.
void AdaptiveTailDrive::setUp(const RunSetup& r) {
    const DriveSetup& s = setup_;
    const double T = r.recordEvery * r.dt, Df = s.Df, tau = s.filterTime;
    const double column = s.rho * s.gaugeLength * program().v0 / T;
    lim_ = {program().speedup, p_.tailMaxSpeedup, p_.tailLoad, p_.tailDrag, p_.tailStep, s.splitWindow,
            tau > 0 ? column * (1 + Df * tau) : column, tau > 0 ? 0.0 : Df * T, T};
    pace_ = CrackPace({p_.crackPace, p_.crackKinetic, column > 0 ? p_.tailDrag / column : 0.0, p_.tailStep,
                       p_.crackSecant, p_.crackBand, program().rampTime > 0 ? T / program().rampTime : 0.0});
    tail_ = AdaptiveDrive(lim_);
}

void AdaptiveTailDrive::record(const DriveRecord& r) {
    const CurvePoint& p = r.point;
    const double t = clock(p.time);
    if (r.lossNow) {
        const AdaptiveDrive::Ramp ramp = AdaptiveDrive::rampAfterLoss(lim_, r.summary.peakStress, program().rampTime);
        fixed_.speedUp(t, ramp.floor, ramp.time);
    }
    if (!tail_.active() && r.summary.loadLoss.reached() && t >= program().speedupStart + program().speedupRamp) {
        tail_ = atFloor();
        tail_.start(now(p.time, r.dt), before(p.time, r.dt), p.fracture);
    }
    if (tail_.active()) tail_.record(p.time, p.fracture, p.stress, r.summary.peakStress);
    else if (pace_.on()) pace_.record(p.kineticOwn, p.externalWork, p.fracture, r.summary.loadLoss.reached(),
                                      r.summary.peakStress, p.stress, p.meanStrain);
}

std::vector<double> AdaptiveTailDrive::state() const {
    const Drive& d = program();
    std::vector<double> s{d.speedupStart, d.speedup, d.speedupRamp};
    if (pace_.on())
        for (double x : pace_.state()) s.push_back(x);
    if (tail_.active())
        for (double x : tail_.state()) s.push_back(x);
    return s;
}

void AdaptiveTailDrive::setState(const std::vector<double>& s) {
    fixed_.speedUp(s.at(0), s.at(1), s.at(2));
    auto rest = s.begin() + 3;
    if (pace_.on()) pace_.setState({rest, rest + CrackPace::kStateSize}), rest += CrackPace::kStateSize;
    tail_ = AdaptiveDrive(lim_);
    if (rest != s.end()) tail_ = atFloor(), tail_.setState({rest, s.end()});
}

}  // namespace ldem
