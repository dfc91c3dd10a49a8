"""The damping study: one specimen at several damping ratios (the study's
2 % and 200 % on the 0.96 m cube); damping.csv and a figure per load."""
from __future__ import annotations

import os
from typing import List, Optional, Sequence

from .. import io
from ..cube import CubeTest
from .cases import load_case
from .executors import run_cases
from .tables import CASE_COLUMNS, case_row


def run_damping(tests: Sequence[CubeTest], out: str, jobs: int = 1, scheduler: Optional[str] = None,
                progress: Optional[bool] = None, report: bool = True, figure_format: str = "png") -> List[dict]:
    """Runs the cases not finished yet, writes damping.csv and (with report) the
    figures; returns the rows."""
    summaries = run_cases(tests, out, jobs=jobs, scheduler=scheduler, progress=progress)
    rows = [case_row(s) for s in summaries]
    io.write_table(os.path.join(out, "damping.csv"), rows, CASE_COLUMNS)
    if report:
        from .. import report as figures

        figures.damping_figures(out, [load_case(out, t) for t in tests], figure_format)
    return rows
