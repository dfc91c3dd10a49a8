"""Tables of a run and of a study: curve.csv (row by row), summary.json, the
CSV tables and text of the studies. Writers take data; nothing here computes
physics. Registers the writers "curve" and "summary"."""
from __future__ import annotations

import contextlib
import csv
import json
import os
from typing import List, Sequence

import numpy as np

from .. import parallel
from .files import atomic, naming
from .registry import register_writer

CURVE, SUMMARY = "curve.csv", "summary.json"


def _cell(v) -> str:
    """Ten significant digits, as C's %.10g; counts as integers."""
    return str(v) if isinstance(v, int) else format(v, ".10g")


class CurveCsv:
    """curve.csv, a row per record, flushed as it is written so that a run that
    fails or is interrupted keeps every row up to that point. An observer of
    CubeTest.run."""

    def __init__(self, path: str, append: bool = False):
        self.path = path
        self._f = open(path, "a" if append else "w")
        self._columns = None  # the header's, once known
        if append:
            with open(path) as f:
                self._columns = f.readline().strip().split(",")

    def __call__(self, row: dict) -> None:
        if self._columns is None:  # the header: the cube's columns, then a specimen's probes
            self._columns = list(row)
            self._write(",".join(self._columns) + "\n")
        self._write(",".join(_cell(row[c]) for c in self._columns) + "\n")

    def _write(self, line: str) -> None:
        try:
            self._f.write(line)
            self._f.flush()
        except OSError as e:
            raise naming(e, self.path) from e

    def close(self) -> None:
        with contextlib.suppress(OSError):  # a row cut by a full disk was reported already
            self._f.close()


def _curve_writer(run):
    """curve.csv on rank 0 (under MPI every rank has the rows); a restart
    appends to the rows kept up to its checkpoint."""
    if not parallel.is_root():
        return _Nothing()
    return CurveCsv(os.path.join(run.out, CURVE), append=bool(run.options.get("restart")))


class _Nothing:
    """A writer with nothing to write (a rank other than 0)."""


def write_summary(summary: dict, path: str) -> None:
    with atomic(path) as tmp, open(tmp, "w") as f:
        json.dump(summary, f, indent=2)
        f.write("\n")


class SummaryJson:
    """summary.json (rank 0): when the run is done, last of all, and when it
    fails or is interrupted (status says so), if the disk takes it."""

    def __init__(self, run):
        self.path = os.path.join(run.out, SUMMARY)

    def finish(self, result) -> None:
        if parallel.is_root():
            write_summary(result.summary, self.path)

    def failed(self, summary: dict) -> None:
        if parallel.is_root():
            with contextlib.suppress(OSError):  # the first error is the one reported
                write_summary(summary, self.path)


def read_summary(path: str) -> dict:
    with open(path) as f:
        return json.load(f)


def read_curve(path: str) -> dict:
    data = np.genfromtxt(path, delimiter=",", names=True)
    return {k: np.atleast_1d(data[k]) for k in data.dtype.names}


def cut_curve_after(path: str, step: int) -> List[dict]:
    """Drops curve.csv's rows after `step` (a restart writes them again) and
    returns the rows kept, as numbers."""
    with open(path) as f:
        lines = f.readlines()
    keep = [lines[0]] + [ln for ln in lines[1:] if ln.endswith("\n") and int(ln.split(",", 1)[0]) <= step]
    with atomic(path) as tmp, open(tmp, "w") as f:
        f.writelines(keep)
    columns = keep[0].strip().split(",")
    return [dict(zip(columns, (float(x) for x in ln.split(",")))) for ln in keep[1:]]


def write_table(path: str, rows: Sequence[dict], columns: Sequence[str]) -> None:
    with atomic(path) as tmp, open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(columns), extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})


def read_table(path: str) -> List[dict]:
    def conv(v):
        try:
            return int(v)
        except ValueError:
            try:
                return float(v)
            except ValueError:
                return v
    with open(path, newline="") as f:
        return [{k: conv(v) for k, v in r.items()} for r in csv.DictReader(f)]


register_writer("curve", _curve_writer, 0, "curve.csv: a row per record, written as the run goes")
register_writer("summary", SummaryJson, 100, "summary.json: the run's numbers and parameters, written last")
