"""The cases of a study and their folders: naming, what counts as finished,
running one case into its folder, and reading its files back.

A case is any test object with parameters() and run() (and simulation(),
final_strain, energy_tolerance, describe()): ldem.CubeTest, ldem.SpecimenTest,
or a study's own (ldem.study.beams.cases.Beam). It may also say
    case_name()    its folder's name (default: the cube's load_size_seed...,
                   or for any other test its seed and a hash of its parameters)
    cases_folder   the folder of the case folders (default "cases")
    writers        the writers of its run (default CASE_WRITERS)

Layout of a study folder DIR: one folder per case, DIR/cases/<name>/
(curve.csv, summary.json, cracks.png, slice.npz). A case is finished when its
summary.json (written last) says "done" for the same parameters and the files
of its writers are whole. An unfinished case with a checkpoint.npz of its parameters (a case
writes one every CHECKPOINT_SECONDS) continues from it; any other case folder
(failed, other parameters) is computed again from scratch."""
from __future__ import annotations

import dataclasses
import hashlib
import json
import os
import shutil
from typing import Dict, List, Optional, Sequence

from .. import io
from ..cube import TABLE_DEFAULTS, CubeTest


def _number(v) -> str:
    """A parameter's value in a case name: short (%g) when that is exact, else
    every digit, so that two different values never share a name."""
    if not isinstance(v, float):
        return str(v)
    short = f"{v:g}"
    return short if float(short) == v else repr(v)


def case_name(test) -> str:
    """test.case_name() if it has one; for a CubeTest load_size_seed, then every
    parameter that differs from CubeTest's defaults (threads aside: they do not
    change the result); for any other test, its seed and a hash of its
    parameters."""
    if hasattr(test, "case_name"):
        return test.case_name()
    if not isinstance(test, CubeTest):
        key = json.dumps(_comparable(test.parameters(), test), sort_keys=True)
        return f"s{test.seed}_{hashlib.sha256(key.encode()).hexdigest()[:12]}"
    name = f"{test.load}_{_number(test.size)}m_s{test.seed}"
    default = CubeTest()
    for f in dataclasses.fields(CubeTest):
        if f.name in ("load", "size", "seed", "threads"):
            continue
        v = getattr(test, f.name)
        if v != getattr(default, f.name):
            name += f"_{f.name}{_number(v)}"
    return name


def case_dir(out: str, test) -> str:
    """Where a study in directory out keeps the case of test."""
    return os.path.join(out, getattr(test, "cases_folder", "cases"), case_name(test))


# The files of a study case: its curve, its summary, its central slice.
CASE_WRITERS = ("curve", "summary", "slice")


def case_writers(test) -> list:
    return list(getattr(test, "writers", CASE_WRITERS))


def case_title(test) -> str:
    """The title of the case's crack picture."""
    return f"{test.size:g} m, {test.load}, seed {test.seed}" if isinstance(test, CubeTest) else test.describe()


class Named:
    """Any test as a case of a name, folder and writers of its own (e.g. the
    gallery's examples: runs/NAME/ with the pictures of `ldem run`)."""

    def __init__(self, test, name: str, writers: Sequence[str] = CASE_WRITERS, folder: str = "cases"):
        self.test, self.name, self.writers, self.cases_folder = test, name, list(writers), folder

    def __getattr__(self, attribute):
        """Whatever else a runner asks (final_strain, strain_rate, eps_p, ...) is the test's."""
        if attribute == "test" or attribute.startswith("__"):  # not set yet (unpickling): no recursion
            raise AttributeError(attribute)
        return getattr(self.test, attribute)

    def case_name(self) -> str:
        return self.name

    def describe(self) -> str:
        return self.test.describe()

    def parameters(self) -> dict:
        return self.test.parameters()

    def simulation(self):
        return self.test.simulation()

    def run(self, observers=(), simulation=None, previous_rows=()):
        return self.test.run(observers, simulation, previous_rows)


def _comparable(params: dict, test) -> dict:
    """The parameters that decide a case's result (threads, at any depth, do
    not); a table's parameter declared after the case ran counts at the table's
    default (the run it made: a cube's own default, CUBE_DEFAULTS, came later),
    for a CubeTest and in a specimen's "parameters"."""
    if isinstance(test, CubeTest):
        return _table(params)
    if isinstance(params, dict):
        return {k: _table(v) if k == "parameters" and isinstance(v, dict) else _comparable(v, test)
                for k, v in params.items() if k != "threads"}
    return params


def _table(params: dict) -> dict:
    return {k: params.get(k, d) for k, d in TABLE_DEFAULTS.items() if k != "threads"}


def _last_step(path: str) -> int:
    """The step of curve.csv's last complete row (-1 if there is none)."""
    with open(path, "rb") as f:
        f.seek(0, os.SEEK_END)
        f.seek(max(0, f.tell() - 4096))
        lines = f.read().split(b"\n")
    complete = [ln for ln in lines[:-1] if ln.strip()]  # a row is complete once its newline is written
    if not complete or not lines[-1] == b"":
        return -1
    try:
        return int(complete[-1].split(b",")[0])
    except ValueError:
        return -1


def unfinished_reason(case_dir: str, test) -> Optional[str]:
    """None if the case in case_dir is finished for test: summary.json says done
    for the same parameters, curve.csv ends with the summary's last step and
    slice.npz (if the case writes one) loads; else why not (the case is then
    run again)."""
    if not os.path.isdir(case_dir):
        return "not run yet"
    try:
        s = io.read_summary(os.path.join(case_dir, "summary.json"))
    except (OSError, ValueError):
        return "no readable summary.json"
    if s.get("status") != "done":
        return f"status {s.get('status')!r}"
    if _comparable(s.get("parameters", {}), test) != _comparable(json_copy(test.parameters()), test):
        return "other parameters"
    try:
        last = _last_step(os.path.join(case_dir, "curve.csv"))
    except OSError:
        return "no curve.csv"
    if last != s.get("steps"):
        return f"curve.csv incomplete (last row at step {last}, summary.json says {s.get('steps')})"
    if "slice" in case_writers(test):
        try:
            io.read_slice(os.path.join(case_dir, "slice.npz"))
        except (OSError, ValueError, KeyError, EOFError):
            return "no loadable slice.npz"
    return None


def json_copy(params: dict) -> dict:
    """params as summary.json gives them back (tuples as lists)."""
    return json.loads(json.dumps(params))


def is_finished(case_dir: str, test) -> bool:
    return unfinished_reason(case_dir, test) is None


# A case writes checkpoint.npz this often (wall time): a study stopped by a
# kill, a reboot or the end of a batch job loses at most this much of a case.
CHECKPOINT_SECONDS = 600.0


def checkpoint_step(case_dir: str, test) -> Optional[int]:
    """The step of the unfinished case's checkpoint.npz, if it has a readable one
    of test's parameters (threads aside) and a curve.csv; else None."""
    try:
        state, parameters, _ = io.case_checkpoint(case_dir)
    except (OSError, ValueError, KeyError, EOFError):
        return None
    if _comparable(parameters, test) != _comparable(json_copy(test.parameters()), test) or \
            not os.path.exists(os.path.join(case_dir, "curve.csv")):
        return None
    return int(state["counters"][0])


def run_case(test, case_dir: str) -> dict:
    """Runs one case (a test object) into case_dir with its writers and returns
    its summary: from the case's checkpoint if it has one (bit for bit the run
    it would have been), else from scratch in the emptied folder. A top-level
    function, so that worker processes and dask can call it."""
    from ..runner import run_cube

    restart = checkpoint_step(case_dir, test) is not None
    if os.path.isdir(case_dir) and not restart:
        shutil.rmtree(case_dir)  # half-finished or stale: start afresh
    result = run_cube(test, out=case_dir, progress=False, restart=restart, checkpoint_seconds=CHECKPOINT_SECONDS,
                      writers=case_writers(test) + ["checkpoint"], title=case_title(test))
    io.discard_checkpoint(case_dir)  # the case is done: the state is not needed
    return result.summary


def load_summary(case_dir: str) -> dict:
    return io.read_summary(os.path.join(case_dir, "summary.json"))


def load_curve(case_dir: str) -> dict:
    return io.read_curve(os.path.join(case_dir, "curve.csv"))


def load_slice(case_dir: str) -> tuple:
    return io.read_slice(os.path.join(case_dir, "slice.npz"))


def load_curves(out: str, tests: Sequence[CubeTest]) -> Dict[tuple, List[dict]]:
    """(load, size) -> the curves of its specimens in study directory out, in test order."""
    groups: Dict[tuple, List[dict]] = {}
    for t in tests:
        groups.setdefault((t.load, t.size), []).append(load_curve(case_dir(out, t)))
    return groups


def read_discussion(out: str) -> str:
    """The hand-written discussion.md of study folder out ("" if there is none)."""
    path = os.path.join(out, "discussion.md")
    if not os.path.exists(path):
        return ""
    with open(path) as f:
        return f.read()


def load_case(out: str, test: CubeTest):
    """The finished case of test in study folder out, as ldem.report.Case."""
    from ..report import Case

    d = case_dir(out, test)
    return Case(test, load_summary(d), load_curve(d), load_slice(d))
