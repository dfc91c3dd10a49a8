"""The whole-curve table and figure of a prediction: per specimen, the
predicted seeds' curve quantities (ldem.study.curve_quantities) beside the
measured mean curve's, or with the measured column left empty (a blind
prediction, whose measurements stay out of the repository)."""
from __future__ import annotations

import math
from typing import Dict, List, Optional, Sequence

import numpy as np

from .curve_quantities import MULTIPLES, Curve, quantities

Band = Dict[str, np.ndarray]  # a measured curve: x, mean, min, max


def _spread(values: Sequence[float]) -> tuple:
    """(mean, min, max, count) over the seeds whose curve reached the point."""
    got = [v for v in values if not math.isnan(v)]
    return (float(np.mean(got)), min(got), max(got), len(got)) if got else (math.nan, math.nan, math.nan, 0)


def summarize(curves: Sequence[Curve], x_ref: float, measured: Optional[Curve] = None,
              measured_peak: Optional[tuple] = None) -> dict:
    """The predicted quantities of every seed, their spread, and the measured
    ones: of the measured mean curve, else only (peak [kN], opening there)."""
    per_seed = [quantities(c, x_ref) for c in curves]
    keys = list(per_seed[0])
    found = quantities(measured, x_ref) if measured is not None else {}
    if measured is None and measured_peak is not None:
        found = {"peak_kN": measured_peak[0], "x_at_peak": measured_peak[1]}
    return {"x_ref": x_ref, "seeds": per_seed, "predicted": {k: _spread([q[k] for q in per_seed]) for k in keys},
            "measured": {k: found.get(k, math.nan) for k in keys}}


def _label(key: str, x_ref: float, unit: str) -> str:
    if key == "peak_kN":
        return "peak [kN]"
    if key == "x_at_peak":
        return f"opening at the peak [{unit}]"
    if key == "work_J":
        return f"work to {MULTIPLES[-1] * x_ref:.4g} {unit} [J]"
    m = float(key.split("_")[-1])
    return f"load at {m:g} x {x_ref:.4g} = {m * x_ref:.4g} {unit} [kN]"


def table_lines(s: dict, unit: str = "mm", what: str = "measured") -> List[str]:
    """Markdown: a row per quantity, the seeds' mean (min-max; how many reached
    it when not all), the measured value and the predicted/measured ratio."""
    n = len(s["seeds"])
    lines = [f"| quantity | predicted, mean (min-max) | {what} | predicted / {what} |", "|---|---|---|---|"]
    for key, (mean, lo, hi, count) in s["predicted"].items():
        fmt = ".4f" if key == "x_at_peak" else ".4g" if key == "work_J" else ".3f"
        cell = "not reached" if count == 0 else f"{mean:{fmt}} ({lo:{fmt}}-{hi:{fmt}})" + (
            f", {count} of {n}" if count < n else "")
        m = s["measured"][key]
        ratio = mean / m if count and not math.isnan(m) and m != 0 else math.nan
        lines.append(f"| {_label(key, s['x_ref'], unit)} | {cell} | {'' if math.isnan(m) else format(m, fmt)} | "
                     f"{'' if math.isnan(ratio) else f'{ratio:.3f}'} |")
    return lines


def figure(path: str, title: str, curves: Sequence[Curve], x_ref: float, x_label: str,
           band: Optional[Band] = None, measured_peak: Optional[tuple] = None) -> str:
    """The predicted seeds over the measured mean and its min-max band (when
    given), to 1.1 times the last multiple of x_ref, with those multiples marked."""
    from .. import plots
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    if band is not None:
        ax.fill_between(band["x"], band["min"], band["max"], color="0.82", lw=0, label="measured min-max")
        ax.plot(band["x"], band["mean"], "k", lw=1.6, label="measured mean")
    if measured_peak is not None:
        ax.plot(*measured_peak[::-1], "ko", ms=7, label="measured peak")
    for s, (x, load) in enumerate(curves):
        ax.plot(x, load, color=f"C{s}", lw=0.9, label=f"ldem seed {s + 1}")
    for m in MULTIPLES:
        ax.axvline(m * x_ref, color="0.5", ls=":", lw=0.8)
    xmax = 1.1 * MULTIPLES[-1] * x_ref
    top = max(float(np.max(load)) for _, load in curves)
    if band is not None:
        top = max(top, float(np.max(band["max"])))
    ax.set(xlabel=x_label, ylabel="load [kN]", xlim=(0, xmax), ylim=(0, 1.08 * top))
    ax.set_title(f"{title}\n(dotted: " + ", ".join(f"{m:g}" for m in MULTIPLES) + f" x {x_ref:.4g})", fontsize=10)
    ax.legend(fontsize=7, loc="best")
    plots.save(fig, path, palette=True)
    return path

