#!/usr/bin/python3
"""A whole study case against the benchmark of its lattice: `ldem cube --size S`
(uniform, to separation, one thread; its wall time / steps / bars) and
`ldem-bench --modules S/L0 --threads 1` (the bare time step, elastic and past
load loss), in turn, with the ratio pair by pair (docs/performance.md).

    dev/bench_study_case.py --size 0.24 --pairs 3
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

import ldem.bench


def case(size, seed, threads):
    with tempfile.TemporaryDirectory() as out:
        subprocess.run([sys.executable, "-m", "ldem", "cube", "--size", str(size), "--seed", str(seed), "--threads",
                        str(threads), "--out", out, "--no-plots", "--no-progress"], check=True, capture_output=True)
        with open(os.path.join(out, "summary.json")) as f:
            s = json.load(f)
    return s["wall_s"] / s["steps"] / s["n_bars"] * 1e9, s


def bench(modules, threads):
    out = subprocess.run([ldem.bench.bench_program(), "--modules", str(modules), "--threads", str(threads), "--steps", "200",
                          "--damaged", "1"], check=True, capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--size", type=float, default=0.24, help="cube side [m] (modules of 0.02 m)")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--pairs", type=int, default=3)
    p.add_argument("--threads", type=int, default=1)
    a = p.parse_args(argv)
    modules = round(a.size / 0.02)
    rows = []
    for k in range(a.pairs):
        ns_case, s = case(a.size, a.seed, a.threads)
        b = bench(modules, a.threads)
        rows.append((ns_case, b["ns_per_bar_step"], b["damaged_ns_per_bar_step"]))
        print(f"pair {k + 1}: case {ns_case:.3f} ns/bar-step ({s['steps']} steps, {s['wall_s']:.1f} s), bench "
              f"{b['ns_per_bar_step']:.3f} elastic, {b['damaged_ns_per_bar_step']:.3f} past load loss",
              file=sys.stderr, flush=True)
    med = [statistics.median(c) for c in zip(*rows)]
    over = statistics.median(r[0] / r[1] for r in rows)
    over_damaged = statistics.median(r[0] / r[2] for r in rows)
    print(f"{a.size} m cube ({modules}^3 modules), seed {a.seed}, {a.threads} thread(s), {a.pairs} pairs: "
          f"case {med[0]:.3f} ns/bar-step, bench {med[1]:.3f} (elastic) and {med[2]:.3f} (past load loss); "
          f"case/bench {over:.3f} (elastic), {over_damaged:.3f} (past load loss), medians of pair ratios")


if __name__ == "__main__":
    main()
