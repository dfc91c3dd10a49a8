"""Figures and report.md of a study, from its data: the cases (test, summary,
curve, central slice), the tables and the fits. Reads no files; writes the
figures and report.md into the folder it is given."""
from __future__ import annotations

import os
from typing import Dict, List, NamedTuple, Optional, Sequence

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import io, plots  # noqa: E402
from .curves import mean_curve  # noqa: E402
from .markdown import cost_section, damping_words, load_loss_words, md_table, num_cell, pct, stop_rule  # noqa: E402


class Case(NamedTuple):
    """One case of a study, as the report needs it."""
    test: object      # ldem.CubeTest
    summary: dict     # summary.json
    curve: dict       # column -> numpy array (curve.csv)
    slice: tuple      # (segments, damage states) of the central slice at the end


def curve_groups(cases: Sequence[Case]) -> Dict[tuple, List[dict]]:
    """(load, size) -> the curves of its specimens, in case order."""
    groups: Dict[tuple, List[dict]] = {}
    for c in cases:
        groups.setdefault((c.test.load, c.test.size), []).append(c.curve)
    return groups


_save = plots.save


def _strain_axis(ax, ylabel):
    ax.set(xlabel=plots.STRAIN_LABEL, ylabel=ylabel)


def _reach(curves):
    """plots.zoom_reach of specimens' curves: ZOOM x the largest strain at a peak, where they go on far past it."""
    at_peak = max(float(c["mean_strain"][np.argmax(c["stress_MPa"])]) for c in curves)
    return plots.zoom_reach(max(c["mean_strain"][-1] for c in curves), at_peak)


def _zoom(ax, reach, title) -> None:
    """ax's lines shown to the reach (plots.zoom_to), titled as the zoom of title."""
    plots.zoom_to(ax, [(line.get_xdata(), line.get_ydata()) for line in ax.get_lines()], reach)
    ax.set_title(f"{title}: {plots.ZOOM_TITLE}", fontsize=9)


def specimen_curves_figure(groups, load, sizes, path):
    """Every specimen's stress-strain curve and their mean, one panel per size;
    under each, the same near the peak where the runs go on far past it (the
    mean there on its own grid up to the zoom's reach: the whole run's is too coarse)."""
    reaches = [_reach(groups[(load, size)]) for size in sizes]
    rows = 1 + any(r is not None for r in reaches)
    fig, axes = plt.subplots(rows, len(sizes), figsize=(5.2 * len(sizes), 4.2 * rows), squeeze=False,
                             layout="constrained")
    for column, size, reach in zip(axes.T, sizes, reaches):
        curves, title = groups[(load, size)], f"{size:g} m cube, {load}"
        for ax, upto in zip(column, (None, reach)):
            for k, c in enumerate(curves, start=1):
                ax.plot(c["mean_strain"], c["stress_MPa"], lw=0.8, alpha=0.6, label=f"specimen, seed {k}")
            ax.plot(*mean_curve(curves, "stress_MPa", after_end=0.0, upto=upto), "k", lw=2.2,
                    label=f"mean of the {len(curves)} at equal strain")
            _strain_axis(ax, plots.STRESS_LABEL)
        column[0].set_title(title)
        column[0].legend(fontsize=7)
        if reach is not None:
            _zoom(column[1], reach, title)
        elif rows == 2:
            column[1].set_visible(False)
    _save(fig, path)
    return fig


def mean_curves_figure(groups, load, sizes, path):
    """The mean curve of each size; beside it, the same near the peaks where the runs go on far past them,
    and then the whole run on a log strain axis (a linear grid to the separation steps over the peaks)."""
    reach = _reach([c for size in sizes for c in groups[(load, size)]])
    fig, axes = plt.subplots(1, 1 + (reach is not None), figsize=(6.4 * (1 + (reach is not None)), 4.4),
                             squeeze=False, layout="constrained")
    title = f"mean stress-strain curves, {load} loading"
    log_from = None if reach is None else reach / 1000
    for ax, upto, start in zip(axes[0], (None, reach), (log_from, None)):
        for size in sizes:
            curves = groups[(load, size)]
            ax.plot(*mean_curve(curves, "stress_MPa", after_end=0.0, upto=upto, log_from=start), lw=1.6,
                    label=f"{size:g} m: mean of {len(curves)} specimen" + "s" * (len(curves) > 1))
        _strain_axis(ax, "mean normal stress [MPa]")
        ax.set_xscale("linear" if start is None else "log")
    axes[0, 0].set_title(title)
    axes[0, 0].legend(fontsize=8)
    if reach is not None:
        _zoom(axes[0, 1], reach, title)
    _save(fig, path)
    return fig


def fracture_energy_figure(cases, load, sizes, path):
    """U_frac / U_min (fracture energy dissipated so far over G_f x face area)
    against the mean strain on a log axis, to separation: each specimen faint
    with its load loss (|), separation (x) or converged U (s: U_final) marked, and their mean."""
    fig, ax = plt.subplots(figsize=(7.0, 4.6))
    for size in sizes:
        group = [c for c in cases if c.test.load == load and c.test.size == size]
        u_min = group[0].summary["min_fracture_energy_J"]
        color = None
        for s, c in ((g.summary, g.curve) for g in group):
            keep = c["mean_strain"] > 0
            line, = ax.plot(c["mean_strain"][keep], c["fracture_J"][keep] / u_min, lw=0.6, alpha=0.35, color=color)
            color = line.get_color()
            for event, marker in (("load_loss", "|"), ("separation", "x"), ("converged", "s")):
                if s.get(event):
                    ax.plot(s[event]["mean_strain"], s[event]["fracture_energy_J"] / u_min, marker, color=color,
                            ms=7)
        x, y = mean_curve([g.curve for g in group], "fracture_J", scale=1.0 / u_min, log_from=1e-5)
        ax.plot(x, y, lw=1.8, color=color, label=f"{size:g} m (mean)")
    ax.set(xscale="log", xlim=(1e-5, None), xlabel=plots.STRAIN_LABEL, ylabel="U_frac / U_min [-]")
    ax.grid(alpha=0.3, which="both")
    ax.set_title(f"fracture energy to separation, {load} (|: load lost, x: separated, s: U converged)", fontsize=10)
    ax.legend(fontsize=8)
    _save(fig, path)


def cracks_figure(cases, load, sizes, path, seed=1):
    """Central slices at the end of the run, one specimen per size."""
    fig, axes = plt.subplots(1, len(sizes), figsize=(4.6 * len(sizes), 5.0), squeeze=False)
    for ax, size in zip(axes[0], sizes):
        c = next(c for c in cases if c.test.load == load and c.test.size == size and c.test.seed == seed)
        plots.draw_slice(ax, *c.slice)
        ax.set_title(f"{size:g} m, seed {seed}", fontsize=9)
    fig.legend(handles=plots.state_handles(), loc="lower center", ncol=3, fontsize=10, frameon=False)
    fig.suptitle(f"central slices at the end of the test, {load} loading", fontsize=11)
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    _save(fig, path)


def fractal_figure(table, case_rows, fits, path):
    """Mean U_num per size (and each case's, faint) with the fitted law, log-log."""
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for load, fit in fits.items():
        rows = [r for r in table if r["load"] == load and r["U_num_J_mean"] != ""]  # sizes with separated runs
        b = np.array([r["size_m"] for r in rows])
        u = np.array([r["U_num_J_mean"] for r in rows])
        line, = ax.plot(b, u, "o", label=f"{load}: mean U_num")
        each = [(c["size_m"], c["U_num_J"]) for c in case_rows if c["load"] == load and c["U_num_J"] != ""]
        ax.plot(*zip(*each), ".", color=line.get_color(), alpha=0.35)
        bb = np.geomspace(b.min(), b.max(), 50)
        ax.plot(bb, fit["U_b0_J"] * (bb / fit["b0_m"]) ** fit["d"], "-", color=line.get_color(),
                label=f"{load}: U(b0)(b/b0)^d, d = {fit['d']:.3f}")
    ax.set(xscale="log", yscale="log", xlabel="cube side b [m]", ylabel="U_num [J]",
           title="fracture energy to separate the cube (U_num), fractal law with b0 = "
                 f"{next(iter(fits.values()))['b0_m']:g} m")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    _save(fig, path)


def damping_figures(out, cases, fmt: str = "png") -> List[str]:
    """One figure per load: the stress-strain curve at each damping ratio, up
    to 8 times the largest strain at the peak (the runs go on to separation, at
    strains a hundred times larger, where the curves lie on zero)."""
    names = []
    for load in dict.fromkeys(c.test.load for c in cases):
        fig, ax = plt.subplots(figsize=(6.4, 4.4))
        group = [g for g in cases if g.test.load == load]
        for t, s, c in ((g.test, g.summary, g.curve) for g in group):
            ax.plot(c["mean_strain"], c["stress_MPa"], lw=1.4,
                    label=f"zeta = {t.zeta:g}: peak {s['peak_stress_MPa']:.3f} MPa at {s['strain_at_peak']:.3g}"
                          + (f", U_num/U_min {s['U_ratio']:.3f}" if s.get("U_ratio") else ""))
        ax.set_xlim(0, 8 * max(g.summary["strain_at_peak"] for g in group))
        _strain_axis(ax, plots.STRESS_LABEL)
        ax.set_title(f"damping, {cases[0].test.size:g} m cube, {load}, seed {cases[0].test.seed}")
        ax.legend(fontsize=8)
        names.append(f"damping_{load}.{fmt}")
        _save(fig, os.path.join(out, names[-1]))
    return names


def size_effect_report(out, cases: Sequence[Case], rows, table, fits, damping_rows: Optional[list] = None,
                       discussion: Optional[str] = None, fmt: str = "png") -> None:
    """report.md and the figures in folder out. rows: the cases' table rows
    (cases.csv), table: per (load, size) (summary.csv), fits: the fractal law
    per load; damping_rows and discussion, if given, are appended."""
    loads = list(dict.fromkeys(c.test.load for c in cases))
    sizes = sorted({c.test.size for c in cases})
    groups = curve_groups(cases)
    figs = []
    for load in loads:
        ends = sorted({sizes[0], sizes[-1]})
        specimen_curves_figure(groups, load, ends, os.path.join(out, f"curves_{load}.{fmt}"))
        mean_curves_figure(groups, load, sizes, os.path.join(out, f"mean_curves_{load}.{fmt}"))
        cracks_figure(cases, load, sizes, os.path.join(out, f"cracks_{load}.{fmt}"))
        fracture_energy_figure(cases, load, sizes, os.path.join(out, f"fracture_energy_{load}.{fmt}"))
        figs += [(f"curves_{load}.{fmt}", f"every specimen and the mean, {load}"),
                 (f"mean_curves_{load}.{fmt}", f"mean curves of all sizes, {load}"),
                 (f"cracks_{load}.{fmt}", f"crack pictures (central slice, seed 1), {load}"),
                 (f"fracture_energy_{load}.{fmt}", f"U_frac/U_min against mean strain (log) to separation, {load}")]
    if fits:
        fractal_figure(table, rows, fits, os.path.join(out, f"fractal.{fmt}"))
        figs.append((f"fractal.{fmt}", "U_num against size, fractal law"))
    write_report(out, cases, rows, table, fits, figs, damping_rows, discussion, fmt)


def write_report(out, cases, case_rows, table, fits, figs, damping_rows=None, discussion=None, fmt="png") -> None:
    tests = [c.test for c in cases]
    first = cases[0].summary
    p = first["parameters"]
    md = ["# Size-effect study: ldem against the reference study", "",
          f"{len(tests)} cube tension tests: sizes {', '.join(f'{s:g}' for s in sorted({t.size for t in tests}))} m, "
          f"seeds 1-{max(t.seed for t in tests)}, loads {', '.join(dict.fromkeys(t.load for t in tests))}. "
          "Generated by `ldem study size-effect`; every number below is read from `cases.csv` and `summary.csv`.",
          "", "## Parameters", "",
          md_table(["parameter", "value"], [
              ["E, nu, rho", f"{p['E']:g} Pa, {p['nu']:g}, {p['rho']:g} kg/m^3"],
              ["E[G_f], CV(G_f)", f"{p['Gf_mean']:g} N/m, {p['Gf_cv']:g} (Weibull, one draw per bar)"
               if p["corr_length"] == 0 else f"{p['Gf_mean']:g} N/m, {p['Gf_cv']:g}, l_c = {p['corr_length']:g} m"],
              ["eps_p, c_a, L0", f"{p['eps_p']:g}, {p['c_a']:g}, {p['L0']:g} m"],
              ["strain rate", f"{p['strain_rate']:g} 1/s at the upper face, velocity ramped up as 1 - cos over "
                              "two fundamental periods"],
              ["boundaries", f"lower face: lateral {p['bottom_lateral']}, vertical fixed; upper face: lateral "
                             f"{p['top_lateral']}"],
              ["damping", damping_words([c.summary["parameters"] for c in cases])],
              ["time step", f"{first['dt_s']:.4g} s = {p['dt_safety']:g} x 2/omega_max (same for every size: "
                            "same L0)"],
              ["load loss", load_loss_words([c.summary["parameters"] for c in cases])],
              ["stop", "; ".join(dict.fromkeys(stop_rule(c.summary["parameters"]) for c in cases))],
          ]), ""]
    md += ["## Peak stress and strain at peak", ""]
    for load in dict.fromkeys(r["load"] for r in table):
        rows = []
        for r in (r for r in table if r["load"] == load):
            ref = r["ref_peak_stress_MPa"] != ""
            rows.append([f"{r['size_m']:g}", r["seeds"], f"{r['peak_stress_MPa_mean']:.3f}",
                         num_cell(r['peak_stress_MPa_cv'], ".3f"),
                         f"{r['ref_peak_stress_MPa']:.2f} ({pct(r['peak_stress_MPa_mean'], r['ref_peak_stress_MPa'])})"
                         if ref else "-",
                         f"{r['strain_at_peak_mean']:.3e}", num_cell(r['strain_at_peak_cv'], ".3f"),
                         f"{r['ref_strain_at_peak']:.2e} ({pct(r['strain_at_peak_mean'], r['ref_strain_at_peak'])})"
                         if ref else "-", f"{r['edge_strain_at_peak_mean']:.3e}", f"{r['wall_s_mean']:.0f}"])
        md += [f"### {load}", "", md_table(
            ["size [m]", "seeds", "peak [MPa]", "CV", "study (Table 3)", "strain at peak", "CV", "study",
             "at the most-pulled edge", "wall [s] per case"], rows), ""]
        rows = []
        for r in (r for r in table if r["load"] == load and r["mean_curve_peak_MPa"] != ""):
            ref = r["ref_peak_stress_MPa"] != ""
            rows.append([f"{r['size_m']:g}", f"{r['mean_curve_peak_MPa']:.3f}",
                         pct(r["mean_curve_peak_MPa"], r["ref_peak_stress_MPa"]) if ref else "-",
                         f"{r['mean_curve_strain_at_peak']:.3e}",
                         pct(r["mean_curve_strain_at_peak"], r["ref_strain_at_peak"]) if ref else "-"])
        if rows:
            md += ["The peak of the mean curve (the specimens' curves averaged at equal mean strain, then its "
                   "maximum) is another reading of \"mean peak\". It is never above the mean of the peaks, and "
                   "the two readings differ most where the specimens' strains at their peaks scatter most.", "",
                   md_table(["size [m]", "peak of the mean curve [MPa]", "against study", "its strain",
                              "against study"], rows), ""]
    md += cost_section(case_rows)
    md += ["## Fracture energy", "",
           "U_num: fracture energy dissipated up to separation (no chain of intact bars joins the two faces; "
           "the mean is over the separated specimens, counted in 'separated'); beside it the energy when the "
           "load was lost, and the cheapest cut (the least energy of any set of bars whose rupture separates the "
           "faces: a lower bound of U_num). U_min = E[G_f] x face area; corrected c_a = 0.1385 x E[U_num/U_min] "
           "(the study's proposal for coarser meshes). A specimen that hinges (triangular) does not separate: "
           "its run stops at peak_stop_strain_ratio x its strain at the peak (stop_at past_peak; 'at the end' is "
           "U there), or, with --triangular-stop load_loss, at the load loss (never before loss_stop_strain_ratio "
           "x its strain at the peak), or, with --triangular-stop converged, once U has converged (it grew by "
           "less than converged_growth over the last doubling of the strain past the load loss), and U there is "
           "U_final, never U_num (mean over the converged specimens, counted in 'converged'). 'at load loss' is "
           "the mean over the specimens whose load was lost before they stopped.", ""]
    rows = [[r["load"], f"{r['size_m']:g}", f"{r['separated']}/{r['seeds']}",
             num_cell(r["separation_strain_mean"], ".3g"), num_cell(r["U_num_J_mean"], ".4g"),
             f"{r['U_min_J']:.4g}", num_cell(r["U_ratio_mean"], ".3f"), num_cell(r["U_ratio_cv"], ".3f"),
             num_cell(r["U_loss_ratio_mean"], ".3f"), num_cell(r.get("U_end_ratio_mean", ""), ".3f"),
             f"{r.get('converged', 0)}/{r['seeds']}", num_cell(r.get("U_final_ratio_mean", ""), ".3f"),
             f"{r['U_mincut_ratio_mean']:.3f}", num_cell(r["ca_corrected"], ".4f"), str(r["energy_errors"])]
            for r in table]
    md += [md_table(["load", "size [m]", "separated", "strain at separation", "U_num [J]", "U_min [J]", "U_num/U_min",
                     "CV", "at load loss", "at the end", "converged", "U_final/U_min", "cheapest cut", "corrected c_a",
                     "energy errors"], rows), ""]
    if fits:
        md += ["Fractal law U(b) = U(b0) (b/b0)^d, b0 = 0.12 m (least squares in log-log axes through U(b0)):", ""]
        md += [md_table(["load", "d", "energy per unit area ~ b^(d-2)", "rms log residual"],
                         [[ld, f"{f['d']:.3f}", f"{f['d_specific']:+.3f}", f"{f['rms_log_residual']:.3f}"]
                          for ld, f in fits.items()]), ""]
    if damping_rows:  # the damping study run into the same folder: its table and figures
        rows = damping_rows
        md += ["## Damping", "", "`ldem study damping`: the same specimen at several damping ratios.", "",
               md_table(["load", "size [m]", "zeta", "peak [MPa]", "strain at peak", "U_num/U_min"],
                         [[r["load"], f"{r['size_m']:g}", f"{r['zeta']:g}", f"{r['peak_stress_MPa']:.3f}",
                           f"{r['strain_at_peak']:.3e}", num_cell(r["U_ratio"], ".3f")] for r in rows]), ""]
        figs += [(f"damping_{ld}.{fmt}", f"damping, {ld}") for ld in sorted(dict.fromkeys(r["load"] for r in rows))]
    md += ["## Figures", ""] + [f"![{title}]({name})\n" for name, title in figs]
    if discussion:
        md += ["## Discussion", "", discussion.strip(), ""]
    io.write_text(os.path.join(out, "report.md"), "\n".join(md) + "\n")
