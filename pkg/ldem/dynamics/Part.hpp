// The dynamic parts of a run, in the manner of YADE's engines or LAMMPS's
// fixes: a drive, the dampings, the stop rules, each one class in one header
// (and its .cpp) with its name, its parameters (an X-macro list in its header,
// read as its Params), its state for checkpoints and its hooks. Registry.hpp
// lists them, one line each, and checks their hooks at compile time (isDrive,
// isStop, isDamping); Parts.hpp builds the ones a run chose by name and steps
// them, so that Simulation knows none of their rules. What the hooks are given
// is below.
#pragma once
#include <cstdint>
#include <functional>

#include "ldem/Field3.hpp"
#include "ldem/Parameters.hpp"
#include "ldem/dynamics/Record.hpp"

namespace ldem {

// The drive's program that every drive shares (ConstantRateDrive.hpp).
struct ProgramParams {
    LDEM_DRIVE_PARAMETERS(LDEM_DECLARE_MEMBER)
    LDEM_SPEEDUP_PARAMETERS(LDEM_DECLARE_MEMBER)
};

// What a drive is built from, beyond its parameters.
struct DriveSetup {
    ProgramParams program;  // its strain_rate the one driven (rate_periods')
    double gaugeLength = 0, splitWindow = 0, rho = 0;  // [m], [s], [kg/m^3]
    double omegaDrive = 0;  // omega_d, the drive's own frequency (Modal.hpp: driveFrequency), its smooth start's [rad/s]
    double Df = 0, filterTime = 0;  // the mass damping's D_f [1/s]; its filter time, relative (0: absolute) [s]
    bool openingControl = false;    // the specimen has a controlled probe
};

// What a damping is built from, beyond its parameters.
struct DampingSetup {
    double omega1 = 0, omegaMax = 0;  // [rad/s]
    std::int64_t bars = 0;            // of the lattice (its bar numbers)
    int layers = 0;                   // bar layers
    std::int64_t rows = 0;            // bar rows
    std::int64_t nodes = 0;           // of the lattice (its node ids)
    bool slab = false;                // a part of a lattice split over ranks (Lattice::isSlab)
};

// The run's set-up, complete: every drive and stop rule is told it once (setUp), before the first step.
struct RunSetup {
    double dt = 0;             // [s]
    int recordEvery = 1;       // R [steps]
    double epsP = 0;           // the bars' critical strain
    double firstRecord = 0;    // the mean strain at the first record of the default interval
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
