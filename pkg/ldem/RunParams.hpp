// How a run goes: the random specimen, the dampings, the stop rules, the time
// step, records and threads; the registered dampings' and stop rules'
// parameters among them (dynamics/Registry.hpp).
#pragma once
#include "ldem/Parameters.hpp"
#include "ldem/dynamics/Registry.hpp"

// The run: its own parameters, the dampings' choice and every damping's list, the stop's choice and every stop
// rule's list, in registry order.
#define LDEM_RUN_PARAMETERS(X)                                                                               \
    X(std::int64_t, seed, "seed", 1, "", Domain::atLeast(0), "random specimen (same seed, same specimen)")   \
    X(double, gravity, "gravity", 0.0, "m/s^2", Domain::closed(0, 100),                                      \
      "the specimen's weight: a body force m g along -z on every free DOF, rising over the drive's smooth "    \
      "start (9.81: a beam lying on its supports); its work counts as external work")                        \
    X(DampingSet, dampings, "dampings", dampingsNamed("mass,bar_dashpots"), "", Domain::someOf(dampingNames()), \
      dampingHelp())                                                                                         \
    LDEM_DAMPINGS(LDEM_PART_LIST, X)                                                                         \
    X(StopId, stopAt, "stop_at", stopNamed("separation"), "", Domain::choices(stopNames()), stopHelp())      \
    LDEM_STOPS(LDEM_PART_LIST, X)                                                                            \
    X(double, dt, "dt", 0.0, "s", Domain::atLeast(0), "time step (0: safety x stability limit)")             \
    X(double, dtSafety, "dt_safety", 0.9, "", Domain::openClosed(0, 1),                                      \
      "fraction of the stability limit allowed, 2/omega_max x (sqrt(1 + zeta_high^2) - zeta_high), or "      \
      "2/omega_max with dashpot_velocity predicted while zeta_high <= 0.5; without the dashpots (zeta_high 0) "\
      "keep it at 0.4: above, closing cracks pump energy into the highest modes")                             \
    LDEM_LOAD_LOSS_PARAMETERS(X)                                                                             \
    X(double, energyTolerance, "energy_tolerance", 0.01, "", Domain::positive(),                             \
      "a run whose energy balance error exceeds this is flagged energy_error (and ldem exits 1)")            \
    X(int, recordEvery, "record_every", 0, "steps", Domain::atLeast(0),                                      \
      "steps between curve rows (0: one per eps_p/50 of mean strain at the initial rate)")                   \
    X(int, threads, "threads", 0, "", Domain::atLeast(0),                                                   \
      "OpenMP threads (0: OMP_NUM_THREADS if set, else one per 50,000 bars of the lattice, at most the cores " \
      "free to this process: those it may run on less those busy over 0.1 s; at least one)")

namespace ldem {

struct RunParams {
    LDEM_RUN_PARAMETERS(LDEM_DECLARE_MEMBER)
    void validate() const { LDEM_RUN_PARAMETERS(LDEM_CHECK_MEMBER) }
};

}  // namespace ldem
