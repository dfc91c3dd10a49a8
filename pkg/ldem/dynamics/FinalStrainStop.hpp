// Stop at the final strain, if the event has not come. Always on.
// Parameters: LDEM_FINAL_STRAIN_STOP_PARAMETERS (final_strain).
#pragma once
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
    const char* reason(const CurvePoint& p, const RunSummary&) const {
        return p.meanStrain >= p_.finalStrain ? "final_strain" : nullptr;
    }
    std::vector<double> state() const { return {}; }
    void setState(const std::vector<double>&) {}

private:
    Params p_;
};

}  // namespace ldem
