// The dynamic parts of a run, in the manner of YADE's engines or LAMMPS's
// fixes: each is one class in one header (and its .cpp), with its parameters
// (its own X-macro list in Parameters.hpp, spliced into its group's list, read
// as its Params), its state for checkpoints and the hooks below; Registry.hpp
// lists them and builds the ones a run chose by name. Simulation steps them
// in order and knows none of their rules.
//
// Every part:   static constexpr const char* name;   state() -> std::vector<double>;   setState(state)
// A drive (Drives): the displacement U of the drive's DOFs (Specimen.hpp)
//   double now(t_n, dt) const       U(t_n)
//   double before(t_n, dt) const    U(t_n-1)
//   double next(const DriveStep&)   U(t_n+1), once per step (advances its state)
//   void record(const DriveRecord&) at each record, after the load-loss test
//   const Drive& program() const    its program (ConstantRateDrive.hpp): v0, ramp
// A stop rule (StopRules):
//   void record(StopRecord&)        at each record, before the observer: its event in the summary
//   const char* reason(point, summary) const   after the observer: its stop reason, or nullptr
// A damping (Dampings, all of them applied in the registry's order), built from (RunParams, DampingSetup):
//   double stepFactor() const        its share of the stable time step (1: none; dt <= factor x 2/omega_max)
//   CentralDifference nodeUpdate(CentralDifference)   the node update with its terms (Integrator.hpp)
//   DashpotPass barPass(const Field3& v)   its bar forces in the force pass (BarDashpot.hpp), or none
//   double stepWork(int m) const     the work its bar forces of bar layer m dissipated in this step [J]
//   double closingWork(int m), openingWork(int m) const   that work's two halves (BarDashpot.hpp)
//   void record(const DampingRecord&)  at each record, after the drive (Simulation then takes its node update anew)
#pragma once
#include <cstdint>
#include <functional>

#include "ldem/Field3.hpp"
#include "ldem/dynamics/Record.hpp"

namespace ldem {

// What a damping is built from, beyond its parameters.
struct DampingSetup {
    double omega1 = 0, omegaMax = 0;  // [rad/s]
    std::int64_t bars = 0;            // of the lattice (its bar numbers)
    int layers = 0;                   // bar layers
};

// A step of the drive: from state n (time t_n) to n+1.
struct DriveStep {
    double time = 0, dt = 0;
    int k = 0, R = 1;      // the step within its record interval (0..R-1), and R (recordEvery)
    double opening = 0;    // the controlled probe at state n (opening control)
};

// A record, for the drive.
struct DriveRecord {
    const CurvePoint& point;
    const RunSummary& summary;
    bool lossNow;  // the load is lost from this record on (summary.loadLoss is this record)
    double dt;
};

// A record, for the dampings: its events, and v(n-1/2) of every node.
struct DampingRecord {
    const RunSummary& summary;
    const Field3& v;
};

// A record, for the stop rules.
struct StopRecord {
    const CurvePoint& point;
    RunSummary& summary;
    bool lost;                                // the load-loss test's answer at this record
    const std::function<bool()>& facesJoined;  // some chain of intact bars joins the faces (costly: a union-find)
};

}  // namespace ldem
