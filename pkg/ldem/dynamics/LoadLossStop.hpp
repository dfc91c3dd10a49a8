// stop_at load_loss: the event is the load-loss test's (LoadLoss.hpp); this
// rule ends the run there, and never before loss_stop_strain_ratio x the mean
// strain at the peak, so that a specimen whose load falls fast after its peak
// (a small uniform cube) keeps its softening branch and its crack in the record.
#pragma once
#include <vector>

#include "ldem/Parameters.hpp"
#include "ldem/dynamics/Part.hpp"

// Its parameters.
#define LDEM_LOAD_LOSS_STOP_PARAMETERS(X)                                                                    \
    X(double, lossStopStrainRatio, "loss_stop_strain_ratio", 10.0, "", Domain::atLeast(0),                   \
      "stop_at load_loss: the run goes on at least to this multiple of the mean strain at the peak, so that " \
      "the softening branch and the crack are in the record")

namespace ldem {

class LoadLossStop {
public:
    static constexpr const char* name = "load_loss";
    static constexpr const char* doc = "the load-loss test's event, at loss_stop_strain_ratio x the strain at the peak at the earliest";
    static constexpr bool kChoice = true, kAlways = false;
    struct Params {
        LDEM_LOAD_LOSS_STOP_PARAMETERS(LDEM_DECLARE_MEMBER)
    };
    explicit LoadLossStop(const Params& p) : p_(p) {}
    void setUp(const RunSetup&) const {}
    void record(StopRecord&) {}
    const char* reason(const CurvePoint& p, const RunSummary& s) const {
        const bool pastFloor = p.meanStrain >= p_.lossStopStrainRatio * s.strainAtPeak;
        return s.loadLoss.reached() && pastFloor ? "load_lost" : nullptr;
    }
    std::vector<double> state() const { return {}; }
    void setState(const std::vector<double>&) {}

private:
    Params p_;
};

}  // namespace ldem
