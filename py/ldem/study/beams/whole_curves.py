"""The Grégoire et al. (2013) beams with a measured curve, whole: the
calibrated concrete (calibrated/material.json) run under the tests' probable
control, a servo on a clip gauge, to past four times the measured CMOD at the
peak; the load at 1.5, 2 and 4 times it and the work to the last, predicted
against measured (ldem.study.curve_report).

Why a new run set: the committed calibrated runs hold the platen, and stop
at twice the deflection at the peak. The unnotched beams snap there, and two
of the three measured beams end short of 4 CMOD_peak. The tests' curves are
plotted against CMOD, so the tests were probably CMOD-controlled (the data's
README); a servo on the gauge follows the softening to any opening.

The gauges (the data do not give them; those of the models that redistribute
the curves, README of the data): 70 mm on the unnotched D = 50 mm beam
(PeriPy's), 20 mm on the half-notched one (pypd's). The D = 100 mm, D/5 beam
has a peak and a CMOD at it only; it takes 20 mm too, as an assumption.

    ldem study beams whole-curves [--seeds 6] [--jobs J] [--out OUT] [--data DIR]"""
from __future__ import annotations

import json
import os
from typing import Callable, Dict, List, Tuple

import numpy as np

from ... import io
from .comparison import NAMES, _by_beam, measured_curve
from .cases import L0, Beam, Variant, calibrated_variant
from ..curve_quantities import MULTIPLES, quantities
from ..curve_report import figure, summarize, table_lines
from ..executors import run_cases

GAUGES = {(50.0, 0.0): 0.070, (50.0, 0.5): 0.020, (100.0, 0.2): 0.020}  # [m], see the module's text
OPENING_RATE = 0.1  # the gauge's opening rate / D [1/s], as the diagnosis's CMOD servo
QUARTER = 0.25  # the rate check: seed 1 of each beam at a quarter of the rate
PAST = 1.1  # each run stops at PAST x the last multiple of the measured CMOD at the peak


class ToOpening:
    """An observer that stops a run once the gauge has opened to `limit` [m]."""

    def __init__(self, limit: float):
        self.limit = limit

    def __call__(self, row) -> bool:
        return row["gauge_m"] < self.limit


class WholeCurve(Beam):
    """A measured beam under the gauge's servo, to ToOpening; its curve and
    summary only (the report draws the figures). gauge [m] (0: GAUGES') and L0
    [m]: another beam's (the tests' tiny ones)."""

    def __init__(self, D: float, notch: float, material: dict, seed: int, cmod_at_peak_mm: float,
                 rate: float = OPENING_RATE, folder: str = "cases", gauge: float = 0.0, L0: float = L0):
        v = Variant(calibrated_variant(material).material, L0=L0, opening_rate=rate,
                    gauge=gauge or GAUGES[(D * 1e3, notch)])
        super().__init__(D, notch, material["eps_p"], seed, v=v, folder=folder)
        self.writers = ["curve", "summary"]
        self.limit = PAST * MULTIPLES[-1] * cmod_at_peak_mm * 1e-3

    def run(self, observers=(), simulation=None, previous_rows=()):
        return self.test.run(list(observers) + [ToOpening(self.limit)], simulation, previous_rows)


def measured_beams(data: str) -> Dict[Tuple[float, float], dict]:
    """measured.csv's rows by (D [mm], notch / D)."""
    return _by_beam(os.path.join(data, "measured.csv"))


def cases(material: dict, data: str, seeds: int) -> List[WholeCurve]:
    """Six seeds of each measured beam, then seed 1 of each at a quarter of the rate."""
    beams = sorted(measured_beams(data).items())
    tests = [WholeCurve(D * 1e-3, n, material, s, float(m["cmod_at_peak_mm"]))
             for s in range(1, seeds + 1) for (D, n), m in beams]
    return tests + [WholeCurve(D * 1e-3, n, material, 1, float(m["cmod_at_peak_mm"]), QUARTER * OPENING_RATE,
                               "rate_check") for (D, n), m in beams]


def gauge_curve(case: str) -> Tuple[np.ndarray, np.ndarray]:
    """(gauge opening [mm], load [kN]) of a finished case."""
    c = io.read_curve(os.path.join(case, io.tables.CURVE))
    return np.asarray(c["gauge_m"]) * 1e3, np.asarray(c["stress_MPa"]) * 1e3


def beam_name(D: float, notch: float) -> str:
    return f"D{D:g}_n{notch:g}"


def gauge_label(D: float, notch: float) -> str:
    return f"CMOD over {GAUGES[(D, notch)] * 1e3:g} mm [mm]"


def against_measured(curves, band, m: dict) -> dict:
    """curve_report.summarize of predicted curves against a beam's measured
    mean curve (band), or against its measured peak alone (measured.csv's row m)."""
    mean = (band["cmod_mm"], band["load_mean_kN"]) if band is not None else None
    x_ref = float(m["cmod_at_peak_mm"])
    return summarize(curves, x_ref, mean, (float(m["peak_load_kN"]), x_ref))


def measured(band, m: dict) -> dict:
    """curve_report.figure's measured arguments: the band of a measured curve,
    else the measured peak alone (measured.csv's row m)."""
    if band is None:
        return {"measured_peak": (float(m["peak_load_kN"]), float(m["cmod_at_peak_mm"]))}
    return {"band": {"x": band["cmod_mm"], "mean": band["load_mean_kN"], "min": band["load_min_kN"],
                     "max": band["load_max_kN"]}}


def report(out: str, data: str, seeds: int) -> str:
    """whole_curves.md and a figure per beam, from the finished cases."""
    lines = ["# Grégoire et al. (2013): whole curves, the calibrated concrete against the measurements", "",
             "Written by `ldem study beams whole-curves` (ldem.study.beams.whole_curves says why each choice). The "
             "concrete of `../calibrated/material.json`, after the diagnosis, not blind. Each beam under a servo "
             f"on a clip gauge opening at {OPENING_RATE:g} D/s, six seeds, run to {PAST:g} x "
             f"{MULTIPLES[-1]:g} x the measured CMOD at the peak. The quantities are read at multiples of the "
             "measured CMOD at the peak, along each curve past its peak; the work is that of the load along "
             "the gauge's opening, from zero to the last multiple.", "",
             "The gauges are assumed: the data do not give them. They are those of the models that redistribute "
             "the curves, 70 mm for the unnotched beam (PeriPy) and 20 mm for the half-notched one (pypd), and "
             "20 mm for the D = 100 mm beam. A gauge reads the crack's opening plus the elastic stretch of the "
             "concrete it spans, so the rising branch and the opening at the peak depend on it.", ""]
    for (D, n), m in sorted(measured_beams(data).items()):
        name = beam_name(D, n)
        curves = [gauge_curve(os.path.join(out, "cases", f"{name}_s{s}")) for s in range(1, seeds + 1)]
        x_ref = float(m["cmod_at_peak_mm"])
        band = measured_curve(data, m)
        s = against_measured(curves, band, m)
        title = f"D = {D:g} mm, {NAMES[n]}: gauge {GAUGES[(D, n)] * 1e3:g} mm"
        figure(os.path.join(out, f"{name}.png"), title, curves, x_ref, gauge_label(D, n), **measured(band, m))
        quarter = gauge_curve(os.path.join(out, "rate_check", f"{name}_s1"))
        q1, q4 = (quantities(c, x_ref) for c in (curves[0], quarter))
        lines += [f"## {title}", "", *table_lines(s), "",
                  f"Rate check, seed 1: at a quarter of the rate the peak is {q4['peak_kN']:.3f} kN and the "
                  f"work to {MULTIPLES[-1]:g} x {x_ref:g} mm {q4['work_J']:.4g} J; at the study's rate they are "
                  f"{q1['peak_kN'] / q4['peak_kN'] - 1:+.1%} and {q1['work_J'] / q4['work_J'] - 1:+.1%} from "
                  "those.", "", f"![{title}]({name}.png)", ""]
        if band is None:
            lines += ["Only the peak and the CMOD at it were measured (one published curve): the other "
                      "measured cells stay empty.", ""]
    text = "\n".join(lines)
    io.write_text(os.path.join(out, "whole_curves.md"), text)
    return text


def run(out: str, material_path: str, data: str, seeds: int = 6, jobs: int = 1,
        log: Callable[[str], None] = print) -> str:
    """The unfinished cases, then the report."""
    with open(material_path) as f:
        material = json.load(f)["material"]
    run_cases(cases(material, data, seeds), out, jobs=jobs, log=log)
    return report(out, data, seeds)

