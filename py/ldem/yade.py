"""Run an ldem lattice in YADE, with YADE's own integrator and a native YADE
law, as an independent check of the ldem engine (issue 5).

Use inside YADE (``yade-double -n -x script.py``)::

    import ldem.yade
    from ldem import _core
    lp = _core.LoadingParams(); rp = _core.RunParams(); rp.zeta = 0
    sim = _core.Simulation(6, 6, 6, 0.02, _core.Material(), lp, rp)
    spec = ldem.yade.CubeSpecimen(sim)         # fills YADE's O
    result = spec.run()                          # to separation, as sim.run() would
    # dict: peak_stress, strain_at_peak, load_loss, separation, stop_reason, curve...

or, for a specimen that does not come from ldem (scripts/yade_crosscheck.py
builds one from tests/reference/ldem_ref.py), ``LatticeSpecimen(X, mass, n1,
n2, EA, L, eps_p, eps_r, held, top, weights, bottom, drive, dt, height,
face_area, damping_coefficient=D_f)``, damped by ``ViscousDamping``.

Importing this module does not import YADE; the functions that need it import
it when they are called, so the module can be imported (and its pure helpers
used) from any Python.

How one ldem bar becomes one YADE interaction
---------------------------------------------
Node = sphere (radius ``radius_factor * L0``; the radius plays no role in the
forces, see below), ``blockedDOFs`` with the rotations always blocked, mass set
to the lattice's lumped mass. Bar = one interaction made explicitly with
``utils.createInteraction`` (there is no collider, so no other interaction ever
appears), geometry ``Ig2_Sphere_Sphere_ScGeom``, physics
``Ip2_CpmMat_CpmMat_CpmPhys``, law ``Law2_ScGeom_CpmPhys_Cpm`` (the concrete
particle model, "Cpm"). Debian's YADE is built without the closed
``brefcom-mm.hh`` full model, so the law runs its "simplified public model"
(pkg/dem/ConcretePM.cpp), which with our settings is exactly::

    epsN   = (refPD - penetrationDepth) / refLength           = (l - L) / L
             (refPD = r1 + r2 - L, penetrationDepth = r1 + r2 - l)
    kappaD = max(kappaD, max(epsN, 0))                        (equivStrainShearContrib = 0)
    omega  = 0                                    if kappaD < epsCrackOnset
           = (1 - e0/kappaD) / (1 - e0/ef)        otherwise   (damLaw = 0: linear softening)
    sigmaN = (1 - omega) E epsN  if epsN > 0,   E epsN  if epsN <= 0
    Fn     = sigmaN * crossSection                (along the current centre line)
    shear  = G (epsT - epsTPl) * crossSection = 0 (G = 0: no shear stiffness)

With e0 = epsCrackOnset = eps_p, ef = epsFracture = eps_r, E crossSection = EA:

    1 - omega = e0 (ef - kappa) / (kappa (ef - e0))

which is ldem's secant ratio s(kappa) = eps_p (eps_r - kappa) / (kappa (eps_r - eps_p)),
so F = EA eps s(kappa) in tension and EA eps in compression: Hillerborg's
triangle with secant unloading/reloading, identical term by term. Rate
effects (dmgTau, plTau, dmgRateExp, plRateExp) and the yield surfaces exist only
in the closed full model; compressive plasticity is off (Law2.epsSoft = 1 >= 0),
isoPrestress = 0, neverDamage = False.

Per-bar parameters: Ip2 copies the material's values into every CpmPhys, and the
law's first call on an interaction ("fresh") sets crossSection = pi min(r)^2,
refLength = |x2 - x1|, refPD, kn, ks and epsFracture = epsCrackOnset *
relDuctility. So each interaction gets E = EA / (pi r^2), G = 0, epsCrackOnset =
eps_p, relDuctility = eps_r / eps_p before step 0, and after step 0 (all strains
are still exactly zero then) ``finish_first_step`` overwrites crossSection = 1,
E = EA, epsFracture = eps_r, refLength = L, refPD = r1 + r2 - L, kn = EA / L
with ldem's exact numbers.

What YADE cannot express natively, and the guard that fixes it
--------------------------------------------------------------
The Cpm law deletes an interaction as soon as it is in tension with omega >
omegaThreshold (<= 1), or not cohesive; with damLaw = 0, omega > 1 beyond
epsFracture (and the force would change sign if it were kept), and for a
clamped, perfectly brittle bar (eps_r = eps_p) omega is 0/0 = NaN at
kappa = eps_p (YADE's check then fails: "Verification `!math::isnan(sigmaN)'
failed!", terminate, SIGABRT) and +inf beyond. So a ruptured bar disappears
and can never push again: no crack closure. ldem's bar stays and is elastic in
compression after rupture. ``RuptureGuard`` keeps YADE exact: before every
force evaluation (a PyRunner placed before the InteractionLoop) it computes
every bar's strain from the positions the law is about to use, with the same
floating-point operations as Ig2_Sphere_Sphere_ScGeom and the law, so it is
bit-identical to the law's epsN::

    d = x2 - x1;  norm = sqrt(dx dx + (dy dy + dz dz));  pd = (r1 + r2) - norm
    epsN = (refPD - pd) / refLength

and a bar whose strain reaches eps_r (epsN >= epsFracture, i.e. kappa >= eps_r,
where ldem's force is zero) gets epsCrackOnset = 1e-300 before the law sees it.
A clamped bar (eps_r = eps_p) is given epsCrackOnset = epsFracture =
nextafter(eps_p, +inf) = eps_p+ : ldem's bar is elastic up to kappa = eps_p
inclusive and broken for any kappa > eps_p, i.e. kappa >= eps_p+, so the law
(elastic for kappa < epsCrackOnset) never meets its 0/0.
Then omega = (1 - 1e-300/kappa) / (1 - 1e-300/eps_r) == 1.0 exactly in double
precision, so F = 0 in tension, EA eps in compression, omega never exceeds the
threshold and the interaction is never deleted. ``RuptureGuard.verify()``
compares its strains with the law's epsN (they must be equal) and
``GUARD_MARGIN`` (default 0) can switch bars a relative margin before eps_r if
a platform ever rounds differently.

Integration and damping
-----------------------
``NewtonIntegrator``: v += dt F/m; x += dt v (leapfrog = ldem's central
differences with D_f = 0, same dt). YADE's ``damping`` is *non-viscous
(Cundall) damping*: a_i <- a_i (1 - lambda sign(a_i (v_i + a_i dt/2))) per
component, a force-proportional, frequency-independent friction-like term. It is
*not* the spec's mass-proportional viscous damping C = D_f M, for which YADE has
no native engine. ``ViscousDamping`` adds it: a PyRunner after the forces (before
NewtonIntegrator) adds to every free DOF the force

    F_d = -(D_f m v + a F) / (1 + a),   a = D_f dt / 2,   v = v(n-1/2), F = the bars' force

so that NewtonIntegrator's v + dt (F + F_d)/m is, in exact arithmetic, the
spec's central difference v(n+1/2) = [(1 - a) v(n-1/2) + dt F/m] / (1 + a).
It also keeps the damping work as tests/reference/ldem_ref.py defines it
(dt D_f m vbar^2 over the free DOFs, vbar = (v(n-1/2) + v(n+1/2))/2) and the
kinetic energy 1/2 m v(n-1/2)^2. ``CubeSpecimen`` (ldem's own specimen) runs
undamped or with YADE's Cundall ``damping``; ``LatticeSpecimen`` (a specimen
given as arrays, e.g. from the reference) takes D_f and uses ``ViscousDamping``.

Boundary conditions
-------------------
Those of ldem's cubeTestConstraints (pkg/ldem/Loading.cpp), rebuilt from the
lattice: lower face z held (x, y held too, or on rollers with x, y pinned at
corner (0,0) and y at (nx,0) if bottom_lateral_free); upper face z prescribed,
u_z = w U(t) with w = 1 (uniform) or x0/width (triangular), x, y free unless
top_lateral_free is False. U(t) is ldem's Drive (smooth 1 - cos start over
ramp_time, then v0 = strain_rate * height; once the load is lost, loss_speedup
times faster, with the same smooth start: ``CubeSpecimen.drive``, bit for bit
pkg/ldem/Loading.cpp's Drive::displacement). Each step, before the forces,
the drive sets the upper nodes to z0 + w U(t_n) and their velocity to
w (U(t_n+1) - U(t_n))/dt (YADE moves blocked DOFs with their velocity).

Load loss and separation
------------------------
``CubeSpecimen.run`` applies Simulation::run's rules (pkg/ldem/Simulation.cpp)
to YADE's state: the peak at every step; on ldem's record steps (every
sim.record_every steps) the load-loss test (_core.LoadLossDetector; from then on
the drive speeds up) and, once bars have broken and the stress is below half the
peak, at most every SEPARATION_CHECK steps, the separation test:
_core.nodes_joined (ldem's union-find) over the bars still intact, kappa < eps_r,
with kappa tracked by the RuptureGuard from the law's own strains, between the
upper and lower face nodes (body id = ldem node id, interaction k = ldem bar k).
The run stops at separation (or at load loss with stop_at="load_loss", or at
the final strain), and reports both events with the fracture energy dissipated
by then, sum over the bars of ldem's dissipatedEnergy(kappa).
"""
import math
from fractions import Fraction

import numpy as np

from . import _core


# epsCrackOnset given to a ruptured bar: omega = 1 - 1e-300/kappa == 1.0 exactly.
BROKEN_ONSET = 1e-300
# A bar is switched to "ruptured" once its strain reaches eps_r (1 - GUARD_MARGIN);
# 0 because the guard's strain is bit-identical to the law's (see RuptureGuard).
GUARD_MARGIN = 0.0
# Steps between two separation tests at the least: Simulation::run's kSeparationCheck.
SEPARATION_CHECK = 100


def _fma(a, b, c):
    """a b + c rounded once, as the fused multiply-add GCC emits for ldem's Drive
    (-march=native on a CPU with FMA); Fraction arithmetic is exact and
    float(Fraction) rounds to nearest even."""
    return float(Fraction(a) * Fraction(b) + Fraction(c))


def _mul_add(a, b, c):
    """a b + c rounded twice, as without FMA."""
    return a * b + c


def _ramp_integral(t, tr, mul_add=_fma):
    """Loading.cpp's smoothRampIntegral with the same roundings: integral over
    [0, t] of a velocity rising from 0 to 1 as (1 - cos(pi t/tr))/2."""
    if t <= 0:
        return 0.0
    if t < tr:
        return 0.5 * mul_add(-(tr / math.pi), math.sin(math.pi * t / tr), t)
    return t - 0.5 * tr


def drive_mul_add(sim):
    """_fma or _mul_add, whichever reproduces sim's own U(t) on the ramp bit for
    bit: whether the compiler fused ldem's Drive's multiply-adds (it does with
    -march=native on a CPU with FMA)."""
    v0, tr = sim.loading.strain_rate * sim.height, sim.ramp_time
    ts = [tr * k / 97 for k in range(1, 97)]
    for f in (_fma, _mul_add):
        if all(v0 * _ramp_integral(t, tr, f) == sim.drive_displacement(t) for t in ts):
            return f
    raise RuntimeError("ldem.yade cannot reproduce ldem's drive U(t) bit for bit")


def hillerborg_force(eps, kappa, EA, eps_p, eps_r):
    """Reference law in pure Python (same as ldem's hillerborgForce)."""
    if eps <= 0:
        return EA * eps
    if kappa <= eps_p:
        s = 1.0
    elif kappa >= eps_r:
        s = 0.0
    else:
        s = eps_p * (eps_r - kappa) / (kappa * (eps_r - eps_p))
    return EA * eps * s


def _yade():
    """YADE's classes (only importable inside YADE), imported when first needed."""
    from yade import (CpmMat, ForceResetter, Ig2_Sphere_Sphere_ScGeom, InteractionLoop,
                      Ip2_CpmMat_CpmMat_CpmPhys, Law2_ScGeom_CpmPhys_Cpm, NewtonIntegrator, O, PyRunner,
                      Vector3, utils)
    return dict(CpmMat=CpmMat, ForceResetter=ForceResetter, Ig2=Ig2_Sphere_Sphere_ScGeom,
                InteractionLoop=InteractionLoop, Ip2=Ip2_CpmMat_CpmMat_CpmPhys, Law2=Law2_ScGeom_CpmPhys_Cpm,
                NewtonIntegrator=NewtonIntegrator, O=O, PyRunner=PyRunner, Vector3=Vector3, utils=utils)


def _register(name, obj):
    """PyRunner commands run in __main__'s namespace: make obj reachable there."""
    import __main__
    setattr(__main__, name, obj)
    return name


def bar_material(eps_p):
    """One CpmMat for all nodes; everything per bar is set on the interactions."""
    y = _yade()
    return y["CpmMat"](
        young=1.0,  # replaced per interaction by E = EA / crossSection
        poisson=0.0,  # G = young * poisson = 0: no shear stiffness
        frictionAngle=0.0, sigmaT=1.0,  # shear yield: irrelevant with G = 0, must not be NaN
        epsCrackOnset=eps_p, relDuctility=1.0,  # replaced per interaction
        damLaw=0,  # linear softening (Hillerborg); 1 would be exponential
        neverDamage=False, equivStrainShearContrib=0.0, isoPrestress=0.0,
        dmgTau=-1.0, plTau=-1.0,  # rate effects off (and absent from the public model)
        density=1.0,  # masses are set per body
        label="ldem_bars")


def make_engines(damping=0.0, before_forces=(), after_forces=()):
    """ForceResetter, PyRunners that must see the positions of this step,
    InteractionLoop (Cpm), PyRunners that need this step's forces, Newton."""
    y = _yade()
    law = y["Law2"](omegaThreshold=1.0, epsSoft=1.0, label="ldem_law")
    return ([y["ForceResetter"]()] + list(before_forces) +
            [y["InteractionLoop"]([y["Ig2"]()], [y["Ip2"]()], [law], label="ldem_loop")] + list(after_forces) +
            [y["NewtonIntegrator"](damping=damping, gravity=(0, 0, 0), label="ldem_newton")])


def add_node(pos, mass, radius, material, blocked="XYZ"):
    """One sphere = one lattice node; rotations are always blocked."""
    y = _yade()
    O = y["O"]
    b = y["utils"].sphere(tuple(float(c) for c in pos), radius, material=material)
    b.state.mass = float(mass)
    b.state.blockedDOFs = blocked if "XYZ" in blocked else blocked + "XYZ"
    return O.bodies.append(b)


class CpmBars:
    """The bars of a lattice as Cpm interactions, with their ldem parameters
    (end body ids, EA [N], L [m], eps_p (scalar or per bar), eps_r per bar).
    Needs O.engines from make_engines() (createInteraction uses its functors)."""

    def __init__(self, ids1, ids2, EA, L, eps_p, eps_r, radius):
        y = _yade()
        O = self.O = y["O"]
        self.ids1 = np.asarray(ids1, dtype=int)
        self.ids2 = np.asarray(ids2, dtype=int)
        self.EA = np.asarray(EA, dtype=float)
        self.L = np.asarray(L, dtype=float)
        self.eps_r = np.asarray(eps_r, dtype=float)
        self.eps_p = np.broadcast_to(np.asarray(eps_p, dtype=float), self.eps_r.shape).copy()  # scalar or per bar
        self.radius = float(radius)
        # r1 + r2 as Ig2_Sphere_Sphere_ScGeom computes it, and the refPD we give the law
        self.rsum = np.array([O.bodies[int(a)].shape.radius + O.bodies[int(b)].shape.radius
                              for a, b in zip(self.ids1, self.ids2)])
        self.refPD = self.rsum - self.L
        # What the law gets: eps_p and eps_r, except for clamped bars (eps_r = eps_p),
        # elastic up to eps_p inclusive, broken beyond: onset = fracture = eps_p+.
        clamped = self.eps_r <= self.eps_p
        up = np.nextafter(self.eps_p, np.inf)
        self.onset = np.where(clamped, up, self.eps_p)
        self.fracture = np.where(clamped, up, self.eps_r)
        self.clamped = int(clamped.sum())
        area = math.pi * self.radius ** 2  # what the law's first call will use as crossSection
        self.interactions = []
        for k in range(len(self.ids1)):
            i = y["utils"].createInteraction(int(self.ids1[k]), int(self.ids2[k]))
            p = i.phys
            p.E = float(self.EA[k]) / area
            p.G = 0.0
            p.epsCrackOnset = float(self.onset[k])
            p.relDuctility = float(self.fracture[k] / self.onset[k])
            p.isCohesive = True
            self.interactions.append(i)
        self.finished = False

    def finish_first_step(self):
        """After the law's first ("fresh") call: exact ldem numbers per bar."""
        for k, i in enumerate(self.interactions):
            p = i.phys
            p.crossSection = 1.0
            p.E = float(self.EA[k])
            p.kn = float(self.EA[k] / self.L[k])
            p.ks = 0.0
            p.epsCrackOnset = float(self.onset[k])
            p.epsFracture = float(self.fracture[k])
            p.refLength = float(self.L[k])
            p.refPD = float(self.refPD[k])
        self.finished = True

    def check_alive(self):
        """Number of bars whose interaction is gone (must stay 0)."""
        return sum(1 for i in self.interactions if not i.isReal)


class RuptureGuard:
    """Before each force evaluation: bars whose strain reaches eps_r get
    epsCrackOnset = 1e-300 (omega == 1: no tension, elastic compression, never
    deleted). Also tracks ldem's damage kappa of every bar from the same strains."""

    def __init__(self, bars, states):
        self.bars = bars
        self.states = states  # body states, in body-id order
        n = len(bars.ids1)
        self.kappa = np.zeros(n)
        self.switched = np.zeros(n, dtype=bool)
        self.threshold = bars.fracture * (1.0 - GUARD_MARGIN)
        self.early = []  # (bar, strain) of bars switched at a strain below ldem's rupture
        self.closed = np.zeros(n, dtype=bool)  # ruptured bars that were compressed later (crack closure)
        self.last_strain = np.zeros(n)

    def positions(self):
        return np.array([[p[0], p[1], p[2]] for p in (s.pos for s in self.states)])

    def strains(self, x=None):
        """The law's epsN, bit for bit: Ig2_Sphere_Sphere_ScGeom's norm and
        penetration depth, then (refPD - penetrationDepth) / refLength."""
        x = self.positions() if x is None else x
        d = x[self.bars.ids2] - x[self.bars.ids1]
        norm = np.sqrt(d[:, 0] * d[:, 0] + (d[:, 1] * d[:, 1] + d[:, 2] * d[:, 2]))  # Eigen's squaredNorm order
        pd = self.bars.rsum - norm
        return (self.bars.refPD - pd) / self.bars.L

    def __call__(self):
        eps = self.strains()
        self.last_strain = eps
        if not self.bars.finished:
            return  # step 0: the law measures its own refLength (all strains are 0)
        np.maximum(self.kappa, eps, out=self.kappa)
        self.closed |= self.switched & (eps < 0)
        hit = np.nonzero((eps >= self.threshold) & ~self.switched)[0]
        for k in hit:
            self.bars.interactions[k].phys.epsCrackOnset = BROKEN_ONSET
            self.switched[k] = True
            if eps[k] < self.bars.fracture[k]:
                self.early.append((int(k), float(eps[k])))

    def verify(self):
        """Largest |guard strain - law's epsN| over the bars (after a step,
        before the bodies move again; must be 0)."""
        epsN = np.array([i.phys.epsN for i in self.bars.interactions])
        return float(np.max(np.abs(epsN - self.last_strain))) if len(epsN) else 0.0

    def counts(self):
        """(damaged, broken) as ldem's damageState on the tracked kappa."""
        broken = self.kappa >= self.bars.eps_r
        damaged = (self.kappa > self.bars.eps_p) & ~broken
        return int(damaged.sum()), int(broken.sum())

    def intact(self):
        """1 for every bar that can still carry tension, kappa < eps_r (ldem's
        intactBars), in ldem's bar order, for _core.nodes_joined."""
        return (self.kappa < self.bars.eps_r).astype(np.uint8)

    def fracture_energy(self):
        """Energy dissipated by the bars [J]: ldem's dissipatedEnergy(kappa) summed
        (0 up to eps_p, 1/2 L EA eps_p eps_r from eps_r on, linear in between)."""
        b, k = self.bars, self.kappa
        full = 0.5 * b.L * b.EA * b.eps_p * b.eps_r
        span = np.where(b.eps_r > b.eps_p, b.eps_r - b.eps_p, 1.0)  # clamped bars: never used
        e = np.where(k <= b.eps_p, 0.0, np.where(k >= b.eps_r, full, full * (k - b.eps_p) / span))
        return float(e.sum())


def cube_constraints(sim):
    """ldem's prescribed DOFs (Simulation.prescribed_dofs) in YADE's terms: per
    node a blockedDOFs string (translations), and the drive weight of each upper node."""
    dofs = sim.prescribed_dofs()
    held = [""] * sim.lattice.n_nodes
    weight = {}
    for n, d, w in zip(dofs["node"], dofs["dim"], dofs["weight"]):
        held[int(n)] += "xyz"[int(d)]
        if d == 2:
            weight[int(n)] = float(w)
    return held, np.array([weight[int(n)] for n in sim.top_nodes])


def _event(step, time, mean_strain, fracture):
    """An event of the run, with the keys of ldem cube's summary.json."""
    return {"step": int(step), "time_s": float(time), "mean_strain": float(mean_strain),
            "fracture_energy_J": float(fracture)}


class CubeSpecimen:
    """The ldem specimen ``sim`` (an ldem._core.Simulation) rebuilt in YADE's O:
    same nodes, masses, bars, per-bar eps_r (from the same seed, read from
    sim.eps_r), boundary conditions, drive U(t) (with its speed-up after the load
    loss), dt and record steps."""

    def __init__(self, sim, damping=0.0, radius_factor=0.25, reset=True, name="_ldem_yade_cube"):
        if sim.steps != 0:
            raise ValueError("CubeSpecimen needs an ldem Simulation that has not run yet (its initial state)")
        y = _yade()
        O = self.O = y["O"]
        if reset:
            O.reset()
        lat = sim.lattice
        self.sim = sim
        self.height, self.face_area = sim.height, sim.face_area
        self.dt = sim.dt
        self.radius = radius_factor * lat.L0
        held, self.top_weights = cube_constraints(sim)
        self.mean_top_weight = sum(float(w) for w in self.top_weights) / len(self.top_weights)  # ldem's order
        self.bottom = [int(n) for n in sim.bottom_nodes]
        self.top = [int(n) for n in sim.top_nodes]
        # ldem's Drive: v0, ramp, and the speed-up from the load loss on (never, until then)
        self.v0 = sim.loading.strain_rate * sim.height
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
        self.z0_top = z0[self.top]
        self.z0_top_mean = float(np.mean(self.z0_top))
        table = lat.bar_table()
        self.bars = CpmBars(table["n1"], table["n2"], table["EA"], table["length"], sim.eps_p, sim.eps_r, self.radius)
        self.states = [b.state for b in O.bodies]
        self.top_states = [self.states[n] for n in self.top]
        self.guard = RuptureGuard(self.bars, self.states)
        self.curve = []  # (step, time, mean_strain, stress_bottom, stress_top, damaged, broken)
        self.peak_stress, self.strain_at_peak = 0.0, 0.0
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
        return _core.nodes_joined(self.sim.lattice, self.guard.intact(), self.top, self.bottom)

    # -- engines -------------------------------------------------------------
    def _before_forces(self):
        O = self.O
        t, dt = O.time, O.dt
        U, Unext = self.drive(t), self.drive(t + dt)
        for s, z0, w in zip(self.top_states, self.z0_top, self.top_weights):
            p, v = s.pos, s.vel
            s.pos = type(p)(p[0], p[1], z0 + w * U)
            s.vel = type(v)(v[0], v[1], w * (Unext - U) / dt)
        self.guard()

    def _after_forces(self):
        O = self.O
        if not self.bars.finished:
            self.bars.finish_first_step()
        fz_bottom = sum(O.forces.f(n)[2] for n in self.bottom)
        fz_top = sum(O.forces.f(n)[2] for n in self.top)
        disp = sum(s.pos[2] for s in self.top_states) / len(self.top) - self.z0_top_mean
        strain = disp / self.height
        stress = fz_bottom / self.face_area
        damaged, broken = self.guard.counts()
        self.curve.append((O.iter, O.time, strain, stress, -fz_top / self.face_area, damaged, broken))
        if stress > self.peak_stress:
            self.peak_stress, self.strain_at_peak = stress, strain
        keep = True if self.callback is None else self.callback(self.curve[-1]) is not False
        if O.iter % self.record_every == 0:  # ldem's record steps: its events and stops come only there
            self._events(stress, broken)
        if not self.stop_reason and not keep:
            self.stop_reason = "stopped"
        if self.stop_reason:
            O.pause()

    def _events(self, stress, broken):
        """Simulation::run's tests at a record step, in its order."""
        O = self.O
        n, t = O.iter, O.time
        mean_strain = self.drive(t) * self.mean_top_weight / self.height  # ldem's meanStrainAt(t)
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
        joins the faces; the drive sped up by loss_speedup from the load loss on),
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
        stress_bottom, stress_top, damaged, broken: every step), guard_early,
        lost_bars."""
        if stop_at not in ("separation", "load_loss"):
            raise ValueError(f"unknown stop event '{stop_at}' (expected separation or load_loss)")
        defaults = _core.RunParams()
        final_strain = defaults.final_strain if final_strain is None else final_strain
        stop_fraction = defaults.stop_fraction if stop_fraction is None else stop_fraction
        self.final_strain, self.callback, self.stop_at = final_strain, callback, stop_at
        self.split = _core.LoadLossDetector(self.sim.split_window, stop_fraction)
        self.stop_reason = ""
        if max_steps is None:  # time to the final strain + ramp at the initial rate (no speed-up), with margin
            t_final = final_strain * self.height / (self.v0 * self.mean_top_weight) + 0.5 * self.ramp_time
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
