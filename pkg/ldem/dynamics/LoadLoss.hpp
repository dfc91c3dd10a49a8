// The load-loss test, fed one record at a time (Simulation::run, and ldem.yade
// for the same specimen in YADE): bars have broken and the lower face no longer
// carries load. The reaction rings around zero for a while after the last
// large ruptures, so the stress averaged over the last `window` seconds (two
// fundamental periods by default) must be below fraction x peak.
#pragma once
#include <cstdint>
#include <deque>
#include <utility>
#include <vector>

#include "ldem/Parameters.hpp"
#include "ldem/dynamics/Record.hpp"

// Its parameters.
#define LDEM_LOAD_LOSS_PARAMETERS(X)                                                                         \
    X(double, stopFraction, "stop_fraction", 0.01, "", Domain::closedOpen(0, 1),                             \
      "the load is lost when the stress, averaged over the split window, is below this fraction of the peak")\
    X(double, splitWindow, "split_window", 0.0, "s", Domain::atLeast(0),                                     \
      "averaging time of the load-loss test (0: two fundamental periods)")

namespace ldem {

class LoadLossDetector {
public:
    static constexpr const char* name = "load_loss";
    struct Params {
        LDEM_LOAD_LOSS_PARAMETERS(LDEM_DECLARE_MEMBER)
    };
    LoadLossDetector(double window = 0, double fraction = 0) : window_(window), fraction_(fraction) {}
    // Whether the load is lost at this record (fed every record, also once it was).
    bool update(double time, double stress, double peakStress, std::int64_t broken);
    // At a record of a run: update(), and the summary's load-loss event at the first record where it is lost.
    bool record(const CurvePoint& p, RunSummary& s);
    // Its records (time, stress, time, stress, ...), for a checkpoint, and back.
    std::vector<double> state() const;
    void setState(const std::vector<double>& s);

private:
    double window_, fraction_;
    std::deque<std::pair<double, double>> recent_;  // (time, stress) of the records in the window
};

}  // namespace ldem
