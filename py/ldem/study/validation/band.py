"""The input band of a blind prediction (`ldem study validation
NAME --band`, ldem.study.validation.predict_band): the inputs the laboratory
did not measure, or measured with a scatter, drawn by a Latin hypercube
(ldem.study.bands), each point calibrated by the procedure of
docs/calibration.md (concrete.calibrate, unchanged) and run once with a seed
of its own; with the committed prediction's seeds at the mean inputs, the
5-95 % band of the peak and of the loads at the whole curve's abscissae
(1.5, 2 and 4 times the prediction's own opening at the peak), and of the
load along the curve for the figure.

The inputs (`inputs`), each normal, and their sources:
- from f_c alone (fib Model Code 2010, ldem.study.mc2010):
  - f_t = f_ctm (eq. 5.1-3): eqs. 5.1-4 and 5.1-5 give its fractiles,
    f_ctk,0.05 = 0.7 f_ctm and f_ctk,0.95 = 1.3 f_ctm: CV 0.3 / 1.645 = 0.182;
  - E = E_ci (eq. 5.1-21) with alpha_E = 1 (quartzite): MC2010's aggregate
    factor alpha_E runs from 0.7 (sandstone) to 1.2 (basalt, dense limestone)
    and the source does not name its aggregate. A stated default, not
    MC2010's: 5-95 % at 0.8 and 1.2 E_ci (CV 0.122);
  - G_F (eq. 5.1-9): MC2010 gives the mean and no fractiles. A stated
    default: those of f_ctm, 0.7 and 1.3 G_F (CV 0.182);
- given by the laboratory, when its source states no scatter (Blind.scatter
  holds a source's own): stated defaults, CV 0.05 for E, 0.10 for f_t, 0.15
  for G_F.
nu is not drawn (the regular lattice's is 0.21-0.25 whatever is asked:
docs/calibration.md), nor rho (given, or 2400 kg/m^3; it enters only the weight).

OUT/band/: design.csv (each point's inputs and seed), calibration/p{i}.json
(each point's calibration, kept in the folder of the entry whose concrete it
is), cases/s{seed}/ (the runs), band.csv and band.md (the table), band.png
(the prediction's figure with the band)."""
from __future__ import annotations

import concurrent.futures as cf
import json
import math
import multiprocessing
import os
import time
from typing import Callable, Dict, List, Sequence

import numpy as np

from ... import io
from ..bands import MIN_POINTS, Scatter, band, band_lines, cv_of_fractiles, design, inputs_share
from ..concrete import calibrate
from ..curve_quantities import MULTIPLES, load_at_opening, quantities
from ..mc2010 import lab_values, mc2010_fracture_energy

DESIGN_SEED = 70  # the Latin hypercube's
POINT_SEED = 100  # point i (1, 2, ...) runs with lattice seed POINT_SEED + i: none of the prediction's 1-6
DRAWN = ("E", "f_t", "G_F")
UNITS = {"E": (1e9, "GPa"), "f_t": (1e6, "MPa"), "G_F": (1.0, "N/m")}  # of the report
MC2010_SCATTER = {
    "E": (cv_of_fractiles(0.8, 1.2), "fib MC2010 eq. 5.1-21, E_ci with alpha_E = 1; the aggregate (alpha_E 0.7-1.2 "
                                     "in MC2010) not named: stated default, 5-95 % at 0.8-1.2 E_ci"),
    "f_t": (cv_of_fractiles(0.7, 1.3), "fib MC2010 eq. 5.1-3, f_ctm; eqs. 5.1-4/5.1-5: f_ctk,0.05 = 0.7 f_ctm, "
                                       "f_ctk,0.95 = 1.3 f_ctm"),
    "G_F": (cv_of_fractiles(0.7, 1.3), "fib MC2010 eq. 5.1-9, which gives no fractiles: stated default, 5-95 % at "
                                       "0.7-1.3 G_F (those of f_ctm)"),
}
GIVEN_SCATTER = {"E": 0.05, "f_t": 0.10, "G_F": 0.15}  # a given value whose source states no scatter: defaults
COLUMNS = ["quantity", "mean", "low", "high", "sd_inputs", "sd_seeds", "share_inputs", "share_seeds",
           *(f"share_{k}" for k in DRAWN), "centre", "residual", "points"]


def inputs(lab: dict, scatter: Dict[str, tuple] = None) -> List[Scatter]:
    """E, f_t and G_F at the values the calibration takes (mc2010.lab_values;
    G_F given or fib MC2010's from f_c), each with its scatter: the source's
    (scatter: {name: (cv, source)}), MC2010's for a value from f_c, else the
    stated default of GIVEN_SCATTER."""
    given, sources = lab_values(lab.get("E"), lab.get("nu"), lab.get("f_t"), lab.get("f_c"), lab.get("G_F"))
    given["G_F"] = lab["G_F"] if "G_F" in lab else mc2010_fracture_energy(lab["f_c"])
    out = []
    for k in DRAWN:
        if k in (scatter or {}):
            cv, source = scatter[k]
        elif sources[k] == "given":
            cv, source = GIVEN_SCATTER[k], "given; its source's scatter not recorded here: stated default"
        else:
            cv, source = MC2010_SCATTER[k]
        out.append(Scatter(k, float(given[k]), cv, source))
    return out


def committed_curves(out: str) -> tuple:
    """(predictions.csv's row, [(x, load [kN]) of each seed], the seeds) of the committed prediction in out."""
    for name in ("predictions.csv", "curves.csv"):
        if not os.path.isfile(os.path.join(out, name)):
            raise ValueError(f"{out}: no {name}: the prediction comes first (ldem study validation NAME --out {out})")
    row = io.read_table(os.path.join(out, "predictions.csv"))[0]
    table = io.read_table(os.path.join(out, "curves.csv"))
    seeds = sorted(int(k[len("x_s"):]) for k in table[0] if k.startswith("x_s"))
    curves = []
    for s in seeds:
        points = [(float(r[f"x_s{s}"]), float(r[f"load_kN_s{s}"])) for r in table if r[f"x_s{s}"] != ""]
        curves.append(tuple(np.array(c) for c in zip(*points)))
    return row, curves, seeds


def point_design(folder: str, drawn: Sequence[Scatter], points: int) -> np.ndarray:
    """x[points, 3]: the Latin hypercube of DESIGN_SEED over the inputs (also OUT/band/design.csv)."""
    if points < len(drawn) + 2:
        raise ValueError(f"--points {points}: a band of {len(drawn)} inputs needs at least {len(drawn) + 2} "
                         f"(a linear fit and its residual; the issue's design: {MIN_POINTS})")
    x = design(drawn, points, DESIGN_SEED)
    io.prepare_dir(folder)
    io.write_table(os.path.join(folder, "design.csv"),
                   [{"point": i + 1, "seed": POINT_SEED + i + 1, **{s.name: x[i, k] for k, s in enumerate(drawn)}}
                    for i in range(points)], ["point", "seed", *DRAWN])
    return x


def _calibrate_point(path: str, target: dict, nu: float, rho: float, L0: float) -> dict:
    """One point's calibration into path (a worker's task): concrete.calibrate,
    its wall time and rounds (each of three prisms) beside it."""
    rounds, start = [], time.time()
    result = calibrate(target["E"], nu, target["f_t"], None, target["G_F"], rho, L0,
                       log=lambda s: rounds.append(s) if s.startswith("round ") else None)
    result.update(wall_s=time.time() - start, rounds=len(rounds))
    io.write_text(path, json.dumps(result, indent=1) + "\n")
    return result


def _calibrated(path: str, target: dict):
    """The calibration in path if it is of target's inputs, else None."""
    try:
        with open(path) as f:
            result = json.load(f)
    except (OSError, ValueError):
        return None
    same = all(math.isclose(result["target"][k], v, rel_tol=1e-12) for k, v in target.items())
    return result if same else None


def calibrate_points(folder: str, drawn: Sequence[Scatter], x: np.ndarray, lab: dict, L0: float, jobs: int = 1,
                     log: Callable[[str], None] = print) -> List[dict]:
    """Each point's calibration at module L0 (folder/p{i}.json; one already
    there for the same inputs is kept), `jobs` at a time in processes."""
    io.prepare_dir(folder)
    nu = lab_values(lab.get("E"), lab.get("nu"), lab.get("f_t"), lab.get("f_c"), lab.get("G_F"))[0]["nu"]
    rho = lab.get("rho", 2400.0)
    tasks = [(os.path.join(folder, f"p{i + 1}.json"), {s.name: float(v) for s, v in zip(drawn, x[i])}, nu, rho, L0)
             for i in range(len(x))]
    results = [_calibrated(t[0], t[1]) for t in tasks]
    todo = [i for i, r in enumerate(results) if r is None]
    if len(todo) < len(tasks):
        log(f"{len(tasks) - len(todo)} of {len(tasks)} points already calibrated in {folder}")

    def done(i, r):
        results[i] = r
        m = r["measured"]
        log(f"  p{i + 1}: E {m['E'] / 1e9:.2f} GPa, f_t {m['f_t'] / 1e6:.3f} MPa, G_F {r['target']['G_F']:.1f} N/m "
            f"in {r['rounds']} rounds, {r['wall_s']:.1f} s")
    if jobs == 1 or len(todo) <= 1:
        for i in todo:
            done(i, _calibrate_point(*tasks[i]))
    else:  # spawn, not fork: a forked OpenMP runtime can hang in the child (executors)
        with cf.ProcessPoolExecutor(jobs, mp_context=multiprocessing.get_context("spawn")) as pool:
            futures = {pool.submit(_calibrate_point, *tasks[i]): i for i in todo}
            for fut in cf.as_completed(futures):
                done(futures[fut], fut.result())
    return results


def quantity_bands(drawn: Sequence[Scatter], x: np.ndarray, points: Sequence, seeds: Sequence,
                   x_ref: float) -> Dict[str, dict]:
    """The band (bands.band) of the peak and of the load at each multiple of
    x_ref past the peak (curve_quantities), from the points' curves and the
    committed seeds' (each (x, load [kN]))."""
    qp, qs = ([quantities(c, x_ref) for c in curves] for curves in (points, seeds))
    keys = ["peak_kN", *(f"load_at_{m:g}" for m in MULTIPLES)]
    return {k: band(drawn, x, [q[k] for q in qp], [q[k] for q in qs]) for k in keys}


def curve_band(drawn: Sequence[Scatter], x: np.ndarray, points: Sequence, seeds: Sequence, grid) -> dict:
    """The band of the load where each curve first reaches each abscissa of grid (nan where too few do)."""
    found = [band(drawn, x, [load_at_opening(c, g) for c in points], [load_at_opening(c, g) for c in seeds])
             for g in grid]
    return {"x": np.asarray(grid, float), "low": np.array([b.get("low", np.nan) for b in found]),
            "high": np.array([b.get("high", np.nan) for b in found])}


def point_seeds(points: int) -> List[int]:
    return [POINT_SEED + i for i in range(1, points + 1)]


def report(folder: str, name: str, drawn: Sequence[Scatter], x: np.ndarray, points: Sequence, seeds: Sequence,
           x_ref: float, x_label: str, calibrations: Sequence[dict], runs: Sequence[dict], L0: float,
           draw: Callable[[dict], None]) -> str:
    """band.csv, band.md and the figure (draw(band): the prediction's, with
    the band along the curve and the peak's) from the points' curves and the
    committed seeds' (each (x, load [kN])); x_ref: the prediction's opening at the peak."""
    bands = quantity_bands(drawn, x, points, seeds, x_ref)
    if "mean" in bands["peak_kN"]:
        top = max(float(c[0].max()) for c in seeds)
        draw(dict(curve_band(drawn, x, points, seeds, np.linspace(0.0, top, 121)[1:]), peak=bands["peak_kN"],
                  x_at_peak=x_ref))
    unit = x_label[x_label.rfind("[") + 1:x_label.rfind("]")]
    return write_band(folder, name, drawn, bands, x_ref, unit, calibrations, runs, len(seeds), L0)


def write_band(folder: str, name: str, drawn: Sequence[Scatter], bands: Dict[str, dict], x_ref: float, unit: str,
               calibrations: Sequence[dict], runs: Sequence[dict], seeds: int, L0: float) -> str:
    """band.csv and band.md (the figure is the prediction's: validation)."""
    n = len(calibrations)
    rows = [{"quantity": k, "points": b["points"], **({} if "mean" not in b else {
        **{c: b[c] for c in ("mean", "low", "high", "sd_inputs", "sd_seeds", "centre", "residual")},
        "share_inputs": inputs_share(b), "share_seeds": b["shares"]["seeds"],
        **{f"share_{s}": b["shares"][s] for s in DRAWN}})} for k, b in bands.items()]
    io.write_table(os.path.join(folder, "band.csv"), rows, COLUMNS)
    labels = ["peak [kN]", *(f"load at {m:g} x {x_ref:.4g} = {m * x_ref:.4g} {unit} [kN]" for m in MULTIPLES)]
    rounds = sum(c["rounds"] for c in calibrations)
    text = "\n".join([
        f"# {name}: the input band of the blind prediction", "",
        f"The committed prediction (`../predictions.csv`, `../curves.csv`: {seeds} seeds at the mean inputs) with "
        "what its inputs may be: each drawn input below, a Latin hypercube of "
        f"{n} points (seed {DESIGN_SEED}; `design.csv`), each point calibrated by the procedure of "
        f"docs/calibration.md at L0 = {L0 * 1e3:g} mm and run once with a lattice seed of its own "
        f"({POINT_SEED + 1}-{POINT_SEED + n}). Written by `ldem study validation {name} --band` "
        "(ldem.study.validation.band and ldem.study.bands say how).", "",
        "| input | mean | CV | 5-95 % | source |", "|---|---|---|---|---|",
        *(f"| {s.name} [{UNITS[s.name][1]}] | {s.mean / UNITS[s.name][0]:.4g} | {s.cv:.3f} | "
          f"{s.ppf(0.05) / UNITS[s.name][0]:.4g}-{s.ppf(0.95) / UNITS[s.name][0]:.4g} | {s.source} |" for s in drawn), "",
        "The 5-95 % band of each quantity: a normal about the prediction's mean whose variance is the inputs' part "
        "(a linear fit of the points' answers on their inputs) plus the seeds' (the committed seeds' variance). "
        "The columns *inputs* and *seeds* are their shares of that variance, *of which* each input's. The fit's "
        "residual holds the points' own seeds: near the seeds' sd, the linear fit holds.", "",
        *band_lines(DRAWN, list(bands.values()), labels, n), "",
        f"Cost: {n} calibrations ({rounds} rounds of three prisms, {sum(c['wall_s'] for c in calibrations):.0f} s of "
        f"wall in all) and {n} runs ({sum(r['steps'] for r in runs):,} steps, "
        f"{sum(r['wall_s'] for r in runs):.0f} s of wall in all, one thread each), against the prediction's one "
        f"calibration and {seeds} runs.", "",
        f"![the prediction and its band](band.png)", ""])
    io.write_text(os.path.join(folder, "band.md"), text)
    return text
