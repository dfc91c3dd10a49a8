"""Blind predictions of laboratory tests: a specimen file, the concrete a
laboratory reported, the calibration of docs/calibration.md at the file's
module (ldem.study.concrete.calibrate, unchanged), six random specimens each
stopped past their peak; the peak load (mean, CV), the curves and the crack
pictures, written before any measurement is seen.

OUT/material.json: the calibration; OUT/cases/s{seed}/: the runs (seed 1 with
its pictures); OUT/predictions.csv, curves.csv, curves.png; OUT/cracks.png (seed 1's).

    ldem study validation NAME [--calibrate-only | --whole-curve | --band] [--seeds 6] [--jobs J] [--out OUT] [--root .]

NAME: l_panel (Winkler et al. 2001), eccentric_notch_beam (García-Álvarez et
al. 2012), malvar_warren_s1 or _s2 (Malvar and Warren 1988, from f_c alone;
with _weight: lying on the supports under gravity); OUT:
ROOT/results/validation/NAME. Finished cases are not run again. --whole-curve
runs nothing: OUT/whole_curve.md|png, the committed prediction's curve
quantities (ldem.study.curve_quantities) at multiples of its own opening at the peak, the
measured column left empty (the measurements stay out of the repository).
--band [--points 12]: the committed prediction's input band, OUT/band/ (ldem.study.validation.band)."""
from __future__ import annotations

import json
import os
import shutil
import statistics
from dataclasses import dataclass, field
from typing import Callable, Dict, List

import numpy as np

from ... import io
from ...specimen import SpecimenTest
from ..concrete import calibrate, slope
from ..mc2010 import lab_values
from ..curve_report import figure as curve_figure, summarize, table_lines
from ..beams.cases import PastThePeak
from ..cases import Named
from ..executors import run_cases
from .band import (MIN_POINTS, calibrate_points, committed_curves, inputs as band_inputs, point_design,
                   point_seeds, report as band_report)
from ..options import add_seeds, seed_count
from ..registry import Study, register
from ..tables import mean_cv


@dataclass(frozen=True)
class Blind:
    file: str  # the specimen file, from the repository's root
    # what the laboratory reported: E, nu, f_t, G_F, f_c, rho; what is missing
    # comes from fib MC2010 and f_c (mc2010.lab_values), rho is 2400 if not given
    lab: Dict[str, float] = field(default_factory=dict)
    x: str = "mean_strain"  # the curve's abscissa: a column of the run's curve
    x_label: str = ""
    x_scale: float = 1.0  # to the unit of x_label
    past_the_peak: bool = True  # stop each run past its peak (PastThePeak); else at the file's final strain
    beyond: float = 2.0  # past the peak: at this multiple of the abscissa at the peak (PastThePeak)
    gravity: float = 0.0  # [m/s^2]: the specimen lies on its supports under its own weight
    from_elastic_zero: bool = False  # x from where the elastic line crosses zero load (elastic_zero)
    calibration: str = ""  # the entry whose material.json this one uses (the same concrete)
    scatter: Dict[str, tuple] = field(default_factory=dict)  # a source's own scatter: {E|f_t|G_F: (cv, source)}


SPECIMENS = {
    # Winkler, Hofstetter and Niederwieser (2001)
    "l_panel": Blind("examples/l_panel.toml", {"E": 25.85e9, "nu": 0.18, "f_t": 2.7e6, "G_F": 90.0},
                     "mean_strain", "load-point displacement [mm]", 500.0,  # gauge 0.5 m, to mm
                     beyond=4.0),  # to 4 times its displacement at the peak
    # García-Álvarez, Gettu and Carol (2012)
    "eccentric_notch_beam": Blind("examples/eccentric_notch_beam.toml",
                                  {"E": 33.8e9, "nu": 0.2, "f_t": 3.5e6, "G_F": 125.0, "rho": 2346.0},
                                  "cmod_m", "CMOD over 20 mm [mm]", 1e3),
}
# Malvar and Warren (1988): f_c alone; the curve to a load-point deflection of 1.5 mm
for _series, _fc in (("s1", 29.0e6), ("s2", 58.9e6)):
    _beam = dict(file="examples/malvar_warren_beam.toml", lab={"f_c": _fc}, x_label="load-point deflection [mm]",
                 x_scale=102.0, past_the_peak=False, from_elastic_zero=True)  # gauge D = 0.102 m, to mm
    SPECIMENS[f"malvar_warren_{_series}"] = Blind(**_beam)
    SPECIMENS[f"malvar_warren_{_series}_weight"] = Blind(**_beam, gravity=9.81, calibration=f"malvar_warren_{_series}")
COLUMNS = ["specimen", "peak_load_kN", "cv", "seeds", "min_kN", "max_kN", "x_at_peak", "x_label", "calibration",
           "weight_kN", "x_zero"]


class Stopped(Named):
    """A specimen file's run as a study case s{seed}, stopped past its peak
    (PastThePeak) or at the file's final strain, under gravity if asked."""

    def __init__(self, path: str, material: dict, seed: int, blind: Blind):
        test = SpecimenTest.from_file(path, overrides=dict(material, seed=seed, threads=1, gravity=blind.gravity))
        super().__init__(test, f"s{seed}", ["curve", "summary"] + (["figures"] if seed == 1 else []))
        self.past_the_peak, self.beyond = blind.past_the_peak, blind.beyond

    def run(self, observers=(), simulation=None, previous_rows=()):
        stop = [PastThePeak(previous_rows, beyond=self.beyond)] if self.past_the_peak else []
        return self.test.run(list(observers) + stop, simulation, previous_rows)


def free_weight(test: SpecimenTest, gravity: float) -> float:
    """[N] The weight the supports and the platen carry: m g of the nodes whose z
    is free (the held and driven nodes' own weight is not in their reactions)."""
    mass = np.asarray(test.simulation().lattice.mass)
    node, dim, _ = test.build.prescribed
    return gravity * float(mass.sum() - mass[np.unique(node[dim == 2])].sum())


def elastic_zero(x: np.ndarray, load: np.ndarray) -> float:
    """Where the elastic line crosses zero load: load = k (x - x0) fitted on the
    rising branch between 20 % and 60 % of the peak. Under its weight a beam
    already bends before the test's zero (the platen, held at 0, carries part
    of it): by superposition the test's deflection is x - x0."""
    rising = np.arange(len(load)) <= int(np.argmax(load))
    band = rising & (load > 0.2 * load.max()) & (load < 0.6 * load.max())
    return float(x[band].mean() - load[band].mean() / slope(x[band], load[band]))


def material(root: str, name: str, out: str, log: Callable[[str], None] = print) -> dict:
    """The calibration for the specimen's concrete at its file's L0 (kept in
    OUT/material.json; an entry with `calibration` uses that entry's, beside OUT)."""
    b = SPECIMENS[name]
    if b.calibration:
        return material(root, b.calibration, os.path.join(os.path.dirname(os.path.abspath(out)), b.calibration), log)
    path = os.path.join(out, "material.json")
    if os.path.exists(path):
        with open(path) as f:
            return json.load(f)
    L0 = SpecimenTest.from_file(os.path.join(root, b.file)).build.L0
    lab = dict(b.lab)
    given, sources = lab_values(lab.get("E"), lab.get("nu"), lab.get("f_t"), lab.get("f_c"), lab.get("G_F"))
    rho = lab.get("rho", 2400.0)
    sources["rho"] = "given" if "rho" in lab else "2400 kg/m^3, normal-weight concrete (assumed)"
    result = calibrate(given["E"], given["nu"], given["f_t"], lab.get("f_c"), lab.get("G_F"), rho, L0, log=log)
    result["sources"] = sources
    io.prepare_dir(out)
    io.write_text(path, json.dumps(result, indent=1) + "\n")
    return result


def predict(root: str, name: str, out: str, seeds: int = 6, jobs: int = 1,
            log: Callable[[str], None] = print) -> dict:
    """Calibrates, runs the seeds not yet run, writes the tables and figures; returns the prediction's row."""
    if name not in SPECIMENS:
        raise ValueError(f"unknown specimen {name!r} (known: {', '.join(SPECIMENS)})")
    b = SPECIMENS[name]
    m = material(root, name, out, log)["material"]
    path = os.path.join(root, b.file)
    run_cases([Stopped(path, m, s, b) for s in range(1, seeds + 1)], out, jobs=jobs, log=log)
    weight = free_weight(SpecimenTest.from_file(path, overrides=m), b.gravity) if b.gravity else 0.0
    return write_prediction(out, name, seeds, weight)


def write_prediction(out: str, name: str, seeds: int, weight: float = 0.0) -> dict:
    """predictions.csv, curves.csv, the figures. Under gravity (weight [N] > 0)
    the load is the supports' reaction less the weight; with from_elastic_zero
    the abscissa starts at the elastic line's zero (elastic_zero): what the
    test, zeroed with the beam lying on its supports, reads (without gravity
    it takes out the smooth start's lag)."""
    b = SPECIMENS[name]
    peaks, curves, at, zeros = [], {}, [], []
    for seed in range(1, seeds + 1):
        x, load, peak, zero = read_case(os.path.join(out, "cases", f"s{seed}"), b, weight)
        zeros += [zero] if b.from_elastic_zero else []
        peaks.append(peak)
        at.append(float(x[int(np.argmax(load))]))
        curves[f"x_s{seed}"], curves[f"load_kN_s{seed}"] = x, load
    mean, cv = mean_cv(peaks)
    row = {"specimen": name, "peak_load_kN": mean, "cv": cv,
           "seeds": len(peaks), "min_kN": min(peaks), "max_kN": max(peaks), "x_at_peak": statistics.mean(at),
           "x_label": b.x_label, "calibration": "docs/calibration.md", "weight_kN": weight * 1e-3,
           "x_zero": statistics.mean(zeros) if zeros else 0.0}
    io.write_table(os.path.join(out, "predictions.csv"), [row], COLUMNS)
    n = max(len(v) for v in curves.values())
    io.write_table(os.path.join(out, "curves.csv"),
                   [{k: (f"{v[i]:.6g}" if i < len(v) else "") for k, v in curves.items()} for i in range(n)],
                   list(curves))
    _figure(out, name, [(curves[f"x_s{s}"], curves[f"load_kN_s{s}"]) for s in range(1, seeds + 1)], b.x_label)
    cracks = os.path.join(out, "cases", "s1", "cracks.png")
    if os.path.exists(cracks):
        shutil.copyfile(cracks, os.path.join(out, "cracks.png"))
    return row


def read_case(case: str, b: Blind, weight: float = 0.0) -> tuple:
    """(x, load [kN], peak [kN], x's zero) of a finished case as the prediction reads it: the load less the
    weight [N], x from the elastic line's zero if from_elastic_zero (zero 0 else)."""
    s = io.read_summary(os.path.join(case, io.tables.SUMMARY))
    c = io.read_curve(os.path.join(case, io.tables.CURVE))
    load = np.asarray(c["stress_MPa"]) * 1e3 - weight * 1e-3  # F [MN] -> kN
    x = np.asarray(c[b.x]) * b.x_scale
    zero = elastic_zero(x, load) if b.from_elastic_zero else 0.0
    return x - zero, load, s["peak_stress_MPa"] * 1e3 - weight * 1e-3, zero


def _figure(out: str, name: str, curves: list, x_label: str, band=None, file: str = "curves.png") -> None:
    """The seeds' curves [(x, load)]; with band ({x, low, high} along the curve, and peak: a
    bands.band), its 5-95 % shaded and the peak's as a bar at the mean opening there."""
    from ... import plots
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4))
    if band is not None:
        ax.fill_between(band["x"], band["low"], band["high"], color="0.82", lw=0, label="5-95 %: inputs and seeds")
        p = band["peak"]
        ax.errorbar([band["x_at_peak"]], [p["mean"]], yerr=[[p["mean"] - p["low"]], [p["high"] - p["mean"]]],
                    fmt="ko", ms=4, capsize=4, label="peak, 5-95 %")
    for seed, (x, load) in enumerate(curves, 1):
        ax.plot(x, load, lw=1, label=f"seed {seed}")
    ax.set_xlabel(x_label)
    ax.set_ylabel("load [kN]")
    ax.set_title(f"{name}: blind prediction, {len(curves)} specimens" + ", its input band" * (band is not None))
    ax.legend(fontsize=8)
    plots.save(fig, os.path.join(out, file))


def predict_band(root: str, name: str, out: str, points: int = MIN_POINTS, jobs: int = 1,
                 log: Callable[[str], None] = print) -> str:
    """The committed prediction's input band (ldem.study.validation.band): the
    points calibrated and run (those not done yet), OUT/band/band.md|csv|png."""
    b, folder = SPECIMENS[name], os.path.join(out, "band")
    concrete = SPECIMENS[b.calibration or name]  # under its weight: its concrete's calibrations, beside OUT
    home = os.path.join(os.path.dirname(os.path.abspath(out)), b.calibration) if b.calibration else out
    path = os.path.join(root, b.file)
    row, seed_curves, _ = committed_curves(out)
    L0 = SpecimenTest.from_file(path).build.L0
    drawn = band_inputs(concrete.lab, concrete.scatter)
    x = point_design(folder, drawn, points)
    calibrations = calibrate_points(os.path.join(home, "band", "calibration"), drawn, x, concrete.lab,
                                                    L0, jobs, log)
    seeds = point_seeds(points)
    runs = run_cases([Stopped(path, c["material"], s, b) for c, s in zip(calibrations, seeds)], folder, jobs=jobs,
                     log=log)
    weight = float(row.get("weight_kN") or 0.0) * 1e3
    curves = [read_case(os.path.join(folder, "cases", f"s{s}"), b, weight)[:2] for s in seeds]
    return band_report(folder, name, drawn, x, curves, seed_curves, float(row["x_at_peak"]), b.x_label,
                                  calibrations, runs, L0, lambda band: _figure(folder, name, seed_curves, b.x_label,
                                                                               band, "band.png"))


def whole_curve(out: str, name: str) -> str:
    """OUT/whole_curve.md and .png from the committed predictions.csv and curves.csv."""
    row, curves, seeds = committed_curves(out)
    x_ref, label = float(row["x_at_peak"]), row["x_label"]
    unit = label[label.rfind("[") + 1:label.rfind("]")]
    curve_figure(os.path.join(out, "whole_curve.png"), f"{name}: blind prediction", curves, x_ref, label)
    summary = summarize(curves, x_ref)
    text = "\n".join([f"# {name}: the whole curve, blind", "",
                      f"The committed prediction's curves ({len(seeds)} specimens, `curves.csv`), read at multiples "
                      f"of its own mean {label.split(' [')[0]} at the peak, {x_ref:.4g} {unit}, along each curve past "
                      "its peak (ldem.study.curve_quantities). The measured column is empty: the measurements were "
                      "never given to this project. Written by `ldem study validation NAME --whole-curve`.", "",
                      *table_lines(summary, unit), "", *_peak_note(summary, row),
                      "![the whole curve](whole_curve.png)", ""])
    io.write_text(os.path.join(out, "whole_curve.md"), text)
    return text


def _peak_note(summary: dict, row: dict) -> List[str]:
    """A line when the curves' largest recorded loads and the prediction's peak
    (each run's own, predictions.csv) differ by more than 0.5 %."""
    curves, run = summary["predicted"]["peak_kN"][0], float(row["peak_load_kN"])
    if abs(curves / run - 1) <= 0.005:
        return []
    return [f"The peak here is the mean of each curve's largest recorded load; the prediction's (`predictions.csv`, "
            f"each run's own peak) is {run:.3f} kN, {run / curves - 1:+.1%}: a run recorded without the load cell "
            "read its peak at a single step, the top of the ringing.", ""]


def add_arguments(v) -> None:
    v.add_argument("name", choices=sorted(SPECIMENS), metavar="NAME", help=", ".join(sorted(SPECIMENS)))
    only = v.add_mutually_exclusive_group()
    only.add_argument("--calibrate-only", action="store_true", help="OUT/material.json only: run no specimen")
    only.add_argument("--whole-curve", action="store_true", help="run nothing: OUT/whole_curve.md|png from the "
                                                              "committed prediction")
    only.add_argument("--band", action="store_true", help="the committed prediction's 5-95 %% band over the inputs "
                                                        "not measured and the seeds: OUT/band/ (runs --points "
                                                        "calibrations and runs)")
    v.add_argument("--points", type=int, default=MIN_POINTS, help="--band: the Latin hypercube's points, one run each")
    add_seeds(v, "prediction")
    v.add_argument("--jobs", type=int, default=1, metavar="J", help="runs at a time, one thread each")
    v.add_argument("--root", default=".", metavar="DIR", help="the repository, whose examples/ hold the files")
    v.add_argument("--out", default="", metavar="OUT", help="the folder (default: ROOT/results/validation/NAME)")


def cmd_validation(args) -> int:
    # args.out resolved: a signal's message (cli.what_is_kept) names the folder that keeps the finished cases
    out = args.out = args.out or os.path.join(args.root, "results", "validation", args.name)
    log = lambda s: print(s, flush=True)  # noqa: E731
    if args.calibrate_only:
        material(args.root, args.name, out, log)
    elif args.whole_curve:
        print(whole_curve(out, args.name))
    elif args.band:
        if args.points < MIN_POINTS:
            raise ValueError(f"--points {args.points}: the band's design has at least {MIN_POINTS} points")
        print(predict_band(args.root, args.name, out, args.points, args.jobs, log))
    else:
        print(predict(args.root, args.name, out, seed_count(args), args.jobs, log))
    return 0


register(Study("validation", "blind predictions of laboratory tests: a specimen file, its concrete calibrated, "
                             "six specimens past their peak", add_arguments, cmd_validation))
