#include "ldem/Simulation.hpp"

#include <array>
#include <tuple>

#include "ldem/Interrupt.hpp"
#include "ldem/Parallel.hpp"
#include "ldem/Relations.hpp"
#include "ldem/Separation.hpp"
#include "ldem/Slab.hpp"

namespace ldem {

Simulation::Simulation(Specimen specimen, const Material& m, const LoadingParams& load, const RunParams& run)
    : mat_(m), load_(load), run_(run) {
    mat_.validate();
    load_.validate();
    run_.validate();
    validate(specimen);
    checkRelations(mat_, load_, run_, specimen.lattice.L0);
    threads_ = threadsFor(run_.threads, specimen.lattice.numBars(), Comm::world().size());
    setThreads(threads_);
    lat_ = std::move(specimen.lattice);
    pre_ = std::move(specimen.prescribed);
    meas_ = specimen.measures;
    groups_ = std::move(specimen.groups);
    support_ = &groups_.at(meas_.support), loaded_ = &groups_.at(meas_.loaded);

    freq_ = specimenFrequencies(lat_, pre_);
    load_ = drivenLoading(mat_, load_, run_, freq_.omegaDrive, lat_.L0);
    parts_ = Parts(mat_, load_, run_, {freq_.omega1, freq_.omegaMax, freq_.omegaDrive, lat_.numBars(),
                                       lat_.numLayers(), std::int64_t(lat_.barRows.size()), lat_.numNodes(),
                                       meas_.gaugeLength, openingControl(), lat_.isSlab()});
    dt_ = chosenTimeStep(run_, stableTimeStepLimit(), parts_.stepFactor(), freq_.omegaMax);
    const double meanSpeed = drive().v0 * std::abs(meas_.meanDriveWeight);
    const int defaultEvery = defaultRecordEvery(mat_.epsP, meas_.gaugeLength, meanSpeed, dt_);
    recordEvery_ = run_.recordEvery > 0 ? run_.recordEvery : defaultEvery;
    // (the first record at the default interval: a run recorded seldom on purpose still runs)
    parts_.setUp({dt_, recordEvery_, mat_.epsP, meanStrainOf(drive().displacement(defaultEvery * dt_))});
    weight_ = RisingWeight(run_.gravity, drive().rampTime, dt_);

    law_ = makeBarLaw(mat_.law, lat_, mat_, fractureEnergyField());  // G_f drawn, realised, not kept
    clamped_ = commOf(lat_).sum(std::visit([](const auto& law) { return law.clampedOwnedBars(); }, law_));
    std::tie(totalBars_, totalNodes_) = wholeLatticeSize(lat_);
    refuseAllBrittle(clamped_, totalBars_, mat_, lat_.L0);
    u_ = v_ = f_ = Field3(lat_.numNodes());
    stepWork_ = StepWork(lat_, pre_, *support_, *loaded_, meas_.dim);
    cd_ = nodeRule();
    layerDamping_.assign(lat_.numLayers(), 0.0);
    follow_ = parts_.deferred() && threads_ == 1 && !lat_.isSlab();
}

// The node update of the dampings, with the free DOFs' weight under gravity (along -z).
CentralDifference Simulation::nodeRule() {
    CentralDifference cd = parts_.nodeUpdate(dt_);
    cd.gz = weight_.gz();
    return cd;
}

// 0 + x: +0, never -0, when a pushed specimen's force is 0 (curve.csv's first row).
double Simulation::supportStress() const {
    return (0.0 + meas_.sense() * groupSum(lat_, f_[meas_.dim], *support_)) / meas_.area;
}

bool Simulation::facesJoined() const {
    const std::vector<std::uint8_t> intact = std::visit([&](const auto& law) { return intactBars(lat_, law); }, law_);
    return nodesJoined(lat_, intact, *loaded_, *support_);
}

CurvePoint Simulation::measure() const {
    CurvePoint p;
    p.step = step_;
    p.time = time_;
    p.meanStrain = meanStrainOf(parts_.now(time_, dt_));
    p.stress = supportCell_.reading(supportStress());
    p.stressLoaded = loadedCell_.reading((0.0 - meas_.sense() * groupSum(lat_, f_[meas_.dim], *loaded_)) / meas_.area);
    for (const Probe& q : meas_.probes) p.probes.push_back(probeReading(lat_, u_, q));
    const BarEnergies e = barEnergies(lat_, u_, law_);
    p.elastic = e.elastic, p.fracture = e.fracture, p.damaged = e.damaged, p.broken = e.broken;
    p.kinetic = kineticEnergy(lat_, pre_.mask, v_);
    const double U = parts_.now(time_, dt_);
    p.kineticOwn = ownKineticEnergy(lat_, pre_.mask, u_, v_, U != 0 ? (U - parts_.before(time_, dt_)) / (dt_ * U) : 0.0);
    // The weight's work is the drive's companion: the external work (Integrator.hpp, weightWork).
    p.externalWork = externalWork_ + weight_.work(lat_, pre_.mask, u_, v_);
    // With the bars' dashpots, the last step's work is whole once this step's bars know v(n-1/2) (BarDashpot.hpp).
    p.damping = dampingWork_ +
                layerSum<1>(lat_, [&](int m, std::array<double, 1>& w) { w[0] = parts_.closingWork(m); })[0];
    return p;
}

template <class AfterLayer>
void Simulation::layered(AfterLayer afterLayer) {
    std::visit([&](auto& law) { layeredForces(lat_, u_, g_, f_, law.rows(), afterLayer, parts_.barPass(v_)); }, law_);
}

void Simulation::computeForces() {
    layered([](int) {});
    parts_.afterForces(lat_, pre_.mask, u_, v_, f_, [](int) {});
}

void Simulation::step() {
    weighNextStep();
    // A node layer moves once it has its forces, unless it waits for a damping's that need every
    // node's (BarDashpots.hpp: predicted). One visit of the law a step: layered is compiled for it.
    const auto advance = [this](int m) { layerDamping_[m] = advanceNodes(m); };
    if (!parts_.deferred()) {
        layered(advance);
        return finishStep();
    }
    const std::function<void(int)> move = advance;
    if (follow_) {  // (one thread, one rank: the dampings' forces follow the sweep)
        layered([&](int m) { layerDamping_[m] = 0.0, parts_.followLayer(m, lat_, pre_.mask, u_, v_, f_, move); });
        parts_.afterForces(lat_, pre_.mask, u_, v_, f_, move, true);
    } else {
        layered([this](int m) { layerDamping_[m] = parts_.waits(m) ? 0.0 : advanceNodes(m); });
        parts_.afterForces(lat_, pre_.mask, u_, v_, f_, move);
    }
    finishStep();
}

void Simulation::advance() {
    weighNextStep();
#pragma omp parallel for schedule(static)
    for (int m = 0; m < lat_.numLayers(); ++m) layerDamping_[m] = advanceNodes(m);
    finishStep();
}

void Simulation::finishStep() {
    // The drive's U(n+1); under opening control the servo moves U from state n (its opening is that of state n).
    const double tNext = time_ + dt_, Uback = parts_.before(time_, dt_), Unow = parts_.now(time_, dt_);
    const DriveStep next{time_, dt_, int(step_ % recordEvery_), recordEvery_, opening_};
    const double Unext = parts_.next(next);
    const StepSums sums = stepWork_.sum(lat_, f_, 0.5 * (Unext - Uback), [&](int m) {  // (StepWork.hpp)
        const double bars = parts_.stepWork(m);
        return bars != 0 ? layerDamping_[m] + bars : layerDamping_[m];
    });
    dampingWork_ += sums.damping;
    externalWork_ += sums.external;
    if (step_ % recordEvery_ == 0) {  // the record's state n was its interval's last: a new interval
        supportCell_.restart(), loadedCell_.restart();
    } else {
        supportCell_.add((0.0 + meas_.sense() * sums.support) / meas_.area);  // = supportStress() of state n, bit for bit
        loadedCell_.add((0.0 - meas_.sense() * sums.loaded) / meas_.area);
    }
    pre_.follow(Unext, Unow, dt_, u_, v_);
    exchangeHalo(lat_, u_);  // the neighbours' layers next to mine, moved by them
    // The bars' dashpots read v(n+1/2) at both ends of a bar (BarDashpot.hpp): the halo's too.
    if (parts_.barPass(v_).state) exchangeHalo(lat_, v_);
    time_ = tNext;
    ++step_;
    if (openingControl()) opening_ = probeReading(lat_, u_, meas_.probes[meas_.control]);
}

Checkpoint Simulation::checkpoint() const {
    if (lat_.isSlab()) throw std::logic_error("checkpoints of a run split over MPI ranks are not supported");
    if (!progress_.pendingAdvance && progress_.summary.stopReason.empty())
        throw std::logic_error("a checkpoint is taken at a record: from run()'s observer, or once run() returned");
    Checkpoint c{u_, v_, f_, {}, {}, time_, externalWork_, dampingWork_, step_, progress_, parts_.states()};
    lawState(law_, c.bars, c.softening);
    return c;
}

void Simulation::restore(const Checkpoint& c) {
    if (lat_.isSlab()) throw std::invalid_argument("restarts of a run split over MPI ranks are not supported");
    checkSizes(c, lat_);
    parts_.setStates(c.parts);
    setLawState(law_, c.bars, c.softening);
    u_ = c.u, v_ = c.v, f_ = c.f;
    time_ = c.time, externalWork_ = c.externalWork, dampingWork_ = c.dampingWork, step_ = c.step;
    weight_.restoreAt(step_);
    cd_ = nodeRule();
    if (openingControl()) opening_ = probeReading(lat_, u_, meas_.probes[meas_.control]);
    progress_ = c.progress;
    progress_.summary.stopReason.clear();  // a finished run set back to its last record goes on
    progress_.pendingAdvance = true;
}

RunSummary Simulation::run(const std::function<bool(const CurvePoint&)>& observer) {
    setThreads(threads_);
    RunProgress& g = progress_;
    g.begin();
    RunSummary& s = g.summary;
    if (g.pendingAdvance) {  // restored at a record: the rest of that step
        g.pendingAdvance = false;
        advance();
    }
    InterruptCheck interruptPoint;
    for (;;) {
        if (step_ % recordEvery_ != 0) {
            step();
            interruptPoint();  // a signal may stop here, between records (a checkpoint needs a record)
            continue;
        }
        // A record step: forces, measure state n, then the rest of the step.
        computeForces();
        const CurvePoint p = measure();
        g.record(p, parts_.now(time_, dt_) / meas_.gaugeLength, dt_, stableTimeStep(freq_.omegaMax));
        parts_.record(p, s, v_, [this] { return facesJoined(); }, dt_);
        cd_ = nodeRule();  // (relative damping: from the load loss on)
        // The record is complete: what the observer sees (and may checkpoint) is state n with its events.
        g.pendingAdvance = true;
        // Rank 0's answer for every rank (an observer that stops on one rank alone would leave the others waiting).
        const bool keepGoing = commOf(lat_).broadcast(!observer || observer(p));
        g.pendingAdvance = false;
        s.stopReason = parts_.stopReason(p, s);
        if (s.stopReason.empty() && !keepGoing) s.stopReason = "stopped";
        if (!s.stopReason.empty()) break;
        advance();
    }
    g.finish(run_.energyTolerance);
    return s;
}

}  // namespace ldem
