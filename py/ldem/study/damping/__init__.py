"""The damping study: one specimen at several damping ratios (the study's
2 % and 200 % on the 0.96 m cube); damping.csv and a figure per load."""
from __future__ import annotations

import os
from typing import List, Optional, Sequence

from ... import io
from ...cube import CubeTest
from ..cases import load_case
from ..settings import damping_tests
from ..executors import run_cases
from ..options import (add_common, check_tests, common_settings, parse_floats, parse_loads,
                       parameter_option, values_option)
from ..registry import Study, register
from ..tables import CASE_COLUMNS, case_row


def run_damping(tests: Sequence[CubeTest], out: str, jobs: int = 1, scheduler: Optional[str] = None,
                progress: Optional[bool] = None, report: bool = True, figure_format: str = "png") -> List[dict]:
    """Runs the cases not finished yet, writes damping.csv and (with report) the
    figures; returns the rows."""
    summaries = run_cases(tests, out, jobs=jobs, scheduler=scheduler, progress=progress)
    rows = [case_row(s) for s in summaries]
    io.write_table(os.path.join(out, "damping.csv"), rows, CASE_COLUMNS)
    if report:
        from ... import report as figures

        figures.damping_figures(out, [load_case(out, t) for t in tests], figure_format)
    return rows


def add_arguments(d) -> None:
    add_common(d)
    parameter_option(d, "size", default=0.96)
    parameter_option(d, "seed")
    values_option(d, "zeta", "--zetas", (0.02, 2), " (above 1: overcritical)")


def cmd_damping(args) -> int:
    zetas = parse_floats(args.zetas, "--zetas")
    if any(z < 0 for z in zetas):
        raise ValueError("damping ratios must be >= 0")
    common = common_settings(args)
    if "zeta" in common:
        raise ValueError("--set zeta: the damping study sets it (use --zetas)")
    tests = damping_tests(args.size, zetas, parse_loads(args.loads), seed=args.seed, **common)
    check_tests(tests)
    rows = run_damping(tests, args.out, jobs=args.jobs, scheduler=args.scheduler,
                       progress=False if args.no_progress else None, report=not args.no_report,
                       figure_format=args.figure_format)
    for r in rows:
        print(f"  {r['load']:10s} zeta {r['zeta']:g}: peak {r['peak_stress_MPa']:.4f} MPa at "
              f"{r['strain_at_peak']:.4e}, U_num/U_min "
              + (f"{r['U_ratio']:.3f}" if r["separated"] else "(not separated)"))
    return 0


register(Study("damping", "one cube at several damping ratios (default: 0.96 m, 2 % and 200 %)",
               add_arguments, cmd_damping))
