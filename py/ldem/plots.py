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
from .cube import STRAIN_LABEL, STRESS_LABEL, label_words, labels as test_labels  # noqa: E402, F401  (report axes too)

STYLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "ldem.mplstyle")
plt.style.use(STYLE)
FIGURE_FORMATS = ("png", "pdf", "svg")


def save(fig, path: str, palette: bool = False) -> None:
    """Writes fig (whole, or not at all) in the format of path's extension, then frees it.
    palette: a PNG of 256 colours (median cut), a third of the bytes of a line plot's
    RGBA: for figures committed under results/, whose binaries have a budget."""
    from .io.files import atomic

    try:
        with atomic(path) as tmp:
            kind = os.path.splitext(path)[1][1:]
            if palette and kind == "png":
                import io
                from PIL import Image

                buffer = io.BytesIO()
                fig.savefig(buffer, format="png")
                buffer.seek(0)
                Image.open(buffer).convert("RGB").quantize(256, Image.Quantize.MEDIANCUT).save(tmp, "png",
                                                                                                optimize=True)
            else:
                fig.savefig(tmp, format=kind)
    finally:
        plt.close(fig)


# The study's colours; its cyan darkened (darkcyan) to stand out on white, even drawn faint.
STATE_COLOURS = {UNDAMAGED: "darkcyan", DAMAGED: "orange", BROKEN: "red"}
STATE_ALPHA = {UNDAMAGED: 0.55, DAMAGED: 1.0, BROKEN: 1.0}  # undamaged bars faint: the crack stands out
STATE_NAMES = {UNDAMAGED: "undamaged", DAMAGED: "damaged", BROKEN: "broken"}


ZOOM = 4.0  # a zoom reaches ZOOM x the abscissa of the peak: the rise, the peak and the start of the softening
FAR = 2.0  # it is drawn when the run goes on past FAR x that reach: the peak then fills under 1/8 of the whole axis


def axis_labels(test) -> tuple:
    """(strain, stress) axis labels: a specimen's own quantities (its measure.strain_label
    and stress_label: a beam's deflection/D and F/(bD)), else a cube's mean strain and normal stress."""
    words = test_labels(test)
    return words["strain"], words["stress"]


def zoom_reach(x_end: float, at_peak: float):
    """The zoom's right end, ZOOM x the abscissa of the peak, where the run goes
    on past FAR x it (its whole axis squeezes the peak to a sliver); else None."""
    reach = ZOOM * at_peak
    return reach if reach > 0 and x_end > FAR * reach else None


def zoom_to(ax, lines, reach: float) -> None:
    """Limits ax to 0 <= x <= reach, its y range that of the curves lines ((x, y)
    pairs) there (5 % margins)."""
    inside = [y[x <= reach] for x, y in lines]
    lo, hi = min(y.min() for y in inside if y.size), max(y.max() for y in inside if y.size)
    pad = 0.05 * (hi - lo or 1.0)
    ax.set(xlim=(0.0, reach), ylim=(lo - pad, hi + pad))


ZOOM_TITLE = f"near the peak (to {ZOOM:g} x its abscissa)"


def _parameters(summary: dict) -> dict:
    """The run's parameters: a cube's summary holds them flat, a specimen's under 'parameters'."""
    p = summary.get("parameters") or {}
    return p.get("parameters", p)


def event_lines(ax, summary: dict) -> None:
    """Vertical lines at the run's events, each labelled with what it marks:
    the load loss (the stop rule's: the stress averaged over the split window
    fell below stop_fraction x the peak), the separation and the converged U."""
    fraction = _parameters(summary).get("stop_fraction")
    words = {"load_loss": "load lost: averaged stress < " + (f"{fraction:g} x" if fraction else "a fraction of")
                          + " the peak",
             "separation": "separated: no intact bars join the loaded faces",
             "converged": "U converged (U_final)"}
    for (event, label), style in zip(words.items(), (":", "--", "-.")):
        at = (summary.get(event) or {}).get("mean_strain")
        if at is not None:
            ax.axvline(at, color="0.35", lw=0.9, ls=style, label=label)


def _peak_panel(ax, c, s, strain_label, stress_label) -> None:
    """The curves of both loaded groups, the peak and the events on ax."""
    ax.plot(c["mean_strain"], c["stress_MPa"], label="support (reaction)")
    ax.plot(c["mean_strain"], c["stress_top_MPa"], lw=0.8, ls="--", alpha=0.7, label="loaded group")
    if "peak_stress_MPa" in s:
        unit = label_words(stress_label)[1] or "MPa"  # the specimen's own (an L-panel's load: MN)
        ax.plot(s["strain_at_peak"], s["peak_stress_MPa"], "ko", ms=5,
                label=f"peak {s['peak_stress_MPa']:#.4g} {unit} at {s['strain_at_peak']:.3g}")
    event_lines(ax, s)
    ax.set(xlabel=strain_label, ylabel=stress_label)


def _probe_panel(ax, c, stress_label) -> None:
    """Stress against each probe (NAME_m, in mm); an inset near the peak where
    the probes run far past their value at the peak."""
    probes = [k for k in c if k.endswith("_m")]
    top = int(np.argmax(c["stress_MPa"])) if len(c["stress_MPa"]) else 0
    lines = [(c[name] * 1e3, c["stress_MPa"]) for name in probes]
    for (x, y), name in zip(lines, probes):
        ax.plot(x, y, lw=1, label=name[:-2].upper())
    ax.set(xlabel=" / ".join(name[:-2].upper() for name in probes) + " [mm]", ylabel=stress_label)
    ax.legend(loc="upper right")
    reach = zoom_reach(min(x.max() for x, _ in lines), max(x[top] for x, _ in lines)) if len(c["stress_MPa"]) else None
    if reach is not None:
        inset = ax.inset_axes((0.45, 0.3, 0.52, 0.42))
        for x, y in lines:
            inset.plot(x, y, lw=1)
        zoom_to(inset, lines, reach)
        inset.set_title(ZOOM_TITLE, fontsize=7)
        inset.tick_params(labelsize=6)


def curve_plot(curve, summary: dict, title: str, labels=(STRAIN_LABEL, STRESS_LABEL)):
    """The curve figure: stress against strain over the whole run; beside it, for a run
    far past its peak, the same to ZOOM x the strain at the peak; then stress against
    each probe (NAME_m: a beam's load against its CMOD, the curve laboratories report)."""
    c, s, (strain_label, stress_label) = curve, summary, labels
    x = c["mean_strain"]
    reach = zoom_reach(x[-1], s.get("strain_at_peak", 0.0)) if len(x) else None
    probes = any(k.endswith("_m") for k in c)
    n = 1 + (reach is not None) + probes
    fig, axes = plt.subplots(1, n, figsize=(5.2 * n, 4.4), squeeze=False, layout="constrained")
    for ax in axes[0, :1 + (reach is not None)]:
        _peak_panel(ax, c, s, strain_label, stress_label)
    axes[0, 0].legend(fontsize=8)
    if reach is not None:
        axes[0, 0].set_title("whole run")
        zoom_to(axes[0, 1], [(x, c["stress_MPa"]), (x, c["stress_top_MPa"])], reach)
        axes[0, 1].set_title(ZOOM_TITLE)
    if probes:
        _probe_panel(axes[0, -1], c, stress_label)
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
    a sliver of the stack), to ZOOM x the strain at the peak for a run far past it (zoom_reach)."""
    c, x = curve, curve["mean_strain"]
    fig, (whole, each) = plt.subplots(1, 2, figsize=(10.4, 4.4), layout="constrained")
    whole.plot(x, c["external_work_J"], "k", lw=2, label="external work")
    whole.stackplot(x, *(c[k] for k, _ in ENERGIES), labels=[name for _, name in ENERGIES], alpha=0.6)
    whole.set(xlabel=strain_label, ylabel="energy [J]", title="budget, whole run")
    whole.legend(loc="upper left")
    reach = zoom_reach(x[-1], summary.get("strain_at_peak", 0.0))
    x_max = x[-1] if reach is None else reach
    inside = x <= x_max
    each.plot(x[inside], c["external_work_J"][inside], "k", lw=2, label="external work")
    for i, (k, name) in enumerate(ENERGIES):
        each.plot(x[inside], c[k][inside], color=f"C{i}", label=name)
    top = max(c["external_work_J"][inside].max(), 1e-30)
    each.set(yscale="log", ylim=(1e-5 * top, 2 * top), xlim=(0.0, x_max), xlabel=strain_label, ylabel="energy [J]",
             title="each energy" + ("" if reach is None else ", " + ZOOM_TITLE))
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


LEGEND_STRIP = 0.42  # [in]: a one-row legend's height at the foot of a crack picture


def crack_figure_from_slice(seg, state, path: str, title: str = ""):
    """The crack picture of a slice (draw_slice), saved to path; returns the figure."""
    # A cube's slice is square: 5.6 x 6.2 in; a beam's is flat, and its figure with it.
    aspect = np.ptp(seg[:, :, 1]) / max(np.ptp(seg[:, :, 0]), 1e-30) if len(seg) else 1.0
    height = min(6.2, 1.6 + 4.6 * aspect)
    fig, ax = plt.subplots(figsize=(5.6, height))
    # The legend in a strip of its own at the figure's foot, below the x label
    # (under the axes it sat on the label of a slender beam's flat slice).
    fig.legend(handles=state_handles(draw_slice(ax, seg, state)), loc="lower center", ncol=3)
    ax.set_title(title or "central slice")
    fig.tight_layout(rect=(0, LEGEND_STRIP / height, 1, 1))
    save(fig, path)
    return fig
