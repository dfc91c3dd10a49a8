// A run's dynamic parts, built by name from the registry (Registry.hpp) and
// stepped in order: the dampings (those dampings names), the drive (tail_drive's, or the
// specimen's servo), the load-loss test, the stop rules (those in every run and
// stop_at's) and the quasi-static guard (QuasiStatic.hpp: it refuses a drive
// too fast or too slow at set-up, and flags K/W at the peak). At a record the
// load-loss test and the stop rules find their events, then the drive and the
// dampings answer them; after the observer the first stop rule's reason ends
// the run. A checkpoint holds each part's state under its role and name
// (drive_adaptive, test_load_loss, stop_separation, damping_mass, quasi_static).
#pragma once
#include <functional>
#include <optional>
#include <tuple>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "ldem/Loading.hpp"
#include "ldem/Material.hpp"
#include "ldem/RunParams.hpp"
#include "ldem/dynamics/Registry.hpp"

namespace ldem {

// What the parts are built from, beyond the parameters.
struct PartsSetup {
    double omega1 = 0, omegaMax = 0;  // [rad/s]: the dampings'
    double omegaDrive = 0;            // omega_d [rad/s]: what times the drive (its smooth start, rule (c)'s N)
    std::int64_t bars = 0;            // of the lattice
    int layers = 0;                   // bar layers
    std::int64_t rows = 0;            // bar rows
    std::int64_t nodes = 0;           // of the lattice
    double gaugeLength = 0;           // [m]
    bool openingControl = false;      // the specimen has a controlled probe
    bool slab = false;                // a part of a lattice split over ranks (Lattice::isSlab)
};

// The loading as driven: rate_periods > 0 sets strain_rate from the drive's own
// frequency omega_d (rule (c), QuasiStatic.hpp), and the relations are checked at that rate.
LoadingParams drivenLoading(const Material& m, const LoadingParams& l, const RunParams& r, double omegaDrive,
                            double L0);

using PartStates = std::vector<std::pair<std::string, std::vector<double>>>;

// The dampings of a run: each registered one, built if dampings names it.
template <class... D>
std::tuple<std::optional<D>...> optionalEach(const std::tuple<D...>*);
using BuiltDampings = decltype(optionalEach(static_cast<const Dampings*>(nullptr)));

class Parts {
public:
    Parts() = default;
    Parts(const Material& m, const LoadingParams& load, const RunParams& run, const PartsSetup& s);
    // The run's set-up is complete: every drive and stop rule is told it, the guard checks the drive.
    void setUp(const RunSetup& r);

    // The dampings built: their share of the stable time step, their node update from the undamped
    // one, the bar forces of the one that has them (or none), the work of bar layer m's in this step.
    // A damping not built is skipped: it costs a test per call, none per bar or node.
    double stepFactor() const {
        double f = 1.0;
        eachDamping([&](const auto& d) { f *= d.stepFactor(); });
        return f;
    }
    CentralDifference nodeUpdate(double dt) {
        CentralDifference cd(dt, 0.0);
        eachDamping([&](auto& d) { cd = d.nodeUpdate(cd); });
        return cd;
    }
    DashpotPass barPass(const Field3& v) {  // one damping at most has bar forces
        DashpotPass pass;
        eachDamping([&](auto& d) { pass = pass.state ? pass : d.barPass(v); });
        return pass;
    }
    // Whether a damping's bar forces wait for every node's force (then the nodes wait for them), and
    // those forces, added to f once the force pass gave every node its own; moveWaiting(m) then
    // moves each node layer that waited (a record's step moves none: a no-op). On one thread and
    // one rank they follow the force pass instead (followLayer(m) once node layer m has its
    // forces, which moves the layers that do not wait), and afterForces ends them (followed).
    bool deferred() const {
        bool wait = false;
        eachDamping([&](const auto& d) { wait = wait || d.deferred(); });
        return wait;
    }
    // Whether node layer m waits for those forces in this step (asked once its bar layers m-2..m are done).
    bool waits(int m) const {
        bool wait = false;
        eachDamping([&](const auto& d) { wait = wait || d.waits(m); });
        return wait;
    }
    // Only the deferred damping is asked: the one with bar forces (barPass), which moves the layers.
    void followLayer(int m, const Lattice& lat, const std::vector<std::uint8_t>& mask, const Field3& u,
                     const Field3& v, Field3& f, const std::function<void(int)>& move) {
        eachDeferred([&](auto& d) { d.followLayer(m, lat, mask, u, v, f, move); });
    }
    void afterForces(const Lattice& lat, const std::vector<std::uint8_t>& mask, const Field3& u, const Field3& v,
                     Field3& f, const std::function<void(int)>& moveWaiting, bool followed = false) {
        eachDeferred([&](auto& d) { d.afterForces(lat, mask, u, v, f, moveWaiting, followed); });
    }
    double stepWork(int m) const {
        double w = 0.0;
        eachDamping([&](const auto& d) { w += d.stepWork(m); });
        return w;
    }
    double closingWork(int m) const {
        double w = 0.0;
        eachDamping([&](const auto& d) { w += d.closingWork(m); });
        return w;
    }
    double dampingCoefficient() const {  // D_f [1/s]
        double Df = 0.0;
        eachDamping([&](const auto& d) { Df += d.coefficient(); });
        return Df;
    }
    double splitWindow() const { return splitWindow_; }

    // The drive: its U at t_n and t_n-1, U(n+1) (once a step), its program.
    double now(double t, double dt) const { return std::visit([&](const auto& d) { return d.now(t, dt); }, drive_); }
    double before(double t, double dt) const {
        return std::visit([&](const auto& d) { return d.before(t, dt); }, drive_);
    }
    double next(const DriveStep& c) { return std::visit([&](auto& d) { return d.next(c); }, drive_); }
    const Drive& program() const {
        return std::visit([](const auto& d) -> const Drive& { return d.program(); }, drive_);
    }

    // A record (state n, v(n-1/2)): every part's events, in order, and the summary's.
    void record(const CurvePoint& p, RunSummary& s, const Field3& v, const std::function<bool()>& facesJoined,
                double dt);
    // After the observer: the first stop rule's reason, in the registry's order, else "".
    std::string stopReason(const CurvePoint& p, const RunSummary& s) const;

    // Each part's state by role and name, and back (throws if the names are not this set-up's).
    PartStates states() const;
    void setStates(const PartStates& saved);
    std::vector<std::string> names() const;

    const Drives& drive() const { return drive_; }
    template <class D>
    const D* damping() const {  // the damping of type D, or nullptr where dampings did not name it
        const std::optional<D>& d = std::get<std::optional<D>>(dampings_);
        return d ? &*d : nullptr;
    }

private:
    // f(d) on each damping built, in registry order.
    template <class F>
    void eachDamping(F f) {
        std::apply([&](auto&... d) { ((d ? f(*d) : void()), ...); }, dampings_);
    }
    template <class F>
    void eachDamping(F f) const {
        std::apply([&](const auto&... d) { ((d ? f(*d) : void()), ...); }, dampings_);
    }
    // The first deferred damping: at most one has bar forces, and so waits (a second would move the layers twice).
    template <class F>
    void eachDeferred(F f) {
        bool done = false;
        eachDamping([&](auto& d) { done = done || (d.deferred() && (f(d), true)); });
    }

    BuiltDampings dampings_;
    Drives drive_;
    LoadLossDetector loadLoss_;
    std::vector<StopRules> stops_;
    KineticAtPeak kineticAtPeak_;
    double splitWindow_ = 0, omegaDrive_ = 0;
    RunSetup run_;
};

}  // namespace ldem
