"""Run an ldem lattice in YADE, with YADE's own integrator and a native YADE
law, as an independent check of the ldem engine.

Use inside YADE (``yade-double -n -x script.py``)::

    import ldem.yade
    from ldem import _core
    lp = _core.LoadingParams(); lp.tail_drive = "fixed"; rp = _core.RunParams(); rp.zeta = 0
    rp.zeta_high, rp.dt_safety = 0.0, 0.4            # YADE has no bar dashpots: 0.4 of the limit without them
    sim = _core.Simulation(6, 6, 6, 0.02, _core.Material(), lp, rp)
    spec = ldem.yade.SimulationSpecimen(sim)         # fills YADE's O
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
kinetic energy 1/2 m v(n-1/2)^2. ``SimulationSpecimen`` (ldem's own specimen) runs
undamped or with YADE's Cundall ``damping``; ``LatticeSpecimen`` (a specimen
given as arrays, e.g. from the reference) takes D_f and uses ``ViscousDamping``.

Boundary conditions
-------------------
Those of ldem's cubeTestConstraints (pkg/ldem/Loading.cpp), rebuilt from the
lattice: lower face z held (x, y held too, or on rollers with x, y pinned at
corner (0,0) and y at (nx,0) if bottom_lateral is "free"); upper face z prescribed,
u_z = w U(t) with w = 1 (uniform) or x0/width (triangular), x, y free unless
top_lateral is "fixed". U(t) is ldem's Drive (smooth 1 - cos start over
ramp_time, then v0 = strain_rate * height; once the load is lost, loss_speedup
times faster, with the same smooth start (tail_drive 'fixed'; the adaptive drive is ldem's own): ``SimulationSpecimen.drive``, bit for bit
pkg/ldem/Loading.cpp's Drive::displacement). Each step, before the forces,
the drive sets the upper nodes to z0 + w U(t_n) and their velocity to
w (U(t_n+1) - U(t_n))/dt (YADE moves blocked DOFs with their velocity).

Load loss and separation
------------------------
``SimulationSpecimen.run`` applies Simulation::run's rules (pkg/ldem/Simulation.cpp)
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

Modules: ``scene`` (bars as CPM interactions, nodes, engines, the rupture
guard, ldem's drive reproduced bit for bit), ``cube`` (SimulationSpecimen: an ldem
Simulation rebuilt in YADE and run by Simulation::run's rules), ``lattice``
(LatticeSpecimen and ViscousDamping: any lattice given as arrays).
"""
from .cube import SimulationSpecimen, constraints  # noqa: F401
from .lattice import LatticeSpecimen, ViscousDamping  # noqa: F401
from .scene import (BROKEN_ONSET, GUARD_MARGIN, SEPARATION_CHECK, CpmBars, RuptureGuard, _register,  # noqa: F401
                    _yade, add_node, bar_material, drive_mul_add, make_engines)
