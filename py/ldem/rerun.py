"""`ldem rerun DIR`: the run of a result's folder again, from its summary.json
(an `ldem cube` run, a study's case or an `ldem run` specimen), compared field
by field (every field of the summary, nested ones too, but the few named in
RERUN_SKIPS) and curve by curve."""
from __future__ import annotations

import dataclasses
import math
import os

import numpy as np

EXIT_FAILED = 1  # as ldem.cli's: a difference is a failed check

# The summary's fields a rerun (or a restart) may change, and why: when, where and how fast it ran, never what.
RERUN_SKIPS = {
    "wall_s": "the wall time: how fast, not what",
    "provenance": "when, where and by which build it ran",
    "restarted_at_step": "where a restarted run continued: a rerun runs straight through",
    "threads": "the thread count the machine's load chose (the results are bit-identical on any count)",
    "mpi_ranks": "the processes it was split over (the results are bit-identical on any number)",
}
# What a restarted run may change against a run never stopped: its wall time, its restart count, its date.
RESTART_SKIPS = ("wall_s", "restarted_at_step", "provenance.date")


def differences(old, new, skip=(), path: str = "") -> list:
    """The paths ("quasi_static.kinetic_over_work_at_peak") where two summaries
    differ, nested dicts and lists compared field by field; the paths in skip
    ("wall_s", "provenance.date") are left out. A field on one side only is a difference."""
    if isinstance(old, dict) and isinstance(new, dict):
        paths = {k: f"{path}.{k}" if path else k for k in {**old, **new}}
        return [d for k, p in paths.items() if p not in skip
                for d in differences(old.get(k, _MISSING), new.get(k, _MISSING), skip, p)]
    if isinstance(old, list) and isinstance(new, list) and len(old) == len(new):
        return [d for i, (a, b) in enumerate(zip(old, new)) for d in differences(a, b, skip, f"{path}[{i}]")]
    return [] if _same(old, new) else [path]


_MISSING = object()


def _same(a, b) -> bool:
    """Equal as JSON values (true is not 1), NaN equal to NaN."""
    if a is _MISSING or b is _MISSING:
        return False
    if isinstance(a, bool) or isinstance(b, bool):
        return type(a) is type(b) and a == b
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return a == b


def field(summary: dict, path: str):
    """The value at a path of differences()."""
    value = summary
    for part in path.replace("[", ".[").split("."):
        if not isinstance(value, (dict, list)):
            return None
        value = value[int(part[1:-1])] if part.startswith("[") else value.get(part)
    return value


def rerun_test_of(summary: dict, path: str):
    """The test a summary's parameters describe: a cube test's fields, or an `ldem run` specimen's description
    with the parameters it ran with (its file's, with --set)."""
    from .cube import TABLE_DEFAULTS, CubeTest
    from .specimen import SpecimenTest

    params = summary.get("parameters") or {}
    if "description" in params:  # the parameters its file does not give came from --set
        given = SpecimenTest(params["description"]).build.params
        ran = {**TABLE_DEFAULTS, **params["parameters"]}  # one declared after the run: the table's default
        return SpecimenTest(params["description"], overrides={k: v for k, v in ran.items()
                                                              if k in given and given[k] != v})
    known = {f.name for f in dataclasses.fields(CubeTest)}
    cube = {k: v for k, v in params.items() if k in known}
    if not cube:
        raise ValueError(f"{path} holds no parameters to rerun")
    # One declared after the run ran at the table's default (a cube's own, CUBE_DEFAULTS, came later).
    return CubeTest(**{**TABLE_DEFAULTS, **cube})


def cmd_rerun(args) -> int:
    import json

    from .io import read_curve, read_summary
    from .runner import run_cube

    path = os.path.join(args.dir, "summary.json")
    try:
        old = read_summary(path)
    except OSError as e:
        raise ValueError(f"cannot read {path}: {e.strerror}") from None
    except json.JSONDecodeError as e:
        raise ValueError(f"{path} is not JSON: {e}") from None
    test = rerun_test_of(old, path)
    out = args.out or os.path.join(args.dir, "rerun")
    prov = old.get("provenance") or {}
    print(f"rerun of {args.dir} (ldem {prov.get('ldem_version', '?')}, git {prov.get('git_commit') or '?'}, "
          f"{prov.get('date', '?')} on {prov.get('host', '?')}) into {out}")
    new = run_cube(test, out=out, progress=False if args.no_progress else None, plots=False).summary
    differ = differences(old, new, RERUN_SKIPS)
    a, b = read_curve(os.path.join(args.dir, "curve.csv")), read_curve(os.path.join(out, "curve.csv"))
    same_curve = a.keys() == b.keys() and all(np.array_equal(a[k], b[k]) for k in a)
    for k in differ[:10]:
        print(f"  differs: {k}: {field(old, k)!r} then, {field(new, k)!r} now")
    if not same_curve:
        print("  differs: curve.csv")
    skipped = "; ".join(f"{k} ({why})" for k, why in RERUN_SKIPS.items() if k in old or k in new)
    print(f"not compared: {skipped}")
    count = len(differ) + (not same_curve)
    print("identical: the curve and every other field of the summary" if not count else f"{count} difference(s)")
    return 0 if not count else EXIT_FAILED
