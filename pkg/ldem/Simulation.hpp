// A run of a specimen (Specimen.hpp; the study's cube test, LDEM_SPEC section
// 6, is one) from rest to separation: random G_f + the bar law (laws/) + the
// specimen's prescribed DOFs + central differences + energy bookkeeping. run()
// is the time-step loop; everything it calls per step is in InternalForces
// (bars, through the law), Integrator (nodes) and the dynamic parts
// (dynamics/Registry.hpp: the drive, the dampings, the load-loss test and the
// stop rules), which it steps in order. A record step computes the same step in two halves
// (computeForces, measure, advance) so that state n can be measured between
// them; the arithmetic is that of step(), bit for bit (tests/cpp/test_dynamics).
#pragma once
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "ldem/Field3.hpp"
#include "ldem/Integrator.hpp"
#include "ldem/InternalForces.hpp"
#include "ldem/Lattice.hpp"
#include "ldem/Loading.hpp"
#include "ldem/Material.hpp"
#include "ldem/Modal.hpp"
#include "ldem/RunParams.hpp"
#include "ldem/Specimen.hpp"
#include "ldem/dynamics/QuasiStatic.hpp"
#include "ldem/dynamics/Record.hpp"
#include "ldem/dynamics/Registry.hpp"
#include "ldem/laws/Registry.hpp"

namespace ldem {

// What run() has found so far, kept in the Simulation so that a run can stop at
// a record (a checkpoint) and continue bit-identically (restore()).
struct RunProgress {
    RunSummary summary;
    double maxEnergy = 0, maxResidual = 0;  // the largest of W and K + E + F + D, and of |W - (K + E + F + D)|
    bool started = false;
    bool pendingAdvance = false;       // state n is recorded: the run goes on with its advance()
};

// The whole state of a run at a record: with the specimen's parameters, enough
// to continue it (ldem.io.write_checkpoint stores it).
struct Checkpoint {
    Field3 u, v, f;
    std::vector<std::pair<std::string, std::vector<double>>> bars;  // the law's per-bar state, by name
    std::vector<std::uint8_t> softening;                             // the law's softening rows
    double time = 0, externalWork = 0, dampingWork = 0;
    std::int64_t step = 0;
    RunProgress progress;
    // Each dynamic part's state, by role and name (Simulation::partNames(): "drive_adaptive", "stop_separation", ...).
    std::vector<std::pair<std::string, std::vector<double>>> parts;
};

// Thrown when the integration blows up (NaN, or energy created from nothing).
class InstabilityError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class Simulation {
public:
    // Runs any specimen (the cube test: cubeTestSpecimen): its lattice was
    // built with material m; load gives the drive (rate, smooth start, speed-up
    // after load loss).
    Simulation(Specimen specimen, const Material& m, const LoadingParams& load, const RunParams& run);
    Simulation(const Simulation&) = delete;  // holds pointers into its own groups
    Simulation& operator=(const Simulation&) = delete;

    // The time-step loop: records every recordEvery steps, calls observer (which may
    // return false to stop), speeds the drive up once the load is lost, stops
    // at separation (or load loss, or convergence: RunParams::stopAt) or the final strain.
    RunSummary run(const std::function<bool(const CurvePoint&)>& observer = {});
    // Separation is tested on record steps at most every this many steps, once
    // the stress has fallen below half the peak (ldem-bench prints its cost).
    static constexpr std::int64_t kSeparationCheckSteps = SeparationStop::checkSteps;

    // One step, forces at x(n) then x(n+1), in one pass over the lattice.
    void step();
    // The same step in two halves, to measure() state n in between; the
    // arithmetic is the same, so both ways give bit-identical results.
    void computeForces();
    CurvePoint measure() const;
    void advance();

    // The state at the record being observed (call it from run()'s observer,
    // or after run() returned: its last record), and a specimen set back to
    // such a state: its next run() continues the interrupted one step for
    // step, bit for bit. A finished run set back to its last record goes on
    // to a later stop (ldem cube --extend): the run's events so far are kept,
    // its stop is not.
    Checkpoint checkpoint() const;
    void restore(const Checkpoint& c);
    bool resumable() const { return progress_.pendingAdvance; }
    // The names of the parts' states in a checkpoint, in order.
    std::vector<std::string> partNames() const;

    // Sets dt without the stability check: for tests of the instability
    // detector and for studies of the stability limit itself.
    void forceTimeStep(double dt) { dt_ = dt, cd_ = nodeRule(); }

    const Lattice& lattice() const { return lat_; }
    const Prescribed& prescribed() const { return pre_; }
    const Measures& measures() const { return meas_; }
    const std::map<std::string, std::vector<std::int32_t>>& groups() const { return groups_; }
    const std::vector<std::int32_t>& group(const std::string& name) const;  // throws on an unknown name
    const BarLaws& law() const { return law_; }
    // The law's per-bar state array `name` and its constant `name` (throw on an unknown name).
    const std::vector<double>& barArray(const std::string& name) const;
    double lawConstant(const std::string& name) const;
    std::vector<std::uint8_t> damageStates() const;  // DamageState of every bar
    const Field3& displacements() const { return u_; }
    std::vector<double> fractureEnergyField() const;  // G_f of every bar (recomputed from the seed)
    // Energy each bar dissipates when it breaks (the capacities of the cheapest cut).
    std::vector<double> ruptureEnergies() const;
    // Axial force of every bar at the current state [N], tension positive (the law at its strain and damage).
    std::vector<double> barForces() const;
    const Material& material() const { return mat_; }
    const LoadingParams& loading() const { return load_; }
    const RunParams& runParams() const { return run_; }
    const Frequencies& frequencies() const { return freq_; }
    double dt() const { return dt_; }
    double stableTimeStepLimit() const;  // dtSafety x 2 / omega_max x the dampings' factor (zeta_high)
    double dampingCoefficient() const { return ldem::dampingCoefficient(dampings_); }
    double supportStress() const;  // reactions of the support group / area, state n [Pa]
    bool facesJoined() const;      // some chain of intact bars joins the support and loaded groups
    double rampTime() const { return drive().rampTime; }
    bool openingControl() const { return meas_.control >= 0; }
    double splitWindow() const { return splitWindow_; }
    const Drive& drive() const {  // the drive's program
        return std::visit([](const auto& d) -> const Drive& { return d.program(); }, drive_);
    }
    const Drives& drivePart() const { return drive_; }  // the drive chosen (dynamics/Registry.hpp)
    const Dampings& dampingParts() const { return dampings_; }  // the dampings (dynamics/Registry.hpp)
    std::int64_t clampedBars() const { return clamped_; }
    // Bars and nodes of the whole lattice (of all ranks' slabs under MPI).
    std::int64_t totalBars() const { return totalBars_; }
    std::int64_t totalNodes() const { return totalNodes_; }
    std::int64_t stepCount() const { return step_; }
    int recordEvery() const { return recordEvery_; }
    int threads() const { return threads_; }  // OpenMP threads of the run (threadsFor, Parallel.hpp)
    // U_min = E[G_f] x the ligament's area: the energy of the cheapest plane crack (0: no ligament declared).
    double minFractureEnergy() const { return mat_.GfMean * meas_.ligament; }
    // The run's summary so far, as of its last record (an interrupted run's peak and events).
    const RunSummary& summarySoFar() const { return progress_.summary; }

private:
    // The drive's displacement U at t_n and at t_n-1.
    double driveNow() const {
        return std::visit([this](const auto& d) { return d.now(time_, dt_); }, drive_);
    }
    double driveBefore() const {
        return std::visit([this](const auto& d) { return d.before(time_, dt_); }, drive_);
    }
    double meanStrainOf(double U) const { return U * std::abs(meas_.meanDriveWeight) / meas_.gaugeLength; }
    double probe(const Probe& q) const;  // its reading at the current state [m]
    // The layered pass with the law's rows and every damping's bar forces; afterLayer(m) as in layeredForces.
    template <class AfterLayer>
    void layered(AfterLayer afterLayer) {
        std::visit([&](auto& law) { layeredForces(lat_, u_, g_, f_, law.rows(), afterLayer, barPass(dampings_, v_)); },
                   law_);
    }
    // The record's events and stop (run()): the load-loss test, the drive, the stop rules.
    void recordParts(const CurvePoint& p);
    std::string stopReason(const CurvePoint& p) const;
    double advanceNodes(int layer);
    CentralDifference nodeRule();
    double weightAt(std::int64_t n) const;
    void weighNextStep();
    double ownedLayerSum(const std::function<double(int)>& ofLayer) const;  // in layer order, over the ranks
    // Sum over the nodes of a group of a force component along the measured direction.
    double groupForce(const std::vector<std::int32_t>& nodes) const;
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
    Dampings dampings_;
    Drives drive_;
    LoadLossDetector loadLoss_;
    std::vector<StopRules> stops_;
    KineticAtPeak kineticAtPeak_;
    double opening_ = 0;  // the controlled probe at the current state (opening control)
    BarLaws law_;
    Field3 u_, v_, f_;  // per node
    BarForceBuffers g_;  // bar forces of the layers in use
    double dt_ = 0, time_ = 0, splitWindow_ = 0;
    CentralDifference cd_{0, 0};
    std::vector<double> layerDamping_;  // damping work of each node layer in the current step
    std::vector<std::int32_t> preSlot_, supportSlot_, loadedSlot_;  // owned layer (- ownBegin) of each prescribed DOF's node, support and loaded node; -1 if not owned
    std::vector<double> stepPartials_;  // finishStep's per-layer sums, kept between steps
    double externalWork_ = 0, dampingWork_ = 0;
    double gz_ = 0, weightRise_ = 0;  // the weight's g_z in the last step; the time it rises over [s]
    double stressBefore_ = 0;  // supportStress() of the state the last step started from
    // The load cells: sums of the support's and the loaded group's stresses over
    // the states since the last record, and how many (measure()).
    double cellSupport_ = 0, cellLoaded_ = 0;
    int cellStates_ = 0;
    std::int64_t step_ = 0, clamped_ = 0, totalBars_ = 0, totalNodes_ = 0;
    int recordEvery_ = 1, defaultRecordEvery_ = 1;  // its record interval, and the default's [steps]
    int threads_ = 1;
    RunProgress progress_;
};

}  // namespace ldem
