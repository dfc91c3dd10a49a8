"""An ldem Simulation rebuilt in YADE's O (SimulationSpecimen: the study's
cube or any specimen of ldem.specimen) and run to separation by
Simulation::run's rules (see ldem.yade)."""
import math

import numpy as np

from .. import _core
from .scene import (SEPARATION_CHECK, CpmBars, RuptureGuard, _ramp_integral, _register, _yade, add_node, bar_material,
                    drive_mul_add, make_engines)


def constraints(sim):
    """ldem's prescribed DOFs (Simulation.prescribed_dofs) in YADE's terms: per
    node a blockedDOFs string (translations), and the driven DOFs (node,
    direction, weight): u = weight x U(t)."""
    dofs = sim.prescribed_dofs()
    held = [""] * sim.lattice.n_nodes
    driven = []
    for n, d, w in zip(dofs["node"], dofs["dim"], dofs["weight"]):
        held[int(n)] += "xyz"[int(d)]
        if w != 0:
            driven.append((int(n), int(d), float(w)))
    return held, driven


def _event(step, time, mean_strain, fracture):
    """An event of the run, with the keys of ldem cube's summary.json."""
    return {"step": int(step), "time_s": float(time), "mean_strain": float(mean_strain),
            "fracture_energy_J": float(fracture)}


class SimulationSpecimen:
    """The ldem specimen ``sim`` (an ldem._core.Simulation: the cube test or any
    ldem.SpecimenTest's) rebuilt in YADE's O: same nodes, masses, bars, per-bar
    eps_r (from the same seed, read from sim.eps_r), held and driven DOFs, drive
    U(t) (with its speed-up after the load loss), measures (the support group's
    reactions along the drive over the area, positive in the sense of the
    drive), dt and record steps."""

    def __init__(self, sim, damping=0.0, radius_factor=0.25, reset=True, name="_ldem_yade_specimen"):
        if sim.steps != 0:
            raise ValueError("SimulationSpecimen needs an ldem Simulation that has not run yet (its initial state)")
        if sim.measures["control"] >= 0:
            raise ValueError("the YADE bridge drives by displacement only: opening control (measure.control) is "
                             "ldem's own")
        if sim.dt * sim.omega_max / 2 > 0.4 * (1 + 1e-12):  # ldem's default step leans on its bar dashpots
            raise ValueError(f"the YADE bridge has no bar dashpots (ldem's zeta_high), so its step must stay at 0.4 of "
                             f"the limit: build the ldem specimen with zeta_high=0 and dt_safety=0.4 (its step is "
                             f"{sim.dt * sim.omega_max / 2:.3g} of 2/omega_max)")
        y = _yade()
        O = self.O = y["O"]
        if reset:
            O.reset()
        lat = sim.lattice
        self.sim = sim
        self.height, self.face_area = sim.gauge_length, sim.area
        self.dt = sim.dt
        self.radius = radius_factor * lat.L0
        held, self.driven = constraints(sim)
        m = sim.measures
        self.dim, self.sense = int(m["dim"]), m["sense"]
        self.mean_weight = abs(m["mean_drive_weight"])  # ldem's own number
        self.support = [int(n) for n in sim.group(m["support"])]
        self.loaded = [int(n) for n in sim.group(m["loaded"])]
        # ldem's Drive: v0, ramp, and the speed-up from the load loss on (never, until then)
        self.v0 = sim.loading.strain_rate * sim.gauge_length
        self.speedup = sim.loading.loss_speedup
        self.ramp_time = sim.ramp_time
        self.speedup_start = math.inf
        self._mul_add = drive_mul_add(sim)
        self.record_every = sim.record_every

        self._name = _register(name, self)
        O.engines = make_engines(
            damping=damping,
            before_forces=[y["PyRunner"](command=self._name + "._before_forces()", iterPeriod=1, initRun=True,
                                         label="ldem_drive_guard")],
            after_forces=[y["PyRunner"](command=self._name + "._after_forces()", iterPeriod=1, initRun=True,
                                        label="ldem_recorder")])
        O.dt = self.dt
        mat = O.materials.append(bar_material(sim.eps_p))
        x0, y0, z0, mass = (np.asarray(a) for a in (lat.x0, lat.y0, lat.z0, lat.mass))
        for n in range(lat.n_nodes):
            bid = add_node((x0[n], y0[n], z0[n]), mass[n], self.radius, mat, held[n])
            assert bid == n
        x0 = np.column_stack([x0, y0, z0])
        self.driven_x0 = [float(x0[n, d]) for n, d, _ in self.driven]
        self.loaded_x0_mean = float(np.mean(x0[self.loaded, self.dim]))
        table = lat.bar_table()
        self.bars = CpmBars(table["n1"], table["n2"], table["EA"], table["length"], sim.eps_p, sim.eps_r, self.radius)
        self.states = [b.state for b in O.bodies]
        self.driven_states = [self.states[n] for n, _, _ in self.driven]
        self.loaded_states = [self.states[n] for n in self.loaded]
        self.guard = RuptureGuard(self.bars, self.states)
        self.curve = []  # (step, time, mean_strain, stress_support, stress_loaded, damaged, broken)
        self.peak_stress, self.strain_at_peak = 0.0, 0.0
        self._cell_sum, self._cell_states = 0.0, 0  # ldem's load cell: the states since the last record
        self.stop_reason = ""
        self.final_strain, self.callback, self.stop_at = math.inf, None, "separation"
        self.load_loss = self.separation = None
        self.separation_checks = 0
        self._last_check = -SEPARATION_CHECK
        self.split = _core.LoadLossDetector(sim.split_window, 0.01)

    def drive(self, t):
        """U(t) [m], pkg/ldem/Loading.cpp's Drive::displacement with the same
        roundings: sim's U(t) (never sped up, sim has not run), plus
        (speedup - 1) v0 rampIntegral(t - t_loss) once the load is lost."""
        U = self.sim.drive_displacement(t)
        if t <= self.speedup_start:
            return U
        fma = self._mul_add
        return fma((self.speedup - 1) * self.v0, _ramp_integral(t - self.speedup_start, self.ramp_time, fma), U)

    def faces_joined(self):
        """Some chain of intact bars (kappa < eps_r) joins the upper and lower
        faces: ldem's own test (_core.nodes_joined), on YADE's bar states."""
        self.separation_checks += 1
        return _core.nodes_joined(self.sim.lattice, self.guard.intact(), self.loaded, self.support)

    # -- engines -------------------------------------------------------------
    def _before_forces(self):
        O = self.O
        t, dt = O.time, O.dt
        U, Unext = self.drive(t), self.drive(t + dt)
        for s, x0, (_, d, w) in zip(self.driven_states, self.driven_x0, self.driven):
            p, v = list(s.pos), list(s.vel)
            p[d], v[d] = x0 + w * U, w * (Unext - U) / dt
            s.pos, s.vel = type(s.pos)(*p), type(s.vel)(*v)
        self.guard()

    def _after_forces(self):
        O = self.O
        if not self.bars.finished:
            self.bars.finish_first_step()
        d, sense = self.dim, self.sense
        f_support = sum(O.forces.f(n)[d] for n in self.support)
        f_loaded = sum(O.forces.f(n)[d] for n in self.loaded)
        disp = sum(s.pos[d] for s in self.loaded_states) / len(self.loaded) - self.loaded_x0_mean
        strain = sense * disp / self.height
        stress = sense * f_support / self.face_area
        damaged, broken = self.guard.counts()
        self.curve.append((O.iter, O.time, strain, stress, -sense * f_loaded / self.face_area, damaged, broken))
        self._cell_sum += stress
        self._cell_states += 1
        keep = True if self.callback is None else self.callback(self.curve[-1]) is not False
        if O.iter % self.record_every == 0:  # ldem's record steps: its events and stops come only there
            # ldem's record is a load cell's: the mean over the states of its interval, and its peak the largest
            cell = self._cell_sum / self._cell_states
            self._cell_sum, self._cell_states = 0.0, 0
            if cell > self.peak_stress:
                self.peak_stress, self.strain_at_peak = cell, strain
            self._events(cell, broken)
        if not self.stop_reason and not keep:
            self.stop_reason = "stopped"
        if self.stop_reason:
            O.pause()

    def _events(self, stress, broken):
        """Simulation::run's tests at a record step, in its order."""
        O = self.O
        n, t = O.iter, O.time
        mean_strain = self.drive(t) * self.mean_weight / self.height  # ldem's meanStrainAt(t)
        if self.load_loss is None and self.split.update(t, stress, self.peak_stress, broken):
            self.load_loss = _event(n, t, mean_strain, self.guard.fracture_energy())
            self.speedup_start = t  # U(t_n) unchanged; from t_n+1 on, faster
        if broken > 0 and stress < 0.5 * self.peak_stress and n - self._last_check >= SEPARATION_CHECK:
            self._last_check = n
            if not self.faces_joined():
                self.separation = _event(n, t, mean_strain, self.guard.fracture_energy())
        if self.separation is not None:
            self.stop_reason = "separated"
        elif self.stop_at == "load_loss" and self.load_loss is not None:
            self.stop_reason = "load_lost"
        elif mean_strain >= self.final_strain:
            self.stop_reason = "final_strain"

    # -- run -----------------------------------------------------------------
    def run(self, final_strain=None, stop_fraction=None, stop_at="separation", max_steps=None, callback=None):
        """Runs as ldem's Simulation.run: until separation (no chain of intact bars
        joins the faces; the drive sped up by loss_speedup from the load loss on: a
        Simulation with tail_drive 'fixed', else ValueError),
        or with stop_at="load_loss" until the load-loss test (_core.LoadLossDetector:
        stress averaged over the split window < stop_fraction x peak, after bars
        broke), or until the mean strain reaches final_strain, or callback(row)
        returns False. final_strain and stop_fraction default to ldem's RunParams.
        Returns a dict with peak_stress [Pa], strain_at_peak, steps (the step of
        the last row, as ldem's summary.steps), stop_reason ("separated",
        "load_lost", "final_strain", "stopped" or "max_steps"), load_loss and
        separation (None, or dict step, time_s, mean_strain, fracture_energy_J,
        as in ldem's summary.json), fracture_energy_J (at the end),
        separation_checks, curve (numpy array of step, time, mean_strain,
        stress_support, stress_loaded, damaged, broken: every step), guard_early,
        lost_bars."""
        if stop_at != "load_loss" and self.sim.loading.tail_drive != "fixed":
            raise ValueError("past the load loss the YADE bridge follows ldem's fixed drive only: build the "
                             "Simulation with tail_drive='fixed' (the adaptive one is ldem's own)")
        if stop_at not in ("separation", "load_loss"):
            raise ValueError(f"unknown stop event '{stop_at}' (expected separation or load_loss)")
        defaults = _core.RunParams()
        final_strain = defaults.final_strain if final_strain is None else final_strain
        stop_fraction = defaults.stop_fraction if stop_fraction is None else stop_fraction
        self.final_strain, self.callback, self.stop_at = final_strain, callback, stop_at
        self.split = _core.LoadLossDetector(self.sim.split_window, stop_fraction)
        self.stop_reason = ""
        if max_steps is None:  # time to the final strain + ramp at the initial rate (no speed-up), with margin
            t_final = final_strain * self.height / (self.v0 * self.mean_weight) + 0.5 * self.ramp_time
            max_steps = int(1.2 * t_final / self.dt) + 10
        self.O.run(int(max_steps), True)
        if not self.stop_reason:
            self.stop_reason = "max_steps"
        steps = int(self.curve[-1][0]) if self.curve else 0
        return dict(peak_stress=self.peak_stress, strain_at_peak=self.strain_at_peak, steps=steps,
                    stop_reason=self.stop_reason, load_loss=self.load_loss, separation=self.separation,
                    fracture_energy_J=self.guard.fracture_energy(), separation_checks=self.separation_checks,
                    curve=np.array(self.curve), guard_early=list(self.guard.early),
                    lost_bars=self.bars.check_alive())
