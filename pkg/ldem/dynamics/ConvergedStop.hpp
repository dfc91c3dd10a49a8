// stop_at converged: a specimen that hinges (a triangular cube) may never
// separate; its fracture energy U(e) grows in bursts as the mean strain e doubles.
// Rungs: e_0 the strain at the load loss, then the first record past 2 e_k. A rung
// is quiet when U(e_k+1) - U(e_k) < converged_growth x U(e_k+1) with the load
// lost there, and U has converged after `quietRungs` (2) quiet rungs in a row: one
// is not enough (results/dynamics/README.md). U_final = U there.
#pragma once
#include <vector>

#include "ldem/Parameters.hpp"
#include "ldem/dynamics/Part.hpp"

// Its parameters.
#define LDEM_CONVERGED_STOP_PARAMETERS(X)                                                                    \
    X(double, convergedGrowth, "converged_growth", 0.01, "", Domain::open(0, 1),                             \
      "stop_at converged: U has converged when it grew by less than this fraction over the last doubling of "\
      "the mean strain since load loss, with the load still below stop_fraction x peak")

namespace ldem {

class EnergyConvergence {
public:
    static constexpr int quietRungs = 2;
    explicit EnergyConvergence(double growth = 0.01) : growth_(growth) {}
    // Fed the records past the load loss; true once U has converged.
    bool update(double meanStrain, double fracture, bool loadLost);
    // Its state, for a checkpoint, and back.
    std::vector<double> state() const { return {rungStrain_, rungFracture_, double(quiet_)}; }
    void setState(const std::vector<double>& s) { rungStrain_ = s.at(0), rungFracture_ = s.at(1), quiet_ = int(s.at(2)); }

private:
    double growth_;
    double rungStrain_ = 0, rungFracture_ = 0;  // the last rung (0: none yet)
    int quiet_ = 0;                             // quiet rungs in a row
};

// The stop rule: the summary's converged event, and the run ends there.
class ConvergedStop {
public:
    static constexpr const char* name = "converged";
    static constexpr const char* doc =
        "separation or, for a specimen that hinges (triangular), U no longer growing after load loss";
    static constexpr bool kChoice = true, kAlways = false;
    struct Params {
        LDEM_CONVERGED_STOP_PARAMETERS(LDEM_DECLARE_MEMBER)
    };
    explicit ConvergedStop(const Params& p) : convergence_(p.convergedGrowth) {}
    void setUp(const RunSetup&) const {}
    void record(StopRecord& r);
    const char* reason(const CurvePoint&, const RunSummary& s) const {
        return s.converged.reached() ? "converged" : nullptr;
    }
    std::vector<double> state() const { return convergence_.state(); }
    void setState(const std::vector<double>& s) { convergence_.setState(s); }

private:
    EnergyConvergence convergence_;
};

}  // namespace ldem
