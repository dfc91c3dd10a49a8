"""The beams' tables (ldem.study.beams.cases): their size effect and their curves.

Size effect: nominal strength sigma_N = 1.5 F S / (b D^2) (S = 2.5 D the
span, b the thickness) of every case; for each notch depth, Bažant's law
sigma_N = B f_t / sqrt(1 + D / D0) fitted to the cases (least squares on
1/sigma_N^2, which the law makes linear in D: 1/sigma_N^2 = (1 + D/D0) / (B f_t)^2),
B and D0 with 95 % confidence intervals, the brittleness number beta = D / D0
of each size; for the unnotched beams, the slope of log sigma_N against log D
(a Weibull-type size effect is a straight line there, sigma_N ~ D^(-n/m)).
The same for the beams with a uniform G_f (cases_cv0/) when they are there."""
from __future__ import annotations

import glob
import os
import re
from typing import List

import numpy as np

from ... import io
from .cases import B, DEPTHS, FT, NOTCHES, beam_case

SIZE_EFFECT_COLUMNS = ["Gf_cv", "D_m", "notch", "seed", "F_N", "sigma_N_MPa"]


def beam_cases(folder: str, sub: str = "cases") -> List[dict]:
    """One row per finished case of folder/sub: D, notch, seed, peak force, sigma_N."""
    out = []
    for path in sorted(glob.glob(os.path.join(folder, sub, "*", io.tables.SUMMARY))):
        m = re.search(r"D([0-9.]+)_n([0-9.]+)_s(\d+)", path)
        s = io.read_summary(path)
        if s.get("status") != "done":
            continue
        D = float(m.group(1)) / 1e3
        F = s["peak_stress_MPa"] * 1e6  # the force [N]: area 1
        out.append({"D_m": D, "notch": float(m.group(2)), "seed": int(m.group(3)), "F_N": F,
                    "sigma_N_MPa": 1.5 * F * 2.5 * D / (B * D * D) / 1e6})
    return out


def bazant_fit(D: np.ndarray, s: np.ndarray) -> tuple:
    """Bažant's law by linear regression of Y = 1/sigma^2 on D: Y = a + c D with
    a = 1/(B f_t)^2 and D0 = a / c; (B, its 95 % half-interval, D0, its) by the
    delta method."""
    A = np.column_stack([np.ones_like(D), D])
    Y = 1.0 / s ** 2
    coef, *_ = np.linalg.lstsq(A, Y, rcond=None)
    a, c = coef
    dof = max(len(D) - 2, 1)
    sigma2 = float(np.sum((Y - A @ coef) ** 2)) / dof
    cov = sigma2 * np.linalg.inv(A.T @ A)
    b = 1.0 / np.sqrt(a) / (FT / 1e6)
    D0 = a / c
    gB = np.array([-0.5 * a ** -1.5 / (FT / 1e6), 0.0])
    gD0 = np.array([1.0 / c, -a / c ** 2])
    t = 2.0 if dof > 30 else {1: 12.7, 2: 4.30, 3: 3.18, 4: 2.78, 5: 2.57}.get(dof, 2.1)  # Student's t, 95 %
    return b, t * np.sqrt(gB @ cov @ gB), D0, t * np.sqrt(gD0 @ cov @ gD0)


def size_effect_table(rows: list, title: str) -> tuple:
    """The lines of size_effect.md for one set of cases, and the fits by notch."""
    lines = [f"## {title} ({len(rows)} cases)", "",
             "| notch / D | D [mm] | specimens | sigma_N [MPa] (CV) | beta = D/D0 |", "|---|---|---|---|---|"]
    fits = {}
    for notch in sorted({r["notch"] for r in rows}):
        sel = [r for r in rows if r["notch"] == notch]
        D = np.array([r["D_m"] for r in sel])
        s = np.array([r["sigma_N_MPa"] for r in sel])
        if notch > 0 and len(set(D)) >= 3:
            fits[notch] = bazant_fit(D, s)
        for d in sorted(set(D)):
            v = s[D == d]
            beta = f"{d / fits[notch][2]:.2f}" if notch in fits else "-"
            cv = f"{v.std(ddof=1) / v.mean():.3f}" if len(v) > 1 else "-"
            lines.append(f"| {notch:g} | {d * 1e3:g} | {len(v)} | {v.mean():.3f} ({cv}) | {beta} |")
    lines += ["", "Bažant's law sigma_N = B f_t / sqrt(1 + D/D0), f_t = 3.9 MPa:", ""]
    for notch, (b, db, D0, dD0) in fits.items():
        lines.append(f"- notch {notch:g} D: B = {b:.3f} +- {db:.3f}, D0 = {D0 * 1e3:.1f} +- {dD0 * 1e3:.1f} mm")
    plain = [r for r in rows if r["notch"] == 0]
    if len({r["D_m"] for r in plain}) >= 2:
        slope = np.polyfit(np.log([r["D_m"] for r in plain]), np.log([r["sigma_N_MPa"] for r in plain]), 1)[0]
        lines.append(f"- unnotched: d log sigma_N / d log D = {slope:.3f} (Weibull with n = 2 dimensions: -2/m)")
    return lines + [""], fits


def write_size_effect(folder: str) -> tuple:
    """size_effect.md and size_effect.csv of the cases in folder; returns (lines,
    rows, fits, uniform rows, uniform fits), or None if no case is finished."""
    rows = beam_cases(folder)
    if not rows:
        return None
    lines, fits = size_effect_table(rows, "Random G_f (CV 1)")
    uniform, uniform_fits = beam_cases(folder, "cases_cv0"), {}
    if uniform:
        more, uniform_fits = size_effect_table(uniform, "Uniform G_f (CV 0)")
        lines += more
    io.write_text(os.path.join(folder, "size_effect.md"), "# Size effect of the beams\n\n" + "\n".join(lines))
    io.write_table(os.path.join(folder, "size_effect.csv"), [dict(r, Gf_cv=1.0) for r in rows] +
                   [dict(r, Gf_cv=0.0) for r in uniform], SIZE_EFFECT_COLUMNS)
    return lines, rows, fits, uniform, uniform_fits


def write_curve_tables(out: str, seeds: int) -> dict:
    """out/curves/D{mm}_n{notch}.csv: load [kN], deflection [mm] and CMOD [mm] of
    every seed's run (columns per seed); returns (D, notch) -> {seed: curve}."""
    os.makedirs(os.path.join(out, "curves"), exist_ok=True)
    found = {}
    for D in DEPTHS:
        for notch in NOTCHES:
            columns, curves = {}, {}
            for seed in range(1, seeds + 1):
                path = os.path.join(beam_case(out, D, notch, seed), io.tables.CURVE)
                if not os.path.exists(path):
                    continue
                c = curves[seed] = io.read_curve(path)
                columns[f"deflection_mm_s{seed}"] = c["mean_strain"] * D * 1e3
                columns[f"load_kN_s{seed}"] = c["stress_MPa"] * 1e3
                columns[f"cmod_mm_s{seed}"] = c["cmod_m"] * 1e3
            if columns:
                n = max(len(v) for v in columns.values())
                rows = [{k: (f"{v[i]:.6g}" if i < len(v) else "") for k, v in columns.items()} for i in range(n)]
                io.write_table(os.path.join(out, "curves", f"D{D * 1e3:g}_n{notch:g}.csv"), rows, list(columns))
            found[D, notch] = curves
    return found
