"""The blind prediction of the Grégoire et al. (2013) beams against their
measurements: comparison.md and comparison.png in the prediction's folder,
from its predictions.csv and curves/*.csv (never changed) and the data
folder's measured.csv and D50_*_load_cmod.csv (CMOD [mm], mean, min and max
load [kN] over the specimens)."""
from __future__ import annotations

import os
from typing import Dict, List, Optional, Tuple

import numpy as np

from ... import io
from ...markdown import mean_cv_cell
from ..curve_quantities import cmod_at_peak, load_at_opening, rising

DATA = os.path.join("..", "shared", "data", "gregoire2013")  # beside the repository
NAMES = {0.0: "no notch", 0.2: "notch D/5", 0.5: "notch D/2"}
Beam = Tuple[float, float]  # (D [mm], notch / D)


def default_data(out: str) -> str:
    """../shared/data/gregoire2013 beside the repository that holds the
    prediction folder out (the first parent with a .git), else beside the
    working directory."""
    here = os.path.abspath(out)
    while os.path.dirname(here) != here and not os.path.exists(os.path.join(here, ".git")):
        here = os.path.dirname(here)
    root = here if os.path.exists(os.path.join(here, ".git")) else os.getcwd()
    return os.path.normpath(os.path.join(root, DATA))


def _by_beam(path: str) -> Dict[Beam, dict]:
    return {(float(r["D_mm"]), float(r["notch_ratio"])): r for r in io.read_table(path)}


def measured_curve(data: str, row: dict) -> Optional[np.ndarray]:
    """The measured load-CMOD curve of a beam (columns cmod_mm, load_mean_kN,
    load_min_kN, load_max_kN), or None when only its peak is known."""
    name = row.get("curve_file") or ""
    return np.genfromtxt(os.path.join(data, name), delimiter=",", names=True) if name else None


def predicted_curves(out: str, beam: Beam) -> List[Tuple[np.ndarray, np.ndarray]]:
    """(CMOD [mm], load [kN]) of each seed of curves/D{mm}_n{notch}.csv."""
    table = np.genfromtxt(os.path.join(out, "curves", f"D{beam[0]:g}_n{beam[1]:g}.csv"), delimiter=",", names=True)
    seeds = sorted(int(n.rsplit("_s", 1)[1]) for n in table.dtype.names if n.startswith("load_kN_s"))
    curves = []
    for s in seeds:
        load, cmod = table[f"load_kN_s{s}"], table[f"cmod_mm_s{s}"]
        ok = ~np.isnan(load)  # a shorter run leaves its columns empty
        curves.append((cmod[ok], load[ok]))
    return curves


def rising_branch(out: str, data: str, beam: Beam, m: dict) -> Optional[dict]:
    """The stiffness check: at half the measured CMOD at peak, the load of the
    measured mean curve and of each predicted seed (None without a measured curve)."""
    curve = measured_curve(data, m)
    if curve is None:
        return None
    x = 0.5 * float(m["cmod_at_peak_mm"])
    return {"cmod_mm": x, "measured_kN": load_at_opening((curve["cmod_mm"], curve["load_mean_kN"]), x),
            "predicted_kN": [load_at_opening(rising(c), x) for c in predicted_curves(out, beam)]}


def comparison_rows(out: str, data: str) -> List[dict]:
    """One row per measured beam: the prediction's peak (mean over the seeds, CV,
    min, max; predictions.csv), the measured one and its envelope, their ratio,
    and the CMOD at the peak of both."""
    for path in (os.path.join(data, "measured.csv"), os.path.join(out, "predictions.csv")):
        if not os.path.isfile(path):
            raise FileNotFoundError(f"{path} not found: the comparison needs the measurements (default "
                                    f"{DATA} beside the repository, see its README.md) and the committed prediction")
    predicted, rows = _by_beam(os.path.join(out, "predictions.csv")), []
    for beam, m in sorted(_by_beam(os.path.join(data, "measured.csv")).items()):
        p = predicted[beam]
        curves = predicted_curves(out, beam)
        cmods = [cmod_at_peak(c) for c in curves]
        ratio = float(p["peak_load_kN"]) / float(m["peak_load_kN"])
        rows.append({"D_mm": beam[0], "notch": beam[1], "predicted_kN": float(p["peak_load_kN"]),
                     "cv": p["cv"], "min_kN": float(p["min_kN"]), "max_kN": float(p["max_kN"]),
                     "measured_kN": float(m["peak_load_kN"]),
                     "envelope_kN": (m["peak_of_min_envelope_kN"], m["peak_of_max_envelope_kN"]),
                     "ratio": ratio, "difference_pct": 100.0 * (ratio - 1.0),
                     "cmod_predicted_mm": (float(np.mean(cmods)), min(cmods), max(cmods)),
                     "cmod_measured_mm": float(m["cmod_at_peak_mm"]), "measured": m,
                     "cmod_max_mm": max(float(c[0].max()) for c in curves),
                     "rising": rising_branch(out, data, beam, m)})
    return rows


def _envelope(e) -> str:
    return "-" if e[0] == "" else f"{float(e[0]):.3f}-{float(e[1]):.3f}"


def table_lines(rows: List[dict]) -> List[str]:
    lines = ["| beam | predicted peak [kN] (CV) | predicted min-max [kN] | measured peak [kN] | "
             "measured envelope [kN] | predicted / measured | difference | CMOD at peak, predicted [mm] "
             "(min-max) | CMOD at peak, measured [mm] |", "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        c = r["cmod_predicted_mm"]
        lines.append(f"| D = {r['D_mm']:g} mm, {NAMES[r['notch']]} | {mean_cv_cell(r['predicted_kN'], r['cv'])} | "
                     f"{r['min_kN']:.3f}-{r['max_kN']:.3f} | {r['measured_kN']:.3f} | {_envelope(r['envelope_kN'])} | "
                     f"{r['ratio']:.3f} | {r['difference_pct']:+.1f} % | {c[0]:.4f} ({c[1]:.4f}-{c[2]:.4f}) | "
                     f"{r['cmod_measured_mm']:.4f} |")
    return lines


def rising_lines(rows: List[dict]) -> List[str]:
    """One line per beam with a measured curve: the loads at half its CMOD at peak."""
    lines = []
    for r in rows:
        g = r["rising"]
        if g is None:
            continue
        reached = [f for f in g["predicted_kN"] if not np.isnan(f)]
        seeds = (f"the predicted seeds {min(reached):.3f}-{max(reached):.3f} kN ({len(reached)} of "
                 f"{len(g['predicted_kN'])} reach it before their peak)" if reached else
                 f"no predicted seed reaches it before its peak (at most {r['cmod_predicted_mm'][2]:.4f} mm)")
        lines.append(f"- D = {r['D_mm']:g} mm, {NAMES[r['notch']]}: at CMOD = {g['cmod_mm']:.5f} mm the measured mean "
                     f"carries {g['measured_kN']:.3f} kN; {seeds}.")
    return lines


def report(rows: List[dict]) -> str:
    """comparison.md: the table, then what it compares and what it cannot."""
    weakest = [f"D = {r['D_mm']:g} mm, {NAMES[r['notch']]}: {r['min_kN']:.3f} kN against "
               f"{float(r['envelope_kN'][1]):.3f} kN" for r in rows if r["envelope_kN"][1] != ""]
    snap = max((r["cmod_max_mm"] for r in rows if r["notch"] == 0), default=float("nan"))
    return "\n".join([
        "# The blind prediction of Grégoire et al. (2013) against the measurements", "",
        "The prediction (`predictions.csv`, `curves/`, committed before the measurements were given and "
        "unchanged since) against the measured beams of `../shared/data/gregoire2013/` (its README.md: "
        "provenance and caveats). Only three of the nine beams have public measurements. Written by "
        "`ldem study beams compare [--out DIR] [--data DATA]`.", "",
        *table_lines(rows), "",
        "![prediction against measurement](comparison.png)", "",
        f"The prediction is too strong for every measured beam, by {min(r['difference_pct'] for r in rows):+.0f} "
        f"to {max(r['difference_pct'] for r in rows):+.0f} %. Even the weakest of the six predicted specimens "
        "is stronger than the peak of the measured max envelope (the strongest measured specimen): "
        + "; ".join(weakest) + ". The known biases of the prediction (its README) are far smaller: the loading "
        "rate adds 1 to 2 % to the notched peaks at D = 50 mm.", "",
        "The rising branches, at half the measured CMOD at peak (the load when the CMOD first reaches it):", "",
        *rising_lines(rows), "",
        "Caveats:",
        "- **Measured peak.** It is the maximum of the mean measured curve, not the mean of the specimens' "
        "peaks, which is at least as large; the envelope is the peaks of the pointwise min and max curves "
        "(the max one's is the strongest specimen's peak, the min one's a lower bound on the weakest's). "
        "The D = 100 mm beam's peak is that of one published curve (mean or replicate not stated), "
        "with no envelope. The predicted peak is the mean over six seeds of each run's peak.",
        "- **CMOD gauge.** The gauge length of the tests' CMOD is unknown (the models that redistribute "
        "the curves used 20 mm and 70 mm). The prediction's CMOD is the opening across the 5 mm notch "
        "module of the notched beams, and between the two nodes 5 mm apart at mid-span on the lower face "
        "of the unnotched ones. A gauge reads the crack's (or notch's) opening plus the stretching of the "
        "concrete it spans, about (f_t / E) x gauge at the peak: 0.5 micrometres over 5 mm, 2 to 7 "
        "micrometres over 20 to 70 mm. For the unnotched beam, where the opening before the peak is that "
        "stretching and a process zone, the predicted and measured CMODs are therefore not comparable "
        "before or at the peak. For the notched beams the notch's opening dominates and the gauges differ "
        "by that elastic part only (the half-notched beam's rising branches above agree). After the peak "
        "the crack opening dominates either way, and the elastic part falls with the load.",
        "- **Post-peak branch.** The prediction is under displacement control of the platen, the tests "
        "were probably under CMOD control (their curves are against CMOD). The unnotched predicted beams "
        "snap: past the peak the load drops while their CMOD grows to at most "
        f"{snap:.4f} mm (some seeds' CMOD even closes "
        "again) and the run stops, so they have no softening branch to compare with the measured one. "
        "The notched ones soften stably, and their branch can be compared in shape (the prediction's "
        "lies above the measured one throughout).",
        "- The predicted CMOD at peak is that of the recorded point of largest load of each seed's curve "
        "(`curves/`, sampled more coarsely than the run's peak in `predictions.csv`).", ""])


def comparison_figure(out: str, data: str, rows: List[dict], what: str = "the blind prediction") -> str:
    """comparison.png: for each beam with a measured curve, the predicted load-CMOD
    curves of every seed over the measured mean and its min-max envelope, the
    peaks marked; upper row up to three times the larger CMOD at peak, lower row
    the whole range."""
    from ... import plots
    import matplotlib.pyplot as plt

    from matplotlib.lines import Line2D

    beams = [(r, measured_curve(data, r["measured"])) for r in rows]
    beams = [(r, m) for r, m in beams if m is not None]
    fig, axes = plt.subplots(2, len(beams), figsize=(6.2 * len(beams), 8.8), squeeze=False)
    for k, (r, m) in enumerate(beams):
        curves = predicted_curves(out, (r["D_mm"], r["notch"]))
        zoom = 3.0 * max(r["cmod_measured_mm"], r["cmod_predicted_mm"][2])
        for ax, xmax in ((axes[0, k], zoom), (axes[1, k], None)):
            ax.fill_between(m["cmod_mm"], m["load_min_kN"], m["load_max_kN"], color="0.8", lw=0,
                            label="measured min-max")
            ax.plot(m["cmod_mm"], m["load_mean_kN"], "k", lw=1.6, label="measured mean")
            i = np.argmax(m["load_mean_kN"])
            ax.plot(m["cmod_mm"][i], m["load_mean_kN"][i], "ko", ms=7, label="measured peak (of the mean)")
            for s, c in enumerate(curves):
                j = np.argmax(c[1])
                ax.plot(c[0], c[1], color=f"C{s}", lw=0.9, label=f"ldem seed {s + 1}")
                ax.plot(c[0][j], c[1][j], "^", color=f"C{s}", ms=6)
            top = 1.08 * max(r["max_kN"], float(m["load_max_kN"].max()))
            whole = 1.02 * max(m["cmod_mm"].max(), max(c[0].max() for c in curves))
            ax.set(xlabel="CMOD [mm]", ylabel="load [kN]", ylim=(0, top), xlim=(0, xmax or whole))
        axes[0, k].set_title(f"D = {r['D_mm']:g} mm, {NAMES[r['notch']]}: predicted {r['predicted_kN']:.2f} kN, "
                             f"measured {r['measured_kN']:.2f} kN ({r['difference_pct']:+.0f} %)", fontsize=9)
        axes[1, k].set_title(f"D = {r['D_mm']:g} mm, {NAMES[r['notch']]}: the whole range", fontsize=9)
    handles, labels = axes[0, 0].get_legend_handles_labels()
    handles.append(Line2D([], [], color="0.4", marker="^", ls="none", ms=6))
    labels.append("ldem peak of each seed")
    fig.legend(handles, labels, loc="upper center", ncol=5, fontsize=8, bbox_to_anchor=(0.5, 0.955))
    fig.suptitle(f"Grégoire et al. (2013): {what} (ldem, CMOD on a 5 mm gauge) "
                 "against the measurements (gauge unknown)", fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.915))
    path = os.path.join(out, "comparison.png")
    plots.save(fig, path)
    return path


def compare(out: str, data: Optional[str] = None) -> List[dict]:
    """Writes out/comparison.md and out/comparison.png; returns the rows."""
    data = data or default_data(out)
    if not os.path.isdir(data):
        raise FileNotFoundError(f"{data}: no such folder; the measurements of Grégoire et al. (2013) go there "
                                f"(measured.csv and D50_*_load_cmod.csv; default {DATA} beside the repository)")
    rows = comparison_rows(out, data)
    io.write_text(os.path.join(out, "comparison.md"), report(rows))
    comparison_figure(out, data, rows)
    return rows
