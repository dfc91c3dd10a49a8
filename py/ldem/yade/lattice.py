"""Any lattice given as arrays (LatticeSpecimen), run in YADE with
mass-proportional damping (ViscousDamping) (see ldem.yade)."""
import math

import numpy as np

from .scene import CpmBars, RuptureGuard, _register, _yade, add_node, bar_material, make_engines


class ViscousDamping:
    """Mass-proportional viscous damping C = D_f M (LDEM_SPEC section 5), which
    YADE does not have: call it once per step after the forces and before
    NewtonIntegrator (with NewtonIntegrator.damping = 0). On every free DOF it
    adds the force

        F_d = -(D_f m v + a F) / (1 + a),    a = D_f dt / 2,

    v = v(n-1/2) (the body's velocity before Newton), F = the force on the DOF
    (the bars'), so that NewtonIntegrator's v + dt (F + F_d)/m equals, in exact
    arithmetic, the spec's

        v(n+1/2) = [(1 - a) v(n-1/2) + dt F/m] / (1 + a).

    Energies as tests/reference/ldem_ref.py keeps them: ``kinetic`` is
    1/2 m v(n-1/2)^2 over the free DOFs at the last call; the call returns the
    damping work of the steps before this one, sum over k < n of
    dt D_f m vbar_k^2, vbar_k = (v(k-1/2) + v(k+1/2))/2, and adds step n's.

    states: the bodies' states in body-id order; mass: per body; free: (bodies, 3)
    bool, the DOFs that are integrated (not blocked)."""

    def __init__(self, states, mass, free, damping_coefficient, dt):
        free = np.asarray(free, dtype=bool)
        sel = free.any(axis=1)
        self.ids = [int(i) for i in np.flatnonzero(sel)]
        self.states = [states[i] for i in self.ids]
        self.m = np.asarray(mass, dtype=float)[sel][:, None]
        self.free = free[sel]
        self.D, self.dt = float(damping_coefficient), float(dt)
        self.a = 0.5 * self.D * self.dt
        self.work = 0.0
        self.kinetic = 0.0

    def __call__(self, forces, vector3):
        v = np.array([[u[0], u[1], u[2]] for u in (s.vel for s in self.states)])
        self.kinetic = float(0.5 * (self.m * v * v)[self.free].sum())
        before = self.work
        if self.D == 0.0:
            return before
        F = np.array([[f[0], f[1], f[2]] for f in (forces.f(i) for i in self.ids)])
        a, dt, D, m = self.a, self.dt, self.D, self.m
        v_new = ((1.0 - a) * v + dt * F / m) / (1.0 + a)
        vbar = 0.5 * (v + v_new)
        self.work += float(dt * D * (m * vbar * vbar)[self.free].sum())
        Fd = np.where(self.free, -(D * m * v + a * F) / (1.0 + a), 0.0)
        for i, f in zip(self.ids, Fd):
            forces.addF(i, vector3(float(f[0]), float(f[1]), float(f[2])))
        return before


class LatticeSpecimen:
    """A lattice given as plain arrays, built in YADE's O without ldem: the
    YADE side of scripts/yade_crosscheck.py, whose specimen comes from
    tests/reference/ldem_ref.py (the spec), not from the engine it checks.

    X (nodes, 3) [m], mass (nodes,) [kg]; bars n1, n2, EA [N], L [m], eps_p,
    eps_r (per bar); held: per node the blocked translations ("xyz", "z", "");
    top: the upper nodes, whose z is prescribed z0 + w U(t) with w =
    top_weights and U = drive(t) [m]; bottom: the lower nodes (their vertical
    reactions are the stress); dt [s]; damping_coefficient D_f [1/s]
    (``ViscousDamping``; 0: undamped); height, face_area of the specimen.

    Each step n (t_n = n dt), as the reference's bookkeeping: before the forces
    the upper nodes are put at z0 + w U(t_n), moving at w (U(t_n+1) - U(t_n))/dt,
    and the RuptureGuard runs; after the forces a row (step, time, mean_strain,
    stress_bottom, stress_top, external_work, kinetic, damping, damaged, broken)
    is recorded, the work and damping of the steps before n; then the damping
    force is added and the external work of step n,
    1/2 sum_top R_z w (U(t_n+1) - U(t_n-1)) (R_z the bars' pull on the node),
    is added. Every energy_every steps also (step, elastic, fracture): elastic
    from YADE's own interactions, 1/2 sum |normalForce| |epsN| L; fracture
    = dissipated(kappa) (default RuptureGuard.fracture_energy) on the guard's
    kappa."""

    def __init__(self, X, mass, n1, n2, EA, L, eps_p, eps_r, held, top, top_weights, bottom, drive, dt,
                 height, face_area, damping_coefficient=0.0, radius=None, energy_every=10, dissipated=None,
                 reset=True, name="_ldem_yade_lattice"):
        y = _yade()
        O = self.O = y["O"]
        if reset:
            O.reset()
        self._vector3 = y["Vector3"]
        X = np.asarray(X, dtype=float)
        mass = np.asarray(mass, dtype=float)
        self.L = np.asarray(L, dtype=float)
        self.dt, self.height, self.face_area = float(dt), float(height), float(face_area)
        self.drive = drive
        self.top = [int(n) for n in top]
        self.bottom = [int(n) for n in bottom]
        self.top_weights = np.asarray(top_weights, dtype=float)
        self.radius = 0.25 * float(np.min(self.L)) if radius is None else float(radius)
        self.energy_every = int(energy_every)
        self._name = _register(name, self)
        O.engines = make_engines(
            damping=0.0,
            before_forces=[y["PyRunner"](command=self._name + "._before_forces()", iterPeriod=1, initRun=True,
                                         label="ldem_drive_guard")],
            after_forces=[y["PyRunner"](command=self._name + "._after_forces()", iterPeriod=1, initRun=True,
                                        label="ldem_recorder_damping")])
        O.dt = self.dt
        mat = O.materials.append(bar_material(float(np.max(eps_p))))
        free = np.ones((len(X), 3), dtype=bool)
        for n in range(len(X)):
            bid = add_node(X[n], mass[n], self.radius, mat, held[n])
            assert bid == n
            for c, axis in enumerate("xyz"):
                free[n, c] = axis not in held[n]
        self.z0_top = X[self.top, 2]
        self.z0_top_mean = float(np.mean(self.z0_top))
        self.bars = CpmBars(n1, n2, EA, self.L, eps_p, eps_r, self.radius)
        self.states = [b.state for b in O.bodies]
        self.top_states = [self.states[n] for n in self.top]
        self.guard = RuptureGuard(self.bars, self.states)
        self.damper = ViscousDamping(self.states, mass, free, damping_coefficient, self.dt)
        self.dissipated = self.guard.fracture_energy if dissipated is None else (
            lambda: float(dissipated(self.guard.kappa)))
        self.curve, self.energies = [], []
        self.external_work = 0.0
        self.peak_stress, self.strain_at_peak, self.peak_step = -math.inf, 0.0, -1
        self.final_strain = math.inf

    def elastic_energy(self):
        """1/2 sum over the bars of |F| |eps| L, F and eps YADE's own (CpmPhys
        normalForce and epsN): the secant energy, F and eps having one sign."""
        return 0.5 * sum(i.phys.normalForce.norm() * abs(i.phys.epsN) * L
                         for i, L in zip(self.bars.interactions, self.L))

    # -- engines -------------------------------------------------------------
    def _before_forces(self):
        n = self.O.iter
        U, Unext = self.drive(n * self.dt), self.drive((n + 1) * self.dt)
        for s, z0, w in zip(self.top_states, self.z0_top, self.top_weights):
            p, v = s.pos, s.vel
            s.pos = type(p)(p[0], p[1], z0 + w * U)
            s.vel = type(v)(v[0], v[1], w * (Unext - U) / self.dt)
        self.guard()

    def _after_forces(self):
        O = self.O
        if not self.bars.finished:
            self.bars.finish_first_step()
        n, dt = O.iter, self.dt
        forces = O.forces
        fz_bottom = sum(forces.f(i)[2] for i in self.bottom)
        fz_top = np.array([forces.f(i)[2] for i in self.top])
        strain = (sum(s.pos[2] for s in self.top_states) / len(self.top) - self.z0_top_mean) / self.height
        stress = fz_bottom / self.face_area
        damping_work = self.damper(forces, self._vector3)  # adds the damping forces (free DOFs only)
        damaged, broken = self.guard.counts()
        self.curve.append((n, n * dt, strain, stress, -fz_top.sum() / self.face_area, self.external_work,
                           self.damper.kinetic, damping_work, damaged, broken))
        if n % self.energy_every == 0:
            self.energies.append((n, self.elastic_energy(), self.dissipated()))
        if stress > self.peak_stress:
            self.peak_stress, self.strain_at_peak, self.peak_step = stress, strain, n
        U_prev = self.drive((n - 1) * dt) if n > 0 else 0.0  # x(-1) = x(0): the specimen starts at rest
        self.external_work += 0.5 * float(np.dot(-fz_top, self.top_weights)) * (self.drive((n + 1) * dt) - U_prev)
        if strain >= self.final_strain:
            O.pause()

    def run(self, final_strain, max_steps):
        """Runs until the mean strain reaches final_strain (that step recorded) or
        max_steps. Returns a dict: peak_stress [Pa], strain_at_peak, peak_step,
        steps (the last row's step), curve (array: step, time, mean_strain,
        stress_bottom, stress_top, external_work, kinetic, damping, damaged,
        broken), energies (array: step, elastic, fracture), lost_bars (must be
        0), guard_early (bars switched before eps_r; must be empty),
        guard_strain_mismatch (RuptureGuard.verify(); must be 0), ruptured (bars
        that reached eps_r), closed (of those, compressed later: crack closure)."""
        self.final_strain = float(final_strain)
        self.O.run(int(max_steps), True)
        return dict(peak_stress=self.peak_stress, strain_at_peak=self.strain_at_peak, peak_step=self.peak_step,
                    steps=int(self.curve[-1][0]) if self.curve else 0, curve=np.array(self.curve),
                    energies=np.array(self.energies), lost_bars=self.bars.check_alive(),
                    guard_early=list(self.guard.early), guard_strain_mismatch=self.guard.verify(),
                    ruptured=int(self.guard.switched.sum()), closed=int(self.guard.closed.sum()))
