#include "ldem/Simulation.hpp"

#include <cmath>
#include <sstream>

#include "ldem/Integrator.hpp"
#include "ldem/Parallel.hpp"
#include "ldem/RandomField.hpp"

namespace ldem {

void RunParams::validate() const {
    auto fail = [](const std::string& s) { throw std::invalid_argument(s); };
    if (!(zeta >= 0) || !std::isfinite(zeta)) fail("damping ratio must be >= 0 (got " + std::to_string(zeta) + ")");
    if (!(dt >= 0) || !std::isfinite(dt)) fail("time step must be >= 0 (got " + std::to_string(dt) + " s)");
    if (!(dtSafety > 0 && dtSafety <= 1)) fail("time-step safety factor must be in (0, 1]");
    if (!(finalStrain > 0)) fail("final strain must be positive (got " + std::to_string(finalStrain) + ")");
    if (!(stopFraction >= 0 && stopFraction < 1)) fail("stop fraction must be in [0, 1)");
    if (!(splitWindow >= 0) || !std::isfinite(splitWindow)) fail("split window must be >= 0 s");
    if (recordEvery < 0) fail("record interval must be >= 0 steps");
    if (threads < 0) fail("threads must be >= 0");
}

bool SplitDetector::update(double time, double stress, double peakStress, std::int64_t broken) {
    recent_.emplace_back(time, stress);
    while (recent_.front().first < time - window_) recent_.pop_front();
    double sum = 0;
    for (const auto& r : recent_) sum += r.second;
    return broken > 0 && time >= window_ && sum / recent_.size() < fraction_ * peakStress;
}

Simulation::Simulation(int nx, int ny, int nz, double L0, const Material& m, const LoadingParams& load,
                       const RunParams& run)
    : mat_(m), load_(load), run_(run) {
    mat_.validate();
    load_.validate();
    run_.validate();
    setThreads(run_.threads);
    lat_ = buildCubicLattice(nx, ny, nz, L0, mat_);
    con_ = cubeTestConstraints(lat_, load_);

    freq_ = latticeFrequencies(lat_, con_.mask);
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
    drive_ = {load_.strainRate * con_.height, load_.rampTime > 0 ? load_.rampTime : 2 * period1};
    splitWindow_ = run_.splitWindow > 0 ? run_.splitWindow : 2 * period1;
    if (run_.recordEvery > 0) {
        recordEvery_ = run_.recordEvery;
    } else {  // about 2000 records up to the final strain
        const double tFinal = run_.finalStrain * con_.height / (drive_.v0 * con_.meanTopWeight) + 0.5 * drive_.rampTime;
        recordEvery_ = std::max(1, int(tFinal / dt_ / 2000));
    }

    // Random G_f -> limit strain of each bar (the field itself is not kept).
    {
        const std::vector<double> gf = fractureEnergyField();
        std::vector<double> epsR(lat_.numBars());
        for (const BarRow& row : lat_.barRows) {
            const BarFamily& fam = lat_.families[row.family];
            for (int p = 0; p < row.count; ++p) {
                const std::int64_t b = row.first + p;
                const double share = row.shareAt(p);
                const LimitStrain ls = limitStrain(fam.Af * share, gf[b], fam.EA * share, mat_.epsP, fam.L);
                epsR[b] = ls.epsR;
                clamped_ += ls.clamped;
            }
        }
        bars_ = BarState(lat_, mat_.epsP, std::move(epsR));
    }
    u_ = v_ = f_ = Field3(lat_.numNodes());
    cd_ = CentralDifference(dt_, Df_);
    layerDamping_.assign(lat_.numLayers(), 0.0);
}

std::vector<double> Simulation::fractureEnergyField() const {
    return ldem::fractureEnergyField(lat_, mat_, run_.seed);
}

double Simulation::stableTimeStepLimit() const { return run_.dtSafety * stableTimeStep(freq_.omegaMax); }

void Simulation::computeForces() { computeInternalForces(lat_, u_, bars_, g_, f_); }

CurvePoint Simulation::measure() const {
    CurvePoint p;
    p.step = step_;
    p.time = time_;
    p.meanStrain = meanStrainAt(time_);
    double bottom = 0, top = 0;
    for (auto n : con_.bottomNodes) bottom += f_.z[n];
    for (auto n : con_.topNodes) top -= f_.z[n];
    p.stressBottom = bottom / con_.faceArea;
    p.stressTop = top / con_.faceArea;
    const BarEnergies e = barEnergies(lat_, u_, bars_);
    p.elastic = e.elastic, p.fracture = e.fracture, p.damaged = e.damaged, p.broken = e.broken;
    p.kinetic = kineticEnergy(lat_.mass, con_.mask, v_);
    p.externalWork = externalWork_;
    p.damping = dampingWork_;
    return p;
}

void Simulation::step() {
    layeredForces(lat_, u_, g_, f_, HillerborgBars(bars_),
                  [this](int m) { layerDamping_[m] = advanceNodes(m); });
    finishStep();
}

void Simulation::advance() {
#pragma omp parallel for schedule(static)
    for (int m = 0; m < lat_.numLayers(); ++m) layerDamping_[m] = advanceNodes(m);
    finishStep();
}

void Simulation::finishStep() {
    for (double d : layerDamping_) dampingWork_ += d;  // layer order: the same sum for any thread count
    // External work of the prescribed DOFs over the centred increment
    // (x(n+1) - x(n-1))/2: the drive holds each against the bars with -f.
    const double tNext = time_ + dt_;
    const double Unext = drive_.displacement(tNext), Unow = drive_.displacement(time_);
    const double centred = 0.5 * (Unext - drive_.displacement(time_ - dt_));
    for (std::size_t k = 0; k < con_.node.size(); ++k) {
        const auto n = con_.node[k];
        const int d = con_.dim[k];
        const double w = con_.weight[k];
        std::vector<double>& fd = d == 0 ? f_.x : d == 1 ? f_.y : f_.z;
        externalWork_ -= fd[n] * w * centred;
        (d == 0 ? u_.x : d == 1 ? u_.y : u_.z)[n] = w * Unext;
        (d == 0 ? v_.x : d == 1 ? v_.y : v_.z)[n] = w * (Unext - Unow) / dt_;
    }
    time_ = tNext;
    ++step_;
}

RunSummary Simulation::run(const std::function<bool(const CurvePoint&)>& observer) {
    setThreads(run_.threads);
    RunSummary s;
    double maxWork = 0, maxResidual = 0;
    SplitDetector split(splitWindow_, run_.stopFraction);
    for (;;) {
        if (step_ % recordEvery_ != 0) {
            step();
            continue;
        }
        // A record step: forces, measure state n, then the rest of the step.
        computeForces();
        const CurvePoint p = measure();
        const double total = p.kinetic + p.elastic + p.fracture + p.damping;
        // Energy from nothing (kinetic above all the work put in) or NaN: the
        // integration is unstable; stop before it writes garbage.
        if (!std::isfinite(total) || !std::isfinite(p.stressBottom) ||
            p.kinetic > 1.5 * p.externalWork + 1e-9 * (1 + maxWork)) {
            std::ostringstream msg;
            msg << "numerical instability at step " << step_ << " (t = " << time_ << " s): kinetic energy "
                << p.kinetic << " J against external work " << p.externalWork << " J; dt = " << dt_
                << " s, stability limit " << stableTimeStep(freq_.omegaMax) << " s";
            throw InstabilityError(msg.str());
        }
        maxWork = std::max(maxWork, p.externalWork);
        maxResidual = std::max(maxResidual, std::abs(p.balanceResidual()));
        if (p.stressBottom > s.peakStress) s.peakStress = p.stressBottom, s.strainAtPeak = p.meanStrain;
        s.fractureEnergy = p.fracture;
        s.steps = step_;
        const bool keepGoing = !observer || observer(p);
        if (split.update(p.time, p.stressBottom, s.peakStress, p.broken)) s.stopReason = "split";
        else if (p.meanStrain >= run_.finalStrain) s.stopReason = "final_strain";
        else if (!keepGoing) s.stopReason = "stopped";
        if (!s.stopReason.empty()) break;
        advance();
    }
    s.energyBalanceError = maxWork > 0 ? maxResidual / maxWork : 0.0;
    return s;
}

}  // namespace ldem
