#include "ldem/dynamics/Parts.hpp"

#include <algorithm>
#include <stdexcept>

#include "ldem/Relations.hpp"

namespace ldem {

namespace {
// Each registered part's Params from its group's struct: paramsOf(load, (Part*)nullptr).
#define LDEM_PARAMS_OF(Type, LIST, Group)                          \
    [[maybe_unused]] Type::Params paramsOf(const Group& from, const Type*) { \
        Type::Params to;                                           \
        LIST(LDEM_COPY_MEMBER)                                     \
        (void)from;                                                \
        return to;                                                 \
    }
LDEM_DRIVES(LDEM_PARAMS_OF, LoadingParams)
LDEM_DAMPINGS(LDEM_PARAMS_OF, RunParams)
LDEM_STOPS(LDEM_PARAMS_OF, RunParams)
#undef LDEM_PARAMS_OF

// The dampings run.dampings names (bit i: the registry's i-th), built; the others left empty.
BuiltDampings makeDampings(const RunParams& run, const DampingSetup& s) {
    BuiltDampings built;
    std::size_t i = 0;
    forEachPartType(static_cast<const Dampings*>(nullptr), [&](auto* type) {
        using D = std::remove_pointer_t<decltype(type)>;
        if (std::uint64_t(run.dampings) >> i++ & 1) std::get<std::optional<D>>(built).emplace(paramsOf(run, type), s);
    });
    return built;
}

template <class Part>
std::pair<std::string, std::vector<double>> stateOf(const char* role, const Part& p) {
    return {std::string(role) + "_" + Part::name, p.state()};
}
}  // namespace

LoadingParams drivenLoading(const Material& m, const LoadingParams& l, const RunParams& r, double omegaDrive,
                            double L0) {
    LoadingParams driven = l;
    if (l.ratePeriods > 0) {
        driven.strainRate = rateForPeriods(l.ratePeriods, m.epsP, omegaDrive);
        checkRelations(m, driven, r, L0);  // the smooth start against the rate driven
    }
    return driven;
}

Parts::Parts(const Material& m, const LoadingParams& load, const RunParams& run, const PartsSetup& s)
    : dampings_(makeDampings(run, {s.omega1, s.omegaMax, s.bars, s.layers, s.rows, s.nodes, s.slab})),
      omegaDrive_(s.omegaDrive) {
    const double pi = 3.14159265358979323846;
    splitWindow_ = run.splitWindow > 0 ? run.splitWindow : 2 * (2 * pi / s.omega1);
    DriveSetup d{{}, s.gaugeLength, splitWindow_, m.rho, s.omegaDrive, dampingCoefficient(), 0.0, s.openingControl};
    {
        auto& to = d.program;
        const auto& from = load;
        LDEM_DRIVE_PARAMETERS(LDEM_COPY_MEMBER)
        LDEM_SPEEDUP_PARAMETERS(LDEM_COPY_MEMBER)
    }
    eachDamping([&](const auto& damping) { d.filterTime = std::max(d.filterTime, damping.lag()); });
    // The drive chosen: tail_drive's, or under opening control the one that is no choice (the servo);
    // each drive checks its parameters, and the one chosen may hand over to another (select).
    std::string chosen = driveNames().at(std::size_t(load.tailDrive)), built;
    forEachPartType(static_cast<const Drives*>(nullptr), [&](auto* type) {
        if (s.openingControl && !std::remove_pointer_t<decltype(type)>::kChoice)
            chosen = std::remove_pointer_t<decltype(type)>::name;
    });
    forEachPartType(static_cast<const Drives*>(nullptr), [&](auto* type) {
        using D = std::remove_pointer_t<decltype(type)>;
        const char* pick = D::select(paramsOf(load, type), d, chosen == D::name);
        if (chosen == D::name) built = pick;
    });
    forEachPartType(static_cast<const Drives*>(nullptr), [&](auto* type) {
        using D = std::remove_pointer_t<decltype(type)>;
        if (built == D::name) drive_.template emplace<D>(paramsOf(load, type), d);
    });
    loadLoss_ = LoadLossDetector(splitWindow_, run.stopFraction);
    const std::string stopAt = stopNames().at(std::size_t(run.stopAt));
    forEachPartType(static_cast<const StopRules*>(nullptr), [&](auto* type) {
        using S = std::remove_pointer_t<decltype(type)>;
        if (S::kAlways || stopAt == S::name) stops_.emplace_back(S(paramsOf(run, type)));
    });
}

void Parts::setUp(const RunSetup& r) {
    run_ = r;
    refuseDriveJump(program().strainRate, r.dt, r.epsP);
    refuseDriveCrawl(program().strainRate, r.dt, r.epsP);
    std::visit([&](auto& d) { d.setUp(r); }, drive_);
    for (const StopRules& stop : stops_) std::visit([&](const auto& x) { x.setUp(r); }, stop);
}

void Parts::record(const CurvePoint& p, RunSummary& s, const Field3& v, const std::function<bool()>& facesJoined,
                   double dt) {
    const double rate = program().strainRate;
    s.driveStepOverEpsP = driveStep(rate, dt, run_.epsP);
    s.drivePeriodsToEpsP = periodsToEpsP(rate, run_.epsP, omegaDrive_);
    s.driveStrainRate = rate;
    const bool lossBefore = s.loadLoss.reached();
    StopRecord sr{p, s, loadLoss_.record(p, s), facesJoined};
    std::visit([&](auto& d) { d.record(DriveRecord{p, s, !lossBefore && s.loadLoss.reached(), dt}); }, drive_);
    eachDamping([&](auto& d) { d.record(DampingRecord{s, v}); });
    for (StopRules& r : stops_) std::visit([&](auto& x) { x.record(sr); }, r);
    kineticAtPeak_.record(p);
    s.kineticOverWorkAtPeak = kineticAtPeak_.ratio(), s.quasiStaticFlagged = kineticAtPeak_.flagged();
}

std::string Parts::stopReason(const CurvePoint& p, const RunSummary& s) const {
    for (const StopRules& r : stops_)
        if (const char* why = std::visit([&](const auto& x) { return x.reason(p, s); }, r)) return why;
    return {};
}

PartStates Parts::states() const {
    PartStates s;
    s.push_back(std::visit([](const auto& d) { return stateOf("drive", d); }, drive_));
    s.emplace_back("test_load_loss", loadLoss_.state());
    for (const StopRules& r : stops_) s.push_back(std::visit([](const auto& x) { return stateOf("stop", x); }, r));
    eachDamping([&](const auto& d) { s.push_back(stateOf("damping", d)); });
    s.emplace_back("quasi_static", kineticAtPeak_.state());
    return s;
}

std::vector<std::string> Parts::names() const {
    std::vector<std::string> n;
    for (const auto& [name, state] : states()) n.push_back(name);
    return n;
}

void Parts::setStates(const PartStates& saved) {
    std::vector<std::string> savedNames;
    for (const auto& [name, state] : saved) savedNames.push_back(name);
    if (savedNames != names())
        throw std::invalid_argument("the checkpoint is of another set-up (its dynamic parts differ: tail_drive, "
                                    "stop_at, dampings, opening control)");
    std::size_t k = 0;  // in states()' order
    std::visit([&](auto& d) { d.setState(saved[k++].second); }, drive_);
    loadLoss_.setState(saved[k++].second);
    for (StopRules& r : stops_) std::visit([&](auto& x) { x.setState(saved[k++].second); }, r);
    eachDamping([&](auto& d) { d.setState(saved[k++].second); });
    kineticAtPeak_.setState(saved[k++].second);
}

}  // namespace ldem
