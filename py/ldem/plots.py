"""Pictures of a run: stress-strain curve, energy budget, crack slice. One
style for every figure (ldem.mplstyle); the file's extension (png, pdf, svg)
chooses the format."""
from __future__ import annotations

import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

from ._core import BROKEN, DAMAGED, UNDAMAGED  # noqa: E402  (the law's damage states)

STYLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "ldem.mplstyle")
plt.style.use(STYLE)
FIGURE_FORMATS = ("png", "pdf", "svg")
STRAIN_LABEL, STRESS_LABEL = "mean strain [-]", "normal stress [MPa]"


def save(fig, path: str) -> None:
    """Writes fig (whole, or not at all) in the format of path's extension, then frees it."""
    from .io.files import atomic

    try:
        with atomic(path) as tmp:
            fig.savefig(tmp, format=os.path.splitext(path)[1][1:])
    finally:
        plt.close(fig)


# The study's colours.
STATE_COLOURS = {UNDAMAGED: "cyan", DAMAGED: "orange", BROKEN: "red"}
STATE_NAMES = {UNDAMAGED: "undamaged", DAMAGED: "damaged", BROKEN: "broken"}


def curve_figure(result, path: str) -> None:
    """Stress against strain; beside it, stress against each probe (NAME_m: a
    beam's load against its CMOD, the curve laboratories report)."""
    c, s = result.curve, result.summary
    probes = [k for k in c if k.endswith("_m")]
    fig, axes = plt.subplots(1, 1 + bool(probes), figsize=(6.4 * (1 + 0.9 * bool(probes)), 4.8), squeeze=False)
    ax = axes[0, 0]
    if probes:
        for name in probes:
            axes[0, 1].plot(c[name] * 1e3, c["stress_MPa"], lw=1, label=name[:-2])
        axes[0, 1].set(xlabel="probe [mm]", ylabel=STRESS_LABEL)
        axes[0, 1].legend()
    ax.plot(c["mean_strain"], c["stress_MPa"], label="support (reaction)")
    ax.plot(c["mean_strain"], c["stress_top_MPa"], lw=0.8, ls="--", alpha=0.7, label="loaded group")
    if "peak_stress_MPa" in s:
        ax.plot(s["strain_at_peak"], s["peak_stress_MPa"], "ko", ms=5,
                label=f"peak {s['peak_stress_MPa']:.3f} MPa at {s['strain_at_peak']:.3g}")
    ax.set(xlabel=STRAIN_LABEL, ylabel=STRESS_LABEL, title=result.test.describe() + energy_flag(s))
    ax.legend()
    save(fig, path)


def energy_flag(summary: dict) -> str:
    """A title's warning when the run's energy balance is off (energy_error)."""
    if not summary.get("energy_error"):
        return ""
    return f"\nENERGY ERROR {summary['energy_balance_error']:.2e}: not trustworthy"


def energy_figure(result, path: str) -> None:
    c = result.curve
    x = c["mean_strain"]
    fig, ax = plt.subplots()
    ax.plot(x, c["external_work_J"], "k", lw=2, label="external work")
    ax.stackplot(x, c["elastic_J"], c["fracture_J"], c["damping_J"], c["kinetic_J"],
                 labels=["elastic", "fracture", "damping", "kinetic"], alpha=0.6)
    ax.set(xlabel=STRAIN_LABEL, ylabel="energy [J]",
           title=f"energy budget (balance error {result.summary.get('energy_balance_error', float('nan')):.2e})"
           + energy_flag(result.summary))
    ax.legend(loc="upper left")
    save(fig, path)


def draw_slice(ax, seg, state) -> dict:
    """Draws segments coloured by damage state (broken on top); returns the counts.
    Lines thin out (as 1/sqrt) beyond 12 modules across, so that large cubes stay legible."""
    counts = {}
    if len(seg) == 0:
        return {st: 0 for st in (UNDAMAGED, DAMAGED, BROKEN)}
    modules = np.ptp(seg[:, :, 0]) / np.linalg.norm(seg[:, 1] - seg[:, 0], axis=1).max()
    thin = min(1.0, np.sqrt(12.0 / max(modules, 1.0)))
    for st, lw in ((UNDAMAGED, 0.5), (DAMAGED, 1.2), (BROKEN, 1.8)):
        sel = state == st
        counts[st] = int(sel.sum())
        ax.add_collection(LineCollection(seg[sel], colors=STATE_COLOURS[st], linewidths=lw * thin))
    ax.set_aspect("equal")
    ax.autoscale()
    ax.grid(False)
    ax.set(xlabel="x [m]", ylabel="z [m]")
    return counts


def state_handles(counts=None) -> list:
    """Legend entries of the three damage states (with their counts, if given)."""
    return [Line2D([], [], color=STATE_COLOURS[s], lw=2, label=STATE_NAMES[s] + (f" ({counts[s]})" if counts else ""))
            for s in (UNDAMAGED, DAMAGED, BROKEN)]


def crack_figure_from_slice(seg, state, path: str, title: str = "") -> None:
    # A cube's slice is square: 5.6 x 6.2 in; a beam's is flat, and its figure with it.
    aspect = np.ptp(seg[:, :, 1]) / max(np.ptp(seg[:, :, 0]), 1e-30) if len(seg) else 1.0
    fig, ax = plt.subplots(figsize=(5.6, min(6.2, 1.6 + 4.6 * aspect)))
    ax.legend(handles=state_handles(draw_slice(ax, seg, state)), loc="upper center",
              bbox_to_anchor=(0.5, -0.1 - 0.25 * max(0.0, 1 - aspect)), ncol=3)
    ax.set_title(title or "central slice", fontsize=9)
    fig.tight_layout()
    save(fig, path)
