"""YADE pieces of the bridge: a bar as a CPM interaction, a node as a sphere,
the engines, the rupture guard, and ldem's drive U(t) reproduced bit for bit
(see ldem.yade for how one bar becomes one interaction)."""
import math
from fractions import Fraction

import numpy as np

from .. import _core

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
    v0, tr = sim.loading.strain_rate * sim.gauge_length, sim.ramp_time
    ts = [tr * k / 97 for k in range(1, 97)]
    for f in (_fma, _mul_add):
        if all(v0 * _ramp_integral(t, tr, f) == sim.drive_displacement(t) for t in ts):
            return f
    raise RuntimeError("ldem.yade cannot reproduce ldem's drive U(t) bit for bit")


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
        """Energy dissipated by the bars [J]: ldem's own law, dissipatedEnergy(kappa)
        (pkg/ldem/laws/Hillerborg.hpp), summed over the bars (called at the run's events only)."""
        b = self.bars
        return float(sum(_core.dissipated_energy(float(k), float(EA), float(ep), float(er), float(L))
                         for k, EA, ep, er, L in zip(self.kappa, b.EA, b.eps_p, b.eps_r, b.L)))
