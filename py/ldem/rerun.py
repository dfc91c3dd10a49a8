"""`ldem rerun DIR`: the run of a result's folder again, from its summary.json,
compared number by number and curve by curve."""
from __future__ import annotations

import dataclasses
import os

import numpy as np

EXIT_FAILED = 1  # as ldem.cli's: a difference is a failed check


# The summary's numbers that a rerun must reproduce exactly (not when, where, how fast).
RERUN_KEYS = ("peak_stress_MPa", "strain_at_peak", "edge_strain_at_peak", "separated", "U_num_J", "load_loss",
              "separation", "fracture_energy_J", "U_mincut_J", "energy_balance_error", "stop_reason", "steps",
              "n_bars", "clamped_bars", "dt_s")


def cmd_rerun(args) -> int:
    import json

    from .cube import CubeTest
    from .io import read_curve, read_summary
    from .runner import run_cube

    path = os.path.join(args.dir, "summary.json")
    try:
        old = read_summary(path)
    except OSError as e:
        raise ValueError(f"cannot read {path}: {e.strerror}") from None
    except json.JSONDecodeError as e:
        raise ValueError(f"{path} is not JSON: {e}") from None
    known = {f.name for f in dataclasses.fields(CubeTest)}
    params = {k: v for k, v in old.get("parameters", {}).items() if k in known}
    if not params:
        raise ValueError(f"{path} holds no parameters to rerun")
    out = args.out or os.path.join(args.dir, "rerun")
    prov = old.get("provenance") or {}
    print(f"rerun of {args.dir} (ldem {prov.get('ldem_version', '?')}, git {prov.get('git_commit') or '?'}, "
          f"{prov.get('date', '?')} on {prov.get('host', '?')}) into {out}")
    new = run_cube(CubeTest(**params), out=out, progress=False if args.no_progress else None, plots=False).summary
    differ = [k for k in RERUN_KEYS if k in old and old[k] != new.get(k)]
    a, b = read_curve(os.path.join(args.dir, "curve.csv")), read_curve(os.path.join(out, "curve.csv"))
    same_curve = a.keys() == b.keys() and all(np.array_equal(a[k], b[k]) for k in a)
    if not same_curve:
        differ.append("curve.csv")
    for k in differ[:10]:
        print(f"  differs: {k}: {old.get(k)!r} then, {new.get(k)!r} now" if k != "curve.csv" else "  differs: curve.csv")
    print("identical: the curve and every number of the summary" if not differ else
          f"{len(differ)} difference(s)")
    return 0 if not differ else EXIT_FAILED
