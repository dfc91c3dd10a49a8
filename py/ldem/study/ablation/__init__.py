"""Why the large uniform cubes are weaker: one factor at a time on a cube
(both loads), each run stopped past its peak. Per run: peak, its strain,
damaged and broken bars at the peak (pre-peak nonlinearity) and where the
damage is (mean height of the damaged-or-broken bars over H, and the share
within one module of the lower face), kept in the case's summary.json under
"ablation"; ablation.jsonl (a line per run) and the markdown table of the
means per load and variant, against "base".

    ldem study ablation --out DIR [--size 0.48] [--seeds 3] [--loads L,..] [--variants V,..] [--jobs J]
    ldem study ablation --table RUNS.jsonl      the markdown table of those runs"""
from __future__ import annotations

import json
import os
import sys
from typing import Callable, List, Sequence

import numpy as np

from ... import _core, io
from ...cube import CubeTest
from ..options import add_loads, add_seeds, check_tests, parameter_option, parse_loads, parse_names, seed_count
from ..cases import Named, case_name
from ..executors import run_cases
from ..registry import Study, register

VARIANTS = {"base": {}, "rollers": {"bottom_lateral": "free"}, "rate/2": {"strain_rate": 0.01},
            "rate*2": {"strain_rate": 0.04}, "no smooth start": {"ramp_time": 1e-9},
            "G_f per module": {"Gf_draw": "module"}}
RUNS = [(ld, v) for ld in ("uniform", "triangular") for v in VARIANTS]


class AblationCube(Named):
    """The CubeTest of one variant as a study case: its summary also says
    where its damage is (the "ablation" entry); its folder is the cube's."""

    def __init__(self, variant: str, **cube):
        self.variant, self.cube = variant, CubeTest(**cube)
        super().__init__(self.cube, case_name(self.cube))

    def describe(self) -> str:
        return f"{self.cube.describe()}, {self.variant}"

    def run(self, observers=(), simulation=None, previous_rows=()):
        result = self.cube.run(observers, simulation, previous_rows)
        result.summary["ablation"] = damage_at_peak(self.cube, self.variant, result)
        return result


def damage_at_peak(test: CubeTest, variant: str, result) -> dict:
    """The run's numbers of the ablation table."""
    s, c, sim = result.summary, result.curve, result.sim
    i = int(np.argmin(np.abs(c["mean_strain"] - s["strain_at_peak"])))
    bars = sim.lattice.bar_table()
    z0 = np.asarray(sim.lattice.z0)
    hurt = np.asarray(sim.damage_state) != _core.UNDAMAGED  # kappa > eps_p, whatever the law
    zmid = 0.5 * (z0[bars["n1"]] + z0[bars["n2"]]) / test.size
    return {"load": test.load, "variant": variant, "seed": test.seed, "peak_MPa": s["peak_stress_MPa"],
            "strain_at_peak": s["strain_at_peak"], "damaged_at_peak": int(c["damaged_bars"][i]),
            "broken_at_peak": int(c["broken_bars"][i]), "end_strain": float(c["mean_strain"][-1]),
            "hurt_mean_height": float(zmid[hurt].mean()) if hurt.any() else None,
            "hurt_share_lowest_module": float((zmid[hurt] < 1.0 / test.modules()).mean()) if hurt.any() else None,
            "energy_error": s["energy_balance_error"]}


def ablation_tests(size: float, seeds: Sequence[int], threads: int = 0, runs=RUNS) -> List[AblationCube]:
    return [AblationCube(name, size=size, load=load, seed=seed, threads=threads, stop_at="load_loss",
                         final_strain=3e-4 if load == "uniform" else 2e-4, **VARIANTS[name])
            for load, name in runs for seed in seeds]


def run_ablation(tests: Sequence[AblationCube], out: str, jobs: int = 1,
                 log: Callable[[str], None] = print) -> List[dict]:
    """Runs the unfinished cases; writes ablation.jsonl and ablation.md; returns the runs' rows."""
    runs = [s["ablation"] for s in run_cases(tests, out, jobs=jobs, log=log)]
    io.write_text(os.path.join(out, "ablation.jsonl"), "".join(json.dumps(r) + "\n" for r in runs))
    io.write_text(os.path.join(out, "ablation.md"), ablation_table(runs))
    return runs


def read_runs(path: str) -> List[dict]:
    with open(path) as f:
        return [json.loads(line) for line in f]


def ablation_table(runs: Sequence[dict]) -> str:
    """Per load and variant, the means over the seeds and their change against base."""
    lines = ["| load | variant | seeds | peak [MPa] | change | strain at peak | change | damaged / broken bars at "
             "the peak | energy error (max) |", "|---|---|---|---|---|---|---|---|---|"]
    for load in dict.fromkeys(r["load"] for r in runs):
        group = lambda v: [r for r in runs if r["load"] == load and r["variant"] == v]  # noqa: E731
        base = group("base")
        b_peak, b_strain = np.mean([r["peak_MPa"] for r in base]), np.mean([r["strain_at_peak"] for r in base])
        for v in dict.fromkeys(r["variant"] for r in runs if r["load"] == load):
            g = group(v)
            peak, strain = np.mean([r["peak_MPa"] for r in g]), np.mean([r["strain_at_peak"] for r in g])
            lines.append(f"| {load} | {v} | {len(g)} | {peak:.4f} | {100 * (peak / b_peak - 1):+.1f} % | "
                         f"{strain:.3e} | {100 * (strain / b_strain - 1):+.1f} % | "
                         f"{np.mean([r['damaged_at_peak'] for r in g]):.0f} / "
                         f"{np.mean([r['broken_at_peak'] for r in g]):.0f} | {max(r['energy_error'] for r in g):.1e} |")
    return "\n".join(lines) + "\n"


def add_arguments(a) -> None:
    a.add_argument("--out", default="", metavar="DIR", help="study folder (cases/, ablation.jsonl, ablation.md); "
                                                            "required to run")
    parameter_option(a, "size", default=0.48)
    add_seeds(a, "load and variant")
    a.set_defaults(seeds=3)
    add_loads(a)
    a.add_argument("--variants", default=",".join(VARIANTS), help=f"comma-separated, of: {', '.join(VARIANTS)}")
    a.add_argument("--jobs", type=int, default=1, metavar="J", help="cases run at once in separate processes")
    parameter_option(a, "threads", note="; per case")
    a.add_argument("--table", default="", metavar="RUNS.jsonl", help="run nothing: print the table of those runs")


def cmd_ablation(args) -> int:
    """Prints one JSON line per run (also in OUT/ablation.jsonl) and the table (OUT/ablation.md)."""
    if args.table:
        print(ablation_table(read_runs(args.table)), end="")
        return 0
    if not args.out:
        raise ValueError("--out DIR: the study folder (or --table RUNS.jsonl)")
    variants = parse_names(args.variants, VARIANTS, "variant", "some of " + ", ".join(VARIANTS))
    runs = [(ld, v) for ld in parse_loads(args.loads) for v in variants]
    tests = ablation_tests(args.size, range(1, seed_count(args) + 1), args.threads, runs)
    check_tests([t.cube for t in tests])
    rows = run_ablation(tests, args.out, args.jobs, log=lambda s: print(s, file=sys.stderr))
    print("".join(json.dumps(r) + "\n" for r in rows) + ablation_table(rows), end="")
    return 0


register(Study("ablation", "one factor at a time on a cube, both loads, each run stopped past its peak",
               add_arguments, cmd_ablation))
