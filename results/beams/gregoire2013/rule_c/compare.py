"""The D/2 beams at rule (c) on omega_d (cases/) against the same seeds at
0.1 D/s: the committed prediction (../size_effect.csv, the engine of
2026-11-30) and today's engine (rate_0.1/cases/). Seed by seed: peaks, each
run's rate, steps and wall; the means of sigma_N with the changes paired by
seed; sigma_N against D = 50 mm and Bazant's law on these seeds. Run from the
repository with ldem importable:
    python3 results/beams/gregoire2013/rule_c/compare.py"""
import csv
import os

import numpy as np

from ldem import io
from ldem.study.beams.tables import bazant_fit, beam_cases

HERE = os.path.dirname(os.path.abspath(__file__))


def by_seed(rows):
    return {(float(r["D_m"]), int(r["seed"])): float(r["sigma_N_MPa"]) for r in rows
            if float(r["notch"]) == 0.5 and float(r.get("Gf_cv", 1)) == 1}


with open(os.path.join(HERE, "..", "size_effect.csv")) as f:
    runs = {"committed 0.1 D/s": by_seed(csv.DictReader(f))}
runs["today 0.1 D/s"] = by_seed(beam_cases(os.path.join(HERE, "rate_0.1")))
runs["today rule (c)"] = by_seed(beam_cases(HERE))
keys = sorted(runs["today rule (c)"])
seeds = sorted({s for _, s in keys})
sizes = sorted({D for D, _ in keys})
kN = lambda D, sigma: sigma * D * 0.05 / 3.75 * 1e3  # noqa: E731  sigma_N = 1.5 F (2.5 D) / (b D^2), b = 50 mm


def summary(folder, D, s):
    return io.read_summary(os.path.join(HERE, folder, "cases", f"D{D * 1e3:g}_n0.5_s{s}", "summary.json"))


print("| D [mm] | seed | committed 0.1 D/s [kN] | today 0.1 D/s | today rule (c) | engine | rate "
      "| rule (c) [D/s] | steps at 0.1 D/s | at rule (c) | wall at 0.1 D/s [s] | at rule (c) |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
for D, s in keys:
    c, t, r = (runs[k][D, s] for k in runs)
    fast, slow = summary("rate_0.1", D, s), summary(".", D, s)
    print(f"| {D * 1e3:g} | {s} | {kN(D, c):.4f} | {kN(D, t):.4f} | {kN(D, r):.4f} | {t / c - 1:+.2%} | "
          f"{r / t - 1:+.2%} | {slow['quasi_static']['strain_rate']:.4g} | {fast['steps']:,} | {slow['steps']:,} | "
          f"{fast['wall_s']:.0f} | {slow['wall_s']:.0f} |")


def se(x):
    return x.std(ddof=1) / len(x) ** 0.5


print(f"\nMeans of sigma_N over seeds {seeds[0]}-{seeds[-1]} [MPa] (standard error), and the changes paired by seed:\n")
print("| D [mm] | " + " | ".join(runs) + " | engine (SE) | rate (SE) |")
print("|---|---|---|---|---|---|")
for D in sizes:
    c, t, r = (np.array([runs[k][D, s] for s in seeds]) for k in runs)
    print(f"| {D * 1e3:g} | " + " | ".join(f"{x.mean():.4f} ({se(x):.4f})" for x in (c, t, r))
          + f" | {(t / c - 1).mean():+.2%} ({se(t / c - 1):.2%}) | {(r / t - 1).mean():+.2%} ({se(r / t - 1):.2%}) |")

print("\n| | " + " | ".join(f"sigma_N({D * 1e3:g}) / sigma_N(50)" for D in sizes[1:]) + " | B | D0 [mm] |")
print("|---|" + "---|" * (len(sizes) + 1))
for name, sigma in runs.items():
    mean = {D: np.mean([sigma[D, s] for s in seeds]) for D in sizes}
    B, dB, D0, dD0 = bazant_fit(np.array([D for D, _ in keys]), np.array([sigma[k] for k in keys]))
    print(f"| {name} | " + " | ".join(f"{mean[D] / mean[sizes[0]]:.4f}" for D in sizes[1:])
          + f" | {B:.3f} +- {dB:.3f} | {D0 * 1e3:.1f} +- {dD0 * 1e3:.1f} |")
