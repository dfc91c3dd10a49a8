#include "ldem/dynamics/CrackPace.hpp"

#include <algorithm>

namespace ldem {

double CrackPace::target(const Limits& l, double kinetic, double work, bool cracking, bool nearPeak, bool lost) {
    return !lost && (nearPeak || (cracking && kinetic > l.kinetic * work)) ? l.slowest : 1.0;
}

bool CrackPace::nearPeak(const Limits& l, double secant, double elasticSecant, double stress, double peakStress) {
    return l.secant > 0 && elasticSecant > 0 && secant < l.secant * elasticSecant && stress >= l.band * peakStress;
}

double CrackPace::next(const Limits& l, double P0, double target, double peakStress) {
    const double glide = l.glide > 0 ? l.glide : 1.0;
    if (target >= P0) return std::min({target, P0 * l.step, P0 + glide});
    return std::max({target, l.brake > 0 ? P0 - l.brake * peakStress : target, P0 - glide});
}

void CrackPace::record(double kinetic, double work, double fracture, bool lost, double peakStress, double stress,
                       double strain) {
    const bool cracking = fracture > fracture_;
    fracture_ = fracture;
    const double secant = strain > 0 ? stress / strain : 0.0;
    if (fracture == 0) elasticSecant_ = std::max(elasticSecant_, secant);
    const bool near = nearPeak(lim_, secant, elasticSecant_, stress, peakStress);
    P0_ = P1_;
    P1_ = next(lim_, P0_, target(lim_, kinetic, work, cracking, near, lost), peakStress);
}

void CrackPace::setState(const std::vector<double>& s) {
    tau = s.at(0), tauBefore = s.at(1), P0_ = s.at(2), P1_ = s.at(3), fracture_ = s.at(4), elasticSecant_ = s.at(5);
}

}  // namespace ldem
