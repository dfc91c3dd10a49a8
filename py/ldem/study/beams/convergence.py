"""The peak's convergence with the module on the Grégoire et al. (2013) beams,
whence the module rule (ldem.module_rule): the concrete
fitted on the half-notched D = 50 mm beam at L0 = 5 mm (transfer/on_D50_n0.5/
fit.json), unchanged at every module, each beam as the transfer runs it
(whole_curves.WholeCurve: the servo on its clip gauge) but stopped at STOP
times its measured CMOD at the peak (only the peak is read):

    D = 50 mm, notch D/2 and unnotched: L0 = 5, 2.5, 1.667 and 1.25 mm (10, 20, 30, 40 modules deep)
    D = 100 mm, notch D/5:              L0 = 5 and 2.5 mm (20, 40 modules deep)

three seeds each. The table gives each beam's mean peak against its finest
module's, and the rule: the fewest modules over the ligament (or the depth)
at which every beam's peak lies within WITHIN of its finest's.

    ldem study beams convergence [--seeds 3] [--jobs J] [--beams D50_n0.5,...] [--L0 5,2.5,1.667,1.25] [--fit FIT.json]

OUT/L{mm}mm/D{mm}_n{notch}_s{seed}/: the runs; OUT/convergence.csv|md."""
from __future__ import annotations

import json
import os
from typing import Dict, List, Sequence, Tuple

import numpy as np

from ... import io
from ...module_rule import RULE_MODULES, RULE_MODULES_DEPTH, governing_length
from ..cases import case_dir, is_finished, load_summary
from ..executors import run_cases
from .whole_curves import WholeCurve, beam_name, measured_beams

# D = 50 mm over 10, 20, 30 and 40 modules (every length of the beams a whole number of them); 1.25 mm
# because the unnotched beam's peak had not settled at 1.667 mm (3.7 % above 2.5 mm's)
D50_MODULES = (0.005, 0.0025, 0.05 / 30, 0.00125)
PLAN: Dict[Tuple[float, float], Tuple[float, ...]] = {
    (50.0, 0.5): D50_MODULES, (50.0, 0.0): D50_MODULES, (100.0, 0.2): (0.005, 0.0025)}
SEEDS = 3
STOP = 2.0  # a run stops at this multiple of the measured CMOD at the peak (the transfer's go on to 4.4)
WITHIN = 0.02  # the rule: the peak within 2 % of the finest module's
COLUMNS = ["beam", "L0_mm", "modules", "over", "bars", "seeds", "peak_kN", "min_kN", "max_kN", "sem_kN",
           "vs_finest", "past_peak", "steps", "wall_s"]


def folder(L0: float) -> str:
    return f"L{L0 * 1e3:.4g}mm"


def plan(beams: Sequence[str] = (), modules: Sequence[float] = ()) -> List[Tuple[Tuple[float, float], float]]:
    """(beam, L0) of PLAN, of the beams named (D50_n0.5, ...) and the modules [m] given (all if none)."""
    names = {beam_name(*b): b for b in PLAN}
    unknown = [b for b in beams if b not in names]
    if unknown:
        raise ValueError(f"unknown beam {', '.join(unknown)} (of {', '.join(names)})")
    return [(b, L0) for b, levels in PLAN.items() for L0 in levels if (not beams or beam_name(*b) in beams)
            and (not modules or any(abs(L0 - m) <= 1e-3 * m for m in modules))]


def cases(material: dict, data: str, seeds: int = SEEDS, which=None) -> List[WholeCurve]:
    """The runs of `which` (plan()'s pairs; all of PLAN if None), the finest modules first (the longest runs
    first: none is left alone at the end)."""
    measured = measured_beams(data)
    tests = []
    for (D, n), L0 in sorted(which if which is not None else plan(), key=lambda p: p[1]):
        cmod = float(measured[(D, n)]["cmod_at_peak_mm"])
        for s in range(1, seeds + 1):
            t = WholeCurve(D * 1e-3, n, material, s, cmod, folder=folder(L0), L0=L0)
            t.limit = STOP * cmod * 1e-3
            tests.append(t)
    return tests


def rows(out: str, tests: Sequence[WholeCurve]) -> List[dict]:
    """convergence.csv's rows: per beam and module, its finished seeds' peaks."""
    groups: Dict[tuple, list] = {}
    for t in tests:
        d = case_dir(out, t)
        if is_finished(d, t):
            groups.setdefault(((t.D * 1e3, t.notch), t.v.L0), []).append((load_summary(d), io.read_curve(
                os.path.join(d, io.tables.CURVE))["stress_MPa"]))
    table = []
    for ((D, n), L0), runs in sorted(groups.items(), key=lambda g: (g[0][0], -g[0][1])):
        peaks = np.array([s["peak_stress_MPa"] * 1e3 for s, _ in runs])
        what, length = governing_length({"kind": "box", "size": [3.5 * D * 1e-3, 0.05, D * 1e-3],
                                         **({"notch": {"depth": n * D * 1e-3}} if n else {})})
        table.append({"beam": beam_name(D, n), "L0_mm": L0 * 1e3, "modules": length / L0, "over": what,
                      "bars": runs[0][0]["n_bars"], "seeds": len(runs), "peak_kN": float(peaks.mean()),
                      "min_kN": float(peaks.min()), "max_kN": float(peaks.max()),
                      "sem_kN": float(peaks.std(ddof=1) / np.sqrt(len(peaks))) if len(peaks) > 1 else float("nan"),
                      # past the peak: the last load below 95 % of the largest (not stopped on the rising branch)
                      "past_peak": all(float(c[-1]) < 0.95 * float(np.max(c)) for _, c in runs),
                      "steps": float(np.mean([s["steps"] for s, _ in runs])),
                      "wall_s": float(np.mean([s["wall_s"] for s, _ in runs]))})
    for r in table:
        finest = min((q for q in table if q["beam"] == r["beam"]), key=lambda q: q["L0_mm"])
        r["vs_finest"] = r["peak_kN"] / finest["peak_kN"] - 1
    return table


def rule(table: Sequence[dict]) -> dict:
    """Per beam, the fewest modules from which on every finer module's peak lies within WITHIN of its
    finest module's (its count at the finest alone: not shown converged; a beam with one module only is
    left out). The rule is counted apart over the ligament (notched beams) and over the depth: for each,
    the largest count of its beams, shown if every one of them converged (else None)."""
    per_beam = {}
    for beam in dict.fromkeys(r["beam"] for r in table):
        levels = sorted((r for r in table if r["beam"] == beam), key=lambda r: r["L0_mm"])
        if len(levels) < 2:
            continue
        count = levels[0]["modules"]
        for r in levels[1:]:
            if abs(r["vs_finest"]) > WITHIN:
                break
            count = r["modules"]
        per_beam[beam] = {"modules": count, "only_finest": count == levels[0]["modules"], "over": levels[0]["over"]}
    rules = {}
    for over in dict.fromkeys(b["over"] for b in per_beam.values()):
        beams = [b for b in per_beam.values() if b["over"] == over]
        rules[over] = None if any(b["only_finest"] for b in beams) else max(b["modules"] for b in beams)
    return {"per_beam": per_beam, "rules": rules}


def report(out: str, tests: Sequence[WholeCurve], fit: str) -> str:
    """convergence.csv and convergence.md from the finished runs."""
    table = rows(out, tests)
    io.write_table(os.path.join(out, "convergence.csv"), table, COLUMNS)
    r = rule(table)
    lines = ["# The peak's convergence with the module (Grégoire et al. 2013)", "",
             f"The concrete of `{os.path.relpath(fit, out)}`, unchanged at every module; each beam under the servo on its clip gauge "
             f"(as the transfer), stopped at {STOP:g} times its measured CMOD at the peak. Written by `ldem study "
             "beams convergence` (ldem.study.beams.convergence).", "",
             "| beam | L0 [mm] | modules over | bars | seeds | peak [kN], mean (min-max) | its sem | vs the finest "
             "| past its peak | steps | wall [s] |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    for q in table:
        lines.append(f"| {q['beam']} | {q['L0_mm']:.4g} | {q['modules']:.3g} ({q['over']}) | {q['bars']:,} | "
                     f"{q['seeds']} | {q['peak_kN']:.3f} ({q['min_kN']:.3f}-{q['max_kN']:.3f}) | {q['sem_kN']:.3f} | "
                     f"{q['vs_finest']:+.1%} | {'yes' if q['past_peak'] else 'NO'} | {q['steps']:,.0f} | "
                     f"{q['wall_s']:.0f} |")
    lines += ["", f"The rule, the fewest modules over the ligament (or the depth) with every beam's peak within "
                  f"{WITHIN * 100:g} % of its finest module's:", ""]
    for beam, b in r["per_beam"].items():
        lines.append(f"- {beam}: {b['modules']:.3g} modules over the {b['over']}"
                     + (" (only its finest module: not shown converged)" if b["only_finest"] else ""))
    lines.append("")
    for over, n in r["rules"].items():
        lines.append(f"- **Over the {over}: " + (f"at least {n:.3g} modules**" if n is not None else
                                                 "no count shown** (a beam's peak had not settled at its finest)"))
    lines += ["", f"(ldem.module_rule: RULE_MODULES {RULE_MODULES} over the ligament above a notch, "
                  f"RULE_MODULES_DEPTH {RULE_MODULES_DEPTH} over the depth without one.)"
              if r["rules"] else "No beam has two modules finished yet: no rule.", ""]
    text = "\n".join(lines)
    io.write_text(os.path.join(out, "convergence.md"), text)
    return text


def run(out: str, fit: str, data: str, seeds: int = SEEDS, jobs: int = 1, which=None, log=print) -> str:
    """The runs not finished yet, then the report."""
    with open(fit) as f:
        material = json.load(f)["material"]
    tests = cases(material, data, seeds, which)
    run_cases(tests, out, jobs=jobs, log=log)
    return report(out, tests, fit)
