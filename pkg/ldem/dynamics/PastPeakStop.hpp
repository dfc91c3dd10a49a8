// stop_at past_peak: the run ends at peak_stop_strain_ratio x the mean strain at
// the peak, lost load or not. What a study reports of a triangular cube (its
// peak, its softening curve, its crack) is in the record by then, and the slow
// creep of its stress to the load loss is not (results/dynamics/README.md).
// Before the peak the peak so far is the latest record: the rule cannot hold there.
#pragma once
#include <vector>

#include "ldem/Parameters.hpp"
#include "ldem/dynamics/Part.hpp"

// Its parameters.
#define LDEM_PAST_PEAK_STOP_PARAMETERS(X)                                                                    \
    X(double, peakStopStrainRatio, "peak_stop_strain_ratio", 10.0, "", Domain::atLeast(1),                   \
      "stop_at past_peak: the run ends at this multiple of the mean strain at the peak, lost load or not")

namespace ldem {

class PastPeakStop {
public:
    static constexpr const char* name = "past_peak";
    static constexpr const char* doc = "peak_stop_strain_ratio x the strain at the peak";
    static constexpr bool kChoice = true, kAlways = false;
    struct Params {
        LDEM_PAST_PEAK_STOP_PARAMETERS(LDEM_DECLARE_MEMBER)
    };
    explicit PastPeakStop(const Params& p) : p_(p) {}
    void setUp(const RunSetup&) const {}
    void record(StopRecord&) {}
    const char* reason(const CurvePoint& p, const RunSummary& s) const {
        const bool peaked = s.strainAtPeak > 0;
        return peaked && p.meanStrain >= p_.peakStopStrainRatio * s.strainAtPeak ? "past_peak" : nullptr;
    }
    std::vector<double> state() const { return {}; }
    void setState(const std::vector<double>&) {}

private:
    Params p_;
};

}  // namespace ldem
