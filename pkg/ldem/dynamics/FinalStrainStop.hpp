// Stop at the final strain, if the event has not come. In every run; one before
// the first record of the default interval is refused (results/dynamics/README.md).
#pragma once
#include <stdexcept>
#include <string>
#include <vector>

#include "ldem/Parameters.hpp"
#include "ldem/dynamics/Part.hpp"

// Its parameters.
#define LDEM_FINAL_STRAIN_STOP_PARAMETERS(X)                                                                 \
    X(double, finalStrain, "final_strain", 0.5, "", Domain::positive(),                                      \
      "stop at this mean strain if the event has not come; one before the first record is refused (exit 2): "\
      "it can never reach the peak")

namespace ldem {

class FinalStrainStop {
public:
    static constexpr const char* name = "final_strain";
    static constexpr const char* doc = "the final strain";
    static constexpr bool kChoice = false, kAlways = true;
    struct Params {
        LDEM_FINAL_STRAIN_STOP_PARAMETERS(LDEM_DECLARE_MEMBER)
    };
    explicit FinalStrainStop(const Params& p) : p_(p) {}
    void record(StopRecord&) {}
    const char* reason(const CurvePoint& p, const RunSummary&) const {
        return p.meanStrain < p_.finalStrain ? nullptr : "final_strain";
    }
    // A run that would stop before its first record has next to no curve, and its energies
    // are of the smooth start's first steps.
    void setUp(const RunSetup& r) const {
        if (p_.finalStrain > r.firstRecord) return;
        throw std::invalid_argument("final_strain " + formatNumber(p_.finalStrain) + " comes before the first record "
                                    "(at mean strain " + formatNumber(r.firstRecord) + "): the run would record "
                                    "nothing and can never reach the peak; raise final_strain");
    }
    std::vector<double> state() const { return {}; }
    void setState(const std::vector<double>&) {}

private:
    Params p_;
};

}  // namespace ldem
