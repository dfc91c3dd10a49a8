"""Where a mesh or refinement study finds its cases: finished in its own
folder, finished in a reference study's folder, or as rows of an earlier
run's cases.csv (a committed study keeps its tables, not its case folders);
the rest are run in its folder. A case's row is case_row with its role,
variant, module and correlation length (MESH_CASE_COLUMNS)."""
from __future__ import annotations

import os
from typing import List, Sequence, Tuple

from .. import io
from ..cube import CubeTest
from .cases import case_dir, is_finished, load_summary
from .executors import run_cases
from .tables import CASE_COLUMNS, case_row

MESH_CASE_COLUMNS = ("role", "variant", "module_m", "corr_length_m") + CASE_COLUMNS


def _dirs(tests: Sequence[CubeTest], out: str, references: Sequence[str]) -> List[tuple]:
    """(folder, found) per test: the first reference study holding it finished
    (found True), else its folder in out."""
    def where(t):
        for ref in references:
            if is_finished(case_dir(ref, t), t):
                return case_dir(ref, t), True
        return case_dir(out, t), False
    return [where(t) for t in tests]


def run_located(tests, out: str, references: Sequence[str] = (), run: bool = True, **kw) -> List[tuple]:
    """(summary, folder) of each test, those not finished in a reference study
    run in out (unless run is False: then summary None for a case not
    finished yet)."""
    dirs = _dirs(tests, out, references)
    mine = [t for t, (_, found) in zip(tests, dirs) if not found]
    if run and mine:
        run_cases(mine, out, **kw)
    return [(load_summary(d) if is_finished(d, t) else None, d) for t, (d, _) in zip(tests, dirs)]


def finished_rows(tests: Sequence[CubeTest], roles: Sequence[tuple], out: str, references: Sequence[str] = (),
                  earlier: Sequence[dict] = (), run: bool = True, **kw) -> Tuple[List[dict], int]:
    """The cases.csv rows of the finished tests, in their order, and how many
    of them are kept from `earlier`, the rows of an earlier run's cases.csv
    (a committed study keeps its tables, not its case folders): those cases
    are not run again and enter the tables as they are. roles: (role,
    variant) per test; the others are found or run as run_located does."""
    kept = {_row_key(r): r for r in earlier}
    keys = [_test_key(t, variant) for t, (_, variant) in zip(tests, roles)]
    fresh = iter(run_located([t for t, k in zip(tests, keys) if k not in kept], out, references, run=run, **kw))
    rows = []
    for k, (role, variant) in zip(keys, roles):
        if k in kept:
            rows.append(kept[k])
            continue
        s, folder = next(fresh)
        if s is not None:
            rows.append(mesh_row(role, variant, s, folder))
    return rows, sum(k in kept for k in keys)


def _test_key(t: CubeTest, variant: str) -> tuple:
    """What tells a case from another in cases.csv: variant, load, seed, size,
    module, correlation length, damping and strain rate."""
    return _key(variant, t.load, t.seed, t.size, t.L0, t.corr_length, t.zeta, t.strain_rate)


def _row_key(r: dict) -> tuple:
    return _key(r["variant"], r["load"], r["seed"], r["size_m"], r["module_m"], r["corr_length_m"], r["zeta"],
                r["strain_rate"])


def _key(variant, load, seed, *numbers) -> tuple:
    return (variant, load, int(seed)) + tuple(round(float(x), 12) for x in numbers)


def read_earlier(folder: str, files: Sequence[str] = ("cases.csv",)) -> List[dict]:
    """The rows of cases.csv in an earlier study folder ([] for no folder),
    after checking that folder has every one of `files`."""
    if not folder:
        return []
    for name in files:
        if not os.path.isfile(os.path.join(folder, name)):
            raise ValueError(f"--earlier {folder}: no {name} in it (the folder of an earlier run of this study)")
    return io.read_table(os.path.join(folder, "cases.csv"))


def mesh_row(role: str, variant: str, summary: dict, folder: str = "") -> dict:
    """case_row with the case's role (fine, coarse, law), variant, module and
    correlation length; `dir`, its folder, is not a column."""
    p = summary["parameters"]
    return {"role": role, "variant": variant, "module_m": p["L0"], "corr_length_m": p["corr_length"],
            **case_row(summary), "dir": folder}
