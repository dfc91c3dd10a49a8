"""What the studies' command lines share: the options every cube study takes,
the options of a parameter (from the parameter table, pkg/ldem/Parameters.hpp,
as `ldem cube`'s), and the checks of their values before anything runs."""
from __future__ import annotations

import argparse
import dataclasses
from typing import List, Sequence

from ..cube import CubeTest
from ..helptext import add_output_flags, add_parameter_option, parameter_help, settings
from .executors import default_threads

FIELDS = {f.name: f for f in dataclasses.fields(CubeTest)}  # one per row of the parameter table
LOADS = FIELDS["load"].metadata["choices"]  # the load parameter's choices


def parameter_option(p: argparse.ArgumentParser, name: str, option: str = "", note: str = "", **kw) -> None:
    """The option of the parameter `name` with its table's type, unit, help and
    domain (note: what the study adds; kw: a study's default)."""
    add_parameter_option(p, FIELDS[name], option, note, **kw)


def values_option(p: argparse.ArgumentParser, name: str, option: str, values: Sequence[float], note: str = "",
                  **kw) -> None:
    """An option that takes several values of the parameter `name`, comma-separated
    (default: `values`), said with the table's help, unit and domain."""
    p.add_argument(option, default=",".join(f"{v:g}" for v in values),
                   help=f"comma-separated values of {name}, " + parameter_help(FIELDS[name], note, "each "), **kw)


def parse_floats(text: str, what: str) -> List[float]:
    try:
        values = [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise ValueError(f"{what} must be a comma-separated list of numbers (got '{text}')") from None
    if not values:
        raise ValueError(f"{what} is empty")
    return values


def parse_names(text: str, known, what: str, expected: str) -> List[str]:
    """A comma-separated list of names, each one of `known` (else: unknown `what`, expected ...)."""
    out = [x.strip() for x in text.split(",") if x.strip()]
    for x in out:
        if x not in known:
            raise ValueError(f"unknown {what} '{x}' (expected {expected})")
    return out


def parse_loads(text: str) -> List[str]:
    """A comma-separated list of the load parameter's choices."""
    return parse_names(text, LOADS, "load", " or ".join(LOADS))


def add_loads(p: argparse.ArgumentParser, default: str = ",".join(LOADS)) -> None:
    p.add_argument("--loads", default=default, help=f"comma-separated loads, of: {', '.join(LOADS)}")


def seed_count(args) -> int:
    if args.seeds < 1:
        raise ValueError(f"--seeds must be at least 1 (got {args.seeds})")
    return args.seeds


def study_settings(pairs: Sequence[str]) -> dict:
    """--set NAME=VALUE pairs as CubeTest fields of the right type."""
    out = settings(pairs)
    for name in ("size", "load", "seed"):
        if name in out:
            raise ValueError(f"--set {name}: the study sets it (use its own options)")
    return out


def common_settings(args) -> dict:
    """The settings every case of the study gets. Threads per case: --threads;
    0 means the library's rule for one case at a time (threads = 0: one per
    50,000 bars, up to the free cores: the 0.12 m cubes' 3,150 bars ran 2.3-2.7 times
    slower on two threads than on one), this machine's cores over --jobs for
    several, or, on a dask cluster, one thread per case (dask runs cases side by
    side on the workers, whose cores are not this machine's)."""
    if args.threads > 0:
        threads = args.threads
    elif args.scheduler:
        threads = 1
    else:
        threads = 0 if args.jobs == 1 else default_threads(args.jobs)
    return {"threads": threads, "strain_rate": args.strain_rate, **study_settings(args.set)}


def run_options(args) -> dict:
    return {"jobs": args.jobs, "scheduler": args.scheduler, "progress": False if args.no_progress else None}


def check_tests(tests: Sequence) -> None:
    """Every case's input checked before anything runs."""
    for t in tests:
        t.params()


def add_common(q: argparse.ArgumentParser) -> None:
    """The options of every study of cubes (size-effect, damping, mesh, refinement)."""
    q.add_argument("--out", required=True, metavar="DIR", help="study folder (cases/, tables, figures, report)")
    add_loads(q)
    q.add_argument("--jobs", type=int, default=1, metavar="J", help="cases run at once in separate processes")
    q.add_argument("--threads", type=int, default=0, metavar="T",
                   help="OpenMP threads per case (0: one job: one per 50,000 bars up to the free cores; "
                        "several: this machine's cores / jobs; with --scheduler, 1)")
    q.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="send cases to this dask.distributed scheduler instead (e.g. tcp://host:8786)")
    parameter_option(q, "strain_rate")
    q.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                   help="any other CubeTest parameter for every case, e.g. --set bottom_lateral=free "
                        "(repeatable; see ldem cube --help)")
    q.add_argument("--no-report", action="store_true", help="tables only: no figures, no report.md")
    add_output_flags(q)


def add_seeds(q: argparse.ArgumentParser, what: str = "case") -> None:
    q.add_argument("--seeds", type=int, default=6, help=f"random specimens per {what} (seeds 1..N)")


def add_rerun_options(q: argparse.ArgumentParser, earlier: str) -> None:
    """--report-only and --earlier (earlier: what an earlier run's folder gives)."""
    q.add_argument("--report-only", action="store_true", help="run nothing: tables and report of the finished cases")
    q.add_argument("--earlier", default="", metavar="DIR",
                   help="the folder of an earlier run (a committed study keeps its tables, not its case folders): "
                        + earlier)
