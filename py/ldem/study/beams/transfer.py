"""Calibrate on one Grégoire beam, predict the other two, by the protocol
committed first in results/beams/gregoire2013/transfer/PROTOCOL.md: eps_p and
Gf_mean fitted to one measured beam's peak and its work to 4 times its CMOD at
the peak (eps_p alone to a beam measured at its peak only), the mean of seeds
1-3 within 2 %, by Broyden's method in logarithms; then the other two beams,
six seeds, against their measurements.

The fit is a pure function of one beam's measurement (Target) and of a
function that runs the model for a material (evaluate): it cannot see the
beams it predicts.

    ldem study beams transfer [--on D50_n0,D50_n0.5,D100_n0.2] [--seeds 6] [--jobs J] [--out OUT]

OUT/on_{beam}/: fit.json (each round), rounds/{k}/cases/ (the fit's runs),
cases/ (the predictions), transfer.md (the table); OUT/transfer.md: all."""
from __future__ import annotations

import functools
import json
import math
import os
from dataclasses import dataclass
from typing import Callable, List, Sequence, Tuple

import numpy as np

from ... import io
from .comparison import measured_curve
from ..curve_quantities import MULTIPLES, quantities, work_to
from ..curve_report import figure, table_lines
from .cases import L0 as BEAMS_L0
from ..executors import run_cases
from .whole_curves import (WholeCurve, against_measured, beam_name, gauge_curve, gauge_label, measured,
                           measured_beams)

FITTED = ("eps_p", "Gf_mean")
FIT_SEEDS = (1, 2, 3)
TOLERANCE = 0.02
ROUNDS = 6
CLIP = math.log(2.0)  # a round changes a parameter by at most a factor of 2


@dataclass(frozen=True)
class Target:
    """What the fit is given: one beam's measured peak [kN], CMOD at the peak
    [mm] and work to 4 CMOD_peak [J] (nan when only its peak was measured)."""
    beam: Tuple[float, float]
    peak_kN: float
    cmod_at_peak_mm: float
    work_J: float

    def values(self) -> np.ndarray:
        return np.array([self.peak_kN, self.work_J][:self.fitted()])

    def fitted(self) -> int:
        """How many parameters its measurement can fit."""
        return 1 if math.isnan(self.work_J) else 2


def target(data: str, beam: Tuple[float, float]) -> Target:
    """The measurement of one beam, and of no other."""
    m = measured_beams(data)[beam]
    x_ref, curve = float(m["cmod_at_peak_mm"]), measured_curve(data, m)
    work = math.nan if curve is None else work_to((curve["cmod_mm"], curve["load_mean_kN"]), MULTIPLES[-1] * x_ref)
    return Target(beam, float(m["peak_load_kN"]), x_ref, work)


def fit(t: Target, start: dict, evaluate: Callable[[dict], Sequence[float]],
        log: Callable[[str], None] = print) -> dict:
    """The protocol's iteration: x = ln(FITTED), r = ln(model / measured) of
    (peak, work); x <- x - J^-1 r, each change clipped to CLIP, J from the
    identity by Broyden's update J += (dr - J dx) dx^T / dx.dx. evaluate(material)
    returns the model's (peak [kN], work [J]). The round with the smallest
    largest |r|, with every round and whether it met TOLERANCE."""
    n = t.fitted()
    x, J = np.log([start[k] for k in FITTED[:n]]), np.eye(n)
    rounds, previous = [], None
    for k in range(ROUNDS):
        material = dict(start, **{name: float(math.exp(v)) for name, v in zip(FITTED, x)})
        model = np.asarray(evaluate(material), float)[:n]
        r = np.log(model / t.values())
        rounds.append({"round": k, "material": {name: material[name] for name in FITTED},
                       "model": model.tolist(), "error": (np.exp(r) - 1).tolist()})
        log(f"round {k}: " + ", ".join(f"{name} {material[name]:.5g}" for name in FITTED[:n]) + "; " +
            ", ".join(f"{q} {e:+.2%}" for q, e in zip(("peak", "work"), rounds[-1]["error"])))
        if np.all(np.abs(np.exp(r) - 1) <= TOLERANCE):
            break
        if previous is not None:
            dx, dr = x - previous[0], r - previous[1]
            J += np.outer(dr - J @ dx, dx) / float(dx @ dx)
        previous = (x, r)
        x = x + np.clip(-np.linalg.solve(J, r), -CLIP, CLIP)
    best = min(rounds, key=lambda q: max(abs(e) for e in q["error"]))
    return {"material": dict(start, **best["material"]), "round": best["round"], "rounds": rounds,
            "converged": max(abs(e) for e in best["error"]) <= TOLERANCE, "fitted": list(FITTED[:n])}


def cases(beam: Tuple[float, float], material: dict, x_ref: float, seeds: Sequence[int], make=WholeCurve) -> list:
    return [make(beam[0] * 1e-3, beam[1], material, s, x_ref) for s in seeds]


def seed_quantities(out: str, beam: Tuple[float, float], x_ref: float, seeds: Sequence[int]) -> List[dict]:
    """Each finished seed's quantities (curve_quantities at multiples of x_ref), seed by seed."""
    name = beam_name(*beam)
    return [quantities(gauge_curve(os.path.join(out, "cases", f"{name}_s{s}")), x_ref) for s in seeds]


def evaluator(folder: str, t: Target, jobs: int, make=WholeCurve, seeds: Sequence[int] = FIT_SEEDS,
              log=print) -> Callable[[dict], List[float]]:
    """evaluate(material) for fit: runs the seeds of the target's beam in
    folder/rounds/{k}/ and returns the mean (peak, work) over them."""
    count = [0]

    def evaluate(material: dict) -> List[float]:
        out = os.path.join(folder, "rounds", str(count[0]))
        count[0] += 1
        run_cases(cases(t.beam, material, t.cmod_at_peak_mm, seeds, make), out, jobs=jobs, log=log)
        q = seed_quantities(out, t.beam, t.cmod_at_peak_mm, seeds)
        return [float(np.mean([s["peak_kN"] for s in q])), float(np.mean([s["work_J"] for s in q]))]
    return evaluate


def predicted_beams(data: str, on: Tuple[float, float], predict=None) -> List[Tuple[Tuple[float, float], dict]]:
    """(beam, measured.csv row) of each measured beam other than `on`, of
    those in `predict` if given."""
    return [(b, m) for b, m in sorted(measured_beams(data).items())
            if b != on and (predict is None or b in predict)]


def transfer(out: str, data: str, on: Tuple[float, float], start: dict, seeds: int = 6, jobs: int = 1,
             log: Callable[[str], None] = print, L0: float = BEAMS_L0, predict=None) -> dict:
    """Fit on beam `on` (given its measurement only), then predict every other
    measured beam (those in `predict`, if given), every run at module L0:
    OUT/on_{beam}/fit.json and cases/."""
    folder = os.path.join(out, f"on_{beam_name(*on)}")
    make = functools.partial(WholeCurve, L0=L0)
    t = target(data, on)
    result = fit(t, start, evaluator(folder, t, jobs, make, log=log), log)
    os.makedirs(folder, exist_ok=True)
    io.write_text(os.path.join(folder, "fit.json"), json.dumps(dict(result, target=t.__dict__, L0=L0), indent=1))
    others = [(b, float(m["cmod_at_peak_mm"])) for b, m in predicted_beams(data, on, predict)]
    run_cases([c for b, x in others for c in cases(b, result["material"], x, range(1, seeds + 1), make)], folder,
              jobs=jobs, log=log)
    return result


def _predicted(out: str, data: str, b: Tuple[float, float], seeds: int, draw: bool = False,
               predict=None) -> List[Tuple[str, dict]]:
    """(name, curve_report.summarize) of each beam predicted by the fit on b;
    draw: also OUT/on_{b}/{name}.png, the seeds over the measurement."""
    folder, found = os.path.join(out, f"on_{beam_name(*b)}"), []
    for other, m in predicted_beams(data, b, predict):
        curve, name = measured_curve(data, m), beam_name(*other)
        predicted = [gauge_curve(os.path.join(folder, "cases", f"{name}_s{s}")) for s in range(1, seeds + 1)]
        found.append((name, against_measured(predicted, curve, m)))
        if draw:
            figure(os.path.join(folder, f"{name}.png"), f"{name} predicted, calibrated on {beam_name(*b)}",
                   predicted, float(m["cmod_at_peak_mm"]), gauge_label(*other), **measured(curve, m))
    return found


def error_lines(out: str, data: str, on: Sequence[Tuple[float, float]], seeds: int, predict=None) -> List[str]:
    """One row per (calibration beam, predicted beam): each quantity's error,
    predicted mean over measured minus one."""
    keys = ["peak_kN", *(f"load_at_{m:g}" for m in MULTIPLES), "work_J"]
    lines = ["| calibrated on | predicted | peak | " + " | ".join(f"load at {m:g} CMOD_peak" for m in MULTIPLES)
             + f" | work to {MULTIPLES[-1]:g} CMOD_peak |", "|---|---|" + "---|" * len(keys)]
    for b in on:
        for name, s in _predicted(out, data, b, seeds, predict=predict):
            cells = [s["predicted"][k][0] / s["measured"][k] - 1 for k in keys]
            lines.append(f"| {beam_name(*b)} | {name} | " +
                         " | ".join("" if math.isnan(c) else f"{c:+.1%}" for c in cells) + " |")
    return ["Errors of the transferred predictions (mean of six seeds over the measured, minus one; empty: "
            "not measured):", "", *lines]


def report(out: str, data: str, on: Sequence[Tuple[float, float]], seeds: int, predict=None) -> str:
    """OUT/transfer.md: each fit, then each transferred prediction's table
    (of the beams in `predict`, if given)."""
    lines = ["# Calibrate on one beam, predict the other two (Grégoire et al. 2013)", "",
             "By the protocol of [PROTOCOL.md](PROTOCOL.md), committed before any run. Written by "
             "`ldem study beams transfer`.", "", *error_lines(out, data, on, seeds, predict), ""]
    for b in on:
        folder = os.path.join(out, f"on_{beam_name(*b)}")
        with open(os.path.join(folder, "fit.json")) as f:
            result = json.load(f)
        best = result["rounds"][result["round"]]
        lines += [f"## Calibrated on {beam_name(*b)}", "",
                  f"Fitted {', '.join(result['fitted'])} in {len(result['rounds'])} rounds "
                  f"({'converged' if result['converged'] else 'NOT converged'})" +
                  ("" if result.get("L0", BEAMS_L0) == BEAMS_L0 else f" at L0 = {result['L0'] * 1e3:g} mm") + ": " +
                  ", ".join(f"{k} = {best['material'][k]:.5g}" for k in result["fitted"]) +
                  "; the model's " + ", ".join(f"{q} {e:+.2%}" for q, e in zip(("peak", "work"), best["error"])) +
                  " of the measured.", ""]
        for name, s in _predicted(out, data, b, seeds, draw=True, predict=predict):
            lines += [f"### {name}, predicted", "", *table_lines(s), "",
                      f"![{name} predicted, calibrated on {beam_name(*b)}](on_{beam_name(*b)}/{name}.png)", ""]
    text = "\n".join(lines)
    io.write_text(os.path.join(out, "transfer.md"), text)
    return text
