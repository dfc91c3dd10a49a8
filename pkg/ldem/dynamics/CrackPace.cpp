#include "ldem/dynamics/CrackPace.hpp"

#include <algorithm>

namespace ldem {

double CrackPace::target(const Limits& l, double kinetic, double work, bool cracking, bool lost) {
    return !lost && cracking && kinetic > l.kinetic * work ? l.slowest : 1.0;
}

double CrackPace::next(const Limits& l, double P0, double target, double peakStress) {
    if (target >= P0) return std::min(target, P0 * l.step);
    return l.brake > 0 ? std::max(target, P0 - l.brake * peakStress) : target;
}

void CrackPace::record(double kinetic, double work, double fracture, bool lost, double peakStress) {
    const bool cracking = fracture > fracture_;
    fracture_ = fracture;
    P0_ = P1_;
    P1_ = next(lim_, P0_, target(lim_, kinetic, work, cracking, lost), peakStress);
}

void CrackPace::setState(const std::vector<double>& s) {
    tau = s.at(0), tauBefore = s.at(1), P0_ = s.at(2), P1_ = s.at(3), fracture_ = s.at(4);
}

}  // namespace ldem
