"""Cross-check of ldem against YADE (issue 5): the 0.12 m cube (6x6x6 modules,
L0 = 0.02 m), uniform loading, seed 1, NO damping, run by ldem and by YADE with
its own integrator (NewtonIntegrator, damping = 0) and its native Cpm law set up
as Hillerborg's triangle by ldem.yade (same nodes, masses, bars, per-bar eps_r
from the same seed, boundary conditions, drive U(t) and time step).

Prints one line
    peak_stress_MPa ldem=A yade=B rel_diff=C strain_at_peak ldem=D yade=E rel_diff=F
(after a few diagnostic lines), plots both stress-strain curves to OUT
(default out/yade_crosscheck.png) and exits 1 if the peaks differ by more than
2 % or their strains by more than 5 %. Both runs stop at the final strain or at
the load loss, whichever comes first (stop_at load_loss; scripts/yade_separation.py
runs both to separation).

Run: yade-double -n -x scripts/yade_crosscheck.py [OUT] [--strain-rate R] [--final-strain E] [--seed S]
"""
import argparse
import os
import sys
import time

# ldem as installed by install.sh, or the build tree's (PYTHONPATH=build/python).
import ldem.yade as ly
from ldem import _core
from ldem.scene import exit_with

PEAK_TOL, STRAIN_TOL = 0.02, 0.05


def parse(argv):
    p = argparse.ArgumentParser(prog="yade-double -n -x scripts/yade_crosscheck.py")
    p.add_argument("out", nargs="?", default=os.path.join("out", "yade_crosscheck.png"))
    p.add_argument("--modules", type=int, default=6, help="modules per side (6: the 0.12 m cube)")
    p.add_argument("--L0", type=float, default=0.02)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--strain-rate", type=float, default=0.02, help="[1/s], ldem's default")
    p.add_argument("--final-strain", type=float, default=3e-4, help="both runs stop here (peak is near 1.6e-4)")
    return p.parse_args(argv)


def plot(out, ldem_curve, yade_curve, ldem_peak, yade_peak):
    import matplotlib
    matplotlib.use("Agg", force=True)
    import matplotlib.pyplot as plt
    d = os.path.dirname(out)
    if d:
        os.makedirs(d, exist_ok=True)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot([p[0] * 1e3 for p in ldem_curve], [p[1] / 1e6 for p in ldem_curve], lw=2.5, color="tab:blue",
            label="ldem (central differences, Hillerborg bars)")
    ax.plot(yade_curve[:, 2] * 1e3, yade_curve[:, 3] / 1e6, lw=1, ls="--", color="tab:red",
            label="YADE (NewtonIntegrator, Law2_ScGeom_CpmPhys_Cpm)")
    ax.plot([ldem_peak[1] * 1e3], [ldem_peak[0] / 1e6], "o", color="tab:blue", ms=8, mfc="none")
    ax.plot([yade_peak[1] * 1e3], [yade_peak[0] / 1e6], "x", color="tab:red", ms=8)
    ax.set_xlabel("mean strain [1e-3]")
    ax.set_ylabel("stress on the lower face [MPa]")
    ax.set_title("0.12 m cube, uniform tension, seed 1, no damping: ldem vs YADE")
    ax.grid(alpha=0.3)
    ax.legend(loc="lower center", fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)


def main(argv):
    a = parse(argv)
    n = a.modules
    lp = _core.LoadingParams()
    lp.shape = "uniform"
    lp.strain_rate = a.strain_rate
    rp = _core.RunParams()
    rp.seed = a.seed
    rp.zeta = 0.0  # no damping: YADE's damping is not ldem's (see ldem.yade)
    rp.final_strain = a.final_strain
    rp.record_every = 1  # every step, as the YADE recorder
    rp.stop_at = "load_loss"  # the peaks are compared: no need to run on to separation (both sides)

    t0 = time.time()
    sim = _core.Simulation(n, n, n, a.L0, _core.Material(), lp, rp)
    ldem_curve = []
    summary = sim.run(lambda p: ldem_curve.append((p.mean_strain, p.stress_bottom, p.broken)) or True)
    t_ldem = time.time() - t0

    t0 = time.time()
    fresh = _core.Simulation(n, n, n, a.L0, _core.Material(), lp, rp)  # the same specimen, unrun
    spec = ly.CubeSpecimen(fresh, damping=0.0)
    res = spec.run(final_strain=a.final_strain, stop_fraction=rp.stop_fraction, stop_at=rp.stop_at)
    t_yade = time.time() - t0
    strain_check = spec.guard.verify()

    yc = res["curve"]
    m = min(len(yc), len(ldem_curve))
    # Same steps, same times: compare the curves point by point up to the later peak.
    ipk = max(int(yc[:, 3].argmax()), max(range(len(ldem_curve)), key=lambda i: ldem_curve[i][1]))
    upto = min(m, ipk + 1)
    dmax = max(abs(yc[i, 3] - ldem_curve[i][1]) for i in range(upto)) / summary.peak_stress
    broken_same = all(int(yc[i, 6]) == ldem_curve[i][2] for i in range(upto))
    print(f"specimen: {n}x{n}x{n} modules, {sim.lattice.n_nodes} nodes, {sim.lattice.n_bars} bars, "
          f"{sim.clamped_bars} clamped, dt={sim.dt:.6e} s, ramp={sim.ramp_time:.6e} s, "
          f"strain_rate={a.strain_rate} 1/s, seed={a.seed}, no damping")
    print(f"ldem: {summary.steps} steps, stop={summary.stop_reason}, {t_ldem:.1f} s wall")
    print(f"yade: {res['steps']} steps, stop={res['stop_reason']}, {t_yade:.1f} s wall, "
          f"lost_interactions={res['lost_bars']}, guard_early={len(res['guard_early'])}, "
          f"guard_strain_mismatch={strain_check:.1e}, ruptured_bars={int(spec.guard.switched.sum())}, "
          f"ruptured_then_compressed={int(spec.guard.closed.sum())}")
    print(f"curves up to the peak (step {upto - 1}): max |stress diff| / peak = {dmax:.3e}, "
          f"broken-bar counts identical: {broken_same}")

    pl, py_ = summary.peak_stress, res["peak_stress"]
    sl, sy = summary.strain_at_peak, res["strain_at_peak"]
    rp_, rs = abs(py_ - pl) / pl, abs(sy - sl) / sl
    plot(a.out, ldem_curve, yc, (pl, sl), (py_, sy))
    print(f"plot: {a.out}")
    print(f"peak_stress_MPa ldem={pl / 1e6:.6f} yade={py_ / 1e6:.6f} rel_diff={rp_:.3e} "
          f"strain_at_peak ldem={sl:.6e} yade={sy:.6e} rel_diff={rs:.3e}")
    sys.stdout.flush()
    ok = rp_ <= PEAK_TOL and rs <= STRAIN_TOL and res["lost_bars"] == 0
    return 0 if ok else 1


if __name__ == "__main__":
    exit_with(main, sys.argv[1:])
