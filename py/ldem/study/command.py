"""`ldem study size-effect` and `ldem study damping`: options, input checks,
the printed summary."""
from __future__ import annotations

import argparse
import time
from typing import List, Sequence

from ..helptext import HelpFormatter, add_output_flags
from ..cube import CubeTest, settings
from .cases import damping_tests, size_effect_tests
from .damping import run_damping
from .executors import default_threads
from .size_effect import STUDY_SIZES, run_size_effect


def _floats(text: str, what: str) -> List[float]:
    try:
        values = [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise ValueError(f"{what} must be a comma-separated list of numbers (got '{text}')") from None
    if not values:
        raise ValueError(f"{what} is empty")
    return values


def _loads(text: str) -> List[str]:
    loads = [x.strip() for x in text.split(",") if x.strip()]
    for ld in loads:
        if ld not in ("uniform", "triangular"):
            raise ValueError(f"unknown load '{ld}' (expected uniform or triangular)")
    return loads


def _settings(pairs: Sequence[str]) -> dict:
    """--set NAME=VALUE pairs as CubeTest fields of the right type."""
    out = settings(pairs)
    for name in ("size", "load", "seed"):
        if name in out:
            raise ValueError(f"--set {name}: the study sets it (use its own options)")
    return out


def _common(args) -> dict:
    """The settings every case of the study gets. Threads per case: --threads;
    0 means this machine's cores over --jobs, or, on a dask cluster, one thread
    per case (dask runs cases side by side on the workers, whose cores are not
    this machine's)."""
    if args.threads > 0:
        threads = args.threads
    else:
        threads = 1 if args.scheduler else default_threads(args.jobs)
    return {"threads": threads, "strain_rate": args.strain_rate, **_settings(args.set)}


def _check_tests(tests: Sequence[CubeTest]) -> None:
    """Every case's input checked before anything runs."""
    for t in tests:
        t.params()


def cmd_size_effect(args) -> int:
    sizes = _floats(args.sizes, "--sizes")
    if args.seeds < 1:
        raise ValueError(f"--seeds must be at least 1 (got {args.seeds})")
    tests = size_effect_tests(sizes, args.seeds, _loads(args.loads), **_common(args))
    _check_tests(tests)
    t0 = time.perf_counter()
    table, fits = run_size_effect(tests, args.out, jobs=args.jobs, scheduler=args.scheduler,
                                  progress=False if args.no_progress else None, report=not args.no_report,
                                  figure_format=args.figure_format)
    print(f"study: {len(tests)} cases in {time.perf_counter() - t0:.0f} s; wrote {args.out}/summary.csv, cases.csv"
          + ("" if args.no_report else ", report.md and figures"))
    for r in table:
        print(f"  {r['load']:10s} {r['size_m']:.2f} m: peak {r['peak_stress_MPa_mean']:.3f} MPa "
              f"(cv {r['peak_stress_MPa_cv']:.3f}) at {r['strain_at_peak_mean']:.3e}, "
              + (f"U_num/U_min {r['U_ratio_mean']:.3f}" if r["separated"] else "U_num -")
              + f" ({r['separated']} of {r['seeds']} separated), at load loss "
              + (f"{r['U_loss_ratio_mean']:.3f}" if r["U_loss_ratio_mean"] != "" else "-")
              + f", cheapest cut {r['U_mincut_ratio_mean']:.3f}"
              + (f", {r['energy_errors']} ENERGY ERRORS" if r["energy_errors"] else ""))
    for load, fit in fits.items():
        print(f"  fractal fit ({load}): d = {fit['d']:.3f} (energy per unit area: b^{fit['d_specific']:.3f})")
    return 0


def cmd_damping(args) -> int:
    zetas = _floats(args.zetas, "--zetas")
    if any(z < 0 for z in zetas):
        raise ValueError("damping ratios must be >= 0")
    common = _common(args)
    if "zeta" in common:
        raise ValueError("--set zeta: the damping study sets it (use --zetas)")
    tests = damping_tests(args.size, zetas, _loads(args.loads), seed=args.seed, **common)
    _check_tests(tests)
    rows = run_damping(tests, args.out, jobs=args.jobs, scheduler=args.scheduler,
                       progress=False if args.no_progress else None, report=not args.no_report,
                       figure_format=args.figure_format)
    for r in rows:
        print(f"  {r['load']:10s} zeta {r['zeta']:g}: peak {r['peak_stress_MPa']:.4f} MPa at "
              f"{r['strain_at_peak']:.4e}, U_num/U_min "
              + (f"{r['U_ratio']:.3f}" if r["separated"] else "(not separated)"))
    return 0


def add_parser(sub) -> None:
    p = sub.add_parser("study", help="the size-effect and damping studies of the reference paper",
                       description="Runs many cube tests (resumable, in parallel) and aggregates them.")
    kinds = p.add_subparsers(dest="study", metavar="STUDY", parser_class=type(p))
    kinds.required = True

    def common(q):
        q.add_argument("--out", required=True, metavar="DIR", help="study folder (cases/, tables, figures, report)")
        q.add_argument("--loads", default="uniform,triangular", help="comma-separated loads")
        q.add_argument("--jobs", type=int, default=1, metavar="J", help="cases run at once in separate processes")
        q.add_argument("--threads", type=int, default=0, metavar="T",
                       help="OpenMP threads per case (0: this machine's cores / jobs; with --scheduler, 1)")
        q.add_argument("--scheduler", default=None, metavar="ADDRESS",
                       help="send cases to this dask.distributed scheduler instead (e.g. tcp://host:8786)")
        q.add_argument("--strain-rate", dest="strain_rate", type=float, default=CubeTest().strain_rate,
                       help="vertical strain rate [1/s]")
        q.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                       help="any other CubeTest parameter for every case, e.g. --set bottom_lateral=free "
                            "(repeatable; see ldem cube --help)")
        q.add_argument("--no-report", action="store_true", help="tables only: no figures, no report.md")
        add_output_flags(q)

    s = kinds.add_parser("size-effect", help="sizes x seeds x loads: tables, curves, cracks, energies, fractal fit",
                         formatter_class=HelpFormatter)
    common(s)
    s.add_argument("--sizes", default=",".join(f"{b:g}" for b in STUDY_SIZES), help="cube sides [m]")
    s.add_argument("--seeds", type=int, default=6, help="random specimens per size and load (seeds 1..N)")
    s.set_defaults(func=cmd_size_effect)

    d = kinds.add_parser("damping", help="one cube at several damping ratios (default: 0.96 m, 2 %% and 200 %%)",
                         formatter_class=HelpFormatter)
    common(d)
    d.add_argument("--size", type=float, default=0.96, help="cube side [m]")
    d.add_argument("--seed", type=int, default=1, help="the random specimen")
    d.add_argument("--zetas", default="0.02,2", help="damping ratios on the fundamental mode (above 1: overcritical)")
    d.set_defaults(func=cmd_damping)
