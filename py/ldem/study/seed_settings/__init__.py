"""The settings the reference study does not report, one at a time: what each
does to the uniform cube's peak and its strain at 0.12 and 0.96 m, against
Table 3's flat peaks (LDEM_SPEC section 6).

The study gives no strain rate ("constant strain rate", a displacement that
"increases smoothly in time"), nor the mode its damping ratio is stated on,
nor the upper nodes' lateral freedom, nor how its Weibull field of G_f is drawn
(per bar or per module, correlation length, lower bound). Each setting
is a family of variants of the cube's quasi-static default ("base", variants.py); every run
stops past its peak (stop_at past_peak at PEAK_STOP_RATIO x the strain at the
peak so far), where the peak and its strain are known.

    ldem study seed-settings --out DIR [--sizes 0.12,0.96] [--seeds 3] [--settings rate,damping,..] [--jobs J]

writes DIR/cases/ (a folder per run), runs.csv (a row per run),
sensitivity.csv and sensitivity.md (per variant: the means at each size, the
ratio of the largest to the smallest size's peak, their change against base)
and ratio.png (that ratio against each variant, beside Table 3's)."""
from __future__ import annotations

import dataclasses
import json
import os
import sys
from typing import Callable, List, Sequence

from ... import io
from ..cases import case_name
from ..executors import default_threads, run_cases
from ..options import (add_seeds, check_tests, parse_floats, parse_loads, parse_names, parameter_option,
                       seed_count)
from ..settings import size_effect_tests
from ..size_effect import run_size_effect
from ..registry import Study, register
from .fit import fit_overrides, fit_table, fit_variant, parse_grid, parse_point, run_fit
from .proposal import proposal_table, run_proposal
from .tables import ratio_figure, run_rows, sensitivity, sensitivity_table, study_comparison
from .variants import SETTINGS, SIZES, plan

NAMES = [s for s in SETTINGS if s != "base"]  # the settings one may ask for; base is always run


def run_seed_settings(settings: Sequence[str], sizes: Sequence[float], seeds: Sequence[int], out: str, jobs: int = 1,
                      threads: int = 0, fmt: str = "png", log: Callable[[str], None] = print) -> List[dict]:
    """Runs the unfinished cases; writes runs.csv, sensitivity.csv/.md and the figure; returns the sensitivity rows."""
    pairs, tests = plan(settings, sizes, seeds, threads)
    check_tests(tests)
    summaries = {case_name(t): s for t, s in zip(tests, run_cases(tests, out, jobs=jobs, log=log))}
    rows = run_rows(pairs, summaries)
    io.write_table(os.path.join(out, "runs.csv"), rows, list(rows[0]))
    sens = sensitivity(rows)
    io.write_table(os.path.join(out, "sensitivity.csv"), sens, list(sens[0]))
    io.write_text(os.path.join(out, "sensitivity.md"), sensitivity_table(sens))
    ratio_figure(sens, os.path.join(out, "ratio"), fmt)
    return sens


def run_fitted_study(point: dict, sizes: Sequence[float], seeds: int, loads: Sequence[str], out: str, jobs: int = 1,
                     threads: int = 0, fmt: str = "png") -> tuple:
    """The size-effect study's cases (settings.size_effect_tests: stops, tails) with
    the fitted point's parameters at each size; its tables, fractal fit and report."""
    overrides = fit_variant(point).overrides
    tests = [dataclasses.replace(t, **overrides(t.size))
             for t in size_effect_tests(sizes, seeds, loads, threads=threads or default_threads(jobs))]
    check_tests(tests)
    return run_size_effect(tests, out, jobs=jobs, progress=False, figure_format=fmt)


def write_comparison(reference: str, out: str) -> str:
    """comparison.md in out: the study there against the one in reference (each folder's summary.csv and
    fractal.json, as ldem study size-effect writes them)."""
    def d(folder):
        with open(os.path.join(folder, "fractal.json")) as f:
            return json.load(f)["uniform"]["d"]
    text = study_comparison(io.read_table(os.path.join(reference, "summary.csv")),
                            io.read_table(os.path.join(out, "summary.csv")), d(reference), d(out))
    io.write_text(os.path.join(out, "comparison.md"), text)
    return text


def add_arguments(a) -> None:
    a.add_argument("--out", required=True, metavar="DIR",
                   help="study folder (cases/, runs.csv, sensitivity.csv, sensitivity.md, ratio.png)")
    a.add_argument("--sizes", default=",".join(f"{s:g}" for s in SIZES),
                   help="comma-separated cube sizes [m]; the ratio is the largest's peak over the smallest's")
    add_seeds(a, "size and variant")
    a.set_defaults(seeds=3)
    a.add_argument("--settings", default=",".join(NAMES),
                   help="comma-separated settings, each a family of variants beside base, of: " + ", ".join(NAMES))
    a.add_argument("--jobs", type=int, default=1, metavar="J", help="cases run at once in separate processes")
    parameter_option(a, "threads", note="; per case")
    a.add_argument("--figure-format", default="png", choices=("png", "pdf", "svg"), help="format of the figure")
    a.add_argument("--study", action="store_true",
                   help="run no sensitivity study: the whole size-effect study (ldem study size-effect's cases; "
                        "give its sizes and seeds: --sizes 0.12,0.24,0.48,0.72,0.96 --seeds 6) with the --hold "
                        "settings")
    a.add_argument("--hold", action="append", default=[], metavar="NAME=VALUE",
                   help="--fit, --study: a setting of every case (repeatable; strain_rate and rate_periods: a "
                        "constant drive, rate_periods at each cube's own omega_1; a choice by its name, "
                        "bottom_lateral=free)")
    a.add_argument("--loads", default="uniform,triangular", help="--study: comma-separated loads")
    a.add_argument("--reference", default="", metavar="DIR",
                   help="--study: a size-effect study's folder (its summary.csv and fractal.json, e.g. "
                        "results/size-effect) to set beside this one, table by table, in comparison.md")
    a.add_argument("--proposal", default="", metavar="DIR",
                   help="run no sensitivity study: the study's proposal for coarse meshes (the mesh study's "
                        "criterion) with the --hold settings, modules of --module on the largest of --sizes, "
                        "against the fine cubes of the --study run in DIR; writes proposal.md and proposal.json")
    a.add_argument("--module", type=float, default=0.06, metavar="L", help="--proposal: the coarse module [m]")
    a.add_argument("--fit", action="append", default=[], metavar="NAME=V1,V2,...",
                   help="run no sensitivity study: fit this parameter (once or twice: at most two) on these values "
                        "to Table 3's five sizes (strain_rate and rate_periods: a constant drive); writes fit.csv, "
                        "fit.md, fit_runs.csv")


def cmd_seed_settings(args) -> int:
    held = parse_point(args.hold)
    if args.proposal:
        r = run_proposal(held, args.proposal, args.out, module=args.module,
                         size=max(parse_floats(args.sizes, "--sizes")), seeds=seed_count(args), jobs=args.jobs,
                         threads=args.threads or 1)
        print(proposal_table(r), end="")
        return 0
    if args.study:
        if args.reference and not os.path.isfile(os.path.join(args.reference, "summary.csv")):
            raise ValueError(f"--reference {args.reference}: no summary.csv there (a size-effect study's folder)")
        run_fitted_study(held, parse_floats(args.sizes, "--sizes"), seed_count(args), parse_loads(args.loads),
                         args.out, args.jobs, args.threads, args.figure_format)
        if args.reference:
            print(write_comparison(args.reference, args.out), end="")
        return 0
    if args.fit:
        grid = parse_grid(args.fit)
        for name, values in grid.items():
            for v in values:
                fit_overrides(name, v)
        fit = run_fit(grid, range(1, seed_count(args) + 1), args.out, jobs=args.jobs, threads=args.threads,
                      held=held, log=lambda s: print(s, file=sys.stderr))
        print(fit_table(fit), end="")
        return 0
    names = parse_names(args.settings, NAMES, "setting", "some of " + ", ".join(NAMES))
    sizes = parse_floats(args.sizes, "--sizes")
    if len(sizes) < 2:
        raise ValueError("--sizes needs at least two sizes: the study compares the largest with the smallest")
    sens = run_seed_settings(names, sizes, range(1, seed_count(args) + 1), args.out, args.jobs, args.threads,
                             args.figure_format, log=lambda s: print(s, file=sys.stderr))
    print(sensitivity_table(sens), end="")
    return 0


register(Study("seed-settings", "the settings the study does not report, one at a time: the uniform cube's peak "
                                "and its strain at 0.12 and 0.96 m against Table 3", add_arguments,
               cmd_seed_settings))
