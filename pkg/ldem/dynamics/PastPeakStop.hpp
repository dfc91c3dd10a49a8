// Stop once the specimen is well past its peak (stop_at past_peak): at
// peak_stop_strain_ratio x the mean strain at the peak, whether or not the load
// is lost by then. For the size-effect study's triangular cube: what the study
// reports of it (the peak, the strain at the peak, the softening curve and the
// crack) is in the record by 10 x its strain at the peak, where its stress is
// down to a few per cent of the peak; the load loss (1 %) comes at 15 to 44 x
// on the 0.48-0.96 m cubes, and the slow creep of the stress from a few per
// cent to 1 % took 65 % of the triangular half's steps
// (results/separation/study_hour/, issue 41).
// Before the peak, the peak so far is the latest record, so the rule cannot
// hold on the rising branch.
// Parameters: LDEM_PAST_PEAK_STOP_PARAMETERS (peak_stop_strain_ratio).
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
