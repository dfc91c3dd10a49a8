"""The cases of a study and their folders: naming, what counts as finished,
running one case into its folder, and reading its files back.

Layout of a study folder DIR: one folder per case, DIR/cases/<name>/
(curve.csv, summary.json, cracks.png, slice.npz). A case is finished when its
summary.json says "done" for the same parameters and slice.npz (written last)
exists. An unfinished case with a checkpoint.npz of its parameters (a case
writes one every CHECKPOINT_SECONDS) continues from it; any other case folder
(failed, other parameters) is computed again from scratch."""
from __future__ import annotations

import contextlib
import dataclasses
import os
import shutil
from typing import Dict, Iterable, List, Optional, Sequence

from .. import io
from ..cube import CubeTest


def _number(v) -> str:
    """A parameter's value in a case name: short (%g) when that is exact, else
    every digit, so that two different values never share a name."""
    if not isinstance(v, float):
        return str(v)
    short = f"{v:g}"
    return short if float(short) == v else repr(v)


def case_name(test: CubeTest) -> str:
    """load_size_seed, then every parameter that differs from CubeTest's defaults
    (threads aside: they do not change the result)."""
    name = f"{test.load}_{_number(test.size)}m_s{test.seed}"
    default = CubeTest()
    for f in dataclasses.fields(CubeTest):
        if f.name in ("load", "size", "seed", "threads"):
            continue
        v = getattr(test, f.name)
        if v != getattr(default, f.name):
            name += f"_{f.name}{_number(v)}"
    return name


def case_dir(out: str, test: CubeTest) -> str:
    """Where a study in directory out keeps the case of test."""
    return os.path.join(out, "cases", case_name(test))


def _comparable(params: dict) -> dict:
    """The parameters that decide a case's result; one declared after the case
    ran counts at its default (the run it would have made is the same)."""
    defaults = {f.name: f.default for f in dataclasses.fields(CubeTest)}
    return {k: params.get(k, d) for k, d in defaults.items() if k != "threads"}


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


def unfinished_reason(case_dir: str, test: CubeTest) -> Optional[str]:
    """None if the case in case_dir is finished for test: summary.json says done
    for the same parameters, curve.csv ends with the summary's last step and
    slice.npz loads; else why not (the case is then run again)."""
    if not os.path.isdir(case_dir):
        return "not run yet"
    try:
        s = io.read_summary(os.path.join(case_dir, "summary.json"))
    except (OSError, ValueError):
        return "no readable summary.json"
    if s.get("status") != "done":
        return f"status {s.get('status')!r}"
    if _comparable(s.get("parameters", {})) != _comparable(test.parameters()):
        return "other parameters"
    try:
        last = _last_step(os.path.join(case_dir, "curve.csv"))
    except OSError:
        return "no curve.csv"
    if last != s.get("steps"):
        return f"curve.csv incomplete (last row at step {last}, summary.json says {s.get('steps')})"
    try:
        io.read_slice(os.path.join(case_dir, "slice.npz"))
    except (OSError, ValueError, KeyError, EOFError):
        return "no loadable slice.npz"
    return None


def is_finished(case_dir: str, test: CubeTest) -> bool:
    return unfinished_reason(case_dir, test) is None


# A case writes checkpoint.npz this often (wall time): a study stopped by a
# kill, a reboot or the end of a batch job loses at most this much of a case.
CHECKPOINT_SECONDS = 600.0


def checkpoint_step(case_dir: str, test: CubeTest) -> Optional[int]:
    """The step of the unfinished case's checkpoint.npz, if it has a readable one
    of test's parameters (threads aside) and a curve.csv; else None."""
    try:
        state, parameters, _ = io.read_checkpoint(os.path.join(case_dir, "checkpoint.npz"))
    except (OSError, ValueError, KeyError, EOFError):
        return None
    if _comparable(parameters) != _comparable(test.parameters()) or \
            not os.path.exists(os.path.join(case_dir, "curve.csv")):
        return None
    return int(state["counters"][0])


def run_case(params: dict, case_dir: str) -> dict:
    """Runs one case into case_dir and returns its summary: from the case's
    checkpoint if it has one (bit for bit the run it would have been), else
    from scratch in the emptied folder. A top-level function, so that worker
    processes and dask can call it."""
    from .. import plots  # matplotlib only where pictures are drawn: `ldem cube` starts faster
    from ..runner import run_cube

    test = CubeTest(**params)
    restart = checkpoint_step(case_dir, test) is not None
    if os.path.isdir(case_dir) and not restart:
        shutil.rmtree(case_dir)  # half-finished or stale: start afresh
    result = run_cube(test, out=case_dir, progress=False, plots=False, restart=restart,
                      checkpoint_seconds=CHECKPOINT_SECONDS)
    with contextlib.suppress(FileNotFoundError):
        os.remove(os.path.join(case_dir, "checkpoint.npz"))  # the case is done: the state is not needed
    seg, state = plots.central_slice(result.sim)
    # Written last: its presence marks the case finished (with summary.json "done").
    io.write_slice(os.path.join(case_dir, "slice.npz"), seg, state)
    plots.crack_figure_from_slice(seg, state, os.path.join(case_dir, "cracks.png"),
                                  title=f"{test.size:g} m, {test.load}, seed {test.seed}")
    return result.summary


def size_effect_tests(sizes: Iterable[float], seeds: int, loads: Iterable[str], **common) -> List[CubeTest]:
    return [CubeTest(size=s, load=ld, seed=k, **common) for ld in loads for s in sizes for k in range(1, seeds + 1)]


def damping_tests(size: float, zetas: Iterable[float], loads: Iterable[str], seed: int = 1,
                  **common) -> List[CubeTest]:
    return [CubeTest(size=size, load=ld, seed=seed, zeta=z, **common) for ld in loads for z in zetas]


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
