"""The size-effect study (LDEM_SPEC section 6): sizes x seeds x loads, to
separation; its tables (cases.csv, summary.csv), the fractal fit
(fractal.json) and the report (report.md and figures)."""
from __future__ import annotations

import json
import os
from typing import Optional, Sequence

from .. import io
from ..cube import CubeTest
from .cases import load_case, load_curves, read_discussion
from .executors import run_cases
from .tables import CASE_COLUMNS, SUMMARY_COLUMNS, aggregate, case_row, fractal_fits

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
    from .. import report

    damping_csv = os.path.join(out, "damping.csv")
    report.size_effect_report(out, [load_case(out, t) for t in tests], rows, table, fits,
                              damping_rows=io.read_table(damping_csv) if os.path.exists(damping_csv) else None,
                              discussion=read_discussion(out) or None, fmt=fmt)
