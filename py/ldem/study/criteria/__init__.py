"""Is the recorded load quasi-static? Criteria (a)-(c) of ldem.criteria on five
specimens, each at its drive and at a quarter of its rate, seeds 1..N (three
by default: (b) judges the mean of at least three pairs):

  cube_uniform, cube_triangular  the 0.48 m cube, `ldem cube`'s drive (paced),
                                 stopped at its load loss; (b)'s energy there
  d50_beam                       the Grégoire D = 50 mm beam with a notch of D/2, calibrated concrete
  eccentric_beam                 examples/eccentric_notch_beam.toml, to a deflection of 9e-4 D
  l_panel                        the L-panel at L0 = 25 mm

The beams and the panel are driven by rule (c), eps_p in RULE_PERIODS periods
(--rate-periods) of the mode the drive moves, at a constant rate, to their files' final strains
(the eccentric beam's past its peak, 4.2e-4 D); their quarter is 4 x as many
periods. OUT/cases/{specimen}_{rate|quarter}_s{seed}/, OUT/criteria.csv (a
row a run), OUT/criteria.md (a row a specimen).

    ldem study criteria [--seeds 3] [--specimens NAME,...] [--rate-periods 12] [--jobs J] [--set NAME=VALUE ...]
                        [--root .] [--out OUT]

--set changes every run (e.g. the dynamics before a change: --set
dashpot_velocity=lagged)."""
from __future__ import annotations

import math
import os
from dataclasses import dataclass
from typing import Callable, List, Optional, Sequence

import numpy as np

from ... import criteria, io
from ...cube import RATE_PERIODS, CubeTest
from ...markdown import md_table
from ...specimen import SpecimenTest
from ..cases import Named, case_dir, load_curve, load_summary
from ..executors import run_cases
from ..options import parse_names, seed_count, study_settings
from ..registry import Study, register

RULE_PERIODS = RATE_PERIODS  # rule (c) at a constant drive: eps_p in this many periods of the drive's mode
QUARTER = 0.25
TARGETS = {"a": 0.02, "peak": 0.01, "energy": 0.02}  # (a) at most; (b) the peak's and the energy's change


@dataclass(frozen=True)
class Specimen:
    name: str
    title: str
    file: str = ""  # from the repository's root; "": a cube of `size` and `load`
    load: str = "uniform"
    size: float = 0.48  # [m]
    final_strain: float = 0.0  # 0: the file's

    @property
    def unit(self) -> tuple:
        """(name, factor) of its load: a cube's stress in MPa; a file's force, in MN as its area is 1, in kN."""
        return ("kN", 1e3) if self.file else ("MPa", 1.0)

    def test(self, root: str, seed: int, rate: float, settings: dict, periods: float = RULE_PERIODS):
        """This specimen's run at `rate` times its drive's rate (a file's: rule (c) with N = periods)."""
        if not self.file:
            return CubeTest(size=self.size, load=self.load, seed=seed, stop_at="load_loss",
                            loss_stop_strain_ratio=0.0, **{**settings, "strain_rate": CubeTest.strain_rate * rate})
        more = {"final_strain": self.final_strain} if self.final_strain else {}
        return SpecimenTest.from_file(os.path.join(root, self.file),
                                      overrides={**settings, **more, "seed": seed, "rate_periods": periods / rate})


SPECIMENS = (
    Specimen("cube_uniform", "0.48 m cube, uniform"),
    Specimen("cube_triangular", "0.48 m cube, triangular", load="triangular"),
    Specimen("d50_beam", "D50 beam, notch D/2", file="examples/criteria/gregoire_d50_notch_half.toml"),
    Specimen("eccentric_beam", "eccentric-notch beam", file="examples/eccentric_notch_beam.toml", final_strain=9e-4),
    Specimen("l_panel", "L-panel (L0 25 mm)", file="examples/criteria/l_panel_coarse.toml"),
)
RATES = {"rate": 1.0, "quarter": QUARTER}
COLUMNS = ("specimen", "rate", "seed", "peak", "a", "c", "energy_J", "at_loss", "steps", "wall_s",
           "energy_balance_error", "T_s")


def plan(specimens: Sequence[Specimen], seeds: int) -> list:
    """(specimen, rate's name, seed) of every run."""
    return [(s, r, k) for s in specimens for r in RATES for k in range(1, seeds + 1)]


def cases(runs: list, root: str, settings: dict, periods: float = RULE_PERIODS) -> List[Named]:
    return [Named(s.test(root, k, RATES[r], settings, periods), f"{s.name}_{r}_s{k}", writers=["curve", "summary"])
            for s, r, k in runs]


def measured(folder: str, specimen: Specimen, rate: str, seed: int) -> dict:
    """A run's row: its peak (in the specimen's unit), (a), (c), its fracture energy at the load loss (or at
    its end) and cost."""
    s, c = load_summary(folder), load_curve(folder)
    t, F = c["time_s"], c["stress_MPa"] * specimen.unit[1]
    T = 2 * math.pi / (s.get("omega_d_rad_s") or s["omega1_rad_s"])  # the drive's mode where reported
    loss = (s.get("load_loss") or {}).get("fracture_energy_J")
    return {"specimen": specimen.name, "rate": rate, "seed": seed, "peak": float(F.max()),
            "a": criteria.ringing(t, F, T), "c": criteria.periods_after_start(t, F, T, s["ramp_time_s"]),
            "energy_J": loss if loss is not None else float(c["fracture_J"][-1]), "at_loss": loss is not None,
            "loss": loss,
            "steps": s["steps"], "wall_s": s["wall_s"], "energy_balance_error": s["energy_balance_error"], "T_s": T,
            "strain": c["mean_strain"], "fracture": c["fracture_J"]}


def _percent(x: float) -> str:
    return "-" if x is None or math.isnan(x) else f"{100 * x:.2f} %"


def _effect(e: dict) -> str:
    sem = "" if math.isnan(e["sem"]) else f" ({100 * e['sem']:.2f})"
    return f"{100 * e['mean']:+.2f} %{sem}, {e['verdict']}"


def specimen_row(s: Specimen, runs: List[dict]) -> list:
    """The table's row of one specimen: (a) and (c) at its rate (the mean and the largest (a) over the
    seeds), (b) as ldem.criteria.rate_effect judges the seeds' pairs, the same at a quarter of the rate."""
    at = {r: sorted((x for x in runs if x["specimen"] == s.name and x["rate"] == r), key=lambda x: x["seed"])
          for r in RATES}
    rate, quarter = at["rate"], at["quarter"]
    pairs = [criteria.energies_compared(a, q) for a, q in zip(rate, quarter)]
    mean = lambda rs, k: float(np.mean([x[k] for x in rs]))  # noqa: E731
    largest_a = max(x["a"] for x in rate)
    return [s.title, f"{mean(rate, 'peak'):.5g} {s.unit[0]}", f"{_percent(mean(rate, 'a'))} ({_percent(largest_a)})",
            f"{mean(rate, 'c'):.1f}",
            _effect(criteria.rate_effect([x["peak"] for x in rate], [x["peak"] for x in quarter], TARGETS["peak"])),
            _effect(criteria.rate_effect([p[0] for p in pairs], [p[1] for p in pairs], TARGETS["energy"])),
            _percent(mean(quarter, "a")), f"{mean(quarter, 'c'):.1f}", f"{mean(rate, 'steps'):,.0f}",
            f"{max(x['energy_balance_error'] for x in rate + quarter):.1e}"]


HEADER = ("specimen", "peak", "(a): mean (largest)", "(c) periods", "(b) peak: mean (SE)", "(b) energy: mean (SE)",
          "(a) at 1/4", "(c) at 1/4", "steps", "balance, largest")


def report(specimens: Sequence[Specimen], runs: List[dict], seeds: int, settings: dict,
           periods: float = RULE_PERIODS) -> str:
    changed = ", ".join(f"`{k}={v}`" for k, v in sorted(settings.items()) if k != "threads") or "none"
    return "\n".join([
        f"Criteria (a)-(c) (`ldem.criteria`), seeds 1-{seeds}, each at its drive and at a quarter of its rate "
        f"(the files' specimens: rule (c) with N = {periods:g}, and {4 * periods:g}). "
        f"Settings beside the defaults: {changed}.", "",
        md_table(HEADER, [specimen_row(s, runs) for s in specimens]), "",
        f"- (a): the rms of the load about its mean over one period of the drive's mode, in % of the peak, "
        f"from the peak to the fall and from 3 periods after it (target: at most {TARGETS['a']:.0%}); -: no "
        "record judged (the load fell below 90 % of the peak within a period of it and never below 10 %).",
        f"- (b): each seed's value at the rate over its value at a quarter of it, minus one; the mean over the "
        f"seeds and its standard error, judged against {TARGETS['peak']:.0%} (peak) and {TARGETS['energy']:.0%} "
        "(fracture energy: at the load loss for the cubes, else at the shorter run's end).",
        "- (c): periods of the drive's mode from the end of the smooth start to the peak.",
        "- peak and steps: at the rate, the mean over the seeds.", ""])


def run_criteria(out: str, root: str = ".", seeds: int = 3, specimens: Sequence[Specimen] = SPECIMENS,
                 jobs: int = 1, settings: Optional[dict] = None, log: Callable[[str], None] = print,
                 periods: float = RULE_PERIODS) -> str:
    """Runs the unfinished cases, writes OUT/criteria.csv and OUT/criteria.md; returns the table."""
    if not periods > 0:
        raise ValueError(f"--rate-periods must be positive (got {periods})")
    settings = {"threads": 1, **(settings or {})}
    missing = [s.file for s in specimens if s.file and not os.path.isfile(os.path.join(root, s.file))]
    if missing:
        raise ValueError(f"{os.path.join(root, missing[0])}: no such file: run from the ldem checkout, or give "
                         f"its folder as --root")
    todo = plan(specimens, seeds)
    tests = cases(todo, root, settings, periods)
    run_cases(tests, out, jobs=jobs, log=log)
    runs = [measured(case_dir(out, t), s, r, k) for t, (s, r, k) in zip(tests, todo)]
    io.write_table(os.path.join(out, "criteria.csv"), runs, COLUMNS)
    text = report(specimens, runs, seeds, settings, periods)
    io.write_text(os.path.join(out, "criteria.md"), text)
    return text


def add_arguments(q) -> None:
    q.add_argument("--seeds", type=int, default=3, help="random specimens per specimen and rate (seeds 1..N)")
    q.add_argument("--specimens", default=",".join(s.name for s in SPECIMENS), metavar="NAME,...",
                   help="which of " + ", ".join(s.name for s in SPECIMENS))
    q.add_argument("--rate-periods", type=float, default=RULE_PERIODS, metavar="N",
                   help="the files' specimens' drive: rule (c), eps_p in N periods of the mode the drive moves "
                        "(their quarter: 4 N)")
    q.add_argument("--jobs", type=int, default=1, metavar="J", help="runs at a time, one thread each")
    q.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                   help="any parameter of ldem cube --help for every run (repeatable)")
    q.add_argument("--root", default=".", metavar="DIR", help="the repository, whose examples/ hold the files")
    q.add_argument("--out", default="", metavar="OUT", help="the folder (default: ROOT/results/criteria)")


def cmd_criteria(args) -> int:
    args.out = args.out or os.path.join(args.root, "results", "criteria")
    known = [s.name for s in SPECIMENS]
    names = parse_names(args.specimens, known, "specimen", ", ".join(known))
    settings = study_settings(args.set)
    for k in ("seed", "rate_periods", "strain_rate", "stop_at", "final_strain"):
        if k in settings:
            raise ValueError(f"--set {k}: the study sets it")
    print(run_criteria(args.out, args.root, seed_count(args), [s for s in SPECIMENS if s.name in names],
                       args.jobs, settings, log=lambda s: print(s, flush=True), periods=args.rate_periods))
    return 0


register(Study("criteria", "is the load quasi-static: criteria (a)-(c) on five specimens at their rate and a "
                           "quarter of it, three seeds", add_arguments, cmd_criteria, description=__doc__))
