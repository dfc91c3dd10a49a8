"""The lattice's own fracture energy: the work-of-fracture test of RILEM TC
50-FMC (1985) on a virtual notched beam, run on a calibrated concrete (the
JSON of `ldem study calibration`: its material and its L0) until the load,
averaged over two fundamental periods, is below 2 % of its peak (a load that
rings dips below that long before it is gone),

    G_F = W / ((D - a) b),   W = int F d(delta),

F the load, delta the platen's deflection, (D - a) b the ligament. The
calibration gives the bars the G_F it is told (Gf_mean) and does not scale it
(docs/calibration.md); this measures what the lattice makes of it. RILEM
counts the beam's weight and the tail past the stop; the beam here has no
weight, and the tail past 2 % of the peak is not counted.

The beam: RILEM's for aggregates up to 16 mm is D = b = 100 mm, span 8 D,
length 8.4 D, a notch of D/2 at mid-span. In the lattice the module stands
for the aggregate, so the beam is 10 modules deep and never less than 50 mm
deep (RILEM's beam in half size, the diagnosis's at L0 = 5 mm): D = n L0 with
n = max(10, 2 round(25 mm / L0)), even so that the notch is whole modules.
At L0 = 10.2 mm (Malvar and Warren) it is D = 102 mm, RILEM's full size.
Supports one node line each (a pin and a roller), a platen one module wide,
pushed at 0.1 D per second (the diagnosis's rate).

    ldem study fracture-energy MATERIAL.json [--seeds 3] [--jobs J] [--out DIR]

DIR (default fracture_energy/ beside MATERIAL.json): cases/rilem_s{k}/,
fracture_energy.json (each seed, the means, the cost), fracture_energy.md|png."""
from __future__ import annotations

import json
import math
import os
import statistics
from typing import List

import numpy as np

from ... import _core, io
from ...specimen import SpecimenTest
from ..cases import Named
from ..executors import run_cases
from ..options import seed_count
from ..registry import Study, register

HALF_D = 0.025  # half the smallest depth [m]: RILEM's beam in half size, D = 50 mm
MODULES = 10  # the least depth in modules
SPAN, LENGTH, NOTCH = 8.0, 8.4, 0.5  # over D
RATE = 0.1  # the platen's speed over D [1/s]
STOP = 0.02  # the run ends below this fraction of the peak,
WINDOW_PERIODS = 2.0  # averaged over this many fundamental periods (as the load-loss test's)


def depth(L0: float) -> float:
    """D [m]: an even number of modules, at least MODULES and 2 HALF_D."""
    return max(MODULES, 2 * round(HALF_D / L0)) * L0


def rilem_beam(material: dict, L0: float, seed: int) -> SpecimenTest:
    """The notched beam of the work-of-fracture test at module L0; its load
    is F [MN] (area 1) and its strain the deflection over D."""
    D = depth(L0)
    S, length = SPAN * D, round(LENGTH * D / L0) * L0
    mid = (round(length / 2 / L0 - 0.5) + 0.5) * L0  # a module's centre
    x0 = mid - S / 2
    return SpecimenTest({
        "title": f"RILEM work-of-fracture beam D = {D * 1e3:g} mm, span {S * 1e3:g} mm, notch D/2",
        "shape": {"kind": "box", "L0": L0, "size": [length, D, D],
                  "notch": {"depth": NOTCH * D, "width": L0, "at": mid}},
        "groups": {"left": {"face": "z-", "plane": {"x": x0 - L0 / 2}, "fix": ["x", "y", "z"]},
                   "right": {"face": "z-", "plane": {"x": x0 + S + L0 / 2}, "fix": ["z"]},
                   "supports": {"union": ["left", "right"]},
                   "load": {"box": {"min": [mid - L0 / 2, 0.0, D], "max": [mid + L0 / 2, D, D]}, "drive": {"z": -1.0}}},
        "measure": {"support": "supports", "loaded": "load", "area": 1.0, "gauge_length": D},  # stress = F [MN]
        "material": dict(material), "loading": {"strain_rate": RATE},
        "run": {"seed": seed, "final_strain": 0.06, "threads": 1}})


class LoadGone:
    """Stops a run once, past its peak, the load is gone at the supports and
    at the platen: the core's load-loss test on each (_core.LoadLossDetector:
    bars broken, and the load averaged over the last `window` seconds, two
    fundamental periods, below `fraction` of the peak). A load that rings dips
    below the fraction on a single record long before it is gone
    (docs/calibration.md)."""

    def __init__(self, fraction: float = STOP, window: float = 0.0):
        self.peak = 0.0
        self.support, self.platen = (_core.LoadLossDetector(window, fraction) for _ in range(2))

    def __call__(self, row) -> bool:
        t, broken = row["time_s"], row["broken_bars"]
        self.peak = max(self.peak, row["stress_MPa"])
        support = self.support.update(t, row["stress_MPa"], self.peak, broken)
        platen = self.platen.update(t, row["stress_top_MPa"], self.peak, broken)
        return not (self.peak > 0 and support and platen)


def ligament(D: float) -> float:
    """(D - a) b [m^2], b = D."""
    return (1 - NOTCH) * D * D


def work_of_fracture(curve: dict, D: float) -> float:
    """G_F [N/m]: the work of the load over the platen's deflection, W = int F
    d(delta) by the trapezoidal rule, over the ligament."""
    F = np.asarray(curve["stress_MPa"]) * 1e6  # the force of area 1 [N]
    delta = np.asarray(curve["mean_strain"]) * D
    return float(np.sum(0.5 * (F[1:] + F[:-1]) * np.diff(delta))) / ligament(D)


class RilemCase(Named):
    """One seed of the beam as a study case, run until LoadGone."""

    def __init__(self, material: dict, L0: float, seed: int):
        self.seed = seed
        super().__init__(rilem_beam(material, L0, seed), f"rilem_s{seed}", ["curve", "summary"])

    def run(self, observers=(), simulation=None, previous_rows=()):
        simulation = simulation or self.test.simulation()
        stop = LoadGone(window=WINDOW_PERIODS * 2 * math.pi / simulation.omega1)
        for row in previous_rows:  # a restart: the peak and the window so far
            stop(row)
        return self.test.run(list(observers) + [stop], simulation, previous_rows)


def seed_row(case: str, D: float, seed: int) -> dict:
    """What one finished seed gives: its peak, G_F, the bars' dissipation and
    the elastic energy left at the stop over the ligament, where it stopped,
    its energy balance and its cost."""
    s, c = io.read_summary(os.path.join(case, "summary.json")), io.read_curve(os.path.join(case, "curve.csv"))
    return {"seed": seed, "peak_kN": s["peak_stress_MPa"] * 1e3, "G_F": work_of_fracture(c, D),
            "dissipated_over_ligament": s["fracture_energy_J"] / ligament(D),
            "stored_over_ligament": float(c["elastic_J"][-1]) / ligament(D),
            "end_deflection_mm": float(c["mean_strain"][-1]) * D * 1e3, "stop": s["stop_reason"],
            "balance": s["energy_balance_error"], "steps": s["steps"], "n_bars": s["n_bars"], "wall_s": s["wall_s"]}


def measure(calibration: dict, seeds: int, out: str, jobs: int = 1, log=print) -> dict:
    """Runs the beam on calibration's material (seeds 1..seeds) into out/cases
    and returns each seed's row, the mean G_F and its ratio to Gf_mean."""
    material, L0 = calibration["material"], float(calibration["L0"])
    run_cases([RilemCase(material, L0, s) for s in range(1, seeds + 1)], out, jobs=jobs, log=log)
    D = depth(L0)
    rows = [seed_row(os.path.join(out, "cases", f"rilem_s{s}"), D, s) for s in range(1, seeds + 1)]
    G = [r["G_F"] for r in rows]
    return {"beam": {"D_m": D, "span_m": SPAN * D, "L0_m": L0, "notch": NOTCH, "rate_D_per_s": RATE, "stop": STOP},
            "put_in_Gf_mean": material["Gf_mean"], "seeds": rows, "G_F_mean": statistics.mean(G),
            "G_F_cv": statistics.stdev(G) / statistics.mean(G) if len(G) > 1 else 0.0,
            "ratio": statistics.mean(G) / material["Gf_mean"],
            "cost": {"wall_s": sum(r["wall_s"] for r in rows), "steps": sum(r["steps"] for r in rows),
                     "threads": 1}}


def report_lines(r: dict, name: str) -> List[str]:
    b = r["beam"]
    lines = [f"# The lattice's own fracture energy: {name}", "",
             f"The virtual RILEM work-of-fracture beam (`ldem study fracture-energy`; ldem.study.fracture_energy "
             f"says why each choice): D = b = {b['D_m'] * 1e3:g} mm, span {b['span_m'] * 1e3:g} mm, notch D/2, "
             f"L0 = {b['L0_m'] * 1e3:g} mm, the platen at {b['rate_D_per_s']:g} D/s until the load is below "
             f"{b['stop']:.0%} of its peak.", "",
             "| seed | peak [kN] | G_F [N/m] | bars' dissipation / ligament [N/m] | stored at the stop / ligament "
             "[N/m] | end deflection [mm] | balance | steps | wall [s] |", "|---|---|---|---|---|---|---|---|---|"]
    for s in r["seeds"]:
        lines.append(f"| {s['seed']} | {s['peak_kN']:.4g} | {s['G_F']:.1f} | {s['dissipated_over_ligament']:.1f} | "
                     f"{s['stored_over_ligament']:.1f} | {s['end_deflection_mm']:.2f} | {s['balance']:.1e} | {s['steps']:,} | {s['wall_s']:.0f} |")
    lines += ["", f"**G_F = {r['G_F_mean']:.1f} N/m** (CV {r['G_F_cv']:.3f}) for the {r['put_in_Gf_mean']:.1f} N/m "
                  f"put in (Gf_mean): {r['ratio'] - 1:+.1%}.", "",
              f"Cost: {r['cost']['wall_s'] / 60:.0f} min of one thread for {len(r['seeds'])} seeds, "
              f"{r['cost']['steps']:,} steps.", ""]
    return lines


def figure(out: str, r: dict, name: str) -> str:
    from ... import plots
    import matplotlib.pyplot as plt

    D = r["beam"]["D_m"]
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for s in r["seeds"]:
        c = io.read_curve(os.path.join(out, "cases", f"rilem_s{s['seed']}", "curve.csv"))
        ax.plot(np.asarray(c["mean_strain"]) * D * 1e3, np.asarray(c["stress_MPa"]) * 1e3, lw=0.9,
                label=f"seed {s['seed']}: G_F {s['G_F']:.0f} N/m")
    ax.set(xlabel="deflection [mm]", ylabel="load [kN]", xlim=(0, None), ylim=(0, None),
           title=f"{name}: RILEM beam D = {D * 1e3:g} mm, G_F put in {r['put_in_Gf_mean']:.0f} N/m")
    ax.legend(fontsize=8)
    path = os.path.join(out, "fracture_energy.png")
    plots.save(fig, path, palette=True)
    return path


def add_arguments(c) -> None:
    c.add_argument("material", metavar="MATERIAL.json", help="a calibration (`ldem study calibration --out`): "
                                                             "its material and L0")
    c.add_argument("--seeds", type=int, default=3, help="beams (seeds 1..N)")
    c.add_argument("--jobs", type=int, default=1, metavar="J", help="runs at a time, one thread each")
    c.add_argument("--out", default="", metavar="DIR", help="default: fracture_energy/ beside MATERIAL.json")


def cmd_fracture_energy(args) -> int:
    try:
        with open(args.material) as f:
            calibration = json.load(f)
    except OSError as e:
        raise ValueError(f"cannot read {args.material}: {e.strerror}") from None
    if "material" not in calibration or "L0" not in calibration:
        raise ValueError(f"{args.material} is not a calibration (no 'material' and 'L0'): "
                         "`ldem study calibration --out` writes one")
    # args.out resolved: a signal's message (cli.what_is_kept) names the folder that keeps the finished cases
    out = args.out = args.out or os.path.join(os.path.dirname(os.path.abspath(args.material)), "fracture_energy")
    r = measure(calibration, seed_count(args), out, args.jobs, lambda s: print(s, flush=True))
    name = os.path.basename(os.path.dirname(os.path.abspath(args.material)))
    io.write_text(os.path.join(out, "fracture_energy.json"), json.dumps(r, indent=1) + "\n")
    figure(out, r, name)
    text = "\n".join(report_lines(r, name) + ["![the seeds' load against deflection](fracture_energy.png)", ""])
    io.write_text(os.path.join(out, "fracture_energy.md"), text)
    print(text)
    return 0


register(Study("fracture-energy", "the lattice's own G_F for a calibrated concrete: the virtual RILEM "
                                  "work-of-fracture beam to 2 % of its peak", add_arguments, cmd_fracture_energy,
               "Runs the notched beam of RILEM TC 50-FMC (10 modules deep, at least 50 mm) on the material and "
               "L0 of MATERIAL.json (seeds 1..N) until the load is below 2 % of its peak, and compares its work "
               "of fracture with the Gf_mean the bars were given."))
