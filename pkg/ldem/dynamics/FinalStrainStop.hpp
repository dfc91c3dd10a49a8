// Stop at the final strain, if the event has not come. Always on.
// Parameters: LDEM_FINAL_STRAIN_STOP_PARAMETERS (final_strain).
#pragma once
#include <stdexcept>
#include <string>
#include <vector>

#include "ldem/Parameters.hpp"
#include "ldem/dynamics/Part.hpp"

namespace ldem {

class FinalStrainStop {
public:
    static constexpr const char* name = "final_strain";
    struct Params {
        LDEM_FINAL_STRAIN_STOP_PARAMETERS(LDEM_DECLARE_MEMBER)
    };
    explicit FinalStrainStop(const Params& p) : p_(p) {}
    void record(StopRecord&) {}
    // The final strain reached while every bar is still on its elastic branch: the
    // peak (the first bars must soften for the stress to fall) lies beyond it.
    const char* reason(const CurvePoint& p, const RunSummary&) const {
        if (p.meanStrain < p_.finalStrain) return nullptr;
        if (p.damaged == 0 && p.broken == 0)
            throw std::invalid_argument("final_strain " + formatNumber(p_.finalStrain) + " was reached at step " +
                                        std::to_string(p.step) + " before any bar left its elastic branch: it can "
                                        "never reach the peak; raise final_strain");
        return "final_strain";
    }
    std::vector<double> state() const { return {}; }
    void setState(const std::vector<double>&) {}

private:
    Params p_;
};

}  // namespace ldem
