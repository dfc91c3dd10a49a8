// Stop at separation: no chain of intact bars joins the support and the loaded
// groups (Separation.hpp); U_num is the fracture energy there. Always on: every
// run records the event and stops at it. The union-find is tested on record
// steps at most every checkSteps steps, once the stress has fallen below half
// the peak (ldem-bench prints its cost).
#pragma once
#include <cstdint>
#include <vector>

#include "ldem/dynamics/Part.hpp"

namespace ldem {

class SeparationStop {
public:
    static constexpr const char* name = "separation";
    static constexpr const char* doc = "no chain of intact bars joins the faces";
    static constexpr bool kChoice = true, kAlways = true;  // stop_at separation: no other rule
    static constexpr std::int64_t checkSteps = 100;
    struct Params {};
    explicit SeparationStop(const Params& = {}) {}
    void setUp(const RunSetup&) const {}
    void record(StopRecord& r);
    const char* reason(const CurvePoint&, const RunSummary& s) const {
        return s.separation.reached() ? "separated" : nullptr;
    }
    std::vector<double> state() const { return {double(lastCheck_)}; }
    void setState(const std::vector<double>& s) { lastCheck_ = std::int64_t(s.at(0)); }

private:
    std::int64_t lastCheck_ = -checkSteps;  // step of the last test
};

}  // namespace ldem
