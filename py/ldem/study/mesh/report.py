"""The mesh study's figures and report.md: the laws the criterion gives, the
verdict, the table beside the fine lattice, the peak and U_num against the
module size with the fine values drawn across, and crack pictures side by
side."""
from __future__ import annotations

import os
import shutil
from typing import Dict

from ... import io, plots
from ...markdown import md_table, mean_cv_cell, num_cell
from ..cases import load_slice, read_discussion
from .tables import FINE_L0, PEAK_TOLERANCE, TRIANGULAR_FINAL_STRAIN, U_TOLERANCE, VARIANTS, verdict

_STYLE = {"plain": "o--", "law": "s:", "c_a": "^:", "criterion": "D-", "calibrated": "v-"}
_COLOUR = {"plain": "C0", "law": "C1", "c_a": "C2", "criterion": "C3", "calibrated": "C4"}  # one per variant, every panel


def against_module_figure(table, column: str, ylabel: str, tolerance: float, path: str, loads) -> None:
    """One panel per (load, size): the column's mean against the module size,
    a line per variant; the fine lattice's value drawn across with the
    verdict's tolerance band."""
    import matplotlib.pyplot as plt

    sizes = sorted({t["size_m"] for t in table})
    coarse = sorted({t["module_m"] for t in table if t["variant"] != "fine"}) or [FINE_L0]
    fig, axes = plt.subplots(len(loads), len(sizes), figsize=(4.4 * len(sizes), 3.6 * len(loads) + 0.6),
                             squeeze=False)
    for row, load in zip(axes, loads):
        for ax, size in zip(row, sizes):
            group = [t for t in table if t["load"] == load and t["size_m"] == size and t[column] != ""]
            fine = next((t[column] for t in group if t["variant"] == "fine"), None)
            if fine is not None:
                ax.axhline(fine, color="k", lw=1.2, label=f"fine, L0 = {FINE_L0:g} m")
                ax.axhspan(fine * (1 - tolerance), fine * (1 + tolerance), color="0.88", zorder=0,
                           label=f"fine ± {tolerance:.0%}")
            for v in VARIANTS:
                pts = sorted((t["module_m"], t[column]) for t in group if t["variant"] == v)
                if pts:
                    ax.plot(*zip(*pts), _STYLE[v], color=_COLOUR[v], label=v)
            if not group:
                ax.text(0.5, 0.5, "not run", transform=ax.transAxes, ha="center", color="0.4")
            ax.set(title=f"{size:g} m, {load}", xlabel="module L [m]", ylabel=ylabel,
                   xlim=(coarse[0] - 0.01, coarse[-1] + 0.01))
            ax.grid(alpha=0.3)
    labels = {}
    for ax in axes.flat:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            labels.setdefault(lab, h)
    fig.legend(labels.values(), labels.keys(), loc="lower center", ncol=len(labels), fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    plots.save(fig, path)


def cracks_side_by_side(rows, size: float, module: float, load: str, path: str, seed: int = 1) -> bool:
    """The central slice at the end: the fine lattice beside each variant of
    one coarse module size (seed 1); False if a case is missing."""
    import matplotlib.pyplot as plt

    picks = [r for r in rows if r["load"] == load and r["size_m"] == size and r["seed"] == seed
             and (r["role"] == "fine" or abs(r["module_m"] - module) < 1e-9)]
    if not any(r["role"] == "fine" for r in picks) or len(picks) < 2:
        return False
    if any("dir" not in r for r in picks):   # a row kept from an earlier run: no case folder
        return False
    picks.sort(key=lambda r: (r["role"] != "fine", VARIANTS.index(r["variant"]) if r["variant"] in VARIANTS else 0))
    fig, axes = plt.subplots(1, len(picks), figsize=(4.2 * len(picks), 4.8), squeeze=False)
    for ax, r in zip(axes[0], picks):
        plots.draw_slice(ax, *load_slice(r["dir"]))
        ax.set_title(f"{r['variant']}, L = {r['module_m']:g} m", fontsize=9)
    fig.legend(handles=plots.state_handles(), loc="lower center", ncol=3, frameon=False)
    fig.suptitle(f"{size:g} m cube, {load}, seed {seed}: central slice at the end", fontsize=11)
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    plots.save(fig, path)
    return True


def _order(t: dict) -> tuple:
    """Table rows by load, size, module, then the fine lattice and the variants in their order."""
    return (t["load"], t["size_m"], t["module_m"], VARIANTS.index(t["variant"]) if t["variant"] in VARIANTS else -1)


def _law_rows(laws: Dict[float, dict]):
    return [[f"{m:g}", mean_cv_cell(w['peak_stress_MPa_mean'], w['peak_stress_MPa_cv']),
             mean_cv_cell(w['strain_at_peak_mean'], w['strain_at_peak_cv'], ".3e"),
             f"{mean_cv_cell(w['U_ratio_mean'], w['U_ratio_cv'])}, {w['separated']} of {w['seeds']}",
             f"{w['eps_p']:.4g}", f"{w['Gf_mean']:g}", f"{w['Gf_cv']:.4g}", f"{w['c_a']:.4g}",
             num_cell(w.get("calibrated_eps_p", ""), ".4g"), num_cell(w.get("calibrated_c_a", ""), ".4g")]
            for m, w in sorted(laws.items())]


def _earlier_figure(earlier: str, out: str, name: str) -> bool:
    """Copies figure `name` of the earlier run's folder to out, if it is there."""
    src = os.path.join(earlier, name) if earlier else ""
    if not src or not os.path.isfile(src):
        return False
    if not os.path.samefile(earlier, out):
        shutil.copyfile(src, os.path.join(out, name))
    return True


def write_mesh_report(out: str, laws: Dict[float, dict], table, rows, missing: int = 0, fmt: str = "png",
                      kept: int = 0, earlier: str = "") -> None:
    """report.md and its figures in out (missing: how many of the cases asked
    for are not finished; kept: how many rows come from the earlier run in
    folder `earlier`, whose crack pictures stand for cases without a folder
    here); discussion.md (hand-written), if there is one, is appended."""
    loads = list(dict.fromkeys(t["load"] for t in table))
    figs = []
    against_module_figure(table, "peak_stress_MPa_mean", "mean peak stress [MPa]", PEAK_TOLERANCE,
                          os.path.join(out, f"peak_vs_module.{fmt}"), loads)
    figs.append((f"peak_vs_module.{fmt}", "mean peak stress against the module size"))
    if "uniform" in loads:
        against_module_figure(table, "U_ratio_mean", "mean U_num / U_min", U_TOLERANCE,
                              os.path.join(out, f"U_vs_module.{fmt}"), ["uniform"])
        figs.append((f"U_vs_module.{fmt}", "mean U_num/U_min (at separation) against the module size"))
    for load in loads:
        name = f"cracks_0.96m_L0.06_{load}.{fmt}"
        if cracks_side_by_side(rows, 0.96, 0.06, load, os.path.join(out, name)) or \
                _earlier_figure(earlier, out, name):
            figs.append((name, f"crack pictures, fine and coarse (L = 0.06 m), {load}"))
    v = sorted(verdict(table), key=lambda x: (x["load"] != "uniform", VARIANTS.index(x["variant"])))
    md = ["# Mesh objectivity: coarse modules with the study's criterion against the fine lattice", "",
          "Generated by `ldem study mesh`; every number is read from `laws.csv`, `cases.csv` and `summary.csv`. "
          f"Fine lattice: L0 = {FINE_L0:g} m (the size-effect study). Triangular cubes run to a mean strain of "
          f"{TRIANGULAR_FINAL_STRAIN:g} (they do not separate): peak and its strain only."
          + (f" **{missing} of the cases asked for are not finished**: the tables cover the {len(rows)} that are."
             if missing else "")
          + (f" {kept} cases are rows of an earlier run's cases.csv (`--earlier`), with the commit each ran on; "
             "the laws are that run's." if kept else ""),
          "", "## The law each module size gets (from the fine uniform cubes of side L)", "",
          "eps_p = mean peak / E; E[G_f] unchanged; CV(G_f) = CV(U_num/U_min); c_a = 0.1385 x E[U_num/U_min] "
          "(`ldem.study.mesh` says why). The calibrated variant (a proposal, not the study's): "
          "eps_p and c_a scaled by the fine over the coarse lattice's peak and U_num/U_min on the 0.24 m cube, "
          "CV(G_f) the material's.", "",
          md_table(["L [m]", "fine peak MPa (CV)", "strain at peak (CV)", "U_num/U_min (CV), separated", "eps_p",
                    "E[G_f] N/m", "CV(G_f)", "c_a", "calibrated eps_p", "calibrated c_a"], _law_rows(laws)),
          "", "## Verdict at 0.96 m with L = 0.06 m (peak within 10 %, U_num within 20 % of the fine lattice)", ""]
    md += [md_table(["load", "variant", "peak error", "within 10 %", "U_num error", "within 20 %"],
                    [[x["load"], x["variant"], f"{100 * x['peak_error']:+.1f} %", "yes" if x["peak_ok"] else "NO",
                      "-" if x["U_error"] == "" else f"{100 * x['U_error']:+.1f} %",
                      "-" if x["U_ok"] == "" else ("yes" if x["U_ok"] else "NO")] for x in v])
           if v else "(the 0.96 m cube with L = 0.06 m has not run yet)"]
    md += ["", "## Every group beside the fine lattice", "",
           md_table(["load", "size m", "L m", "variant", "seeds", "peak MPa (CV)", "/ fine", "strain at peak",
                     "/ fine", "U_num/U_min (CV)", "/ fine", "clamped", "bars", "wall s", "speed-up",
                     "fewer bar-steps"],
                    [[t["load"], f"{t['size_m']:g}", f"{t['module_m']:g}", t["variant"], t["seeds"],
                      mean_cv_cell(t['peak_stress_MPa_mean'], t['peak_stress_MPa_cv']),
                      num_cell(t["peak_vs_fine"], ".3f"), f"{t['strain_at_peak_mean']:.3e}",
                      num_cell(t["strain_vs_fine"], ".3f"),
                      "-" if t["U_ratio_mean"] == "" else mean_cv_cell(t['U_ratio_mean'], t['U_ratio_cv']),
                      num_cell(t["U_vs_fine"], ".3f"), f"{t['clamped_fraction']:.3f}", t["n_bars"],
                      f"{t['wall_s_mean']:.1f}", num_cell(t["speedup"], ".0f"), num_cell(t["work_ratio"], ".0f")]
                     for t in sorted(table, key=_order)]),
           "", "## Figures", ""]
    md += [f"![{cap}]({name})\n\n*{cap}*\n" for name, cap in figs]
    md += ["", read_discussion(out)]
    io.write_text(os.path.join(out, "report.md"), "\n".join(md) + "\n")
