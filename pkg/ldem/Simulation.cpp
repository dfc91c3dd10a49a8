#include "ldem/Simulation.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "ldem/Integrator.hpp"
#include "ldem/Interrupt.hpp"
#include "ldem/Parallel.hpp"
#include "ldem/RandomField.hpp"
#include "ldem/Separation.hpp"
#include "ldem/Slab.hpp"

namespace ldem {

bool LoadLossDetector::update(double time, double stress, double peakStress, std::int64_t broken) {
    recent_.emplace_back(time, stress);
    while (recent_.front().first < time - window_) recent_.pop_front();
    double sum = 0;
    for (const auto& r : recent_) sum += r.second;
    return broken > 0 && time >= window_ && sum / recent_.size() < fraction_ * peakStress;
}

Simulation::Simulation(Specimen specimen, const Material& m, const LoadingParams& load, const RunParams& run)
    : mat_(m), load_(load), run_(run) {
    mat_.validate();
    load_.validate();
    run_.validate();
    validate(specimen);
    if (Comm::world().size() > 1 && !specimen.lattice.isSlab())
        throw std::invalid_argument("under mpirun, a specimen must be built as this rank's slab (specimenSlab)");
    threads_ = threadsFor(run_.threads, specimen.lattice.numBars(), Comm::world().size());
    setThreads(threads_);
    lat_ = std::move(specimen.lattice);
    pre_ = std::move(specimen.prescribed);
    meas_ = specimen.measures;
    groups_ = std::move(specimen.groups);
    for (const std::string& g : {meas_.support, meas_.loaded})
        if (!groups_.count(g)) throw std::invalid_argument("the specimen's measures name no node group '" + g + "'");
    support_ = &groups_.at(meas_.support), loaded_ = &groups_.at(meas_.loaded);

    freq_ = latticeFrequencies(lat_, pre_.mask);
    // A mechanism (a motion that stretches no bar) has omega_1 = 0: no damping
    // (D_f = 2 zeta omega_1), an infinite smooth start, NaN at once.
    if (!(freq_.omega1 > 1e-6 * freq_.omegaMax)) {
        std::ostringstream msg;
        msg << "the constraints leave a mechanism: omega_1 = " << freq_.omega1 << " rad/s (omega_max = "
            << freq_.omegaMax << " rad/s); e.g. one module with a laterally free upper face turns about the "
            << "vertical axis: use at least 2 modules a side or hold the upper face laterally";
        throw std::invalid_argument(msg.str());
    }
    const double limit = stableTimeStepLimit();
    if (run_.dt > limit) {
        std::ostringstream msg;
        msg << "time step " << run_.dt << " s is above the stability limit " << limit << " s (" << run_.dtSafety
            << " x 2/omega_max, omega_max = " << freq_.omegaMax << " rad/s)";
        throw std::invalid_argument(msg.str());
    }
    dt_ = run_.dt > 0 ? run_.dt : limit;
    Df_ = massDampingCoefficient(run_.zeta, freq_.omega1);
    const double pi = 3.14159265358979323846;
    const double period1 = 2 * pi / freq_.omega1;
    drive_.v0 = load_.strainRate * meas_.gaugeLength;
    drive_.rampTime = load_.rampTime > 0 ? load_.rampTime : 2 * period1;
    drive_.speedup = load_.lossSpeedup;
    if (load_.tailDrive == TailDrive::Adaptive && load_.tailMaxSpeedup < load_.lossSpeedup)
        throw std::invalid_argument("tail_max_speedup (" + formatNumber(load_.tailMaxSpeedup) +
                                    ") must be at least loss_speedup (" + formatNumber(load_.lossSpeedup) +
                                    ") for the adaptive drive");
    if (openingControl() != (load_.openingRate > 0))
        throw std::invalid_argument(openingControl() ? "opening control (a controlled probe) needs opening_rate > 0"
                                                     : "opening_rate needs a controlled probe (measure.control)");
    servo_.rate = load_.openingRate, servo_.gain = 0.5 * Df_;
    splitWindow_ = run_.splitWindow > 0 ? run_.splitWindow : 2 * period1;
    if (run_.recordEvery > 0) {
        recordEvery_ = run_.recordEvery;
    } else {  // a record per eps_p/50 of mean strain at the initial rate: about 100 before the peak
        const double rowTime = mat_.epsP / 50 * meas_.gaugeLength / (drive_.v0 * std::abs(meas_.meanDriveWeight));
        recordEvery_ = std::max(1, int(rowTime / dt_));
    }

    tail_ = AdaptiveDrive(tailLimits());  // needs dt_, recordEvery_, splitWindow_

    // Random G_f -> the law's per-bar parameters (the field itself is not kept).
    {
        law_ = makeBarLaw(std::size_t(mat_.law), lat_, mat_, fractureEnergyField());
        // each bar counted by the rank that owns it
        clamped_ = commOf(lat_).sum(std::visit([](const auto& law) { return law.clampedOwnedBars(); }, law_));
        const auto owned = lat_.ownedBars();
        std::int64_t nodes = 0;
        for (int m = lat_.ownBegin; m < lat_.ownEnd; ++m) nodes += lat_.layerNodes(m).second;
        totalBars_ = commOf(lat_).sum(owned.second - owned.first), totalNodes_ = commOf(lat_).sum(nodes);
    }
    u_ = v_ = f_ = Field3(lat_.numNodes());
    preSlot_ = ownedLayerSlots(lat_, pre_.node), supportSlot_ = ownedLayerSlots(lat_, *support_);
    cd_ = CentralDifference(dt_, Df_);
    layerDamping_.assign(lat_.numLayers(), 0.0);
}

std::vector<double> Simulation::fractureEnergyField() const {
    return ldem::fractureEnergyField(lat_, mat_, run_.seed);
}

std::vector<double> Simulation::ruptureEnergies() const {
    std::vector<double> e(lat_.numBars());
    std::visit([&](const auto& law) {
        forEachBar(lat_, [&](std::int64_t b, std::int32_t, std::int32_t, const BarRow& row, int p) {
            const BarFamily& fam = lat_.families[row.family];
            e[b] = law.ruptureEnergy(b, fam.EA * row.shareAt(p), fam.L);
        });
    }, law_);
    return e;
}

std::vector<double> Simulation::barForces() const {
    const std::vector<double> eps = barStrains(lat_, u_);
    std::vector<double> f(lat_.numBars());
    std::visit([&](const auto& law) {
        forEachBar(lat_, [&](std::int64_t b, std::int32_t, std::int32_t, const BarRow& row, int p) {
            f[b] = law.force(b, lat_.families[row.family].EA * row.shareAt(p), eps[b]);
        });
    }, law_);
    return f;
}

const std::vector<double>& Simulation::barArray(const std::string& name) const {
    return std::visit([&](const auto& law) -> const std::vector<double>& {
        for (const auto& [key, values] : law.arrays())
            if (key == name) return *values;
        throw std::invalid_argument("the bar law has no per-bar array '" + name + "'");
    }, law_);
}

double Simulation::lawConstant(const std::string& name) const {
    return std::visit([&](const auto& law) {
        for (const auto& [key, value] : law.constants())
            if (key == name) return value;
        throw std::invalid_argument("the bar law has no constant '" + name + "'");
    }, law_);
}

std::vector<std::uint8_t> Simulation::damageStates() const {
    std::vector<std::uint8_t> s(lat_.numBars());
    std::visit([&](const auto& law) {
        for (std::size_t b = 0; b < s.size(); ++b) s[b] = std::uint8_t(law.damage(std::int64_t(b)));
    }, law_);
    return s;
}

double Simulation::stableTimeStepLimit() const { return run_.dtSafety * stableTimeStep(freq_.omegaMax); }

void Simulation::computeForces() {
    std::visit([&](auto& law) { computeInternalForces(lat_, u_, law, g_, f_); }, law_);
}

const std::vector<std::int32_t>& Simulation::group(const std::string& name) const {
    const auto it = groups_.find(name);
    if (it == groups_.end()) throw std::invalid_argument("the specimen has no node group '" + name + "'");
    return it->second;
}

double Simulation::groupForce(const std::vector<std::int32_t>& nodes) const {
    const std::vector<double>& f = meas_.dim == 0 ? f_.x : meas_.dim == 1 ? f_.y : f_.z;
    return listSum(lat_, nodes.size(), [&](std::size_t k) { return nodes[k]; },
                   [&](std::size_t k) { return f[nodes[k]]; });
}

// 0 + x: +0, never -0, when a pushed specimen's force is 0 (curve.csv's first row).
double Simulation::supportStress() const { return (0.0 + meas_.sense() * groupForce(*support_)) / meas_.area; }

bool Simulation::facesJoined() const {
    const std::vector<std::uint8_t> intact = std::visit([&](const auto& law) { return intactBars(lat_, law); }, law_);
    return nodesJoined(lat_, intact, *loaded_, *support_);
}

// u[b] - u[a], read on the ranks that own b and a (a slab's probe node held
// elsewhere is -1); the sum of +u[b] and -u[a] is exact in either order.
double Simulation::probe(const Probe& q) const {
    const std::vector<double>& u = q.dim == 0 ? u_.x : q.dim == 1 ? u_.y : u_.z;
    std::int32_t nodes[2];
    double values[2];
    std::size_t n = 0;
    if (q.b >= 0) nodes[n] = q.b, values[n++] = u[q.b];
    if (q.a >= 0) nodes[n] = q.a, values[n++] = -u[q.a];
    return listSum(lat_, n, [&](std::size_t k) { return nodes[k]; }, [&](std::size_t k) { return values[k]; });
}

CurvePoint Simulation::measure() const {
    CurvePoint p;
    p.step = step_;
    p.time = time_;
    p.meanStrain = meanStrainOf(driveNow());
    p.stress = supportStress();
    p.stressLoaded = (0.0 - meas_.sense() * groupForce(*loaded_)) / meas_.area;  // 0 - x: +0, never -0, when x is 0
    for (const Probe& q : meas_.probes) p.probes.push_back(probe(q));
    const BarEnergies e = barEnergies(lat_, u_, law_);
    p.elastic = e.elastic, p.fracture = e.fracture, p.damaged = e.damaged, p.broken = e.broken;
    p.kinetic = kineticEnergy(lat_, pre_.mask, v_);
    p.externalWork = externalWork_;
    p.damping = dampingWork_;
    return p;
}

void Simulation::step() {
    // One visit of the law per step: the layered pass is compiled for it.
    std::visit([this](auto& law) {
        layeredForces(lat_, u_, g_, f_, law.rows(), [this](int m) { layerDamping_[m] = advanceNodes(m); });
    }, law_);
    finishStep();
}

void Simulation::advance() {
#pragma omp parallel for schedule(static)
    for (int m = 0; m < lat_.numLayers(); ++m) layerDamping_[m] = advanceNodes(m);
    finishStep();
}

// Advances the owned nodes of layer m; the halo's are moved by their owner.
double Simulation::advanceNodes(int m) {
    return lat_.owns(m) ? advanceLayer(lat_, m, cd_, pre_.mask, f_, u_, v_) : 0.0;
}

void Simulation::finishStep() {
    // External work of the prescribed DOFs over the centred increment
    // (x(n+1) - x(n-1))/2: the drive holds each against the bars with -f.
    // Under opening control the servo moves U from state n (its opening is that of state n).
    const double tNext = time_ + dt_, Uback = driveBefore(), Unow = driveNow();
    if (openingControl()) servo_.advance(dt_, time_, opening_, drive_);
    else if (tail_.active()) tail_.advance(dt_, drive_.v0, int(step_ % recordEvery_), recordEvery_);
    const double Unext = openingControl() ? servo_.U : tail_.active() ? tail_.U : drive_.displacement(tNext);
    const double centred = 0.5 * (Unext - Uback);
    // Per owned layer: damping work, external work, support reaction (state n);
    // one exchange of them per step, added in layer order: the same sums for
    // any number of threads and ranks (Slab.hpp).
    const int owned = lat_.ownEnd - lat_.ownBegin;
    std::vector<double>& partial = stepPartials_;
    partial.assign(3 * std::size_t(owned), 0.0);
    for (int i = 0; i < owned; ++i) partial[3 * std::size_t(i)] = layerDamping_[lat_.ownBegin + i];
    addBySlot(partial, 3, 1, preSlot_, [&](std::size_t k) {
        const int d = pre_.dim[k];
        return -(d == 0 ? f_.x : d == 1 ? f_.y : f_.z)[pre_.node[k]] * pre_.weight[k] * centred;
    });
    const std::vector<double>& fm = meas_.dim == 0 ? f_.x : meas_.dim == 1 ? f_.y : f_.z;
    addBySlot(partial, 3, 2, supportSlot_, [&](std::size_t k) { return fm[(*support_)[k]]; });
    const std::vector<double> sums = gatherLayerSums(commOf(lat_), partial, 3);
    dampingWork_ += sums[0];
    externalWork_ += sums[1];
    stressBefore_ = (0.0 + meas_.sense() * sums[2]) / meas_.area;  // = supportStress() of state n, bit for bit
    for (std::size_t k = 0; k < pre_.node.size(); ++k) {
        const auto n = pre_.node[k];
        const int d = pre_.dim[k];
        const double w = pre_.weight[k];
        (d == 0 ? u_.x : d == 1 ? u_.y : u_.z)[n] = w * Unext;
        (d == 0 ? v_.x : d == 1 ? v_.y : v_.z)[n] = w * (Unext - Unow) / dt_;
    }
    exchangeHalo(lat_, u_);  // the neighbours' layers next to mine, moved by them
    time_ = tNext;
    ++step_;
    if (openingControl()) opening_ = probe(meas_.probes[meas_.control]);
}

Checkpoint Simulation::checkpoint() const {
    if (lat_.isSlab()) throw std::logic_error("checkpoints of a run split over MPI ranks are not supported");
    if (!progress_.pendingAdvance && progress_.summary.stopReason.empty())
        throw std::logic_error("a checkpoint is taken at a record: from run()'s observer, or once run() returned");
    Checkpoint c{u_, v_, f_, {}, {}, time_, externalWork_, dampingWork_,
                 drive_.speedupStart, servo_.U, servo_.Uprev, step_, progress_, {}};
    if (tail_.active()) c.tailDrive = tail_.state();
    std::visit([&](const auto& law) {
        for (const auto& [name, values] : law.arrays()) c.bars.emplace_back(name, *values);
        c.softening = law.softeningRows();
    }, law_);
    return c;
}

void Simulation::restore(const Checkpoint& c) {
    if (lat_.isSlab()) throw std::invalid_argument("restarts of a run split over MPI ranks are not supported");
    const std::size_t n = std::size_t(lat_.numNodes()), b = std::size_t(lat_.numBars());
    bool sizesMatch = c.u.x.size() == n && c.v.x.size() == n && c.f.x.size() == n &&
                      c.softening.size() == lat_.barRows.size();
    for (const auto& [name, values] : c.bars) sizesMatch = sizesMatch && values.size() == b;
    if (!sizesMatch) throw std::invalid_argument("the checkpoint is of another specimen (its sizes differ)");
    std::visit([&](auto& law) {
        const auto arrays = law.arrays();
        bool sameLaw = arrays.size() == c.bars.size();
        for (std::size_t k = 0; sameLaw && k < arrays.size(); ++k) sameLaw = arrays[k].first == c.bars[k].first;
        if (!sameLaw) throw std::invalid_argument("the checkpoint is of another bar law (its per-bar arrays differ)");
        for (std::size_t k = 0; k < arrays.size(); ++k) *arrays[k].second = c.bars[k].second;
        law.softeningRows() = c.softening;
    }, law_);
    u_ = c.u, v_ = c.v, f_ = c.f;
    time_ = c.time, externalWork_ = c.externalWork, dampingWork_ = c.dampingWork;
    drive_.speedupStart = c.speedupStart, step_ = c.step;
    servo_.U = c.servoU, servo_.Uprev = c.servoUprev;
    tail_ = AdaptiveDrive(tailLimits());
    if (!c.tailDrive.empty()) tail_.setState(c.tailDrive);
    if (openingControl()) opening_ = probe(meas_.probes[meas_.control]);
    progress_ = c.progress;
    progress_.summary.stopReason.clear();  // a finished run set back to its last record goes on
    progress_.pendingAdvance = true;
}

bool EnergyConvergence::update(double meanStrain, double fracture, bool loadLost) {
    if (rungStrain_ == 0) {  // the load-loss record: the first rung
        rungStrain_ = meanStrain, rungFracture_ = fracture;
        return false;
    }
    if (meanStrain < 2 * rungStrain_) return false;
    const bool quiet = loadLost && fracture - rungFracture_ < growth_ * fracture;
    quiet_ = quiet ? quiet_ + 1 : 0;
    rungStrain_ = meanStrain, rungFracture_ = fracture;
    return quiet_ >= quietRungs;
}

RunSummary Simulation::run(const std::function<bool(const CurvePoint&)>& observer) {
    setThreads(threads_);
    RunProgress& g = progress_;
    if (!g.started) {
        g = RunProgress();
        g.loadLoss = LoadLossDetector(splitWindow_, run_.stopFraction);
        g.convergence = EnergyConvergence(run_.convergedGrowth);
        g.lastCheck = -kSeparationCheckSteps;
        g.started = true;
    } else if (!g.pendingAdvance) {
        throw std::invalid_argument("this specimen has already run: build a new one (or restore a checkpoint)");
    }
    RunSummary& s = g.summary;
    // The peak, at every step: the stress of state n is known once its forces are.
    auto trackPeak = [&](double stress, double U) {
        if (stress <= s.peakStress) return;
        s.peakStress = stress;
        s.strainAtPeak = meanStrainOf(U);
        s.edgeStrainAtPeak = U / meas_.gaugeLength;
    };
    if (g.pendingAdvance) {  // restored at a record: the rest of that step
        g.pendingAdvance = false;
        advance();
    }
    InterruptCheck interruptPoint;
    for (;;) {
        if (step_ % recordEvery_ != 0) {
            step();
            trackPeak(stressBefore_, driveBefore());
            interruptPoint();  // a signal may stop here, between records (a checkpoint needs a record)
            continue;
        }
        // A record step: forces, measure state n, then the rest of the step.
        computeForces();
        trackPeak(supportStress(), driveNow());
        const CurvePoint p = measure();
        const double total = p.kinetic + p.elastic + p.fracture + p.damping;
        // Energy from nothing (kinetic above all the work put in) or NaN: the
        // integration is unstable; stop before it writes garbage.
        if (!std::isfinite(total) || !std::isfinite(p.stress) ||
            p.kinetic > 1.5 * p.externalWork + 1e-9 * (1 + g.maxEnergy)) {
            std::ostringstream msg;
            msg << "numerical instability at step " << step_ << " (t = " << time_ << " s): kinetic energy "
                << p.kinetic << " J against external work " << p.externalWork << " J; dt = " << dt_
                << " s, stability limit " << stableTimeStep(freq_.omegaMax) << " s";
            throw InstabilityError(msg.str());
        }
        // The balance is measured against the largest energy in play, not the
        // work alone: energy that appears without work (a drive that jumps
        // past the bars' elastic branch in a step, before any force did work)
        // is then an error of 1, not 0/0.
        g.maxEnergy = std::max({g.maxEnergy, p.externalWork, total});
        g.maxResidual = std::max(g.maxResidual, std::abs(p.balanceResidual()));
        s.fractureEnergy = p.fracture;
        s.steps = step_;
        const bool lost = g.loadLoss.update(p.time, p.stress, s.peakStress, p.broken);
        if (!s.loadLoss.reached() && lost) {
            s.loadLoss = {p.step, p.time, p.meanStrain, p.fracture};
            drive_.speedupStart = time_;
        }
        // The adaptive drive: from the end of the fixed ramp to the floor on, it picks
        // the velocity of the next record interval from state n. Undamped (D_f = 0)
        // the drive stays fixed: nothing would damp the ringing its changes of speed
        // set off (measured, 0.08 m on rollers, zeta 0: balance error 0.015 against
        // 0.008 fixed, and another path to separation).
        if (load_.tailDrive == TailDrive::Adaptive && !openingControl() && Df_ > 0 && !tail_.active() &&
            s.loadLoss.reached() && time_ >= drive_.speedupStart + drive_.rampTime)
            tail_.start(driveNow(), driveBefore(), p.fracture);
        if (tail_.active()) tail_.record(p.time, p.fracture, p.stress, s.peakStress);
        if (run_.stopAt == StopAt::Converged && s.loadLoss.reached() && !s.converged.reached() &&
            g.convergence.update(p.meanStrain, p.fracture, lost))
            s.converged = {p.step, p.time, p.meanStrain, p.fracture};
        if (p.broken > 0 && p.stress < 0.5 * s.peakStress && step_ - g.lastCheck >= kSeparationCheckSteps) {
            g.lastCheck = step_;
            if (!facesJoined()) s.separation = {p.step, p.time, p.meanStrain, p.fracture};
        }
        // The record is complete: what the observer sees (and may checkpoint) is state n with its events.
        g.pendingAdvance = true;
        // Rank 0's answer for every rank (an observer that stops on one rank alone would leave the others waiting).
        const bool keepGoing = commOf(lat_).broadcast(!observer || observer(p));
        g.pendingAdvance = false;
        if (s.separation.reached()) s.stopReason = "separated";
        else if (run_.stopAt == StopAt::LoadLoss && s.loadLoss.reached()) s.stopReason = "load_lost";
        else if (s.converged.reached()) s.stopReason = "converged";
        else if (p.meanStrain >= run_.finalStrain) s.stopReason = "final_strain";
        else if (!keepGoing) s.stopReason = "stopped";
        if (!s.stopReason.empty()) break;
        advance();
    }
    s.energyBalanceError = g.maxEnergy > 0 ? g.maxResidual / g.maxEnergy : 0.0;  // 0: nothing moved
    s.energyError = s.energyBalanceError > run_.energyTolerance;
    return s;
}

}  // namespace ldem
