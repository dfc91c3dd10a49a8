// What a run records and finds: a record (state n), its events and its
// summary. Simulation fills them; the dynamic parts (Part.hpp) read a record
// and set their own events.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace ldem {

struct CurvePoint {
    std::int64_t step = 0;
    double time = 0;          // [s]
    double meanStrain = 0;    // the loaded group's mean drive displacement / gauge length (the cube's height)
    // What a load cell reads: the impulse over the record interval / its length,
    // the mean of the states since the last record (Simulation::measure).
    double stress = 0;        // reactions of the support group along the measured direction / area [Pa]
    double stressLoaded = 0;  // the same on the loaded group, negated [Pa]
    std::vector<double> probes;  // the specimen's Measures::probes [m]
    double externalWork = 0, kinetic = 0, elastic = 0, fracture = 0, damping = 0;  // [J]
    double kineticOwn = 0;  // the kinetic energy less the drive's quasi-static motion (Integrator.hpp) [J]
    std::int64_t damaged = 0, broken = 0;
    double balanceResidual() const { return externalWork - (kinetic + elastic + fracture + damping); }
};

// An event of the run: when it came and the fracture energy dissipated by then.
struct RunEvent {
    std::int64_t step = -1;  // -1: not reached
    double time = 0, meanStrain = 0, fracture = 0;  // [s], [-], [J]
    bool reached() const { return step >= 0; }
    static RunEvent at(const CurvePoint& p) { return {p.step, p.time, p.meanStrain, p.fracture}; }
};

struct RunSummary {
    double peakStress = 0;        // [Pa], tracked at every step
    double strainAtPeak = 0;      // mean strain at the peak
    double edgeStrainAtPeak = 0;  // strain at the most-pulled edge at the peak (= mean for uniform)
    RunEvent loadLoss;            // stress averaged over the window below stopFraction x peak
    RunEvent separation;          // no chain of intact bars joins the two faces: U_num = separation.fracture
    RunEvent converged;           // (stop_at converged) U stopped growing after load loss: U_final = converged.fracture
    double fractureEnergy = 0;    // fracture energy dissipated at the end [J]
    double energyBalanceError = 0;  // max |residual| / the largest energy in play over the records
    bool energyError = false;     // energyBalanceError > energyTolerance
    double driveStepOverEpsP = 0;      // the drive's step (dynamics/QuasiStatic.hpp)
    double drivePeriodsToEpsP = 0;     // N of rule (c): the fundamental periods to strain eps_p (QuasiStatic.hpp)
    double driveStrainRate = 0;        // the strain rate driven: strain_rate, or rate_periods' [1/s]
    double kineticOverWorkAtPeak = 0;  // K / W at the record of the largest stress (dynamics/QuasiStatic.hpp)
    bool quasiStaticFlagged = false;   // kineticOverWorkAtPeak > kKineticAtPeakLimit
    std::int64_t steps = 0;
    std::string stopReason;       // "separated", "load_lost", "converged", "final_strain" or "stopped"
};

}  // namespace ldem
