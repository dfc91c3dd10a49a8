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
    // A mechanism (a motion that stretches no bar) has omega_1 = 0: no damping
    // (D_f = 2 zeta omega_1), an infinite smooth start, NaN at once.
    if (!(freq_.omega1 > 1e-6 * freq_.omegaMax)) {
        std::ostringstream msg;
        msg << "the constraints leave a mechanism: omega_1 = " << freq_.omega1 << " rad/s (omega_max = "
            << freq_.omegaMax << " rad/s); e.g. one module with a laterally free upper face turns about the "
            << "vertical axis: use at least 2 modules a side or hold the upper face laterally";
        throw std::invalid_argument(msg.str());
    }
    if (load_.ratePeriods > 0) {  // rule (c) as the rate: from the specimen's own omega_1 (QuasiStatic.hpp)
        load_.strainRate = rateForPeriods(load_.ratePeriods, mat_.epsP, freq_.omega1);
        checkRelations(mat_, load_, run_, lat_.L0);  // the smooth start against the rate driven
    }
    dampings_ = makeDampings(run_, DampingSetup{freq_.omega1, freq_.omegaMax, lat_.numBars(), lat_.numLayers()});
    const double limit = stableTimeStepLimit();
    if (run_.dt > limit) {
        std::ostringstream msg;
        msg << "time step " << run_.dt << " s is above the stability limit " << limit << " s (" << run_.dtSafety
            << " x 2/omega_max x " << stepFactor(dampings_) << " for zeta_high, omega_max = " << freq_.omegaMax
            << " rad/s)";
        throw std::invalid_argument(msg.str());
    }
    dt_ = run_.dt > 0 ? run_.dt : limit;
    const double pi = 3.14159265358979323846;
    splitWindow_ = run_.splitWindow > 0 ? run_.splitWindow : 2 * (2 * pi / freq_.omega1);
    DynamicsSetup setup{freq_.omega1, dt_, meas_.gaugeLength, splitWindow_, 1, openingControl()};
    {  // a record per eps_p/50 of mean strain at the initial rate: about 100 before the peak
        const double v0 = fixedDrive(load_, setup).program().v0;
        const double rowTime = mat_.epsP / 50 * meas_.gaugeLength / (v0 * std::abs(meas_.meanDriveWeight));
        defaultRecordEvery_ = std::max(1, int(rowTime / dt_));
        recordEvery_ = run_.recordEvery > 0 ? run_.recordEvery : defaultRecordEvery_;
    }
    setup.recordEvery = recordEvery_;
    drive_ = makeDrive(load_, mat_, setup, dampings_);
    weightRise_ = fixedDrive(load_, setup).program().rampTime;
    loadLoss_ = LoadLossDetector(splitWindow_, run_.stopFraction);
    stops_ = makeStops(run_);

    // Random G_f -> the law's per-bar parameters (the field itself is not kept).
    {
        law_ = makeBarLaw(mat_.law, lat_, mat_, fractureEnergyField());
        // each bar counted by the rank that owns it
        clamped_ = commOf(lat_).sum(std::visit([](const auto& law) { return law.clampedOwnedBars(); }, law_));
        const auto owned = lat_.ownedBars();
        std::int64_t nodes = 0;
        for (int m = lat_.ownBegin; m < lat_.ownEnd; ++m) nodes += lat_.layerNodes(m).second;
        totalBars_ = commOf(lat_).sum(owned.second - owned.first), totalNodes_ = commOf(lat_).sum(nodes);
        if (clamped_ == totalBars_)  // no bar left to soften: a lattice of perfectly brittle bars is no model of concrete
            throw std::invalid_argument("every bar is perfectly brittle: all " + std::to_string(totalBars_) +
                                        " drew a G_f below E A eps_p^2 L / (2 A_f) (" +
                                        formatNumber(brittleFractureEnergy(mat_, lat_.L0, false)) +
                                        " N/m for a normal bar), with Gf_mean " + formatNumber(mat_.GfMean) +
                                        " N/m: raise Gf_mean or c_a (the bound goes as 1 / c_a)");
    }
    u_ = v_ = f_ = Field3(lat_.numNodes());
    preSlot_ = ownedLayerSlots(lat_, pre_.node), supportSlot_ = ownedLayerSlots(lat_, *support_);
    loadedSlot_ = ownedLayerSlots(lat_, *loaded_);
    cd_ = nodeRule();
    layerDamping_.assign(lat_.numLayers(), 0.0);
}

// The node update of the dampings, with the free DOFs' weight under gravity (along -z).
CentralDifference Simulation::nodeRule() {
    CentralDifference cd = nodeUpdate(dampings_, dt_);
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

double Simulation::stableTimeStepLimit() const {
    return run_.dtSafety * stableTimeStep(freq_.omegaMax) * stepFactor(dampings_);
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

double Simulation::ownedLayerSum(const std::function<double(int)>& ofLayer) const {
    std::vector<double> owned(std::size_t(lat_.ownEnd - lat_.ownBegin));
    for (std::size_t i = 0; i < owned.size(); ++i) owned[i] = ofLayer(lat_.ownBegin + int(i));
    return gatherLayerSums(commOf(lat_), owned, 1)[0];
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
    // The mean over the states since the last record and this one: the impulse
    // through each group over the record interval, over the interval (a load
    // cell's reading), never one step's sample (the top of the ringing).
    p.stress = (cellSupport_ + supportStress()) / (cellStates_ + 1);
    p.stressLoaded = (cellLoaded_ + (0.0 - meas_.sense() * groupForce(*loaded_)) / meas_.area) / (cellStates_ + 1);
    for (const Probe& q : meas_.probes) p.probes.push_back(probe(q));
    const BarEnergies e = barEnergies(lat_, u_, law_);
    p.elastic = e.elastic, p.fracture = e.fracture, p.damaged = e.damaged, p.broken = e.broken;
    p.kinetic = kineticEnergy(lat_, pre_.mask, v_);
    const double U = driveNow();
    p.kineticOwn = ownKineticEnergy(lat_, pre_.mask, u_, v_, U != 0 ? (U - driveBefore()) / (dt_ * U) : 0.0);
    // The weight's work is the drive's companion: the external work (Integrator.hpp, weightWork).
    p.externalWork = externalWork_ + weightWork(lat_, pre_.mask, gz_, dt_, u_, v_);
    // With the bars' dashpots, the last step's work is whole once this step's bars know v(n-1/2) (BarDashpot.hpp).
    p.damping = dampingWork_ + ownedLayerSum([&](int m) { return sumOver(dampings_, [m](const auto& d) { return d.closingWork(m); }); });
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
    const double tNext = time_ + dt_, Uback = driveBefore(), Unow = driveNow();
    const DriveStep next{time_, dt_, int(step_ % recordEvery_), recordEvery_, opening_};
    const double Unext = std::visit([&](auto& d) { return d.next(next); }, drive_);
    const double centred = 0.5 * (Unext - Uback);
    // Per owned layer: damping work, external work, support reaction (state n);
    // one exchange of them per step, added in layer order: the same sums for
    // any number of threads and ranks (Slab.hpp).
    const int owned = lat_.ownEnd - lat_.ownBegin;
    std::vector<double>& partial = stepPartials_;
    partial.assign(4 * std::size_t(owned), 0.0);
    for (int i = 0; i < owned; ++i) {
        const int m = lat_.ownBegin + i;
        const double bars = sumOver(dampings_, [m](const auto& d) { return d.stepWork(m); });
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
    stressBefore_ = (0.0 + meas_.sense() * sums[2]) / meas_.area;  // = supportStress() of state n, bit for bit
    if (step_ % recordEvery_ == 0) {  // the record's state n was its interval's last: a new interval
        cellSupport_ = cellLoaded_ = 0, cellStates_ = 0;
    } else {
        cellSupport_ += stressBefore_, cellLoaded_ += (0.0 - meas_.sense() * sums[3]) / meas_.area;
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
    if (barPass(dampings_, v_).state) exchangeHalo(lat_, v_);
    time_ = tNext;
    ++step_;
    if (openingControl()) opening_ = probe(meas_.probes[meas_.control]);
}

// Each part's state, by role and name: the drive, the load-loss test, the stop rules, the dampings, the quasi-static flag.
namespace {
template <class Parts>
std::vector<std::pair<std::string, std::vector<double>>> partStates(const Drives& drive, const LoadLossDetector& loss,
                                                                    const std::vector<StopRules>& stops,
                                                                    const Parts& dampings, const KineticAtPeak& k) {
    std::vector<std::pair<std::string, std::vector<double>>> s;
    s.push_back(std::visit([](const auto& d) { return partState("drive", d); }, drive));
    s.push_back(partState("test", loss));
    for (const StopRules& r : stops) s.push_back(std::visit([](const auto& x) { return partState("stop", x); }, r));
    std::apply([&](const auto&... d) { (s.push_back(partState("damping", d)), ...); }, dampings);
    s.emplace_back("quasi_static", k.state());
    return s;
}
}  // namespace

std::vector<std::string> Simulation::partNames() const {
    std::vector<std::string> names;
    for (const auto& [name, state] : partStates(drive_, loadLoss_, stops_, dampings_, kineticAtPeak_))
        names.push_back(name);
    return names;
}

Checkpoint Simulation::checkpoint() const {
    if (lat_.isSlab()) throw std::logic_error("checkpoints of a run split over MPI ranks are not supported");
    if (!progress_.pendingAdvance && progress_.summary.stopReason.empty())
        throw std::logic_error("a checkpoint is taken at a record: from run()'s observer, or once run() returned");
    Checkpoint c{u_, v_, f_, {}, {}, time_, externalWork_, dampingWork_, step_, progress_,
                 partStates(drive_, loadLoss_, stops_, dampings_, kineticAtPeak_)};
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
    std::vector<std::string> names = partNames(), saved;
    for (const auto& [name, state] : c.parts) saved.push_back(name);
    if (saved != names)
        throw std::invalid_argument("the checkpoint is of another set-up (its dynamic parts differ: tail_drive, "
                                    "stop_at, opening control)");
    std::visit([&](auto& law) {
        const auto arrays = law.arrays();
        bool sameLaw = arrays.size() == c.bars.size();
        for (std::size_t k = 0; sameLaw && k < arrays.size(); ++k) sameLaw = arrays[k].first == c.bars[k].first;
        if (!sameLaw) throw std::invalid_argument("the checkpoint is of another bar law (its per-bar arrays differ)");
        for (std::size_t k = 0; k < arrays.size(); ++k) *arrays[k].second = c.bars[k].second;
        law.softeningRows() = c.softening;
    }, law_);
    u_ = c.u, v_ = c.v, f_ = c.f;
    time_ = c.time, externalWork_ = c.externalWork, dampingWork_ = c.dampingWork, step_ = c.step;
    // The parts in partStates' order.
    std::size_t k = 0;
    std::visit([&](auto& d) { d.setState(c.parts[k++].second); }, drive_);
    loadLoss_.setState(c.parts[k++].second);
    for (StopRules& r : stops_) std::visit([&](auto& x) { x.setState(c.parts[k++].second); }, r);
    std::apply([&](auto&... d) { (d.setState(c.parts[k++].second), ...); }, dampings_);
    kineticAtPeak_.setState(c.parts[k++].second);
    gz_ = step_ > 0 ? weightAt(step_ - 1) : 0.0;  // the last step's
    cd_ = nodeRule();
    if (openingControl()) opening_ = probe(meas_.probes[meas_.control]);
    progress_ = c.progress;
    progress_.summary.stopReason.clear();  // a finished run set back to its last record goes on
    progress_.pendingAdvance = true;
}

// The record's events, in order: the load loss (and the drive's and the
// dampings' responses to it), the stop rules' events, the quasi-static flag.
void Simulation::recordParts(const CurvePoint& p) {
    RunSummary& s = progress_.summary;
    const bool lossBefore = s.loadLoss.reached();
    const bool lost = loadLoss_.record(p, s);
    const DriveRecord dr{p, s, !lossBefore && s.loadLoss.reached(), dt_};
    std::visit([&](auto& d) { d.record(dr); }, drive_);
    recordDampings(dampings_, DampingRecord{s, v_});
    cd_ = nodeRule();  // (relative damping: from the load loss on)
    const std::function<bool()> joined = [this] { return facesJoined(); };
    StopRecord sr{p, s, lost, joined};
    for (StopRules& r : stops_) std::visit([&](auto& x) { x.record(sr); }, r);
    kineticAtPeak_.record(p);
    s.kineticOverWorkAtPeak = kineticAtPeak_.ratio(), s.quasiStaticFlagged = kineticAtPeak_.flagged();
}

// The first stop rule's reason, in the registry's order, else none ("").
std::string Simulation::stopReason(const CurvePoint& p) const {
    for (const StopRules& r : stops_)
        if (const char* why = std::visit([&](const auto& x) { return x.reason(p, progress_.summary); }, r)) return why;
    return {};
}

RunSummary Simulation::run(const std::function<bool(const CurvePoint&)>& observer) {
    setThreads(threads_);
    RunProgress& g = progress_;
    if (!g.started) {
        refuseDriveJump(load_.strainRate, dt_, mat_.epsP);
        refuseDriveCrawl(load_.strainRate, dt_, mat_.epsP);
        // (at the default interval: a run recorded seldom on purpose still runs)
        const double firstRecord = meanStrainOf(drive().displacement(defaultRecordEvery_ * dt_));
        for (const StopRules& r : stops_)
            if (const auto* f = std::get_if<FinalStrainStop>(&r)) f->refuseBeforeFirstRecord(firstRecord);
        g = RunProgress();
        g.summary.driveStepOverEpsP = driveStep(load_.strainRate, dt_, mat_.epsP);
        g.started = true;
    } else if (!g.pendingAdvance) {
        throw std::invalid_argument("this specimen has already run: build a new one (or restore a checkpoint)");
    }
    g.summary.drivePeriodsToEpsP = periodsToEpsP(load_.strainRate, mat_.epsP, freq_.omega1);
    g.summary.driveStrainRate = load_.strainRate;
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
        trackPeak(p.stress, driveNow());  // a record that passed the check: an unstable one is no peak
        // The balance is measured against the largest energy in play, not the
        // work alone: energy that appears without work (a drive that jumps
        // past the bars' elastic branch in a step, before any force did work)
        // is then an error of 1, not 0/0.
        g.maxEnergy = std::max({g.maxEnergy, p.externalWork, total});
        g.maxResidual = std::max(g.maxResidual, std::abs(p.balanceResidual()));
        s.fractureEnergy = p.fracture;
        s.steps = step_;
        recordParts(p);
        // The record is complete: what the observer sees (and may checkpoint) is state n with its events.
        g.pendingAdvance = true;
        // Rank 0's answer for every rank (an observer that stops on one rank alone would leave the others waiting).
        const bool keepGoing = commOf(lat_).broadcast(!observer || observer(p));
        g.pendingAdvance = false;
        s.stopReason = stopReason(p);
        if (s.stopReason.empty() && !keepGoing) s.stopReason = "stopped";
        if (!s.stopReason.empty()) break;
        advance();
    }
    s.energyBalanceError = g.maxEnergy > 0 ? g.maxResidual / g.maxEnergy : 0.0;  // 0: nothing moved
    s.energyError = s.energyBalanceError > run_.energyTolerance;
    return s;
}

}  // namespace ldem
