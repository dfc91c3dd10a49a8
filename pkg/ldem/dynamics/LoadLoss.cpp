#include "ldem/dynamics/LoadLoss.hpp"

namespace ldem {

bool LoadLossDetector::update(double time, double stress, double peakStress, std::int64_t broken) {
    recent_.emplace_back(time, stress);
    while (recent_.front().first < time - window_) recent_.pop_front();
    double sum = 0;
    for (const auto& r : recent_) sum += r.second;
    return broken > 0 && time >= window_ && sum / recent_.size() < fraction_ * peakStress;
}

bool LoadLossDetector::record(const CurvePoint& p, RunSummary& s) {
    const bool lost = update(p.time, p.stress, s.peakStress, p.broken);
    if (lost && !s.loadLoss.reached()) s.loadLoss = RunEvent::at(p);
    return lost;
}

std::vector<double> LoadLossDetector::state() const {
    std::vector<double> s;
    for (const auto& [t, stress] : recent_) s.push_back(t), s.push_back(stress);
    return s;
}

void LoadLossDetector::setState(const std::vector<double>& s) {
    recent_.clear();
    for (std::size_t i = 0; i + 1 < s.size(); i += 2) recent_.emplace_back(s[i], s[i + 1]);
}

}  // namespace ldem
