"""The reference's own run of a cube test: the expected values that
tests/cpp/test_dynamics.cpp and tests/py/test_yade_bridge.py pin come from here.

    PYTHONPATH=build/python /usr/bin/python3 tests/reference/reference_run.py --modules 4 --seed 3
    PYTHONPATH=build/python /usr/bin/python3 tests/reference/reference_run.py --modules 6 --load triangular \\
        --gf-cv 0 --strain-rate 0.1 --steps 4124

Everything is ldem_ref.py's (lattice, masses, law, dt = 0.4 x 2/omega_max and
D_f = 2 zeta omega_1 from its dense eigen-solve, the drive and its smooth start
of two periods of omega_d from its dense solve, the energies),
except, with --gf-cv > 0, the per-bar G_f: a random draw cannot be reproduced
independently, so it is the engine's for that seed (ldem._core, mapped to the
reference's bars by position, as tests/py/test_reference.py does). With
--gf-cv 0 every bar has E[G_f] and ldem is not imported at all.

Prints the peak of the lower-face stress (tracked at every step), its mean
strain and step, and the state at the last step (--steps, or 3000 steps
past the peak).
"""
import argparse
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ldem_ref as R  # noqa: E402


def engine_gf(lat, n, L0, seed, cv):
    """The engine's per-bar G_f for this seed, in the reference's bar order."""
    from ldem import _core
    m = _core.Material()
    m.Gf_cv = cv
    rp = _core.RunParams()
    rp.seed, rp.threads = seed, 1
    sim = _core.Simulation(n, n, n, L0, m, _core.LoadingParams(), rp)
    el = sim.lattice
    key = lambda p: tuple(int(round(c)) for c in p / (L0 / 2))  # noqa: E731  (half-module grid)
    ref_of = {key(p): i for i, p in enumerate(lat.X)}
    nmap = np.array([ref_of[key(p)] for p in np.c_[el.x0, el.y0, el.z0]])
    t = el.bar_table()
    pair = {frozenset((a, b)): i for i, (a, b) in enumerate(zip(lat.n1, lat.n2))}
    bmap = np.array([pair[frozenset((nmap[a], nmap[b]))] for a, b in zip(t["n1"], t["n2"])])
    gf = np.empty(lat.n_bars)
    gf[bmap] = sim.fracture_energy_field
    return gf


def main(argv=None):
    p = argparse.ArgumentParser()
    p.add_argument("--modules", type=int, default=4)
    p.add_argument("--L0", type=float, default=0.02)
    p.add_argument("--load", default="uniform", choices=("uniform", "triangular"))
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--gf-cv", type=float, default=1.0)
    p.add_argument("--zeta", type=float, default=0.02)
    p.add_argument("--strain-rate", type=float, default=0.02)
    p.add_argument("--steps", type=int, default=0, help="0: run until 3000 steps past the peak")
    a = p.parse_args(argv)
    n, L0 = a.modules, a.L0
    mat = R.Material(Gf_cv=a.gf_cv)
    lat = R.Lattice(n, n, n, L0, mat)
    bc = R.Boundary(lat, a.load)
    w1, wmax = R.frequencies(lat, bc)
    gf = np.full(lat.n_bars, mat.Gf_mean) if a.gf_cv == 0 else engine_gf(lat, n, L0, a.seed, a.gf_cv)
    dt, D, ramp = 0.4 * 2 / wmax, 2 * a.zeta * w1, 2 * 2 * math.pi / R.drive_frequency(lat, bc)
    ref = R.Reference(lat, mat, gf, dt, D, load=a.load, strain_rate=a.strain_rate, ramp_time=ramp)
    print(f"{n}^3 {a.load} seed {a.seed} Gf_cv {a.gf_cv} zeta {a.zeta} rate {a.strain_rate}: "
          f"{lat.n_bars} bars, {int(ref.clamped.sum())} clamped, dt {dt!r} s, D_f {D!r} 1/s")
    peak, strain, at, k = -math.inf, 0.0, -1, 0
    while True:
        ref.compute_forces()
        m = ref.measure()
        if m["stress_bottom"] > peak:
            peak, strain, at = m["stress_bottom"], m["mean_strain"], k
        if (a.steps and k == a.steps) or (not a.steps and k >= at + 3000):
            break
        ref.advance()
        k += 1
    print(f"peak_stress_Pa={peak!r} strain_at_peak={strain!r} step={at}")
    print("last " + " ".join(f"{key}={m[key]!r}" for key in ("step", "mean_strain", "stress_bottom", "external_work",
                                                             "kinetic", "elastic", "fracture", "damping", "damaged",
                                                             "broken")))


if __name__ == "__main__":
    main()
