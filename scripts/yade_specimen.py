"""Any specimen of a TOML file (ldem run's) in ldem and in YADE, step by step
(issue 13 item 8): ldem.SpecimenTest builds the specimen, ldem runs it,
ldem.yade.SimulationSpecimen rebuilds the same unrun specimen in YADE's O
(nodes, masses, bars, eps_r, held and driven DOFs in any direction, the
measures) and YADE's own integrator and concrete law run it. Undamped (YADE's
damping is not ldem's), to --final-strain, every step recorded in both.

Prints
    specimen: ...
    curve steps=N peak ldem=A yade=B peak_rel_diff=C max_stress_diff_over_peak=D broken ldem=E yade=F
and exits 1 unless the peaks and every step's stress agree within --tol (of the
peak) and both broke bars.

Run: yade-double -n -x scripts/yade_specimen.py FILE.toml [--final-strain E] [--strain-rate R] [--tol T]
"""
import sys
import time

import numpy as np

import ldem
import ldem.yade as ly
from ldem.helptext import ArgumentParser
from ldem.scene import exit_with


def parse(argv):
    p = ArgumentParser(prog="yade-double -n -x scripts/yade_specimen.py")
    p.add_argument("file", help="a specimen file (examples/*.toml)")
    p.add_argument("--final-strain", type=float, default=6e-4)
    p.add_argument("--strain-rate", type=float, default=1.0, help="[1/s]: fast, for YADE's Python hooks")
    p.add_argument("--tol", type=float, default=1e-8, help="largest stress difference over the peak")
    return p.parse_args(argv)


def main(argv):
    a = parse(argv)
    settings = {"zeta": 0.0, "zeta_high": 0.0, "dt_safety": 0.4, "threads": 1, "record_every": 1, "final_strain": a.final_strain,
                "strain_rate": a.strain_rate, "stop_at": "load_loss"}
    test = ldem.SpecimenTest.from_file(a.file, settings)
    t0 = time.time()
    spec = ly.SimulationSpecimen(test.simulation(), damping=0.0)  # first: what the bridge refuses, before ldem runs
    t_build = time.time() - t0
    t0 = time.time()
    mine = test.run()
    t_ldem = time.time() - t0
    t0 = time.time()
    res = spec.run(final_strain=a.final_strain, stop_at="load_loss")
    t_yade = t_build + time.time() - t0
    sim = mine.sim
    print(f"specimen: {test.build.title}, {sim.lattice.n_nodes} nodes, {sim.lattice.n_bars} bars, "
          f"dt={sim.dt:.6e} s, undamped, {a.strain_rate} 1/s to {a.final_strain:g}; ldem {t_ldem:.1f} s, "
          f"yade {t_yade:.1f} s wall, stop ldem={mine.summary['stop_reason']} yade={res['stop_reason']}")
    # YADE's rows: one per step n (state n, after its forces); ldem's: one per record, at step n too.
    ydict = {int(r[0]): r for r in res["curve"]}
    steps = [int(s) for s in mine.curve["step"] if int(s) in ydict]
    ours = dict(zip(mine.curve["step"].astype(int), mine.curve["stress_MPa"] * 1e6))
    diff = np.array([abs(ours[s] - ydict[s][3]) for s in steps])
    peak = mine.summary["peak_stress_MPa"] * 1e6
    broken_y = int(spec.guard.counts()[1])
    broken_l = int(mine.curve["broken_bars"][-1])
    peak_diff = abs(res["peak_stress"] - peak) / peak
    print(f"curve steps={len(steps)} peak ldem={peak!r} yade={res['peak_stress']!r} peak_rel_diff={peak_diff:.3e} "
          f"max_stress_diff_over_peak={diff.max() / peak:.3e} broken ldem={broken_l} yade={broken_y}")
    ok = len(steps) > 100 and peak_diff <= a.tol and diff.max() <= a.tol * peak and broken_l > 0 and broken_y > 0
    sys.stdout.flush()
    return 0 if ok else 1


if __name__ == "__main__":
    exit_with(main, sys.argv[1:])
