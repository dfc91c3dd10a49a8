// A run of a specimen (Specimen.hpp) from rest to its stop: random G_f + the
// bar law (laws/) + the dynamic parts (dynamics/Parts.hpp: the drive, the
// dampings, the stop rules) + central differences + energy bookkeeping. run()
// is the time-step loop; a record step computes the same step in two halves
// (computeForces, measure, advance) so that state n is measured between them,
// bit for bit the arithmetic of step() (tests/cpp/test_dynamics).
#pragma once
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "ldem/Field3.hpp"
#include "ldem/Integrator.hpp"
#include "ldem/InternalForces.hpp"
#include "ldem/Lattice.hpp"
#include "ldem/LoadCell.hpp"
#include "ldem/Loading.hpp"
#include "ldem/Material.hpp"
#include "ldem/Modal.hpp"
#include "ldem/RandomField.hpp"
#include "ldem/RunParams.hpp"
#include "ldem/RunProgress.hpp"
#include "ldem/Specimen.hpp"
#include "ldem/StepWork.hpp"
#include "ldem/Weight.hpp"
#include "ldem/dynamics/Parts.hpp"
#include "ldem/laws/Registry.hpp"

namespace ldem {

class Simulation {
public:
    // Its lattice was built with material m; refuses parameters that do not fit (one-line messages).
    Simulation(Specimen specimen, const Material& m, const LoadingParams& load, const RunParams& run);
    Simulation(const Simulation&) = delete;  // holds pointers into its own groups
    Simulation& operator=(const Simulation&) = delete;

    // The time-step loop: records every recordEvery steps, calls observer (false: stop) and stops
    // where a stop rule says.
    RunSummary run(const std::function<bool(const CurvePoint&)>& observer = {});

    void step();  // one step, forces at x(n) then x(n+1), in one pass over the lattice
    // The same step in two halves, to measure() state n in between: bit-identical results.
    void computeForces();  // the layered pass, then the dampings' forces that wait for it (Parts::afterForces)
    CurvePoint measure() const;
    void advance();

    // The state at a record (from run()'s observer, or after run() returned), and a specimen set
    // back to it: its next run() continues step for step, bit for bit; a finished run set back
    // to its last record goes on to a later stop (ldem cube --extend).
    Checkpoint checkpoint() const;
    void restore(const Checkpoint& c);
    bool resumable() const { return progress_.pendingAdvance; }
    std::vector<std::string> partNames() const { return parts_.names(); }

    // Sets dt without the stability check: for tests of the instability detector and the stability limit.
    void forceTimeStep(double dt) {
        dt_ = dt, weight_ = RisingWeight(run_.gravity, drive().rampTime, dt), cd_ = nodeRule();
    }

    const Lattice& lattice() const { return lat_; }
    const Prescribed& prescribed() const { return pre_; }
    const Measures& measures() const { return meas_; }
    const std::map<std::string, std::vector<std::int32_t>>& groups() const { return groups_; }
    const std::vector<std::int32_t>& group(const std::string& name) const { return nodeGroup(groups_, name); }
    const BarLaws& law() const { return law_; }
    const std::vector<double>& barArray(const std::string& name) const { return lawArray(law_, name); }
    double lawConstant(const std::string& name) const { return ldem::lawConstant(law_, name); }
    std::vector<std::uint8_t> damageStates() const { return ldem::damageStates(law_, lat_.numBars()); }
    const Field3& displacements() const { return u_; }
    std::vector<double> fractureEnergyField() const { return ldem::fractureEnergyField(lat_, mat_, run_.seed); }
    std::vector<double> ruptureEnergies() const { return ldem::ruptureEnergies(law_, lat_); }
    std::vector<double> barForces() const { return ldem::barForces(law_, lat_, barStrains(lat_, u_)); }
    const Material& material() const { return mat_; }
    const LoadingParams& loading() const { return load_; }  // strain_rate: the one driven
    const RunParams& runParams() const { return run_; }
    const Frequencies& frequencies() const { return freq_; }
    double dt() const { return dt_; }
    double stableTimeStepLimit() const {  // dtSafety x 2 / omega_max x the dampings' factor (zeta_high)
        return run_.dtSafety * stableTimeStep(freq_.omegaMax) * parts_.stepFactor();
    }
    double dampingCoefficient() const { return parts_.dampingCoefficient(); }
    double supportStress() const;  // reactions of the support group / area, state n [Pa]
    bool facesJoined() const;      // some chain of intact bars joins the support and loaded groups
    double rampTime() const { return drive().rampTime; }
    bool openingControl() const { return meas_.control >= 0; }
    double splitWindow() const { return parts_.splitWindow(); }
    const Drive& drive() const { return parts_.program(); }  // the drive's program
    const Parts& parts() const { return parts_; }
    std::int64_t clampedBars() const { return clamped_; }
    std::int64_t totalBars() const { return totalBars_; }  // of the whole lattice (all ranks' slabs)
    std::int64_t totalNodes() const { return totalNodes_; }
    std::int64_t stepCount() const { return step_; }
    int recordEvery() const { return recordEvery_; }
    int threads() const { return threads_; }  // OpenMP threads of the run (threadsFor, Parallel.hpp)
    // U_min = E[G_f] x the ligament's area: the energy of the cheapest plane crack (0: no ligament declared).
    double minFractureEnergy() const { return mat_.GfMean * meas_.ligament; }
    const RunSummary& summarySoFar() const { return progress_.summary; }  // as of its last record

private:
    double meanStrainOf(double U) const { return U * std::abs(meas_.meanDriveWeight) / meas_.gaugeLength; }
    // The layered pass with the law's rows and the dampings' bar forces; afterLayer(m) as in layeredForces.
    // In Simulation.cpp only: the kernel needs ldemcore's -fno-math-errno to vectorize its square roots.
    template <class AfterLayer> void layered(AfterLayer afterLayer);
    double advanceNodes(int m) {  // the owned nodes of layer m; the halo's are moved by their owner
        return lat_.owns(m) ? advanceLayer(lat_, m, cd_, pre_.mask, f_, u_, v_) : 0.0;
    }
    CentralDifference nodeRule();
    void weighNextStep() { externalWork_ -= weight_.stepTo(step_, lat_, pre_.mask, u_, v_), cd_.gz = weight_.gz(); }
    void finishStep();  // damping and external work, prescribed DOFs, clock

    Material mat_;
    LoadingParams load_;
    RunParams run_;
    Lattice lat_;
    Prescribed pre_;
    Measures meas_;
    std::map<std::string, std::vector<std::int32_t>> groups_;
    const std::vector<std::int32_t>* support_ = nullptr;  // groups_[meas_.support]
    const std::vector<std::int32_t>* loaded_ = nullptr;   // groups_[meas_.loaded]
    Frequencies freq_;
    Parts parts_;
    double opening_ = 0;  // the controlled probe at the current state (opening control)
    BarLaws law_;
    Field3 u_, v_, f_;  // per node
    BarForceBuffers g_;  // bar forces of the layers in use
    double dt_ = 0, time_ = 0;
    CentralDifference cd_{0, 0};
    std::vector<double> layerDamping_;  // damping work of each node layer in the current step
    StepWork stepWork_;  // the step's work and reactions, summed by layer
    double externalWork_ = 0, dampingWork_ = 0;
    RisingWeight weight_;
    LoadCell supportCell_, loadedCell_;  // the support's and the loaded group's stresses (measure())
    std::int64_t step_ = 0, clamped_ = 0, totalBars_ = 0, totalNodes_ = 0;
    int recordEvery_ = 1, threads_ = 1;
    bool follow_ = false;  // the dampings' waiting forces follow the force sweep (Parts::followLayer)
    RunProgress progress_;
};

}  // namespace ldem
