// Each dynamic part (pkg/ldem/dynamics/) round-trips its checkpoint state: a
// part fed some records, its state() set into a new part, goes on exactly as
// the first one (the same U, the same events) for the next records and steps.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <vector>

#include "ldem/Loading.hpp"
#include "ldem/Material.hpp"
#include "ldem/RunParams.hpp"
#include "ldem/dynamics/Parts.hpp"
#include "ldem/dynamics/QuasiStatic.hpp"
#include "ldem/dynamics/Registry.hpp"

namespace {
using namespace ldem;

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// A record of a softening specimen after its peak: the stress falls and rings, bars break.
CurvePoint recordAt(int k) {
    CurvePoint p;
    p.step = 100 * k, p.time = 1e-4 * k, p.meanStrain = 1e-5 * k;
    p.stress = 2e6 * std::exp(-0.2 * k) * (1 + 0.3 * std::sin(1.7 * k));
    p.fracture = 0.1 * std::sqrt(double(k)), p.broken = k > 3 ? 10 * k : 0;
    p.externalWork = 1.0 + 0.2 * k, p.kinetic = 0.01 * (1 + std::sin(0.9 * k)), p.kineticOwn = 0.5 * p.kinetic;
    return p;
}

constexpr double kDt = 1e-6;
constexpr int kR = 100;

// Drives: `records` records (with a load loss at record 4) and their steps, then the state
// into `fresh`, then 20 more records on both: U(n+1) of every step bit for bit.
template <class D>
void driveRoundTrip(D first, D fresh, int records) {
    RunSummary s;
    s.peakStress = 2e6;
    double opening = 0;
    auto go = [&](D& d, RunSummary& sum, int from, int to, std::vector<double>& U) {
        for (int k = from; k < to; ++k) {
            const CurvePoint p = recordAt(k);
            const bool lossNow = k == 4;
            if (lossNow) sum.loadLoss = RunEvent::at(p);
            d.record(DriveRecord{p, sum, lossNow, kDt});
            for (int j = 0; j < kR; ++j) {
                opening = 1e-6 * (k + j * 1e-2);
                U.push_back(d.next(DriveStep{p.time + j * kDt, kDt, j, kR, opening}));
            }
            U.push_back(d.now(p.time, kDt)), U.push_back(d.before(p.time, kDt));
        }
    };
    std::vector<double> before, a, b;
    go(first, s, 0, records, before);
    fresh.setState(first.state());
    // The first step after a restart reads U(n) and U(n-1) before any next() (Simulation::finishStep).
    const double at = recordAt(records).time;
    ASSERT_TRUE(sameBits(fresh.now(at, kDt), first.now(at, kDt)));
    ASSERT_TRUE(sameBits(fresh.before(at, kDt), first.before(at, kDt)));
    RunSummary t = s;
    go(first, s, records, records + 20, a);
    go(fresh, t, records, records + 20, b);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) ASSERT_TRUE(sameBits(a[i], b[i])) << i;
    EXPECT_NE(a.front(), a.back());  // it moved
}

ConstantRateDrive fixedDrive() {
    ProgramParams p;
    p.strainRate = 0.5, p.rampTime = 2e-4, p.lossSpeedup = 20;
    return ConstantRateDrive(p, 0.1, 1e-4);
}

AdaptiveDrive::Limits limits() { return {20, 2000, 0.005, 0.1, 1.1, 2e-4, 1e3, 1e-3}; }

TEST(DirectDynamicParts, TheFixedDriveRoundTripsItsSpeedupStart) {
    driveRoundTrip(fixedDrive(), fixedDrive(), 8);  // past the load loss: the speed-up has started
    ConstantRateDrive d = fixedDrive();
    EXPECT_TRUE(std::isinf(d.state().at(0)));  // none before the load loss
}

TEST(DirectDynamicParts, TheAdaptiveDriveRoundTripsBeforeAndAfterItStarts) {
    const AdaptiveTailDrive d(fixedDrive(), limits());
    driveRoundTrip(d, AdaptiveTailDrive(fixedDrive(), limits()), 3);   // not started: the ramp's state only
    driveRoundTrip(d, AdaptiveTailDrive(fixedDrive(), limits()), 12);  // started: its U, factors, averages too
    AdaptiveTailDrive started(fixedDrive(), limits());
    RunSummary s;
    s.peakStress = 2e6;
    for (int k = 0; k < 12; ++k) {
        const CurvePoint p = recordAt(k);
        if (k == 4) s.loadLoss = RunEvent::at(p);
        started.record(DriveRecord{p, s, k == 4, kDt});
    }
    ASSERT_TRUE(started.adaptive().active());
    EXPECT_EQ(started.state().size(), 11u);  // the ramp's start, floor and time, then the adaptive drive's 8
}

// recordAt's K/W runs from 1e-2 to 3e-3: at crack_kinetic 5e-3 the pace brakes and releases.
TEST(DirectDynamicParts, TheAdaptiveDriveRoundTripsItsPace) {
    const CrackPace::Limits pace{0.0625, 5e-3, 1e-7, 1.1};
    const AdaptiveTailDrive d(fixedDrive(), limits(), pace);
    driveRoundTrip(d, AdaptiveTailDrive(fixedDrive(), limits(), pace), 3);   // braking, before the loss
    driveRoundTrip(d, AdaptiveTailDrive(fixedDrive(), limits(), pace), 12);  // the tail started
    AdaptiveTailDrive paced(fixedDrive(), limits(), pace);
    RunSummary s;
    s.peakStress = 2e6;
    for (int k = 0; k < 3; ++k) paced.record(DriveRecord{recordAt(k), s, false, kDt});
    EXPECT_LT(paced.pace().pace(), 1.0);
    EXPECT_EQ(paced.state().size(), 3u + CrackPace::kStateSize);  // the ramp's 3, then the pace's
}

TEST(DirectDynamicParts, TheServoRoundTripsItsDisplacements) {
    ServoDrive::Params p;
    p.openingRate = 1e-3;
    driveRoundTrip(ServoDrive(p, fixedDrive(), 50.0), ServoDrive(p, fixedDrive(), 50.0), 6);
}

// The servo drive closes a lag at the rate g = D_f / 2 (ServoDrive.hpp): on a
// plant whose opening is c = a U, U' = (r S' + g (c* - c)) / a gives
// (c* - c)' = -g (c* - c), so a lag delta left one time constant 1/g later is
// delta/e (dt g = 2.5e-4: to 1e-3). Stepped, the lag tends to -r dt/2 (the
// program is read at mid-step, the opening at t_n): delta - that decays.
// Without the correction the lag stays delta.
TEST(DirectDynamicParts, TheServoClosesALagAtHalfTheDampingRate) {
    ServoDrive::Params p;
    p.openingRate = 1e-3;  // r [m/s]
    const double Df = 50.0, a = 2.0, dt = 1e-5, t0 = 1e-3, delta = 3e-7;
    ServoDrive d(p, fixedDrive(), Df);
    const Drive& program = d.program();
    auto onProgram = [&](double t) { return p.openingRate * smoothRampIntegral(t, program.rampTime); };
    const double U0 = (onProgram(t0) - delta) / a;
    d.setState({U0, U0});
    const int steps = int(std::lround(1.0 / (0.5 * Df) / dt));
    for (int n = 0; n < steps; ++n) d.next(DriveStep{t0 + n * dt, dt, n % kR, kR, a * d.now(0, dt)});
    const double lag = onProgram(t0 + steps * dt) - a * d.now(0, dt), steady = -0.5 * p.openingRate * dt;
    EXPECT_NEAR((lag - steady) / (delta - steady), std::exp(-1.0), 1e-3);
}

// Stop rules and the load-loss test: the same events and reasons after the round trip.
template <class Part, class Feed>
void recordRoundTrip(Part first, Part fresh, int records, Feed feed) {
    RunSummary s;
    s.peakStress = 2e6;
    for (int k = 0; k < records; ++k) feed(first, s, recordAt(k));
    fresh.setState(first.state());
    RunSummary t = s;
    for (int k = records; k < records + 30; ++k) {
        const CurvePoint p = recordAt(k);
        feed(first, s, p), feed(fresh, t, p);
        EXPECT_EQ(first.state(), fresh.state()) << k;
    }
    EXPECT_EQ(s.loadLoss.step, t.loadLoss.step);
    EXPECT_EQ(s.separation.step, t.separation.step);
    EXPECT_EQ(s.converged.step, t.converged.step);
}

TEST(DirectDynamicParts, TheLoadLossTestRoundTripsItsWindow) {
    int lost = 0;
    recordRoundTrip(LoadLossDetector(5e-4, 0.5), LoadLossDetector(5e-4, 0.5), 6,
                    [&](LoadLossDetector& d, RunSummary& s, const CurvePoint& p) { lost += d.record(p, s); });
    EXPECT_GT(lost, 0);
    EXPECT_EQ(LoadLossDetector(5e-4, 0.5).state().size(), 0u);
}

template <class Stop>
auto stopFeed(std::function<bool()> joined) {
    return [joined](Stop& stop, RunSummary& s, const CurvePoint& p) {
        if (p.step == 400 && !s.loadLoss.reached()) s.loadLoss = RunEvent::at(p);
        StopRecord r{p, s, p.step >= 400, joined};
        stop.record(r);
    };
}

TEST(DirectDynamicParts, TheSeparationStopRoundTripsItsLastTest) {
    int tests = 0;
    // Joined until the fifth union-find: the event falls after the round trip.
    const std::function<bool()> joined = [&] { return ++tests < 10; };
    recordRoundTrip(SeparationStop(), SeparationStop(), 8, stopFeed<SeparationStop>(joined));
    EXPECT_GT(tests, 5);
}

TEST(DirectDynamicParts, TheConvergedStopRoundTripsItsRungs) {
    ConvergedStop::Params p;
    p.convergedGrowth = 0.3;
    recordRoundTrip(ConvergedStop(p), ConvergedStop(p), 7, stopFeed<ConvergedStop>([] { return true; }));
}

// The load-loss stop waits for the load loss and for loss_stop_strain_ratio x
// the strain at the peak, whichever comes last.
TEST(DirectDynamicParts, TheLoadLossStopNeverEndsARunBeforeItsMultipleOfThePeakStrain) {
    LoadLossStop::Params p;
    p.lossStopStrainRatio = 10;
    const LoadLossStop stop(p);
    RunSummary s;
    s.strainAtPeak = 1e-4;
    CurvePoint at;
    at.meanStrain = 2e-3;
    EXPECT_EQ(stop.reason(at, s), nullptr);  // past the floor, load not lost
    s.loadLoss.step = 100;
    EXPECT_STREQ(stop.reason(at, s), "load_lost");
    at.meanStrain = 0.99e-3;  // lost, but below 10 x 1e-4
    EXPECT_EQ(stop.reason(at, s), nullptr);
    at.meanStrain = 1e-3;
    EXPECT_STREQ(stop.reason(at, s), "load_lost");
}

// The past-the-peak stop ends the run at peak_stop_strain_ratio x the strain at
// the peak, lost load or not; never before the peak (no strain at the peak yet),
// and never on the rising branch, where the peak so far is the latest record.
TEST(DirectDynamicParts, ThePastPeakStopEndsARunAtItsMultipleOfThePeakStrain) {
    PastPeakStop::Params p;
    p.peakStopStrainRatio = 10;
    const PastPeakStop stop(p);
    RunSummary s;
    CurvePoint at;
    at.meanStrain = 1e-9;
    EXPECT_EQ(stop.reason(at, s), nullptr);  // no peak yet: strainAtPeak 0
    s.strainAtPeak = at.meanStrain = 1e-4;
    EXPECT_EQ(stop.reason(at, s), nullptr);  // at the peak
    at.meanStrain = 0.99e-3;
    EXPECT_EQ(stop.reason(at, s), nullptr);
    at.meanStrain = 1e-3;
    EXPECT_STREQ(stop.reason(at, s), "past_peak");  // the load is not lost: it stops all the same
    s.loadLoss.step = 100;
    EXPECT_STREQ(stop.reason(at, s), "past_peak");
}

TEST(DirectDynamicParts, TheStatelessPartsRoundTripNothing) {
    FinalStrainStop::Params f;
    EXPECT_TRUE(FinalStrainStop(f).state().empty());
    EXPECT_TRUE(LoadLossStop(LoadLossStop::Params{}).state().empty());
    EXPECT_TRUE(PastPeakStop(PastPeakStop::Params{}).state().empty());
    MassDamping::Params m;
    m.zeta = 0.02;
    MassDamping d(m, 800.0);
    EXPECT_TRUE(d.state().empty());
    // Its node update is central differences with D_f = 2 zeta omega_1, bit for bit.
    const CentralDifference cd = d.nodeUpdate(CentralDifference(kDt, 0.0)), want(kDt, 2 * 0.02 * 800.0);
    EXPECT_TRUE(sameBits(cd.a, want.a) && sameBits(cd.b, want.b) && sameBits(cd.Df, want.Df));
}

// Every part of the registry, built as Parts builds it (its Params at their defaults),
// round-trips its checkpoint state: a part added to the registry is tested here at once.
TEST(DynamicParts, EveryRegisteredPartRoundTripsItsState) {
    DriveSetup d;
    d.program.strainRate = 0.5, d.program.rampTime = 2e-4, d.program.lossSpeedup = 20;
    d.gaugeLength = 0.1, d.omegaDrive = 2 * M_PI / 1e-4, d.splitWindow = 2e-4, d.rho = 2400, d.Df = 100;
    const RunSetup r{kDt, kR, 1e-4, 0.0};
    int drives = 0, stops = 0, dampings = 0;
    forEachPartType(static_cast<const Drives*>(nullptr), [&](auto* type) {
        using D = std::remove_pointer_t<decltype(type)>;
        D first(typename D::Params{}, d), fresh(typename D::Params{}, d);
        first.setUp(r), fresh.setUp(r);
        driveRoundTrip(first, fresh, 8);
        ++drives;
    });
    forEachPartType(static_cast<const StopRules*>(nullptr), [&](auto* type) {
        using S = std::remove_pointer_t<decltype(type)>;
        recordRoundTrip(S(typename S::Params{}), S(typename S::Params{}), 8, stopFeed<S>([] { return true; }));
        ++stops;
    });
    forEachPartType(static_cast<const Dampings*>(nullptr), [&](auto* type) {
        using D = std::remove_pointer_t<decltype(type)>;
        const DampingSetup s{800.0, 1e5, 10, 3};
        const D first(typename D::Params{}, s);
        D fresh(typename D::Params{}, s);
        fresh.setState(first.state());
        EXPECT_EQ(fresh.state(), first.state()) << D::name;
        ++dampings;
    });
    EXPECT_EQ(drives, int(std::variant_size_v<Drives>));
    EXPECT_EQ(stops, int(std::variant_size_v<StopRules>));
    EXPECT_EQ(dampings, int(std::tuple_size_v<Dampings>));
}

// The dampings a run names are built, in registry order, and only they: one not
// named has no state in a checkpoint, no share of D_f or of the time step, no
// bar forces; its parameters are not read (zeta_high of bar dashpots not named).
TEST(DynamicParts, OnlyTheDampingsNamedAreBuilt) {
    const double omega1 = 800, omegaMax = 1e5;
    const PartsSetup setup{omega1, omegaMax, omega1, 10, 3, 3, 8, 0.1, false};
    RunParams run;
    const auto parts = [&](const std::string& names) {
        run.dampings = dampingsNamed(names);
        return Parts(Material{}, LoadingParams{}, run, setup);
    };
    const auto dampingNamesOf = [](const Parts& p) {
        std::vector<std::string> n;
        for (const std::string& name : p.names())
            if (name.rfind("damping_", 0) == 0) n.push_back(name);
        return n;
    };
    const Field3 v(10);
    Parts both = parts("bar_dashpots,mass"), mass = parts("mass"), bars = parts("bar_dashpots"), none = parts("none");
    EXPECT_EQ(dampingNamesOf(both), (std::vector<std::string>{"damping_mass", "damping_bar_dashpots"}));
    EXPECT_EQ(dampingNamesOf(mass), std::vector<std::string>{"damping_mass"});
    EXPECT_EQ(dampingNamesOf(bars), std::vector<std::string>{"damping_bar_dashpots"});
    EXPECT_TRUE(dampingNamesOf(none).empty());
    // The defaults' dashpots (predicted, zeta_high 0.5) leave the step whole; lagged they shorten it.
    const double Df = massDampingCoefficient(run.zeta, omega1), factor = 1.0;
    run.dashpotPredicted = false;
    EXPECT_TRUE(sameBits(parts("bar_dashpots").stepFactor(), dampedStepFactor(run.zetaHigh)));
    run.dashpotPredicted = true;
    EXPECT_TRUE(sameBits(both.dampingCoefficient(), Df) && sameBits(both.stepFactor(), factor));
    EXPECT_TRUE(sameBits(mass.dampingCoefficient(), Df) && sameBits(mass.stepFactor(), 1.0));
    EXPECT_TRUE(sameBits(bars.dampingCoefficient(), 0.0) && sameBits(bars.stepFactor(), factor));
    EXPECT_TRUE(both.barPass(v).state && bars.barPass(v).state);
    EXPECT_FALSE(mass.barPass(v).state || none.barPass(v).state);
    // No damping: the node update is central differences undamped, bit for bit.
    const CentralDifference cd = none.nodeUpdate(kDt), want(kDt, 0.0);
    EXPECT_TRUE(sameBits(cd.a, want.a) && sameBits(cd.b, want.b) && sameBits(cd.Df, 0.0) && !cd.mean);
    EXPECT_TRUE(sameBits(none.stepWork(0), 0.0) && sameBits(none.closingWork(0), 0.0));
    // A checkpoint of one set of dampings is refused by another, naming dampings.
    try {
        mass.setStates(both.states());
        FAIL() << "a checkpoint of other dampings was taken";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("dampings"), std::string::npos) << e.what();
    }
}

TEST(DirectDynamicParts, TheQuasiStaticFlagRoundTripsItsPeakRecord) {
    KineticAtPeak first, fresh;
    for (int k = 0; k < 3; ++k) first.record(recordAt(k));
    fresh.setState(first.state());
    for (int k = 3; k < 30; ++k) first.record(recordAt(k)), fresh.record(recordAt(k));
    EXPECT_TRUE(sameBits(first.ratio(), fresh.ratio()));
    EXPECT_GT(first.ratio(), 0.0);
}

// The quasi-static flag's own quantity (QuasiStatic.hpp): K / W at the record of
// the largest stress (the first such record; a later equal stress does not
// move it), flagged above 1 % and only above. Hand values: stresses 1, 3, 2, 3
// MPa with K / W 0.5 %, 1.5 %, 4 %, 0.2 %: the peak is the second record.
TEST(DirectDynamicParts, TheQuasiStaticFlagIsKineticOverWorkAtThePeakAboveOnePercent) {
    auto record = [](double stressMPa, double kinetic) {
        CurvePoint p;
        p.stress = stressMPa * 1e6, p.externalWork = 2.0, p.kinetic = kinetic;
        return p;
    };
    KineticAtPeak q;
    q.record(record(1, 0.010));
    EXPECT_DOUBLE_EQ(q.ratio(), 0.005);
    EXPECT_FALSE(q.flagged());
    for (const auto& [s, k] : {std::pair{3.0, 0.030}, {2.0, 0.080}, {3.0, 0.004}}) q.record(record(s, k));
    EXPECT_DOUBLE_EQ(q.ratio(), 0.015);
    EXPECT_TRUE(q.flagged());
    KineticAtPeak atTheLimit;
    atTheLimit.record(record(1, 0.02));  // exactly 1 %: not above it
    EXPECT_DOUBLE_EQ(atTheLimit.ratio(), kKineticAtPeakLimit);
    EXPECT_FALSE(atTheLimit.flagged());
}

}  // namespace
