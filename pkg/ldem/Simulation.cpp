#include "ldem/Simulation.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "ldem/Integrator.hpp"
#include "ldem/Interrupt.hpp"
#include "ldem/Parallel.hpp"
#include "ldem/RandomField.hpp"
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
    refuseMechanism(freq_);
    load_ = drivenLoading(mat_, load_, run_, freq_.omega1, lat_.L0);
    parts_ = Parts(mat_, load_, run_, {freq_.omega1, freq_.omegaMax, lat_.numBars(), lat_.numLayers(),
                                       meas_.gaugeLength, openingControl()});
    const double limit = stableTimeStepLimit();
    if (run_.dt > limit) {
        std::ostringstream msg;
        msg << "time step " << run_.dt << " s is above the stability limit " << limit << " s (" << run_.dtSafety
            << " x 2/omega_max x " << parts_.stepFactor() << " for zeta_high, omega_max = " << freq_.omegaMax
            << " rad/s)";
        throw std::invalid_argument(msg.str());
    }
    dt_ = run_.dt > 0 ? run_.dt : limit;
    // A record per eps_p/50 of mean strain at the drive's initial rate: about 100 before the peak.
    const double rowTime = mat_.epsP / 50 * meas_.gaugeLength / (drive().v0 * std::abs(meas_.meanDriveWeight));
    const int defaultEvery = std::max(1, int(rowTime / dt_));
    recordEvery_ = run_.recordEvery > 0 ? run_.recordEvery : defaultEvery;
    // (the first record at the default interval: a run recorded seldom on purpose still runs)
    parts_.setUp({dt_, recordEvery_, mat_.epsP, meanStrainOf(drive().displacement(defaultEvery * dt_))});
    weightRise_ = drive().rampTime;

    law_ = makeBarLaw(mat_.law, lat_, mat_, fractureEnergyField());  // G_f drawn, realised, not kept
    clamped_ = commOf(lat_).sum(std::visit([](const auto& law) { return law.clampedOwnedBars(); }, law_));
    const auto owned = lat_.ownedBars();  // each bar and node counted by the rank that owns it
    std::int64_t nodes = 0;
    for (int m = lat_.ownBegin; m < lat_.ownEnd; ++m) nodes += lat_.layerNodes(m).second;
    totalBars_ = commOf(lat_).sum(owned.second - owned.first), totalNodes_ = commOf(lat_).sum(nodes);
    refuseAllBrittle(clamped_, totalBars_, mat_, lat_.L0);
    u_ = v_ = f_ = Field3(lat_.numNodes());
    preSlot_ = ownedLayerSlots(lat_, pre_.node), supportSlot_ = ownedLayerSlots(lat_, *support_);
    loadedSlot_ = ownedLayerSlots(lat_, *loaded_);
    cd_ = nodeRule();
    layerDamping_.assign(lat_.numLayers(), 0.0);
}

// The node update of the dampings, with the free DOFs' weight under gravity (along -z).
CentralDifference Simulation::nodeRule() {
    CentralDifference cd = parts_.nodeUpdate(dt_);
    cd.gz = gz_;
    return cd;
}

// g_z of step n: the weight rises over the drive's smooth start as (1 - cos(pi t/t_r))/2,
// t = n dt. Laid on its supports at once, a specimen would ring in its
// fundamental by its whole static sag (a beam's load by +-100 N on a 1 kN
// peak, decaying as 1/(zeta omega_1)); over two periods the ringing left is
// about 1/((omega_1 t_r/pi)^2 - 1) = 7 % of the sag.
double Simulation::weightAt(std::int64_t n) const {
    return -run_.gravity * smoothRampVelocity(double(n) * dt_, weightRise_);
}

// The weight for the step about to be taken (step_). Its work, sum_n m g_n
// (x(n+1) - x(n-1))/2, summed by parts: g_N Y_N - sum_n (g_{n+1} - g_n) Y_n
// with Y_n = sum m (x(n+1) + x(n))/2, the last step's term being weightWork
// (measure); each change of g puts its term into the external work here,
// where u - dt v/2 is (x(n+1) + x(n))/2.
void Simulation::weighNextStep() {
    const double gz = weightAt(step_);
    if (gz == gz_) return;
    externalWork_ -= weightWork(lat_, pre_.mask, gz - gz_, dt_, u_, v_);
    gz_ = cd_.gz = gz;
}

double Simulation::stableTimeStepLimit() const {
    return run_.dtSafety * stableTimeStep(freq_.omegaMax) * parts_.stepFactor();
}

void Simulation::computeForces() {
    layered([](int) {});
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
    p.meanStrain = meanStrainOf(parts_.now(time_, dt_));
    // The mean over the states since the last record and this one: the impulse
    // through each group over the record interval, over the interval (a load
    // cell's reading), never one step's sample (the top of the ringing).
    p.stress = (cellSupport_ + supportStress()) / (cellStates_ + 1);
    p.stressLoaded = (cellLoaded_ + (0.0 - meas_.sense() * groupForce(*loaded_)) / meas_.area) / (cellStates_ + 1);
    for (const Probe& q : meas_.probes) p.probes.push_back(probe(q));
    const BarEnergies e = barEnergies(lat_, u_, law_);
    p.elastic = e.elastic, p.fracture = e.fracture, p.damaged = e.damaged, p.broken = e.broken;
    p.kinetic = kineticEnergy(lat_, pre_.mask, v_);
    const double U = parts_.now(time_, dt_);
    p.kineticOwn = ownKineticEnergy(lat_, pre_.mask, u_, v_, U != 0 ? (U - parts_.before(time_, dt_)) / (dt_ * U) : 0.0);
    // The weight's work is the drive's companion: the external work (Integrator.hpp, weightWork).
    p.externalWork = externalWork_ + weightWork(lat_, pre_.mask, gz_, dt_, u_, v_);
    // With the bars' dashpots, the last step's work is whole once this step's bars know v(n-1/2) (BarDashpot.hpp).
    std::vector<double> closing(std::size_t(lat_.ownEnd - lat_.ownBegin));
    for (std::size_t i = 0; i < closing.size(); ++i) closing[i] = parts_.closingWork(lat_.ownBegin + int(i));
    p.damping = dampingWork_ + gatherLayerSums(commOf(lat_), closing, 1)[0];
    return p;
}

void Simulation::step() {
    weighNextStep();
    // One visit of the law per step: the layered pass is compiled for it.
    layered([this](int m) { layerDamping_[m] = advanceNodes(m); });
    finishStep();
}

void Simulation::advance() {
    weighNextStep();
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
    const double tNext = time_ + dt_, Uback = parts_.before(time_, dt_), Unow = parts_.now(time_, dt_);
    const DriveStep next{time_, dt_, int(step_ % recordEvery_), recordEvery_, opening_};
    const double Unext = parts_.next(next);
    const double centred = 0.5 * (Unext - Uback);
    // Per owned layer: damping work, external work, support reaction (state n);
    // one exchange of them per step, added in layer order: the same sums for
    // any number of threads and ranks (Slab.hpp).
    const int owned = lat_.ownEnd - lat_.ownBegin;
    std::vector<double>& partial = stepPartials_;
    partial.assign(4 * std::size_t(owned), 0.0);
    for (int i = 0; i < owned; ++i) {
        const int m = lat_.ownBegin + i;
        const double bars = parts_.stepWork(m);
        partial[4 * std::size_t(i)] = bars != 0 ? layerDamping_[m] + bars : layerDamping_[m];
    }
    addBySlot(partial, 4, 1, preSlot_, [&](std::size_t k) {
        const int d = pre_.dim[k];
        return -(d == 0 ? f_.x : d == 1 ? f_.y : f_.z)[pre_.node[k]] * pre_.weight[k] * centred;
    });
    const std::vector<double>& fm = meas_.dim == 0 ? f_.x : meas_.dim == 1 ? f_.y : f_.z;
    addBySlot(partial, 4, 2, supportSlot_, [&](std::size_t k) { return fm[(*support_)[k]]; });
    addBySlot(partial, 4, 3, loadedSlot_, [&](std::size_t k) { return fm[(*loaded_)[k]]; });
    const std::vector<double> sums = gatherLayerSums(commOf(lat_), partial, 4);
    dampingWork_ += sums[0];
    externalWork_ += sums[1];
    if (step_ % recordEvery_ == 0) {  // the record's state n was its interval's last: a new interval
        cellSupport_ = cellLoaded_ = 0, cellStates_ = 0;
    } else {
        cellSupport_ += (0.0 + meas_.sense() * sums[2]) / meas_.area;  // = supportStress() of state n, bit for bit
        cellLoaded_ += (0.0 - meas_.sense() * sums[3]) / meas_.area;
        ++cellStates_;
    }
    for (std::size_t k = 0; k < pre_.node.size(); ++k) {
        const auto n = pre_.node[k];
        const int d = pre_.dim[k];
        const double w = pre_.weight[k];
        (d == 0 ? u_.x : d == 1 ? u_.y : u_.z)[n] = w * Unext;
        (d == 0 ? v_.x : d == 1 ? v_.y : v_.z)[n] = w * (Unext - Unow) / dt_;
    }
    exchangeHalo(lat_, u_);  // the neighbours' layers next to mine, moved by them
    // The bars' dashpots read v(n+1/2) at both ends of a bar (BarDashpot.hpp): the halo's too.
    if (parts_.barPass(v_).state) exchangeHalo(lat_, v_);
    time_ = tNext;
    ++step_;
    if (openingControl()) opening_ = probe(meas_.probes[meas_.control]);
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
    const std::size_t n = std::size_t(lat_.numNodes()), b = std::size_t(lat_.numBars());
    bool sizesMatch = c.u.x.size() == n && c.v.x.size() == n && c.f.x.size() == n &&
                      c.softening.size() == lat_.barRows.size();
    for (const auto& [name, values] : c.bars) sizesMatch = sizesMatch && values.size() == b;
    if (!sizesMatch) throw std::invalid_argument("the checkpoint is of another specimen (its sizes differ)");
    parts_.setStates(c.parts);
    setLawState(law_, c.bars, c.softening);
    u_ = c.u, v_ = c.v, f_ = c.f;
    time_ = c.time, externalWork_ = c.externalWork, dampingWork_ = c.dampingWork, step_ = c.step;
    gz_ = step_ > 0 ? weightAt(step_ - 1) : 0.0;  // the last step's
    cd_ = nodeRule();
    if (openingControl()) opening_ = probe(meas_.probes[meas_.control]);
    progress_ = c.progress;
    progress_.summary.stopReason.clear();  // a finished run set back to its last record goes on
    progress_.pendingAdvance = true;
}

RunSummary Simulation::run(const std::function<bool(const CurvePoint&)>& observer) {
    setThreads(threads_);
    RunProgress& g = progress_;
    if (!g.started) {
        g = RunProgress();
        g.started = true;
    } else if (!g.pendingAdvance) {
        throw std::invalid_argument("this specimen has already run: build a new one (or restore a checkpoint)");
    }
    RunSummary& s = g.summary;
    // The peak: the largest record, a load cell's mean over its interval
    // (measure()), at the drive's displacement at the record.
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
            interruptPoint();  // a signal may stop here, between records (a checkpoint needs a record)
            continue;
        }
        // A record step: forces, measure state n, then the rest of the step.
        computeForces();
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
        trackPeak(p.stress, parts_.now(time_, dt_));  // a record that passed the check: an unstable one is no peak
        // The balance is measured against the largest energy in play, not the
        // work alone: energy that appears without work (a drive that jumps
        // past the bars' elastic branch in a step, before any force did work)
        // is then an error of 1, not 0/0.
        g.maxEnergy = std::max({g.maxEnergy, p.externalWork, total});
        g.maxResidual = std::max(g.maxResidual, std::abs(p.balanceResidual()));
        s.fractureEnergy = p.fracture;
        s.steps = step_;
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
    s.energyBalanceError = g.maxEnergy > 0 ? g.maxResidual / g.maxEnergy : 0.0;  // 0: nothing moved
    s.energyError = s.energyBalanceError > run_.energyTolerance;
    return s;
}

}  // namespace ldem
