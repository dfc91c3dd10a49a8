"""The seed-settings study's tables and figure: a row per run, the means per
variant and size with their standard errors, the ratio of the largest size's
peak to the smallest's, against base and against Table 3."""
from __future__ import annotations

import math
import re
from typing import Dict, List, Sequence

import numpy as np

from ..cases import case_name
from ..tables import REFERENCE_UNIFORM


def run_rows(pairs, summaries: Dict[str, dict]) -> List[dict]:
    """A row per (variant, size, seed): the run's peak, its strain, its cost."""
    rows = []
    for v, t in pairs:
        s = summaries[case_name(t)]
        rows.append({"setting": v.setting, "variant": v.label, "size_m": t.size, "seed": t.seed,
                     "peak_stress_MPa": s["peak_stress_MPa"], "strain_at_peak": s["strain_at_peak"],
                     "strain_rate": s["parameters"]["strain_rate"], "damping_coefficient_1_s":
                     s["damping_coefficient_1_s"], "energy_balance_error": s["energy_balance_error"],
                     "steps": s["steps"], "wall_s": s["wall_s"], "case": case_name(t)})
    return rows


def _mean_se(values) -> tuple:
    v = np.asarray(values, dtype=float)
    return float(v.mean()), (float(v.std(ddof=1) / math.sqrt(len(v))) if len(v) > 1 else float("nan"))


def sensitivity(rows: Sequence[dict]) -> List[dict]:
    """Per variant: the mean peak and strain at each size (with the standard error
    over the seeds), the ratio of the largest size's mean peak to the smallest's
    (its standard error propagated), and both against base's."""
    sizes = sorted({r["size_m"] for r in rows})
    lo, hi = sizes[0], sizes[-1]
    out = []
    for label in dict.fromkeys(r["variant"] for r in rows):
        g = [r for r in rows if r["variant"] == label]
        row = {"setting": g[0]["setting"], "variant": label, "seeds": len({r["seed"] for r in g})}
        for size in sizes:
            at = [r for r in g if r["size_m"] == size]
            row[f"peak_{size:g}"], row[f"peak_se_{size:g}"] = _mean_se([r["peak_stress_MPa"] for r in at])
            row[f"strain_{size:g}"], row[f"strain_se_{size:g}"] = _mean_se([r["strain_at_peak"] for r in at])
        a, b = row[f"peak_{lo:g}"], row[f"peak_{hi:g}"]
        row["peak_ratio"] = b / a
        row["peak_ratio_se"] = row["peak_ratio"] * math.hypot(row[f"peak_se_{lo:g}"] / a, row[f"peak_se_{hi:g}"] / b)
        row["strain_ratio"] = row[f"strain_{hi:g}"] / row[f"strain_{lo:g}"]
        out.append(row)
    return out


def _sizes(row: dict) -> List[float]:
    """The sizes of a sensitivity row, from its columns peak_<size>."""
    return sorted(float(k[5:]) for k in row if re.fullmatch(r"peak_[0-9.]+", k))


def table3_ratio(lo: float, hi: float) -> tuple:
    """Table 3's ratio of peaks and of strains at the peak, largest size over smallest."""
    (p0, e0), (p1, e1) = REFERENCE_UNIFORM[lo], REFERENCE_UNIFORM[hi]
    return p1 / p0, e1 / e0


def sensitivity_table(sens: Sequence[dict]) -> str:
    sizes = _sizes(sens[0])
    lo, hi = sizes[0], sizes[-1]
    base = next(r for r in sens if r["setting"] == "base")
    head = "| setting | variant | " + " | ".join(f"peak {s:g} m [MPa] | strain at peak {s:g} m" for s in sizes)
    head += f" | peak {hi:g} / {lo:g} m | strain {hi:g} / {lo:g} m |"
    lines = [head, "|" + "---|" * (4 + 2 * len(sizes))]
    for r in sens:
        cells = []
        for s in sizes:
            p, e = r[f"peak_{s:g}"], r[f"strain_{s:g}"]
            dp, de = 100 * (p / base[f"peak_{s:g}"] - 1), 100 * (e / base[f"strain_{s:g}"] - 1)
            cells.append(f"{p:.3f} ± {r[f'peak_se_{s:g}']:.3f} ({dp:+.1f} %) | {e:.3e} ({de:+.0f} %)")
        lines.append(f"| {r['setting']} | {r['variant']} | " + " | ".join(cells)
                     + f" | {r['peak_ratio']:.3f} ± {r['peak_ratio_se']:.3f} | {r['strain_ratio']:.2f} |")
    if (lo, hi) == (0.12, 0.96):
        pr, er = table3_ratio(lo, hi)
        lines.append("| Table 3 | the study | " + " | ".join(
            f"{REFERENCE_UNIFORM[s][0]:.2f} | {REFERENCE_UNIFORM[s][1]:.2e}" for s in sizes)
            + f" | {pr:.3f} | {er:.2f} |")
    return "\n".join(lines) + "\n"


def ratio_figure(sens: Sequence[dict], path: str, fmt: str = "png") -> str:
    """The ratio of the largest to the smallest size's mean peak per variant
    (bars: one standard error over the seeds), Table 3's as a line."""
    from ...plots import plt, save
    sizes = _sizes(sens[0])
    lo, hi = sizes[0], sizes[-1]
    fig, ax = plt.subplots(figsize=(7.5, 0.32 * len(sens) + 1.4))
    y = np.arange(len(sens))[::-1]
    ax.errorbar([r["peak_ratio"] for r in sens], y, xerr=[r["peak_ratio_se"] for r in sens], fmt="o", color="C0")
    base = next(r for r in sens if r["setting"] == "base")
    ax.axvline(base["peak_ratio"], color="0.5", ls=":", label="base (quasi-static default)")
    if lo in REFERENCE_UNIFORM and hi in REFERENCE_UNIFORM:
        ax.axvline(table3_ratio(lo, hi)[0], color="C3", ls="--", label="Table 3 of the study")
    ax.set_yticks(y, [f"{r['setting']}: {r['variant']}" for r in sens], fontsize=7)
    ax.set_xlabel(f"mean peak at {hi:g} m / mean peak at {lo:g} m (uniform load)")
    ax.legend(loc="lower right", fontsize=7)
    save(fig, f"{path}.{fmt}", palette=True)
    return f"{path}.{fmt}"




# The columns of the size-effect study's summary.csv a comparison sets side by side: (heading, column, format).
COMPARED = (("peak [MPa]", "peak_stress_MPa_mean", "{:.3f}"), ("strain at peak", "strain_at_peak_mean", "{:.3e}"),
            ("U_num/U_min", "U_ratio_mean", "{:.3f}"), ("its CV", "U_ratio_cv", "{:.3f}"),
            ("strain at separation", "separation_strain_mean", "{:.3g}"))


def _cell(row: dict, column: str, fmt: str) -> str:
    v = row.get(column, "") if row else ""
    return "-" if v in ("", None) or (isinstance(v, float) and math.isnan(v)) else fmt.format(float(v))


def study_comparison(reference: Sequence[dict], rows: Sequence[dict], ref_d: float, d: float) -> str:
    """Markdown: each load's table of two size-effect studies' summary rows (a
    reference, the quasi-static defaults, and one at other settings), column by
    column, Table 3 beside the uniform peaks and strains, then each one's d."""
    ref = {(r["load"], float(r["size_m"])): r for r in reference}
    lines = []
    for load in dict.fromkeys(r["load"] for r in rows):
        heads = [h for h, _, _ in COMPARED if load == "uniform" or h in ("peak [MPa]", "strain at peak")]
        lines += [f"**{load}** (each cell: reference / these settings" + (", Table 3" if load == "uniform" else "")
                  + ")", "", "| size [m] | " + " | ".join(heads) + " |", "|---" * (len(heads) + 1) + "|"]
        for r in (r for r in rows if r["load"] == load):
            size = float(r["size_m"])
            t3 = REFERENCE_UNIFORM.get(round(size, 6)) if load == "uniform" else None
            cells = []
            for h, col, fmt in COMPARED:
                if h not in heads:
                    continue
                cell = f"{_cell(ref.get((load, size)), col, fmt)} / {_cell(r, col, fmt)}"
                if t3 and h in ("peak [MPa]", "strain at peak"):
                    cell += f", {fmt.format(t3[0] if h.startswith('peak') else t3[1])}"
                cells.append(cell)
            lines.append(f"| {size:g} | " + " | ".join(cells) + " |")
        lines.append("")
    lines.append(f"The fractal law's d (uniform): reference {ref_d:.3f}, these settings {d:.3f}.")
    return "\n".join(lines) + "\n"
