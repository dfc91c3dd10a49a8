"""Blind predictions of laboratory tests (issue 28, item 5): a specimen file,
the concrete a laboratory reported, the calibration of docs/calibration.md at
the file's module (ldem.study.concrete.calibrate, unchanged), six random
specimens each stopped past their peak; the peak load (mean, CV), the curves
and the crack pictures, written before any measurement is seen.

OUT/material.json: the calibration; OUT/cases/s{seed}/: the runs (seed 1 with
its pictures); OUT/predictions.csv, curves.csv, curves.png; OUT/cracks.png (seed 1's).

    ldem study validation NAME [--calibrate-only] [--seeds 6] [--jobs J] [--out OUT] [--root .]

NAME: l_panel (Winkler et al. 2001) or eccentric_notch_beam (García-Álvarez et
al. 2012); OUT: ROOT/results/validation/NAME. Finished cases are not run again."""
from __future__ import annotations

import json
import os
import shutil
import statistics
from dataclasses import dataclass, field
from typing import Callable, Dict, List

import numpy as np

from .. import io
from ..specimen import SpecimenTest
from .concrete import calibrate
from .beams import PastThePeak
from .cases import Named
from .executors import run_cases
from .options import add_seeds, seed_count
from .registry import Study, register
from .tables import mean_cv


@dataclass(frozen=True)
class Blind:
    file: str  # the specimen file, from the repository's root
    lab: Dict[str, float] = field(default_factory=dict)  # calibrate's E, nu, f_t, G_F (and f_c), rho
    x: str = "mean_strain"  # the curve's abscissa: a column of the run's curve
    x_label: str = ""
    x_scale: float = 1.0  # to the unit of x_label


SPECIMENS = {
    # Winkler, Hofstetter and Niederwieser (2001)
    "l_panel": Blind("examples/l_panel.toml", {"E": 25.85e9, "nu": 0.18, "f_t": 2.7e6, "G_F": 90.0},
                     "mean_strain", "load-point displacement [mm]", 500.0),  # gauge 0.5 m, to mm
    # García-Álvarez, Gettu and Carol (2012)
    "eccentric_notch_beam": Blind("examples/eccentric_notch_beam.toml",
                                  {"E": 33.8e9, "nu": 0.2, "f_t": 3.5e6, "G_F": 125.0, "rho": 2346.0},
                                  "cmod_m", "CMOD over 20 mm [mm]", 1e3),
}
COLUMNS = ["specimen", "peak_load_kN", "cv", "seeds", "min_kN", "max_kN", "x_at_peak", "x_label", "calibration"]


class Stopped(Named):
    """A specimen file's run as a study case s{seed}, stopped past its peak (PastThePeak)."""

    def __init__(self, path: str, material: dict, seed: int):
        test = SpecimenTest.from_file(path, overrides=dict(material, seed=seed, threads=1))
        super().__init__(test, f"s{seed}", ["curve", "summary"] + (["figures"] if seed == 1 else []))

    def run(self, observers=(), simulation=None, previous_rows=()):
        return self.test.run(list(observers) + [PastThePeak(previous_rows)], simulation, previous_rows)


def material(root: str, name: str, out: str, log: Callable[[str], None] = print) -> dict:
    """The calibration for the specimen's concrete at its file's L0 (kept in OUT/material.json)."""
    path = os.path.join(out, "material.json")
    if os.path.exists(path):
        with open(path) as f:
            return json.load(f)
    b = SPECIMENS[name]
    L0 = SpecimenTest.from_file(os.path.join(root, b.file)).build.L0
    lab = dict(b.lab)
    rho = lab.pop("rho", 2400.0)
    result = calibrate(lab.pop("E"), lab.pop("nu"), lab.pop("f_t"), lab.pop("f_c", None),
                                lab.pop("G_F", None), rho, L0, log=log)
    io.prepare_dir(out)
    io.write_text(path, json.dumps(result, indent=1) + "\n")
    return result


def predict(root: str, name: str, out: str, seeds: int = 6, jobs: int = 1,
            log: Callable[[str], None] = print) -> dict:
    """Calibrates, runs the seeds not yet run, writes the tables and figures; returns the prediction's row."""
    if name not in SPECIMENS:
        raise ValueError(f"unknown specimen {name!r} (known: {', '.join(SPECIMENS)})")
    m = material(root, name, out, log)["material"]
    path = os.path.join(root, SPECIMENS[name].file)
    run_cases([Stopped(path, m, s) for s in range(1, seeds + 1)], out, jobs=jobs, log=log)
    return write_prediction(out, name, seeds)


def write_prediction(out: str, name: str, seeds: int) -> dict:
    b = SPECIMENS[name]
    peaks, curves, at = [], {}, []
    for seed in range(1, seeds + 1):
        case = os.path.join(out, "cases", f"s{seed}")
        s = io.read_summary(os.path.join(case, io.tables.SUMMARY))
        c = io.read_curve(os.path.join(case, io.tables.CURVE))
        load = np.asarray(c["stress_MPa"]) * 1e3  # F [MN] -> kN
        x = np.asarray(c[b.x]) * b.x_scale
        peaks.append(s["peak_stress_MPa"] * 1e3)
        at.append(float(x[int(np.argmax(load))]))
        curves[f"x_s{seed}"], curves[f"load_kN_s{seed}"] = x, load
    mean, cv = mean_cv(peaks)
    row = {"specimen": name, "peak_load_kN": mean, "cv": cv,
           "seeds": len(peaks), "min_kN": min(peaks), "max_kN": max(peaks), "x_at_peak": statistics.mean(at),
           "x_label": b.x_label, "calibration": "docs/calibration.md"}
    io.write_table(os.path.join(out, "predictions.csv"), [row], COLUMNS)
    n = max(len(v) for v in curves.values())
    io.write_table(os.path.join(out, "curves.csv"),
                   [{k: (f"{v[i]:.6g}" if i < len(v) else "") for k, v in curves.items()} for i in range(n)],
                   list(curves))
    _figure(out, name, curves, seeds, b.x_label)
    cracks = os.path.join(out, "cases", "s1", "cracks.png")
    if os.path.exists(cracks):
        shutil.copyfile(cracks, os.path.join(out, "cracks.png"))
    return row


def _figure(out: str, name: str, curves: dict, seeds: int, x_label: str) -> None:
    from .. import plots
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4))
    for seed in range(1, seeds + 1):
        ax.plot(curves[f"x_s{seed}"], curves[f"load_kN_s{seed}"], lw=1, label=f"seed {seed}")
    ax.set_xlabel(x_label)
    ax.set_ylabel("load [kN]")
    ax.set_title(f"{name}: blind prediction, {seeds} specimens")
    ax.legend(fontsize=8)
    plots.save(fig, os.path.join(out, "curves.png"))


def add_arguments(v) -> None:
    v.add_argument("name", choices=sorted(SPECIMENS), metavar="NAME", help=", ".join(sorted(SPECIMENS)))
    v.add_argument("--calibrate-only", action="store_true", help="OUT/material.json only: run no specimen")
    add_seeds(v, "prediction")
    v.add_argument("--jobs", type=int, default=1, metavar="J", help="runs at a time, one thread each")
    v.add_argument("--root", default=".", metavar="DIR", help="the repository, whose examples/ hold the files")
    v.add_argument("--out", default="", metavar="OUT", help="the folder (default: ROOT/results/validation/NAME)")


def cmd_validation(args) -> int:
    out = args.out or os.path.join(args.root, "results", "validation", args.name)
    log = lambda s: print(s, flush=True)  # noqa: E731
    if args.calibrate_only:
        material(args.root, args.name, out, log)
    else:
        print(predict(args.root, args.name, out, seed_count(args), args.jobs, log))
    return 0


register(Study("validation", "blind predictions of laboratory tests: a specimen file, its concrete calibrated, "
                             "six specimens past their peak", add_arguments, cmd_validation))
