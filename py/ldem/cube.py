"""The cube tension test of the study (LDEM_SPEC section 6), from Python.

    import ldem
    test = ldem.CubeTest(size=0.24, load="triangular", seed=3)
    result = test.run(out="out/cube")          # writes curve.csv, summary.json, ...
    result.curve["mean_strain"], result.curve["stress_MPa"]   # numpy arrays

`CubeTest` holds every parameter with its default, unit and help text; the
command line (`ldem cube --help`) is generated from the same fields. `run`
builds the C++ `Simulation` (ldem._core) and calls its time-step loop.
"""
from __future__ import annotations

import dataclasses
import json
import math
import os
import time
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from . import _core
from .mincut import cheapest_cut

_MAT, _LOAD, _RUN = _core.Material(), _core.LoadingParams(), _core.RunParams()


def _param(default, unit, help, **kw):
    return field(default=default, metadata={"unit": unit, "help": help, **kw})


@dataclass
class CubeTest:
    """A concrete cube pulled in tension: geometry, material, loading, run control."""

    size: float = _param(0.12, "m", "side of the cube (a multiple of L0)")
    L0: float = _param(0.02, "m", "side of a cubic module")
    load: str = _param("uniform", "", "upper-face displacement: uniform or triangular",
                       choices=("uniform", "triangular"))
    seed: int = _param(1, "", "random specimen (same seed, same specimen)")
    E: float = _param(_MAT.E, "Pa", "Young's modulus")
    nu: float = _param(_MAT.nu, "", "Poisson's ratio, in [0, 0.5)")
    rho: float = _param(_MAT.rho, "kg/m^3", "density")
    Gf_mean: float = _param(_MAT.Gf_mean, "N/m", "mean specific fracture energy E[G_f]")
    Gf_cv: float = _param(_MAT.Gf_cv, "", "coefficient of variation of G_f (1 = 100%%)")
    corr_length: float = _param(_MAT.corr_length, "m", "correlation length of G_f (0: one draw per bar)")
    Gf_draw: str = _param("module" if _MAT.Gf_per_module else "bar", "", "G_f drawn per bar, or per module "
                          "(the bars of a module alike)", choices=("bar", "module"))
    eps_p: float = _param(_MAT.eps_p, "", "critical strain of a bar (end of the elastic branch)")
    c_a: float = _param(_MAT.c_a, "", "fracture-area coefficient c_a")
    zeta: float = _param(_RUN.zeta, "", "damping ratio on the fundamental mode (D_f = 2 zeta omega_1)")
    strain_rate: float = _param(_LOAD.strain_rate, "1/s", "vertical strain rate at the most-pulled edge")
    stop_at: str = _param("separation", "", "the event that ends the run: separation (no chain of intact bars "
                          "joins the faces) or load_loss", choices=("separation", "load_loss"))
    final_strain: float = _param(_RUN.final_strain, "", "stop at this mean strain if the event has not come")
    loss_speedup: float = _param(_LOAD.loss_speedup, "", "drive velocity factor once the load is lost (reaches "
                                 "separation in fewer steps)")
    ramp_time: float = _param(_LOAD.ramp_time, "s", "smooth start of the loading (0: two fundamental periods)")
    top_lateral: str = _param("free", "", "lateral DOFs of the upper nodes: free or fixed",
                              choices=("free", "fixed"))
    bottom_lateral: str = _param("fixed", "", "lateral DOFs of the lower nodes: fixed, or free (rollers)",
                                 choices=("fixed", "free"))
    dt: float = _param(_RUN.dt, "s", "time step (0: safety x stability limit)")
    dt_safety: float = _param(_RUN.dt_safety, "", "fraction of the stability limit 2/omega_max allowed")
    stop_fraction: float = _param(_RUN.stop_fraction, "", "the load is lost when the stress, averaged over the "
                                  "split window, is below this fraction of the peak")
    split_window: float = _param(_RUN.split_window, "s", "averaging time of the load-loss test (0: two fundamental "
                                 "periods)")
    energy_tolerance: float = _param(_RUN.energy_tolerance, "", "a run whose energy balance error exceeds this "
                                     "is flagged energy_error (and ldem exits 1)")
    record_every: int = _param(_RUN.record_every, "steps", "steps between curve rows (0: one per eps_p/50 of mean "
                               "strain at the initial rate)")
    threads: int = _param(_RUN.threads, "", "OpenMP threads (0: all cores)")

    # -- checks -------------------------------------------------------------
    def modules(self) -> int:
        """Modules along one side; raises ValueError unless size is a positive multiple of L0."""
        if not (self.L0 > 0) or not math.isfinite(self.L0):
            raise ValueError(f"module size L0 must be positive (got {self.L0} m)")
        if not (self.size > 0) or not math.isfinite(self.size):
            raise ValueError(f"cube size must be positive (got {self.size} m)")
        n = self.size / self.L0
        if abs(n - round(n)) > 1e-9 * max(1.0, n):
            raise ValueError(f"cube size {self.size} m is not a multiple of L0 = {self.L0} m")
        return int(round(n))

    def core_params(self):
        """The three C++ parameter structs; raises ValueError on bad input."""
        if self.stop_at not in ("separation", "load_loss"):
            raise ValueError(f"unknown stop event '{self.stop_at}' (expected separation or load_loss)")
        if self.load not in ("uniform", "triangular"):
            raise ValueError(f"unknown load '{self.load}' (expected uniform or triangular)")
        for name in ("top_lateral", "bottom_lateral"):
            if getattr(self, name) not in ("free", "fixed"):
                raise ValueError(f"{name} must be free or fixed (got '{getattr(self, name)}')")
        if self.seed < 0:
            raise ValueError(f"seed must be >= 0 (got {self.seed})")
        m = _core.Material()
        m.E, m.nu, m.rho, m.Gf_mean, m.Gf_cv = self.E, self.nu, self.rho, self.Gf_mean, self.Gf_cv
        m.corr_length, m.eps_p, m.c_a = self.corr_length, self.eps_p, self.c_a
        if self.Gf_draw not in ("bar", "module"):
            raise ValueError(f"Gf_draw must be bar or module (got '{self.Gf_draw}')")
        m.Gf_per_module = self.Gf_draw == "module"
        m.validate()
        lp = _core.LoadingParams()
        lp.shape, lp.strain_rate, lp.ramp_time = self.load, self.strain_rate, self.ramp_time
        lp.top_lateral_free = self.top_lateral == "free"
        lp.bottom_lateral_free = self.bottom_lateral == "free"
        lp.loss_speedup = self.loss_speedup
        rp = _core.RunParams()
        rp.seed, rp.zeta, rp.dt, rp.dt_safety = self.seed, self.zeta, self.dt, self.dt_safety
        rp.final_strain, rp.stop_fraction, rp.split_window = self.final_strain, self.stop_fraction, self.split_window
        rp.record_every, rp.threads = self.record_every, self.threads
        rp.stop_at, rp.energy_tolerance = self.stop_at, self.energy_tolerance
        return m, lp, rp

    def simulation(self) -> "_core.Simulation":
        """Builds the specimen (lattice, random G_f, frequencies, time step)."""
        n = self.modules()
        m, lp, rp = self.core_params()
        return _core.Simulation(n, n, n, self.L0, m, lp, rp)

    def parameters(self) -> dict:
        return dataclasses.asdict(self)

    # -- running ------------------------------------------------------------
    def run(self, out: Optional[str] = None, progress: Optional[bool] = None,
            plots: bool = True, simulation=None) -> "CubeResult":
        """Runs the test to separation (or load loss, see stop_at; or the final strain).

        out: folder for curve.csv (written row by row), summary.json, curve.png,
        energies.png, cracks.png and bars.vtu; None writes nothing. progress: a
        progress bar on stderr (default: when stderr is a terminal).
        simulation: a specimen from self.simulation(), if you built it already.
        """
        from . import output  # plotting and VTK are only needed with files

        if out is not None:
            output.prepare_dir(out)
        t0 = time.perf_counter()
        sim = simulation if simulation is not None else self.simulation()
        rows = []
        writer = _core.CurveCsvWriter(os.path.join(out, "curve.csv")) if out else None
        bar = output.ProgressBar(self.final_strain, enabled=progress)

        def observe(p):
            rows.append(p)
            if writer is not None:
                writer.write(p)
            bar.update(p)
            return True

        summary, error = None, None
        try:
            summary = sim.run(observe)
        except BaseException as e:  # keep what was computed, then let it propagate
            error = e
            raise
        finally:
            bar.close()
            result = CubeResult(self, sim, rows, summary, time.perf_counter() - t0, error)
            if out is not None:
                output.write_summary(result, out)
        if out is not None and plots:
            output.write_outputs(result, out)
        return result


CURVE_COLUMNS = _core.CurveCsvWriter.header.split(",")


class CubeResult:
    """What a run produced: the curve as numpy arrays, the summary, the final state."""

    def __init__(self, test: CubeTest, sim, points, summary, wall_s: float, error=None):
        self.test, self.sim, self.wall_s = test, sim, wall_s
        if error is None:
            self.status = "done"
        else:
            self.status = "interrupted" if isinstance(error, KeyboardInterrupt) else "failed"
        self.curve = _curve_arrays(points)
        self.summary = _summary_dict(test, sim, self.curve, summary, wall_s, self.status)
        if error is not None:
            self.summary["error"] = str(error) or type(error).__name__

    @property
    def peak_stress_MPa(self) -> float:
        return self.summary["peak_stress_MPa"]

    @property
    def strain_at_peak(self) -> float:
        return self.summary["strain_at_peak"]

    def save_summary(self, path: str) -> None:
        with open(path, "w") as f:
            json.dump(self.summary, f, indent=2)
            f.write("\n")


def _curve_arrays(points) -> dict:
    get = {
        "step": "step", "time_s": "time", "mean_strain": "mean_strain", "external_work_J": "external_work",
        "kinetic_J": "kinetic", "elastic_J": "elastic", "fracture_J": "fracture", "damping_J": "damping",
        "damaged_bars": "damaged", "broken_bars": "broken",
    }
    curve = {c: np.array([getattr(p, get[c]) for p in points], dtype=float) for c in get}
    curve["stress_MPa"] = np.array([p.stress_bottom for p in points], dtype=float) * 1e-6
    curve["stress_top_MPa"] = np.array([p.stress_top for p in points], dtype=float) * 1e-6
    return {c: curve[c] for c in CURVE_COLUMNS}


def _event(e) -> dict:
    """An event of the run (RunEvent) for summary.json; None if it never came."""
    if not e.reached:
        return None
    return {"step": e.step, "time_s": e.time, "mean_strain": e.mean_strain, "fracture_energy_J": e.fracture}


def _summary_dict(test, sim, curve, summary, wall_s, status) -> dict:
    u_min = sim.min_fracture_energy
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
            "U_ratio": None if u_num is None else u_num / u_min,
            "load_loss": _event(summary.load_loss),
            "separation": _event(sep),
            "fracture_energy_J": summary.fracture_energy,
            "min_fracture_energy_J": u_min,
            "U_mincut_J": cheapest_cut(sim),
            "energy_balance_error": summary.energy_balance_error,
            "energy_error": summary.energy_error,
            "stop_reason": summary.stop_reason,
        })
    elif len(curve["stress_MPa"]):  # failed run: what the rows recorded so far say
        k = int(np.argmax(curve["stress_MPa"]))
        s.update({"peak_stress_MPa": float(curve["stress_MPa"][k]),
                  "strain_at_peak": float(curve["mean_strain"][k]),
                  "fracture_energy_J": float(curve["fracture_J"][-1]), "min_fracture_energy_J": u_min})
    s.update({
        "clamped_bars": sim.clamped_bars,
        "n_nodes": sim.lattice.n_nodes,
        "n_bars": sim.lattice.n_bars,
        "steps": sim.steps,
        "dt_s": sim.dt,
        "dt_limit_s": sim.dt_limit,
        "omega1_rad_s": sim.omega1,
        "omega_max_rad_s": sim.omega_max,
        "damping_coefficient_1_s": sim.damping_coefficient,
        "ramp_time_s": sim.ramp_time,
        "split_window_s": sim.split_window,
        "threads": test.threads or _core.max_threads(),
        "wall_s": wall_s,
        "parameters": test.parameters(),
    })
    return s
