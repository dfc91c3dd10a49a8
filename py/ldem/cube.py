"""The cube tension test of the study (LDEM_SPEC section 6), from Python.

    import ldem
    test = ldem.CubeTest(size=0.24, load="triangular", seed=3)
    result = test.run()                        # data only: nothing written
    result.curve["mean_strain"], result.curve["stress_MPa"]   # numpy arrays
    ldem.run_cube(test, out="out/cube")        # with curve.csv, summary.json, figures, bars.vtu

`CubeTest` holds every parameter with its default, unit and help text; the
command line (`ldem cube --help`) is generated from the same fields. `run`
builds the C++ `Simulation` (ldem._core), calls its time-step loop and returns
the curve and the summary as data; ldem.run_cube wires the files to it.
"""
from __future__ import annotations

import dataclasses
import time

import numpy as np

from . import _core
from .mincut import cheapest_cut

# Every parameter, declared once in C++ (pkg/ldem/Parameters.hpp): group, name,
# unit, help, kind (float, int, choice, or names: some of the choices,
# comma-separated), default, domain, choices. CubeTest's fields, `ldem cube`'s
# options, summary.json's "parameters" and a study's case keys all come from it.
PARAMETERS = _core.parameter_table()
# The table's defaults by name: a file's specimen's, and what a run made before a
# parameter was declared ran at.
TABLE_DEFAULTS = {p["name"]: p["default"] for p in PARAMETERS}
_KINDS = {"float": float, "int": int, "choice": str, "names": str}


class _CubeTestMethods:
    # -- checks -------------------------------------------------------------
    def params(self) -> "_core.CubeTestParams":
        """The C++ parameters, checked; raises ValueError naming a bad one."""
        p = _core.CubeTestParams()
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if isinstance(value, bool) or not isinstance(value, f.type):
                if not (f.type is float and isinstance(value, int) and not isinstance(value, bool)):
                    raise ValueError(f"{f.name} must be {'a number' if f.type is float else f.type.__name__} "
                                     f"(got {value!r})")
            p[f.name] = value
        p.validate()
        return p

    def modules(self) -> int:
        """Modules along one side; raises ValueError unless size is a positive multiple of L0."""
        return self.params().modules()

    def simulation(self) -> "_core.Simulation":
        """Builds the specimen (lattice, random G_f, frequencies, time step)."""
        return _core.Simulation(self.params())

    def parameters(self) -> dict:
        return dataclasses.asdict(self)

    def describe(self) -> str:
        return f"{self.size:g} m cube, {self.load}, seed {self.seed}"

    def axis_labels(self) -> tuple:
        """(strain, stress) labels: the cube's mean strain and normal stress."""
        return STRAIN_LABEL, STRESS_LABEL

    # -- running ------------------------------------------------------------
    def run(self, observers=(), simulation=None, previous_rows=()) -> "CubeResult":
        """Runs the test to separation (or load loss, see stop_at; or the final
        strain) and returns what it computed; writes nothing.

        observers: callables given each curve row (a dict over CURVE_COLUMNS)
        as it is recorded, e.g. ldem.io.CurveCsv or ldem.progress.ProgressBar;
        one that returns False stops the run at that row (stop_reason "stopped").
        simulation: a specimen from self.simulation(), if you built it already,
        or one restored from a checkpoint (its run continues; previous_rows are
        the curve rows recorded before the checkpoint).
        If the run fails or is interrupted, the exception carries what was
        computed up to then as its `ldem_result` (status failed/interrupted).
        ldem.run_cube(test, out=...) runs it with the files and pictures.
        """
        return run_test(self, observers, simulation, previous_rows)


def run_test(test, observers=(), simulation=None, previous_rows=(), probes=()) -> "CubeResult":
    """test.run (a CubeTest's or an ldem.SpecimenTest's): the C++ loop with the
    observers called on each curve row (probes: the names of its probe columns)."""
    t0 = time.perf_counter()
    sim = simulation if simulation is not None else test.simulation()
    if sim.steps > 0 and not sim.resumable:  # the end of that run: a second run would start from there
        raise ValueError(f"this specimen has already run ({sim.steps} steps): build a new one with "
                         "test.simulation()")
    rows = list(previous_rows)

    def observe(p):
        row = curve_row(p)
        row.update({f"{name}_m": value for name, value in zip(probes, p.probes)})
        rows.append(row)
        keep = True
        for o in observers:  # each sees every row; one that returns False stops the run ("stopped")
            keep = (o(row) is not False) and keep
        return keep

    try:
        summary = sim.run(observe)
    except BaseException as e:  # keep what was computed, then let it propagate
        e.ldem_result = CubeResult(test, sim, rows, None, time.perf_counter() - t0, e)
        raise
    return CubeResult(test, sim, rows, summary, time.perf_counter() - t0)


# Quasi-static loading (docs/cube.md, Outputs): the guards are the core's
# (pkg/ldem/dynamics/QuasiStatic.hpp), so that every run gets them: a drive
# that moves by eps_p or more in one step is refused when the specimen is built,
# and a run whose kinetic energy at the peak is above KINETIC_AT_PEAK_LIMIT of
# the work is flagged.
KINETIC_AT_PEAK_LIMIT = _core.KINETIC_AT_PEAK_LIMIT
# Rule (c) (dynamics/QuasiStatic.hpp): a drive that strains eps_p in fewer periods of its own mode is
# warned; RATE_PERIODS at a constant drive, PACED_RATE_PERIODS under the crack pace (crack_pace < 1).
RATE_PERIODS = _core.RATE_PERIODS
PACED_RATE_PERIODS = _core.PACED_RATE_PERIODS


def quasi_static(summary, crack_pace: float) -> dict:
    """The run's loading speed for summary.json, as the core measured it: the
    drive's step over eps_p, the periods 2 pi/omega_d it takes to strain eps_p
    (rule (c): at least RATE_PERIODS, or PACED_RATE_PERIODS when paced) and the
    kinetic energy over the external work at the record of the largest stress;
    flagged above KINETIC_AT_PEAK_LIMIT."""
    rule = PACED_RATE_PERIODS if crack_pace < 1 else RATE_PERIODS
    return {"strain_rate": summary.drive_strain_rate, "drive_step_over_eps_p": summary.drive_step_over_eps_p,
            "periods_to_eps_p": summary.drive_periods_to_eps_p, "rate_periods": rule,
            "kinetic_over_work_at_peak": summary.kinetic_over_work_at_peak,
            "kinetic_limit": KINETIC_AT_PEAK_LIMIT, "flagged": summary.quasi_static_flagged}


# The cube's own defaults over the table's (which are every specimen's from a
# file): its paced drive (pkg/ldem/ParameterTable.hpp, cubeOwnDefaults, says why).
CUBE_DEFAULTS = _core.cube_own_defaults()


def _field(p: dict) -> tuple:
    metadata = {"unit": p["unit"], "help": p["help"], "group": p["group"], "domain": p["domain"]}
    if p["choices"]:
        metadata["choices"] = tuple(p["choices"])
    if p["kind"] == "names":
        metadata["several"] = True  # some of the choices, comma-separated ("none": not one)
    default = CUBE_DEFAULTS.get(p["name"], p["default"])
    return p["name"], _KINDS[p["kind"]], dataclasses.field(default=default, metadata=metadata)


CubeTest = dataclasses.make_dataclass(
    "CubeTest", [_field(p) for p in PARAMETERS], bases=(_CubeTestMethods,),
    namespace={"__doc__": "A concrete cube pulled in tension: geometry, material, loading, run control. One field "
                          "per parameter of ldem.PARAMETERS (pkg/ldem/Parameters.hpp), with its default "
                          "(CUBE_DEFAULTS: the cube's own).",
               "__module__": __name__})


# What a cube's measures are: the words of its figures' axes, its terminal
# lines and summary.json's "labels" (a specimen says its own: measure.strain_label, stress_label).
STRAIN_LABEL, STRESS_LABEL = "mean strain [-]", "normal stress [MPa]"


def labels(test) -> dict:
    """{"strain": ..., "stress": ...}: test's axis labels, "name [unit]" (a cube's, where a test gives none)."""
    own = test.axis_labels() if hasattr(test, "axis_labels") else ("", "")
    return {"strain": own[0] or STRAIN_LABEL, "stress": own[1] or STRESS_LABEL}


def label_words(label: str) -> tuple:
    """(name, unit) of a label "name [unit]": ("deflection/D", "-"); ("", ...) parts absent stay ""."""
    name, _, unit = label.partition(" [")
    return name.strip(), unit.rstrip("]").strip()


# The curve's columns, in curve.csv's order; stresses in MPa (the core's are Pa).
CURVE_COLUMNS = ["step", "time_s", "mean_strain", "stress_MPa", "stress_top_MPa", "external_work_J", "kinetic_J",
                 "elastic_J", "fracture_J", "damping_J", "damaged_bars", "broken_bars"]


def curve_row(p) -> dict:
    """One record of the run (_core.CurvePoint) as a curve row: the one place
    where the core's SI stresses become MPa."""
    return {"step": p.step, "time_s": p.time, "mean_strain": p.mean_strain, "stress_MPa": p.stress * 1e-6,
            "stress_top_MPa": p.stress_loaded * 1e-6, "external_work_J": p.external_work, "kinetic_J": p.kinetic,
            "elastic_J": p.elastic, "fracture_J": p.fracture, "damping_J": p.damping, "damaged_bars": p.damaged,
            "broken_bars": p.broken}


class CubeResult:
    """What a run produced: the curve as numpy arrays, the summary, the final state."""

    def __init__(self, test: CubeTest, sim, rows, summary, wall_s: float, error=None):
        self.test, self.sim, self.wall_s = test, sim, wall_s
        if error is None:
            self.status = "done"
        else:
            self.status = "interrupted" if isinstance(error, KeyboardInterrupt) else "failed"
        self.curve = {c: np.array([r[c] for r in rows], dtype=float) for c in (list(rows[0]) if rows else CURVE_COLUMNS)}
        self.summary = _summary_dict(test, sim, self.curve, summary, wall_s, self.status)
        if error is not None:
            self.summary["error"] = str(error) or type(error).__name__
            self.summary["stop_reason"] = self.status

    @property
    def peak_stress_MPa(self) -> float:
        return self.summary["peak_stress_MPa"]

    @property
    def strain_at_peak(self) -> float:
        return self.summary["strain_at_peak"]


def _event(e) -> dict:
    """An event of the run (RunEvent) for summary.json; None if it never came."""
    if not e.reached:
        return None
    return {"step": e.step, "time_s": e.time, "mean_strain": e.mean_strain, "fracture_energy_J": e.fracture}


def _run_parameters(test) -> dict:
    """The run's parameters by name: a CubeTest's, or a specimen file's (under "parameters")."""
    p = test.parameters()
    return p.get("parameters", p)


def _summary_dict(test, sim, curve, summary, wall_s, status) -> dict:
    u_min = sim.min_fracture_energy if sim.min_fracture_energy > 0 else None  # None: no ligament declared
    s = {"status": status}
    if summary is not None:
        sep = summary.separation
        u_num = sep.fracture if sep.reached else None
        s.update({
            "peak_stress_MPa": summary.peak_stress * 1e-6,
            "strain_at_peak": summary.strain_at_peak,
            "edge_strain_at_peak": summary.edge_strain_at_peak,
            "separated": sep.reached,
            "U_num_J": u_num,
            "U_ratio": None if u_num is None or u_min is None else u_num / u_min,
            "load_loss": _event(summary.load_loss),
            "separation": _event(sep),
            # stop_at "converged" on a specimen that hinges: the energy at the stop, never U_num.
            "converged": _event(summary.converged),
            "U_final_J": summary.converged.fracture if summary.converged.reached else None,
            "fracture_energy_J": summary.fracture_energy,
            "min_fracture_energy_J": u_min,  # E[G_f] x the ligament (Simulation::minFractureEnergy)
            # The cheapest cut needs the whole lattice on one process: not under mpirun.
            "U_mincut_J": None if _core.mpi_launched() else cheapest_cut(sim),
            "energy_balance_error": summary.energy_balance_error,
            "energy_error": summary.energy_error,
            "quasi_static": quasi_static(summary, _run_parameters(test)["crack_pace"]),
            "stop_reason": summary.stop_reason,
        })
    elif len(curve["stress_MPa"]):  # failed run: the core's summary as of its last record (the tracked peak,
        so_far = sim.summary_so_far  # exact: curve rows restored from curve.csv keep only 10 digits)
        s.update({"peak_stress_MPa": so_far.peak_stress * 1e-6, "strain_at_peak": so_far.strain_at_peak,
                  "edge_strain_at_peak": so_far.edge_strain_at_peak, "fracture_energy_J": so_far.fracture_energy,
                  "min_fracture_energy_J": u_min})
    s.update({
        "clamped_bars": sim.clamped_bars,
        "n_nodes": sim.total_nodes,  # of the whole lattice, also when split over MPI ranks
        "n_bars": sim.total_bars,
        "steps": sim.steps,
        "dt_s": sim.dt,
        "dt_limit_s": sim.dt_limit,
        "dt_over_undamped_limit": sim.dt * sim.omega_max / 2,  # dt over 2/omega_max, the undamped stable step
        "omega1_rad_s": sim.omega1,
        "omega_d_rad_s": sim.omega_d,  # the drive's own mode: its smooth start and rule (c) (Modal.hpp)
        "omega_max_rad_s": sim.omega_max,
        "damping_coefficient_1_s": sim.damping_coefficient,
        "ramp_time_s": sim.ramp_time,
        "split_window_s": sim.split_window,
        "threads": sim.threads,  # those the run used (threadsFor, Parallel.hpp)
        "mpi_ranks": _core.mpi_ranks(),  # processes the lattice was split over (mpirun -np)
        "wall_s": wall_s,
        "labels": labels(test),  # what stress and strain (peak_stress_MPa, strain_at_peak, the curve) are here
        "provenance": provenance(),
        "parameters": test.parameters(),
    })
    return s


def provenance() -> dict:
    """Which ldem ran, where and when: with the parameters, enough to rerun a
    result from its folder alone (`ldem rerun DIR`)."""
    import datetime
    import platform

    from . import __version__

    try:
        from ._build_info import GIT_COMMIT  # written by the build (py/build_info.cmake)
    except ImportError:
        GIT_COMMIT = None
    return {"ldem_version": __version__, "git_commit": GIT_COMMIT or None,
            "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
            "host": platform.node(), "python": platform.python_version()}
