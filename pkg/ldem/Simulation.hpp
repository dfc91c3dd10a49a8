// A run of a specimen (Specimen.hpp; the study's cube test, LDEM_SPEC section
// 6, is one) from rest to separation: random G_f + the bar law (laws/) + the
// specimen's prescribed DOFs + central differences + energy bookkeeping. run()
// is the time-step loop; everything it calls per step is in InternalForces
// (bars, through the law), Integrator (nodes) and Loading (the drive). A record step computes the same step in two halves
// (computeForces, measure, advance) so that state n can be measured between
// them; the arithmetic is that of step(), bit for bit (tests/cpp/test_dynamics).
#pragma once
#include <cmath>
#include <cstdint>
#include <deque>
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
#include "ldem/laws/Registry.hpp"

namespace ldem {

struct CurvePoint {
    std::int64_t step = 0;
    double time = 0;          // [s]
    double meanStrain = 0;    // the loaded group's mean drive displacement / gauge length (the cube's height)
    double stress = 0;        // reactions of the support group along the measured direction / area [Pa]
    double stressLoaded = 0;  // the same on the loaded group, negated [Pa]
    std::vector<double> probes;  // the specimen's Measures::probes [m]
    double externalWork = 0, kinetic = 0, elastic = 0, fracture = 0, damping = 0;  // [J]
    std::int64_t damaged = 0, broken = 0;
    double balanceResidual() const { return externalWork - (kinetic + elastic + fracture + damping); }
};

// An event of the run: when it came and the fracture energy dissipated by then.
struct RunEvent {
    std::int64_t step = -1;  // -1: not reached
    double time = 0, meanStrain = 0, fracture = 0;  // [s], [-], [J]
    bool reached() const { return step >= 0; }
};

struct RunSummary {
    double peakStress = 0;        // [Pa], tracked at every step
    double strainAtPeak = 0;      // mean strain at the peak
    double edgeStrainAtPeak = 0;  // strain at the most-pulled edge at the peak (= mean for uniform)
    RunEvent loadLoss;            // stress averaged over the window below stopFraction x peak
    RunEvent separation;          // no chain of intact bars joins the two faces: U_num = separation.fracture
    RunEvent converged;           // (stop_at converged) U stopped growing after load loss: U_final = converged.fracture
    double fractureEnergy = 0;    // fracture energy dissipated at the end [J]
    double energyBalanceError = 0;  // max |residual| / the largest energy in play over the records
    bool energyError = false;     // energyBalanceError > energyTolerance
    std::int64_t steps = 0;
    std::string stopReason;       // "separated", "load_lost", "converged", "final_strain" or "stopped"
};

// The load-loss test, fed one record at a time (Simulation::run, and ldem.yade
// for the same specimen in YADE): bars have broken and the lower face no longer
// carries load. The reaction rings around zero for a while after the last
// large ruptures, so the stress averaged over the last `window` seconds (two
// fundamental periods by default) must be below fraction x peak.
class LoadLossDetector {
public:
    LoadLossDetector(double window = 0, double fraction = 0) : window_(window), fraction_(fraction) {}
    // Whether the load is lost at this record (fed every record, also once it was).
    bool update(double time, double stress, double peakStress, std::int64_t broken);
    // Its records, for a checkpoint, and back.
    std::vector<std::pair<double, double>> records() const { return {recent_.begin(), recent_.end()}; }
    void setRecords(const std::vector<std::pair<double, double>>& r) { recent_.assign(r.begin(), r.end()); }

private:
    double window_, fraction_;
    std::deque<std::pair<double, double>> recent_;  // (time, stress) of the records in the window
};

// When is a specimen that does not separate done (stop_at converged)? A
// triangular cube hinges about its least-pulled edge: past its load loss it
// hangs on chains that straighten and break one column of modules after the
// other, ever nearer the hinge, and whether the last ones ever break depends
// on the lateral freedom of the faces. Its fracture energy U(e) grows in
// bursts as the mean strain e doubles. The test is on doublings: rungs e_0 =
// the strain at load loss, then the first record at or past 2 e_k. A rung is
// quiet when
//     U(e_k+1) - U(e_k) < growth x U(e_k+1)    and the load is lost there
// (stress averaged over the split window below stopFraction x peak), and U has
// converged after `quietRungs` quiet rungs in a row. One is not enough
// (measured, 0.08 m cube, seed 1: a quiet doubling to e = 6.8e-3, then U grew
// by 49 % to e = 0.11 as the next columns broke). U_final = U there.
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

// What run() has found so far, kept in the Simulation so that a run can stop at
// a record (a checkpoint) and continue bit-identically (restore()).
struct RunProgress {
    RunSummary summary;
    double maxEnergy = 0, maxResidual = 0;  // the largest of W and K + E + F + D, and of |W - (K + E + F + D)|
    LoadLossDetector loadLoss;
    std::int64_t lastCheck = 0;        // step of the last separation test
    EnergyConvergence convergence;
    bool started = false;
    bool pendingAdvance = false;       // state n is recorded: the run goes on with its advance()
};

// The whole state of a run at a record: with the specimen's parameters, enough
// to continue it (ldem.io.write_checkpoint stores it).
struct Checkpoint {
    Field3 u, v, f;
    std::vector<std::pair<std::string, std::vector<double>>> bars;  // the law's per-bar state, by name
    std::vector<std::uint8_t> softening;                             // the law's softening rows
    double time = 0, externalWork = 0, dampingWork = 0, speedupStart = 0;
    double servoU = 0, servoUprev = 0;  // the servo's drive displacement at t_n, t_n-1 (opening control)
    std::int64_t step = 0;
    RunProgress progress;
    std::vector<double> tailDrive;  // AdaptiveDrive::state() (empty: not started)
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
    static constexpr std::int64_t kSeparationCheckSteps = 100;

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

    // Sets dt without the stability check: for tests of the instability
    // detector and for studies of the stability limit itself.
    void forceTimeStep(double dt) { dt_ = dt, cd_ = CentralDifference(dt_, Df_); }

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
    double stableTimeStepLimit() const;  // dtSafety x 2 / omega_max
    double dampingCoefficient() const { return Df_; }
    double supportStress() const;  // reactions of the support group / area, state n [Pa]
    bool facesJoined() const;      // some chain of intact bars joins the support and loaded groups
    double rampTime() const { return drive_.rampTime; }
    bool openingControl() const { return meas_.control >= 0; }
    const Servo& servo() const { return servo_; }
    double splitWindow() const { return splitWindow_; }
    const Drive& drive() const { return drive_; }
    const AdaptiveDrive& adaptiveDrive() const { return tail_; }
    std::int64_t clampedBars() const { return clamped_; }
    // Bars and nodes of the whole lattice (of all ranks' slabs under MPI).
    std::int64_t totalBars() const { return totalBars_; }
    std::int64_t totalNodes() const { return totalNodes_; }
    std::int64_t stepCount() const { return step_; }
    int recordEvery() const { return recordEvery_; }
    int threads() const { return threads_; }  // OpenMP threads of the run (threadsFor, Parallel.hpp)
    double minFractureEnergy() const { return mat_.GfMean * meas_.area; }  // U_min

private:
    // The drive's displacement U at t_n and at t_n-1: the program's, or the
    // servo's state, or the adaptive drive's state once the load is lost.
    double driveNow() const {
        return openingControl() ? servo_.U : tail_.active() ? tail_.U : drive_.displacement(time_);
    }
    double driveBefore() const {
        return openingControl() ? servo_.Uprev : tail_.active() ? tail_.Uprev : drive_.displacement(time_ - dt_);
    }
    double meanStrainOf(double U) const { return U * std::abs(meas_.meanDriveWeight) / meas_.gaugeLength; }
    double probe(const Probe& q) const;  // its reading at the current state [m]
    AdaptiveDrive::Limits tailLimits() const {
        // rho H v0 / T: the face stress of a unit change of S over a record, were a column of the
        // specimen's height to follow the drive; D_f T its drag's share.
        const double T = recordEvery_ * dt_;
        return {load_.lossSpeedup, load_.tailMaxSpeedup, load_.tailLoad, load_.tailDrag, load_.tailStep,
                splitWindow_,      mat_.rho * meas_.gaugeLength * drive_.v0 / T, Df_ * T};
    }
    double advanceNodes(int layer);
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
    Drive drive_;
    Servo servo_;
    AdaptiveDrive tail_;  // tail_drive adaptive: active from the load loss on (displacement control only)
    double opening_ = 0;  // the controlled probe at the current state (opening control)
    BarLaws law_;
    Field3 u_, v_, f_;  // per node
    BarForceBuffers g_;  // bar forces of the layers in use
    double dt_ = 0, Df_ = 0, time_ = 0, splitWindow_ = 0;
    CentralDifference cd_{0, 0};
    std::vector<double> layerDamping_;  // damping work of each node layer in the current step
    std::vector<std::int32_t> preSlot_, supportSlot_;  // owned layer (- ownBegin) of each prescribed DOF's node, support node; -1 if not owned
    std::vector<double> stepPartials_;  // finishStep's per-layer sums, kept between steps
    double externalWork_ = 0, dampingWork_ = 0;
    double stressBefore_ = 0;  // supportStress() of the state the last step started from
    std::int64_t step_ = 0, clamped_ = 0, totalBars_ = 0, totalNodes_ = 0;
    int recordEvery_ = 1;
    int threads_ = 1;
    RunProgress progress_;
};

}  // namespace ldem
