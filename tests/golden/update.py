#!/usr/bin/python3
"""Regenerates the golden files: the default 0.12 m cube's results, pinned
exactly. tests/py/test_golden.py runs the same cases and compares.

    PYTHONPATH=build/python /usr/bin/python3 tests/golden/update.py

A change of the physics (law, integration, loading, lattice, random field, stop
rule, time step...) changes these files: regenerate them in the same commit and
say why in its message. A change that was meant to leave the results alone must
leave them bit for bit.

Each case is run with 1, 2 and 3 threads; the engine claims bit-identical
results for any number of threads, so this script refuses to write anything if
the three differ. Written per case NAME:
- NAME.json: what summary.json says (peak, its strain, the load-loss and
  separation events, U_num, energies, counts, time step, frequencies: every
  float exactly, as JSON's shortest round-trip repr), the energies of the last
  record, and the SHA-256 of the whole curve as float64 arrays (bitwise);
- NAME_curve.csv: curve.csv exactly as ldem writes it (10 significant digits),
  compared byte for byte and readable in a diff.
"""
import hashlib
import json
import os
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))

CASES = {
    # The default run (0.12 m, seed 1): to separation, about 160000 steps
    # (10-15 s on one thread).
    "cube_0.12_uniform_s1": dict(size=0.12, seed=1, load="uniform"),
    # Triangular, capped at mean strain 0.002 (12x the strain at the peak, deep
    # in the softening): the default run holds on the hinge at the edge that is
    # not pulled and loses its load only at mean strain 1.2e-2 (932655 steps,
    # 10 min on 2 threads), then separates much later still. Too long for a test.
    "cube_0.12_triangular_s1": dict(size=0.12, seed=1, load="triangular", final_strain=0.002),
}
THREADS = (1, 2, 3)

# summary.json fields that depend on the physics and the specimen only (not
# wall time, thread count or where the run wrote).
SUMMARY_KEYS = ("status", "peak_stress_MPa", "strain_at_peak", "edge_strain_at_peak", "separated", "U_num_J",
                "U_ratio", "load_loss", "separation", "fracture_energy_J", "min_fracture_energy_J", "U_mincut_J",
                "energy_balance_error", "energy_error", "stop_reason", "clamped_bars", "n_nodes", "n_bars", "steps",
                "dt_s", "dt_limit_s", "omega1_rad_s", "omega_d_rad_s", "omega_max_rad_s", "damping_coefficient_1_s", "ramp_time_s",
                "split_window_s", "parameters")
ENERGIES = ("external_work_J", "kinetic_J", "elastic_J", "fracture_J", "damping_J")


def curve_sha256(curve: dict) -> str:
    """Bitwise digest of the curve: every column (CURVE_COLUMNS order) as little-endian float64."""
    import ldem

    h = hashlib.sha256()
    for col in ldem.CURVE_COLUMNS:
        h.update(col.encode())
        h.update(np.ascontiguousarray(curve[col], dtype="<f8").tobytes())
    return h.hexdigest()


def pinned(result) -> dict:
    """What the golden file pins of a run (a CubeResult)."""
    s = result.summary
    p = {k: s[k] for k in SUMMARY_KEYS}
    p["parameters"] = {k: v for k, v in s["parameters"].items() if k != "threads"}
    p["final_energies_J"] = {k: float(result.curve[k][-1]) for k in ENERGIES}
    p["curve_rows"] = len(result.curve["step"])
    p["curve_sha256"] = curve_sha256(result.curve)
    return json.loads(json.dumps(p))  # as it reads back from the file (tuples -> lists, ...)


def run(name: str, threads: int, out: str, **override):
    """Runs case `name` into folder out (curve.csv and summary.json only)."""
    import ldem

    return ldem.run_cube(ldem.CubeTest(**{**CASES[name], **override}, threads=threads), out=out, progress=False,
                         plots=False)


def golden_paths(name: str):
    return os.path.join(HERE, name + ".json"), os.path.join(HERE, name + "_curve.csv")


def main() -> int:
    for name in CASES:
        got = {}
        for threads in THREADS:
            with tempfile.TemporaryDirectory() as out:
                result = run(name, threads, out)
                with open(os.path.join(out, "curve.csv"), "rb") as f:
                    got[threads] = (pinned(result), f.read())
            print(f"{name}, {threads} thread(s): peak {result.peak_stress_MPa!r} MPa, {result.summary['steps']} "
                  f"steps, {result.wall_s:.1f} s", flush=True)
        if any(got[t] != got[THREADS[0]] for t in THREADS):
            print(f"{name}: results differ between {THREADS} threads; golden files NOT written", file=sys.stderr)
            return 1
        js, csv = golden_paths(name)
        with open(js, "w") as f:
            json.dump(got[THREADS[0]][0], f, indent=2)
            f.write("\n")
        with open(csv, "wb") as f:
            f.write(got[THREADS[0]][1])
        print(f"wrote {os.path.relpath(js)} and {os.path.relpath(csv)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
