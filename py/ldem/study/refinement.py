"""The refinement study (issue 15, item 2): the same cubes and material with
modules finer than the study's, with G_f drawn per bar (a field tied to the
mesh) or with a correlation length (a field tied to space); which quantities
converge as L0 falls and which drift.

Each group is compared with the same cube at the study's L0 = 0.02 m (the
"fine" variant of mesh_tables.summarize is the coarsest here)."""
from __future__ import annotations

import os
from typing import List, Sequence

from .. import io
from ..cube import CubeTest
from .cases import read_discussion
from .mesh import MESH_CASE_COLUMNS, load_settings, mesh_row, run_located
from .mesh_tables import FINE_L0, SUMMARY_COLUMNS, summarize

REFINEMENT = {0.12: (0.02, 0.01, 0.0075, 0.005), 0.24: (0.02, 0.01, 0.005)}  # size -> module sides [m]
CORR_LENGTHS = (0.0, 0.02)  # 0: one independent draw per bar


def refinement_tests(grid: dict, corr_lengths: Sequence[float], loads: Sequence[str], seeds: int,
                     **common) -> List[CubeTest]:
    """grid: size -> module sides; every (size, L0, l_c, load, seed)."""
    return [CubeTest(size=s, L0=m, corr_length=lc, load=ld, seed=k, **{**load_settings(ld), **common})
            for s, modules in grid.items() for m in modules for lc in corr_lengths for ld in loads
            for k in range(1, seeds + 1)]


def run_refinement(tests: Sequence[CubeTest], out: str, run: bool = True, report: bool = True,
                   fmt: str = "png", earlier: Sequence[dict] = (), **kw) -> List[dict]:
    """Runs the unfinished cases (unless run is False), writes cases.csv,
    summary.csv and (with report) report.md and refinement.png from the
    finished ones; returns the summary rows. earlier: rows of an earlier
    run's cases.csv (a committed study keeps its tables, not its case
    folders); their cases are not run again and enter the tables as they are."""
    kept = {_row_key(r): r for r in earlier}
    fresh = iter(run_located([t for t in tests if _test_key(t) not in kept], out, run=run, **kw))
    rows = []
    for t in tests:
        if _test_key(t) in kept:
            rows.append(kept[_test_key(t)])
            continue
        s, _ = next(fresh)
        if s is not None:
            role = "fine" if abs(t.L0 - FINE_L0) < 1e-12 else "refined"
            rows.append(mesh_row(role, role, s))
    io.prepare_dir(out)
    io.write_table(os.path.join(out, "cases.csv"), rows, MESH_CASE_COLUMNS)
    table = summarize(rows)
    io.write_table(os.path.join(out, "summary.csv"), table, SUMMARY_COLUMNS)
    if report and table:
        refinement_figure(table, os.path.join(out, f"refinement.{fmt}"))
        write_refinement_report(out, table, len(tests) - len(rows), fmt,
                                sum(_test_key(t) in kept for t in tests))
    return table


def _test_key(t: CubeTest) -> tuple:
    """What tells a case from another in cases.csv: load, size, module,
    correlation length, seed, damping and strain rate."""
    return _key(t.load, t.size, t.L0, t.corr_length, t.seed, t.zeta, t.strain_rate)


def _row_key(r: dict) -> tuple:
    return _key(r["load"], r["size_m"], r["module_m"], r["corr_length_m"], r["seed"], r["zeta"], r["strain_rate"])


def _key(load, size, L0, corr_length, seed, zeta, strain_rate) -> tuple:
    return (load, int(seed)) + tuple(round(float(x), 12) for x in (size, L0, corr_length, zeta, strain_rate))


_COLUMNS = (("peak_stress_MPa_mean", "mean peak stress [MPa]"), ("strain_at_peak_mean", "mean strain at peak"),
            ("U_ratio_mean", "mean U_num / U_min"))


def refinement_figure(table, path: str) -> None:
    """Peak, its strain and U_num/U_min against L0: a panel per quantity, a
    line per (load, size, correlation length)."""
    import matplotlib.pyplot as plt

    from .. import plots

    fig, axes = plt.subplots(1, len(_COLUMNS), figsize=(5.0 * len(_COLUMNS), 4.2))
    keys = dict.fromkeys((t["load"], t["size_m"], t["corr_length_m"]) for t in table)
    for ax, (col, label) in zip(axes, _COLUMNS):
        for load, size, lc in keys:
            pts = sorted((t["module_m"], t[col]) for t in table if (t["load"], t["size_m"], t["corr_length_m"])
                         == (load, size, lc) and t[col] != "")
            if pts:
                ax.plot(*zip(*pts), "o-" if lc else "s--",
                        label=f"{size:g} m, {load}, " + (f"l_c = {lc:g} m" if lc else "per bar"))
        ax.set(xlabel="module side L0 [m]", ylabel=label, xscale="log")
        modules = sorted({t["module_m"] for t in table})
        ax.set_xticks(modules, [f"{m:g}" for m in modules])
        ax.minorticks_off()
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    seeds = sorted({t["seeds"] for t in table})
    fig.suptitle("refinement: the same cubes with finer modules ("
                 + (f"{seeds[0]}" if len(seeds) == 1 else f"{seeds[0]} to {seeds[-1]}") + " seeds per point)")
    fig.tight_layout()
    plots.save(fig, path)


def write_refinement_report(out: str, table, missing: int, fmt: str = "png", kept: int = 0) -> None:
    from ..report import md_table, num_cell

    md = ["# Refinement: the same cubes with modules finer than the study's", "",
          "Generated by `ldem study refinement`; ratios are against the same cube, load and G_f field at "
          f"L0 = {FINE_L0:g} m." + (f" {missing} cases are not finished yet." if missing else "")
          + (f" {kept} cases are rows of an earlier run's cases.csv (`--earlier`), with the commit each ran on."
             if kept else ""), "",
          md_table(["load", "size m", "L0 m", "l_c m", "seeds", "peak MPa (CV)", "/ L0 0.02", "strain at peak (CV)",
                    "/ L0 0.02", "U_num/U_min (CV)", "/ L0 0.02", "clamped", "bars", "wall s"],
                   [[t["load"], f"{t['size_m']:g}", f"{t['module_m']:g}", f"{t['corr_length_m']:g}", t["seeds"],
                     f"{t['peak_stress_MPa_mean']:.3f} ({t['peak_stress_MPa_cv']:.3f})",
                     num_cell(t["peak_vs_fine"], ".3f"),
                     f"{t['strain_at_peak_mean']:.3e} ({t['strain_at_peak_cv']:.3f})",
                     num_cell(t["strain_vs_fine"], ".3f"),
                     "-" if t["U_ratio_mean"] == "" else f"{t['U_ratio_mean']:.3f} ({t['U_ratio_cv']:.3f})",
                     num_cell(t["U_vs_fine"], ".3f"), f"{t['clamped_fraction']:.3f}", t["n_bars"],
                     f"{t['wall_s_mean']:.1f}"] for t in table]),
          "", f"![refinement](refinement.{fmt})", ""]
    md += [read_discussion(out)]
    io.write_text(os.path.join(out, "report.md"), "\n".join(md) + "\n")
