"""Why the blind prediction of Grégoire et al. (2013) is too strong: one
factor at a time against the prediction, on the two D = 50 mm beams with
measurements (no notch, notch D/2) and the D = 100 mm beam with a notch D/5,
six seeds each.

A factor of the material or of the module changes what the direct tension
prism gives, so eps_p is calibrated again on the prism for it (cases.calibrate:
the prism's mean strength stays f_t), as the prediction's was: the table says
what the factor does to a beam of a concrete of the same f_t. The loading and
bearing factors keep the prediction's eps_p.

Cases: OUT/FACTOR/D{mm}_n{notch}_s{seed}/; eps_p of each: OUT/calibration.json;
table: OUT/diagnosis.md and diagnosis.csv (the mean peak of each beam and its
change against the prediction)."""
from __future__ import annotations

import json
import os
import statistics
from dataclasses import dataclass
from typing import Callable, Dict, List, Sequence, Tuple

from ... import io
from ...markdown import mean_cv_cell
from .cases import GF, PREDICTION, Beam, Variant, calibrate
from ..executors import run_cases
from ..tables import mean_cv

BEAMS = ((0.05, 0.0), (0.05, 0.5), (0.1, 0.2))
MEASURED_KN = {(0.05, 0.0): 4.649, (0.05, 0.5): 0.979, (0.1, 0.2): 4.496}  # ../shared/data/gregoire2013/measured.csv
PREDICTION_EPS_P = 1.01592e-4  # ldem study beams calibrate (results/beams/gregoire2013/README.md)
# Bažant and Becq-Giraudon, Cem. Concr. Res. 32 (2002) 529: G_F / G_f = 2.5 on
# average over their database (CV 0.4); fib MC2010's bilinear law has 0.625 G_F
# under its initial line.
GF_INITIAL = GF / 2.5


@dataclass(frozen=True)
class Factor:
    name: str  # its folder
    label: str  # its row
    v: Variant
    beams: Tuple[Tuple[float, float], ...] = BEAMS

    def recalibrated(self) -> bool:
        """A factor of the prism (material or module) has an eps_p of its own."""
        return (self.v.material, self.v.L0) != (PREDICTION.material, PREDICTION.L0)


FACTORS = (
    Factor("prediction", "the prediction: triangle with G_F = 143 N/m, CV(G_f) 1, L0 5 mm", Variant()),
    Factor("triangle_Gf", f"triangle with G_f = G_F / 2.5 = {GF_INITIAL:.0f} N/m", Variant((("Gf_mean", GF_INITIAL),))),
    Factor("bilinear_mc2010", "bilinear, MC2010: G_F 143 N/m, G_f/G_F 0.625, kink 0.2 f_t",
           Variant((("law", "bilinear"), ("Gf_ratio", 0.625), ("kink_stress", 0.2)))),
    Factor("bilinear_bazant", "bilinear: G_F 143 N/m, G_f/G_F 0.4 (Bažant), kink 0.2 f_t",
           Variant((("law", "bilinear"), ("Gf_ratio", 0.4), ("kink_stress", 0.2)))),
    Factor("cv0.5", "CV(G_f) 0.5", Variant((("Gf_cv", 0.5),))),
    Factor("cv0", "CV(G_f) 0 (uniform G_f)", Variant((("Gf_cv", 0.0),))),
    Factor("corr25", "G_f field correlated over 25 mm (2.5 aggregate sizes)", Variant((("corr_length", 0.025),))),
    Factor("rate_half", "deflection rate 0.05 D/s (half)", Variant(rate=0.05)),
    Factor("cmod", "CMOD servo at 0.1 D/s (the laboratory's control)", Variant(opening_rate=0.1)),
    Factor("platen3", "platen 3 modules (15 mm) wide", Variant(platen=3)),
    Factor("bearing3", "platen 3 modules (15 mm), supports 3 node lines (10 mm) wide", Variant(platen=3, supports=3)),
    Factor("L0_2.5", "module L0 2.5 mm (D = 50 mm only)", Variant(L0=0.0025), BEAMS[:2]),
)
BY_NAME = {f.name: f for f in FACTORS}
COLUMNS = ["factor", "label", "eps_p", "D_mm", "notch", "seeds", "peak_kN", "cv", "change", "measured_kN"]


def calibration(out: str, factor: Factor, log: Callable[[str], None] = print) -> float:
    """eps_p of the factor: the prediction's, or calibrated on the prism (kept
    in OUT/calibration.json)."""
    if not factor.recalibrated():
        return PREDICTION_EPS_P
    path = os.path.join(out, "calibration.json")
    known: Dict[str, float] = json.load(open(path)) if os.path.exists(path) else {}
    if factor.name not in known:
        log(f"{factor.name}: calibrating eps_p on the prism")
        known[factor.name] = calibrate(lambda s: log(f"  {s}"), factor.v)
        io.prepare_dir(out)
        io.write_text(path, json.dumps(known, indent=1) + "\n")
    return known[factor.name]


def factor_tests(out: str, factor: Factor, seeds: int, log: Callable[[str], None] = print) -> List[Beam]:
    eps_p = calibration(out, factor, log)
    return [Beam(D, n, eps_p, s, v=factor.v, folder=factor.name)
            for s in range(1, seeds + 1) for D, n in factor.beams]


def run(out: str, names: Sequence[str], seeds: int = 6, jobs: int = 1,
        log: Callable[[str], None] = print) -> List[dict]:
    """Runs the factors' unfinished cases, then writes the table of all."""
    for name in names:
        if name not in BY_NAME:
            raise ValueError(f"unknown factor {name!r} (known: {', '.join(BY_NAME)})")
        run_cases(factor_tests(out, BY_NAME[name], seeds, log), out, jobs=jobs, log=log)
    return write_table(out, seeds)


def peaks(out: str, factor: Factor, D: float, notch: float, seeds: int) -> Dict[int, float]:
    """The finished cases' peak loads [kN] by seed (the force of area 1 [MN] -> kN)."""
    found = {}
    for seed in range(1, seeds + 1):
        path = os.path.join(out, factor.name, f"D{D * 1e3:g}_n{notch:g}_s{seed}", io.tables.SUMMARY)
        if os.path.exists(path):
            s = io.read_summary(path)
            if s.get("status") == "done":
                found[seed] = s["peak_stress_MPa"] * 1e3
    return found


def write_table(out: str, seeds: int) -> List[dict]:
    """diagnosis.csv and diagnosis.md: each factor's mean peak per beam and
    its change against the prediction's mean over the same seeds."""
    rows = []
    eps = json.load(open(os.path.join(out, "calibration.json"))) if os.path.exists(
        os.path.join(out, "calibration.json")) else {}
    for f in FACTORS:
        for D, n in f.beams:
            p = peaks(out, f, D, n, seeds)
            if not p:
                continue
            base = peaks(out, FACTORS[0], D, n, seeds)
            mean, cv = mean_cv(list(p.values()))
            same = [base[s] for s in p if s in base]  # the prediction's specimens of the same seeds
            rows.append({"factor": f.name, "label": f.label, "eps_p": eps.get(f.name, PREDICTION_EPS_P),
                         "D_mm": D * 1e3, "notch": n, "seeds": len(p), "peak_kN": mean,
                         "cv": cv,
                         "change": mean / statistics.mean(same) - 1 if len(same) == len(p) else "",
                         "measured_kN": MEASURED_KN[(D, n)]})
    io.write_table(os.path.join(out, "diagnosis.csv"), rows, COLUMNS)
    io.write_text(os.path.join(out, "diagnosis.md"), "\n".join(markdown(rows)) + "\n")
    return rows


def markdown(rows: List[dict]) -> List[str]:
    """One line per factor, one column per beam: mean peak [kN] (change against the prediction)."""
    head = "| factor | eps_p | " + " | ".join(f"D = {D * 1e3:g} mm, notch {n:g} D" for D, n in BEAMS) + " |"
    lines = [head, "|---|---|" + "---|" * len(BEAMS)]
    for f in FACTORS:
        mine = {(r["D_mm"] / 1e3, r["notch"]): r for r in rows if r["factor"] == f.name}
        if not mine:
            continue
        cells = []
        for b in BEAMS:
            r = mine.get(b)
            cells.append("-" if r is None else mean_cv_cell(r['peak_kN'], r['cv']) +
                         (f", {r['change']:+.1%}" if r["change"] != "" and f.name != "prediction" else "") +
                         ("" if r["seeds"] == 6 else f" [{r['seeds']} seeds]"))
        eps = next(iter(mine.values()))["eps_p"]
        lines.append(f"| {f.label} | {eps:.4g} | " + " | ".join(cells) + " |")
    lines.append("| **measured** (peak of the mean curve) | | " +
                 " | ".join(f"{MEASURED_KN[b]:.3f}" for b in BEAMS) + " |")
    return lines
