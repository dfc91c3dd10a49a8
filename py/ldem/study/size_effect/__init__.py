"""The size-effect study (LDEM_SPEC section 6): sizes x seeds x loads, to
separation; its tables (cases.csv, summary.csv), the fractal fit
(fractal.json) and the report (report.md and figures)."""
from __future__ import annotations

import json
import os
import time
from typing import Optional, Sequence

from ... import io
from ...markdown import num_cell
from ...cube import CubeTest
from ..cases import load_case, load_curves, read_discussion
from ..settings import TRIANGULAR_CONVERGED_COST, TRIANGULAR_STOPS, size_effect_tests
from ..executors import run_cases
from ..options import (add_common, add_seeds, check_tests, common_settings, parse_floats,
                       parse_loads, seed_count, values_option)
from ..registry import Study, register
from ..tables import CASE_COLUMNS, SUMMARY_COLUMNS, aggregate, case_row, fractal_fits

STUDY_SIZES = (0.12, 0.24, 0.48, 0.72, 0.96)


def run_size_effect(tests: Sequence[CubeTest], out: str, jobs: int = 1, scheduler: Optional[str] = None,
                    progress: Optional[bool] = None, report: bool = True, figure_format: str = "png") -> tuple:
    """Runs the cases not finished yet, writes the tables, fractal.json and
    (with report) report.md with its figures; returns (table, fits)."""
    summaries = run_cases(tests, out, jobs=jobs, scheduler=scheduler, progress=progress)
    rows = [case_row(s) for s in summaries]
    io.write_table(os.path.join(out, "cases.csv"), rows, CASE_COLUMNS)
    table = aggregate(rows, tests[0].c_a, load_curves(out, tests))
    io.write_table(os.path.join(out, "summary.csv"), table, SUMMARY_COLUMNS)
    fits = fractal_fits(table)
    io.write_text(os.path.join(out, "fractal.json"), json.dumps(fits, indent=2))
    if report:
        write_size_effect_report(out, tests, rows, table, fits, figure_format)
    return table, fits


def write_size_effect_report(out: str, tests: Sequence[CubeTest], rows, table, fits, fmt: str = "png") -> None:
    """report.md with the figures, the damping table if the damping study ran
    into the same folder, and discussion.md (hand-written) if there is one."""
    from ... import report

    damping_csv = os.path.join(out, "damping.csv")
    report.size_effect_report(out, [load_case(out, t) for t in tests], rows, table, fits,
                              damping_rows=io.read_table(damping_csv) if os.path.exists(damping_csv) else None,
                              discussion=read_discussion(out) or None, fmt=fmt)


def add_arguments(s) -> None:
    add_common(s)
    values_option(s, "size", "--sizes", STUDY_SIZES)
    add_seeds(s, "size and load")
    s.add_argument("--triangular-stop", choices=TRIANGULAR_STOPS, default="past_peak",
                   help="what ends a triangular case: past_peak (default: 10 x its strain at the peak, where its "
                        "peak, curve and crack are all there), load_loss (the stress below 1 %% of the peak, "
                        "never before 10 x its strain at the peak: 2.6 times the steps at 0.96 m) or converged "
                        f"(U_final, once the fracture energy stops growing: {TRIANGULAR_CONVERGED_COST})")


def cmd_size_effect(args) -> int:
    sizes = parse_floats(args.sizes, "--sizes")
    loads = parse_loads(args.loads)
    tests = size_effect_tests(sizes, seed_count(args), loads, triangular_stop=args.triangular_stop,
                              **common_settings(args))
    check_tests(tests)
    if args.triangular_stop == "converged" and "triangular" in loads:
        print(f"study: the triangular cases run until U converges: {TRIANGULAR_CONVERGED_COST}")
    t0 = time.perf_counter()
    table, fits = run_size_effect(tests, args.out, jobs=args.jobs, scheduler=args.scheduler,
                                  progress=False if args.no_progress else None, report=not args.no_report,
                                  figure_format=args.figure_format)
    print(f"study: {len(tests)} cases in {time.perf_counter() - t0:.0f} s; wrote {args.out}/summary.csv, cases.csv"
          + ("" if args.no_report else ", report.md and figures"))
    for r in table:
        print(f"  {r['load']:10s} {r['size_m']:.2f} m: peak {r['peak_stress_MPa_mean']:.3f} MPa "
              f"(cv {num_cell(r['peak_stress_MPa_cv'], '.3f')}) at {r['strain_at_peak_mean']:.3e}, "
              + (f"U_num/U_min {r['U_ratio_mean']:.3f}" if r["separated"] else "U_num -")
              + f" ({r['separated']} of {r['seeds']} separated), at load loss "
              + (f"{r['U_loss_ratio_mean']:.3f}" if r["U_loss_ratio_mean"] != "" else "-")
              + f", at the end {r['U_end_ratio_mean']:.3f}, cheapest cut {r['U_mincut_ratio_mean']:.3f}"
              + (f", {r['energy_errors']} ENERGY ERRORS" if r["energy_errors"] else ""))
    for load, fit in fits.items():
        print(f"  fractal fit ({load}): d = {fit['d']:.3f} (energy per unit area: b^{fit['d_specific']:.3f})")
    return 0


register(Study("size-effect", "sizes x seeds x loads: tables, curves, cracks, energies, fractal fit",
               add_arguments, cmd_size_effect))
