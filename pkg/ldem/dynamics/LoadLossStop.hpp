// Stop at the load loss (stop_at load_loss): the event is the load-loss
// detector's (LoadLoss.hpp), this rule only ends the run there.
#pragma once
#include <vector>

#include "ldem/dynamics/Part.hpp"

namespace ldem {

class LoadLossStop {
public:
    static constexpr const char* name = "load_loss";
    void record(StopRecord&) {}
    const char* reason(const CurvePoint&, const RunSummary& s) const {
        return s.loadLoss.reached() ? "load_lost" : nullptr;
    }
    std::vector<double> state() const { return {}; }
    void setState(const std::vector<double>&) {}
};

}  // namespace ldem
