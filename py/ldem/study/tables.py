"""The study's tables: one row per case, means and CVs per (load, size), the
corrected c_a and the fractal law of U_num (LDEM_SPEC section 6)."""
from __future__ import annotations

import math
from typing import Dict, List, Optional, Sequence

import numpy as np

from ..curves import mean_curve_peak

REFERENCE_UNIFORM = {  # Table 3 of the study (LDEM_SPEC section 6): size -> (peak MPa, strain at peak)
    0.12: (2.45, 1.47e-4), 0.24: (2.48, 1.41e-4), 0.48: (2.52, 1.50e-4), 0.72: (2.53, 1.50e-4),
    0.96: (2.52, 1.46e-4),
}
B0 = 0.12  # reference size of the fractal law [m]


CASE_COLUMNS = ("load", "size_m", "seed", "zeta", "strain_rate", "peak_stress_MPa", "strain_at_peak",
                "edge_strain_at_peak", "separated", "separation_strain", "U_num_J", "U_min_J", "U_ratio",
                "load_loss_strain", "U_loss_J", "U_loss_ratio", "U_mincut_J", "U_mincut_ratio",
                "converged_strain", "U_final_J", "U_final_ratio", "U_end_J", "U_end_ratio", "energy_balance_error",
                "energy_error", "clamped_bars", "n_bars", "steps", "dt_s", "threads",
                "wall_s", "stop_reason", "ldem_version", "git_commit", "date", "host")


def case_row(s: dict) -> dict:
    """One case's row: U_num is the energy at separation, empty if the run ended
    without separating (its energy at the end is never presented as U_num;
    U_final is that of a run that stopped because U had converged, U_end the
    energy where the run stopped, whatever stopped it);
    then which ldem ran it, where and when (empty for a case from before
    summaries carried their provenance)."""
    p = s["parameters"]
    u_min = s["min_fracture_energy_J"]
    loss, sep, conv = (s.get(k) or {} for k in ("load_loss", "separation", "converged"))
    return {"load": p["load"], "size_m": p["size"], "seed": p["seed"], "zeta": p["zeta"],
            "strain_rate": p["strain_rate"], "peak_stress_MPa": s["peak_stress_MPa"],
            "strain_at_peak": s["strain_at_peak"], "edge_strain_at_peak": s["edge_strain_at_peak"],
            "separated": bool(s["separated"]), "separation_strain": sep.get("mean_strain", ""),
            "U_num_J": s["U_num_J"] if s["separated"] else "", "U_min_J": u_min,
            "U_ratio": s["U_ratio"] if s["separated"] else "",
            "load_loss_strain": loss.get("mean_strain", ""), "U_loss_J": loss.get("fracture_energy_J", ""),
            "U_loss_ratio": loss["fracture_energy_J"] / u_min if loss else "",
            "U_mincut_J": s["U_mincut_J"], "U_mincut_ratio": s["U_mincut_J"] / u_min,
            "converged_strain": conv.get("mean_strain", ""), "U_final_J": conv.get("fracture_energy_J", ""),
            "U_final_ratio": conv["fracture_energy_J"] / u_min if conv else "",
            "U_end_J": s["fracture_energy_J"], "U_end_ratio": s["fracture_energy_J"] / u_min,
            "energy_balance_error": s["energy_balance_error"], "energy_error": bool(s["energy_error"]),
            "clamped_bars": s["clamped_bars"], "n_bars": s["n_bars"], "steps": s["steps"], "dt_s": s["dt_s"],
            "threads": s["threads"], "wall_s": s["wall_s"], "stop_reason": s["stop_reason"],
            **{k: (s.get("provenance") or {}).get(k) or "" for k in ("ldem_version", "git_commit", "date", "host")}}


def mean_cv(values) -> tuple:
    """Mean and coefficient of variation (sample standard deviation, n - 1, over
    the mean); the CV is "" (no value, a table's "-") over fewer than two values
    or a zero mean: one specimen has no scatter to measure, and 0 would claim none."""
    v = np.asarray(values, dtype=float)
    m = float(v.mean())
    cv = float(v.std(ddof=1) / abs(m)) if len(v) > 1 and m != 0 else ""
    return m, cv


SUMMARY_COLUMNS = ("load", "size_m", "seeds", "separated", "energy_errors", "peak_stress_MPa_mean",
                   "peak_stress_MPa_cv", "strain_at_peak_mean", "strain_at_peak_cv", "edge_strain_at_peak_mean",
                   "separation_strain_mean", "U_num_J_mean", "U_min_J", "U_ratio_mean", "U_ratio_cv",
                   "U_loss_ratio_mean", "U_loss_ratio_cv", "U_end_ratio_mean", "converged", "U_final_ratio_mean",
                   "U_final_ratio_cv",
                   "U_mincut_ratio_mean", "U_mincut_ratio_cv", "ca_corrected", "ref_peak_stress_MPa",
                   "ref_strain_at_peak", "mean_curve_peak_MPa", "mean_curve_strain_at_peak", "wall_s_mean")


def _mean_cv_or_empty(values) -> tuple:
    values = [v for v in values if v != ""]
    return mean_cv(values) if values else ("", "")


def aggregate(rows: Sequence[dict], c_a: float, curves: Optional[Dict[tuple, List[dict]]] = None) -> List[dict]:
    """One row per (load, size): means and CVs over the seeds, the corrected
    c_a = c_a x E[U_num/U_min], and Table 3's values where the study gives them.
    U_num and its ratio are averaged over the separated specimens only (the
    column `separated` counts them); `energy_errors` counts the flagged runs.
    With the specimens' curves ((load, size) -> curves), also the peak of their
    mean curve: the mean of the peaks is not the peak of the mean curve, and
    the study does not say which of the two its Table 3 gives."""
    out = []
    for load in dict.fromkeys(r["load"] for r in rows):
        for size in sorted({r["size_m"] for r in rows if r["load"] == load}):
            g = [r for r in rows if r["load"] == load and r["size_m"] == size]
            peak, peak_cv = mean_cv([r["peak_stress_MPa"] for r in g])
            strain, strain_cv = mean_cv([r["strain_at_peak"] for r in g])
            ratio, ratio_cv = _mean_cv_or_empty([r["U_ratio"] for r in g])
            loss, loss_cv = _mean_cv_or_empty([r["U_loss_ratio"] for r in g])
            final, final_cv = _mean_cv_or_empty([r.get("U_final_ratio", "") for r in g])
            end, _ = _mean_cv_or_empty([r.get("U_end_ratio", "") for r in g])  # "" in rows from before U_end
            cut, cut_cv = mean_cv([r["U_mincut_ratio"] for r in g])
            u_num = [r["U_num_J"] for r in g if r["U_num_J"] != ""]
            sep_strain = [r["separation_strain"] for r in g if r["separation_strain"] != ""]
            ref = REFERENCE_UNIFORM.get(round(size, 6)) if load == "uniform" else None
            out.append({"load": load, "size_m": size, "seeds": len(g),
                        "separated": sum(1 for r in g if r["separated"] in (True, "True")),
                        "energy_errors": sum(1 for r in g if r["energy_error"] in (True, "True")),
                        "peak_stress_MPa_mean": peak, "peak_stress_MPa_cv": peak_cv, "strain_at_peak_mean": strain,
                        "strain_at_peak_cv": strain_cv,
                        "edge_strain_at_peak_mean": float(np.mean([r["edge_strain_at_peak"] for r in g])),
                        "separation_strain_mean": float(np.mean(sep_strain)) if sep_strain else "",
                        "U_num_J_mean": float(np.mean(u_num)) if u_num else "", "U_min_J": g[0]["U_min_J"],
                        "U_ratio_mean": ratio, "U_ratio_cv": ratio_cv, "U_loss_ratio_mean": loss,
                        "U_end_ratio_mean": end,
                        "converged": sum(1 for r in g if r.get("U_final_J", "") != ""),
                        "U_final_ratio_mean": final, "U_final_ratio_cv": final_cv,
                        "U_loss_ratio_cv": loss_cv, "U_mincut_ratio_mean": cut, "U_mincut_ratio_cv": cut_cv,
                        "ca_corrected": c_a * ratio if ratio != "" else "",
                        "ref_peak_stress_MPa": ref[0] if ref else "", "ref_strain_at_peak": ref[1] if ref else "",
                        "mean_curve_peak_MPa": "", "mean_curve_strain_at_peak": "",
                        "wall_s_mean": float(np.mean([r["wall_s"] for r in g]))})
            if curves is not None:
                out[-1]["mean_curve_peak_MPa"], out[-1]["mean_curve_strain_at_peak"] = \
                    mean_curve_peak(curves[(load, size)])
    return out


def fit_fractal(sizes, energies, b0: float = B0) -> dict:
    """Carpinteri-Chiaia's fractal law U(b) = U(b0) (b/b0)^d, with U(b0) the
    value at the reference size b0: least squares of ln(U/U(b0)) = d ln(b/b0),
    a line through the origin, so d = sum(x y) / sum(x^2).
    Also the exponent of the energy per unit area, U/b^2 ~ b^(d - 2)."""
    b = np.asarray(sizes, dtype=float)
    u = np.asarray(energies, dtype=float)
    ref = np.isclose(b, b0)
    if not ref.any():
        raise ValueError(f"the fractal fit needs the reference size b0 = {b0} m")
    if len(b) < 2 or np.any(u <= 0):
        raise ValueError("the fractal fit needs at least two sizes with positive energies")
    u0 = float(u[ref][0])
    x, y = np.log(b / b0), np.log(u / u0)
    d = float(np.dot(x, y) / np.dot(x, x))
    resid = y - d * x
    return {"b0_m": b0, "U_b0_J": u0, "d": d, "d_specific": d - 2.0,
            "rms_log_residual": float(np.sqrt(np.mean(resid ** 2)))}


def fractal_fits(table: Sequence[dict]) -> Dict[str, dict]:
    """The fractal law per load, over the sizes with separated specimens (at
    least two, b0 among them)."""
    fits = {}
    for load in dict.fromkeys(r["load"] for r in table):
        g = [r for r in table if r["load"] == load and r["U_num_J_mean"] != ""]
        if len(g) >= 2 and any(math.isclose(r["size_m"], B0) for r in g):
            fits[load] = fit_fractal([r["size_m"] for r in g], [r["U_num_J_mean"] for r in g])
    return fits
