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
from .cube import STRAIN_LABEL, STRESS_LABEL, labels as test_labels  # noqa: E402, F401  (the report's axes too)

STYLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "ldem.mplstyle")
plt.style.use(STYLE)
FIGURE_FORMATS = ("png", "pdf", "svg")


def save(fig, path: str) -> None:
    """Writes fig (whole, or not at all) in the format of path's extension, then frees it."""
    from .io.files import atomic

    try:
        with atomic(path) as tmp:
            fig.savefig(tmp, format=os.path.splitext(path)[1][1:])
    finally:
        plt.close(fig)


# The study's colours; its cyan darkened (darkcyan) to stand out on white, even drawn faint.
STATE_COLOURS = {UNDAMAGED: "darkcyan", DAMAGED: "orange", BROKEN: "red"}
STATE_ALPHA = {UNDAMAGED: 0.55, DAMAGED: 1.0, BROKEN: 1.0}  # undamaged bars faint: the crack stands out
STATE_NAMES = {UNDAMAGED: "undamaged", DAMAGED: "damaged", BROKEN: "broken"}


ZOOM = 3.0  # the zoom panels reach ZOOM x the strain where the softening ends: the pre-peak and the softening
SOFTENED = 0.1  # without a load loss in reach, the softening ends where the stress first falls below this x the peak


def axis_labels(test) -> tuple:
    """(strain, stress) axis labels: a specimen's own quantities (its measure.strain_label
    and stress_label: a beam's deflection/D and F/(bD)), else a cube's mean strain and normal stress."""
    words = test_labels(test)
    return words["strain"], words["stress"]


def softening_end(curve, summary):
    """(strain, name) where the softening ends, if ZOOM x that strain is inside
    the run (its whole axis then hides the peak at x = 0); else None. That
    strain is the load loss's; or, where the load loss comes late or never (a
    triangular cube hinges and keeps some load long after its peak), the first
    strain past the peak with the stress below SOFTENED x the peak."""
    x, y = curve["mean_strain"], curve["stress_MPa"]
    ends = [((summary.get("load_loss") or {}).get("mean_strain"), "load loss")]
    if len(y):
        top = int(y.argmax())
        below = (y[top:] < SOFTENED * y[top]).nonzero()[0]
        if below.size:
            ends.append((x[top + below[0]], f"{SOFTENED:.0%} of the peak"))
    return next(((e, name) for e, name in ends if e and ZOOM * e < x[-1]), None)


def zoom_to(ax, x, ys, end) -> None:
    """Limits ax to 0 <= x <= ZOOM x the softening's end (strain, name), its y
    range that of the curves ys there (5 % margins)."""
    x_max = ZOOM * end[0]
    inside = x <= x_max
    lo, hi = min(y[inside].min() for y in ys), max(y[inside].max() for y in ys)
    pad = 0.05 * (hi - lo or 1.0)
    ax.set(xlim=(0.0, x_max), ylim=(lo - pad, hi + pad),
           title=f"pre-peak and softening (to {ZOOM:g} x the strain at {end[1]})")
    ax.axvline(end[0], color="0.4", lw=0.8, ls=":", label=end[1])
    ax.legend(handles=ax.get_lines()[-1:], loc="upper right")


def curve_plot(curve, summary: dict, title: str, labels=(STRAIN_LABEL, STRESS_LABEL)):
    """The curve figure: stress against strain over the whole run; beside it, for a run
    past its load loss, the same to ZOOM x the strain at load loss; then stress against
    each probe (NAME_m: a beam's load against its CMOD, the curve laboratories report)."""
    c, s, (strain_label, stress_label) = curve, summary, labels
    probes = [k for k in c if k.endswith("_m")]
    end = softening_end(c, s)
    n = 1 + (end is not None) + bool(probes)
    fig, axes = plt.subplots(1, n, figsize=(5.2 * n, 4.4), squeeze=False, layout="constrained")
    for ax in axes[0, :1 + (end is not None)]:
        ax.plot(c["mean_strain"], c["stress_MPa"], label="support (reaction)")
        ax.plot(c["mean_strain"], c["stress_top_MPa"], lw=0.8, ls="--", alpha=0.7, label="loaded group")
        if "peak_stress_MPa" in s:
            ax.plot(s["strain_at_peak"], s["peak_stress_MPa"], "ko", ms=5,
                    label=f"peak {s['peak_stress_MPa']:.3f} MPa at {s['strain_at_peak']:.3g}")
        ax.set(xlabel=strain_label, ylabel=stress_label)
    axes[0, 0].legend()
    if end is not None:
        axes[0, 0].set_title("whole run")
        zoom_to(axes[0, 1], c["mean_strain"], (c["stress_MPa"], c["stress_top_MPa"]), end)
    if probes:
        ax = axes[0, -1]
        for name in probes:
            ax.plot(c[name] * 1e3, c["stress_MPa"], lw=1, label=name[:-2].upper())
        ax.set(xlabel=" / ".join(name[:-2].upper() for name in probes) + " [mm]", ylabel=stress_label)
        ax.legend()
    fig.suptitle(title + energy_flag(s))
    return fig


def curve_figure(result, path: str):
    """curve_plot of a run, saved to path; returns the figure."""
    fig = curve_plot(result.curve, result.summary, result.test.describe(), axis_labels(result.test))
    save(fig, path)
    return fig


def energy_flag(summary: dict) -> str:
    """A title's warning when the run's energy balance is off (energy_error)."""
    if not summary.get("energy_error"):
        return ""
    return f"\nENERGY ERROR {summary['energy_balance_error']:.2e}: not trustworthy"


ENERGIES = (("elastic_J", "elastic"), ("fracture_J", "fracture"), ("damping_J", "damping"), ("kinetic_J", "kinetic"))


def energy_plot(curve, summary: dict, strain_label: str = STRAIN_LABEL):
    """The energy budget stacked under the external work over the whole run; beside
    it each energy on its own on a log scale (the elastic and kinetic energies are
    a sliver of the stack), to ZOOM x the strain where the softening ends for a run past it."""
    c, x = curve, curve["mean_strain"]
    fig, (whole, each) = plt.subplots(1, 2, figsize=(10.4, 4.4), layout="constrained")
    whole.plot(x, c["external_work_J"], "k", lw=2, label="external work")
    whole.stackplot(x, *(c[k] for k, _ in ENERGIES), labels=[name for _, name in ENERGIES], alpha=0.6)
    whole.set(xlabel=strain_label, ylabel="energy [J]", title="budget, whole run")
    whole.legend(loc="upper left")
    end = softening_end(c, summary)
    x_max = x[-1] if end is None else ZOOM * end[0]
    inside = x <= x_max
    each.plot(x[inside], c["external_work_J"][inside], "k", lw=2, label="external work")
    for i, (k, name) in enumerate(ENERGIES):
        each.plot(x[inside], c[k][inside], color=f"C{i}", label=name)
    top = max(c["external_work_J"][inside].max(), 1e-30)
    each.set(yscale="log", ylim=(1e-5 * top, 2 * top), xlim=(0.0, x_max), xlabel=strain_label, ylabel="energy [J]",
             title="each energy" + (f", to {ZOOM:g} x the strain at {end[1]}" if end else ""))
    each.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=5)  # below: clear of the curves
    fig.suptitle(f"energy budget (balance error {summary.get('energy_balance_error', float('nan')):.2e})"
                 + energy_flag(summary))
    return fig


def energy_figure(result, path: str):
    """energy_plot of a run, saved to path; returns the figure."""
    fig = energy_plot(result.curve, result.summary, axis_labels(result.test)[0])
    save(fig, path)
    return fig


def draw_slice(ax, seg, state) -> dict:
    """Draws segments coloured by damage state (broken on top, undamaged faint
    beneath); returns the counts. Lines thin out (as 1/sqrt) beyond 12 modules
    across, so that large cubes and long beams stay legible."""
    counts = {}
    if len(seg) == 0:
        return {st: 0 for st in (UNDAMAGED, DAMAGED, BROKEN)}
    modules = np.ptp(seg[:, :, 0]) / np.linalg.norm(seg[:, 1] - seg[:, 0], axis=1).max()
    thin = min(1.0, np.sqrt(12.0 / max(modules, 1.0)))
    for st, lw in ((UNDAMAGED, 0.6), (DAMAGED, 1.2), (BROKEN, 1.8)):
        sel = state == st
        counts[st] = int(sel.sum())
        ax.add_collection(LineCollection(seg[sel], colors=STATE_COLOURS[st], linewidths=lw * thin,
                                         alpha=STATE_ALPHA[st]))
    ax.set_aspect("equal")
    ax.autoscale()
    ax.grid(False)
    ax.set(xlabel="x [m]", ylabel="z [m]")
    return counts


def state_handles(counts=None) -> list:
    """Legend entries of the three damage states (with their counts, if given)."""
    return [Line2D([], [], color=STATE_COLOURS[s], alpha=STATE_ALPHA[s], lw=2,
                   label=STATE_NAMES[s] + (f" ({counts[s]})" if counts else ""))
            for s in (UNDAMAGED, DAMAGED, BROKEN)]


def crack_figure_from_slice(seg, state, path: str, title: str = ""):
    """The crack picture of a slice (draw_slice), saved to path; returns the figure."""
    # A cube's slice is square: 5.6 x 6.2 in; a beam's is flat, and its figure with it.
    aspect = np.ptp(seg[:, :, 1]) / max(np.ptp(seg[:, :, 0]), 1e-30) if len(seg) else 1.0
    fig, ax = plt.subplots(figsize=(5.6, min(6.2, 1.6 + 4.6 * aspect)))
    ax.legend(handles=state_handles(draw_slice(ax, seg, state)), loc="upper center",
              bbox_to_anchor=(0.5, -0.1 - 0.25 * max(0.0, 1 - aspect)), ncol=3)
    ax.set_title(title or "central slice")
    fig.tight_layout()
    save(fig, path)
    return fig
