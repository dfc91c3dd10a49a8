"""The mesh study's laws (laws.csv: the coarse bars' law for each module
side L, by the criterion and by the calibration; the mesh module's docstring
has the equations) and its tables: means and CVs per (load, size, module, variant,
correlation length), each beside the fine lattice's, and the verdict (the
fine peak within 10 %, the fine U_num within 20 %)."""
from __future__ import annotations

from typing import List, Sequence

import numpy as np

from ...cube import CubeTest
from ..tables import mean_cv

FINE_L0 = 0.02                       # the size-effect study's module [m]
VARIANTS = ("plain", "law", "c_a", "criterion", "calibrated")
TRIANGULAR_FINAL_STRAIN = 1e-3       # triangular cubes do not separate: peak only, 7 to 14 x its strain
GROUP = ("load", "size_m", "module_m", "corr_length_m", "variant")
SUMMARY_COLUMNS = GROUP + (
    "seeds", "separated", "peak_stress_MPa_mean", "peak_stress_MPa_cv", "strain_at_peak_mean", "strain_at_peak_cv",
    "U_ratio_mean", "U_ratio_cv", "clamped_fraction", "n_bars", "wall_s_mean", "peak_vs_fine", "strain_vs_fine",
    "U_vs_fine", "speedup", "bar_steps_mean", "work_ratio")
PEAK_TOLERANCE, U_TOLERANCE = 0.10, 0.20   # the verdict: the fine peak within 10 %, the fine U_num within 20 %



def _round(x: float, digits: int = 4) -> float:
    return float(f"{x:.{digits}g}")


def criterion_law(fine_rows: Sequence[dict], base: CubeTest) -> dict:
    """The coarse bars' law for modules of side L from the rows (case_row) of
    the fine uniform cubes of side L: the statistics it used and the law
    (eps_p, Gf_mean, Gf_cv, c_a), as in the docstring of ldem.study.mesh."""
    separated = [r for r in fine_rows if r["separated"] in (True, "True")]
    if len(separated) < 2:
        raise ValueError(f"{len(separated)} of the fine cubes of side {fine_rows[0]['size_m']:g} m separated: "
                         "the criterion needs E[U_num/U_min] and its CV over at least two")
    peak, peak_cv = mean_cv([r["peak_stress_MPa"] for r in fine_rows])
    strain, strain_cv = mean_cv([r["strain_at_peak"] for r in fine_rows])
    ratio, ratio_cv = mean_cv([r["U_ratio"] for r in separated])
    return {"module_m": fine_rows[0]["size_m"], "seeds": len(fine_rows), "separated": len(separated),
            "peak_stress_MPa_mean": peak, "peak_stress_MPa_cv": peak_cv, "strain_at_peak_mean": strain,
            "strain_at_peak_cv": strain_cv, "U_ratio_mean": ratio, "U_ratio_cv": ratio_cv,
            "eps_p": _round(peak * 1e6 / base.E), "Gf_mean": base.Gf_mean, "Gf_cv": _round(ratio_cv),
            "c_a": _round(base.c_a * ratio)}


def calibrated_law(fine_rows: Sequence[dict], coarse_rows: Sequence[dict], base: CubeTest) -> dict:
    """The calibrated variant's eps_p and c_a for one module size, from the
    fine and the coarse (plain law) cubes of CALIBRATION_SIZE: ratios of their
    mean peaks and of their mean U_num/U_min (separated specimens)."""
    def means(rows):
        sep = [r["U_ratio"] for r in rows if r["separated"] in (True, "True")]
        if len(sep) < 2:
            raise ValueError(f"{len(sep)} calibration cubes separated: the calibrated variant needs two")
        return mean_cv([r["peak_stress_MPa"] for r in rows])[0], mean_cv(sep)[0]
    (fine_peak, fine_u), (coarse_peak, coarse_u) = means(fine_rows), means(coarse_rows)
    return {"calibration_peak_ratio": fine_peak / coarse_peak, "calibration_U_ratio": fine_u / coarse_u,
            "calibrated_eps_p": _round(base.eps_p * fine_peak / coarse_peak),
            "calibrated_c_a": _round(base.c_a * fine_u / coarse_u)}


def variant_law(variant: str, law: dict, base: CubeTest) -> dict:
    """The CubeTest fields a variant changes: none (plain), eps_p and G_f's
    statistics (law), c_a (c_a), all of them (criterion), or eps_p and c_a
    from the calibration (calibrated)."""
    keys = {"plain": (), "law": ("eps_p", "Gf_mean", "Gf_cv"), "c_a": ("c_a",),
            "criterion": ("eps_p", "Gf_mean", "Gf_cv", "c_a"), "calibrated": ("calibrated_eps_p", "calibrated_c_a")}
    if variant not in keys:
        raise ValueError(f"unknown variant '{variant}' (expected one of {', '.join(VARIANTS)})")
    fields = {k: k.replace("calibrated_", "") for k in keys[variant]}
    return {f: law[k] for k, f in fields.items() if law[k] != getattr(base, f)}

def _group_stats(g: Sequence[dict]) -> dict:
    peak, peak_cv = mean_cv([r["peak_stress_MPa"] for r in g])
    strain, strain_cv = mean_cv([r["strain_at_peak"] for r in g])
    sep = [r["U_ratio"] for r in g if r["separated"] in (True, "True") and r["U_ratio"] != ""]
    ratio, ratio_cv = mean_cv(sep) if sep else ("", "")
    return {"seeds": len(g), "separated": len(sep), "peak_stress_MPa_mean": peak, "peak_stress_MPa_cv": peak_cv,
            "strain_at_peak_mean": strain, "strain_at_peak_cv": strain_cv, "U_ratio_mean": ratio,
            "U_ratio_cv": ratio_cv,
            "clamped_fraction": float(np.mean([r["clamped_bars"] / r["n_bars"] for r in g])),
            "n_bars": g[0]["n_bars"], "wall_s_mean": float(np.mean([r["wall_s"] for r in g])),
            "bar_steps_mean": float(np.mean([r["n_bars"] * r["steps"] for r in g]))}


def _ratio(a, b):
    return a / b if a != "" and b not in ("", 0) else ""


def summarize(rows: Sequence[dict], reference: str = "fine") -> List[dict]:
    """One row per group (GROUP), in the order met; each beside the group of
    the same load, size and correlation length whose variant is `reference`
    (the fine lattice; in a refinement study, the coarsest module): ratios of
    peak, strain at peak and U_num/U_min, the speed-up in wall time (runs on
    other days and loads: noisy) and the work ratio (bar-steps: exact)."""
    groups = {}
    for r in rows:
        groups.setdefault(tuple(r[k] for k in GROUP), []).append(r)
    table = [{**dict(zip(GROUP, key)), **_group_stats(g)} for key, g in groups.items()]
    for t in table:
        ref = next((f for f in table if f["variant"] == reference and all(
            f[k] == t[k] for k in ("load", "size_m", "corr_length_m"))), None)
        if ref is None:
            t.update(peak_vs_fine="", strain_vs_fine="", U_vs_fine="", speedup="", work_ratio="")
            continue
        t.update(peak_vs_fine=_ratio(t["peak_stress_MPa_mean"], ref["peak_stress_MPa_mean"]),
                 strain_vs_fine=_ratio(t["strain_at_peak_mean"], ref["strain_at_peak_mean"]),
                 U_vs_fine=_ratio(t["U_ratio_mean"], ref["U_ratio_mean"]),
                 speedup=_ratio(ref["wall_s_mean"], t["wall_s_mean"]),
                 work_ratio=_ratio(ref["bar_steps_mean"], t["bar_steps_mean"]))
    return table


def verdict(table: Sequence[dict], size: float = 0.96, module: float = 0.06) -> List[dict]:
    """Per load and variant at (size, module): the peak's and U_num's distance
    from the fine lattice's and whether they are within PEAK_TOLERANCE and U_TOLERANCE."""
    out = []
    for t in table:
        if abs(t["size_m"] - size) > 1e-9 or abs(t["module_m"] - module) > 1e-9 or t["peak_vs_fine"] == "":
            continue
        peak_err = t["peak_vs_fine"] - 1.0
        u_err = t["U_vs_fine"] - 1.0 if t["U_vs_fine"] != "" else ""
        out.append({"load": t["load"], "variant": t["variant"], "peak_error": peak_err,
                    "peak_ok": abs(peak_err) <= PEAK_TOLERANCE, "U_error": u_err,
                    "U_ok": (abs(u_err) <= U_TOLERANCE) if u_err != "" else ""})
    return out
