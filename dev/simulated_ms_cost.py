#!/usr/bin/python3
"""The wall time of one millisecond of a cube's simulated time, for two builds
in turn (issue 41, item 5: the 0.96 m cube on 2 threads, before and after).

Each build runs `ldem cube --size S` to two final mean strains; the difference
of the two runs' walls over the difference of their simulated times is the
cost of the stretch between them, free of the set-up (lattice, omega_1) that
both runs share. The builds alternate, pair by pair, and the ratio B/A of each
pair is printed with the medians.

    dev/simulated_ms_cost.py --a OLD/build/python --b build/python --size 0.96 --threads 2 --pairs 3
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import sys
import tempfile


def run(pythonpath, size, threads, strain, load):
    """(wall [s], simulated time [s], steps) of one run to mean strain `strain`."""
    env = dict(os.environ, PYTHONPATH=pythonpath, OMP_WAIT_POLICY="passive")
    with tempfile.TemporaryDirectory() as out:
        subprocess.run([sys.executable, "-m", "ldem", "cube", "--size", str(size), "--load", load, "--seed", "1",
                        "--threads", str(threads), "--final-strain", str(strain), "--out", out, "--no-plots",
                        "--no-progress"], check=True, capture_output=True, env=env)
        with open(os.path.join(out, "summary.json")) as f:
            s = json.load(f)
        with open(os.path.join(out, "curve.csv")) as f:
            last = list(csv.DictReader(f))[-1]
    return s["wall_s"], float(last["time_s"]), s["steps"]


def per_ms(pythonpath, a):
    """Wall seconds per simulated millisecond between the two final strains, and the steps per ms."""
    w1, t1, n1 = run(pythonpath, a.size, a.threads, a.strains[0], a.load)
    w2, t2, n2 = run(pythonpath, a.size, a.threads, a.strains[1], a.load)
    return (w2 - w1) / ((t2 - t1) * 1e3), (n2 - n1) / ((t2 - t1) * 1e3)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--a", required=True, help="PYTHONPATH of build A (before)")
    p.add_argument("--b", required=True, help="PYTHONPATH of build B (after)")
    p.add_argument("--size", type=float, default=0.96)
    p.add_argument("--load", default="uniform")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--strains", type=lambda s: [float(x) for x in s.split(",")], default=[1e-4, 2e-4],
                   help="the two final mean strains (default: 1e-4,2e-4, the peak and the cracks of a uniform cube)")
    p.add_argument("--pairs", type=int, default=3)
    a = p.parse_args(argv)
    alternate(a.pairs, lambda path: per_ms(path, a), a.a, a.b, "s/ms")


def alternate(pairs, measure, a, b, unit):
    """Builds a and b in turn, pair by pair: measure(build) gives (cost, steps per unit or None);
    prints each pair's costs and B/A, then the medians (dev/checkpoint_step_cost.py uses it too)."""
    A, B, ratios = [], [], []
    for k in range(pairs):
        (ca, sa), (cb, sb) = measure(a), measure(b)
        A.append(ca), B.append(cb), ratios.append(cb / ca)
        rate = (lambda s: "" if s is None else f" ({s:.0f} steps/ms)")
        print(f"pair {k + 1}: A {ca:.3f} {unit}{rate(sa)}, B {cb:.3f} {unit}{rate(sb)}, B/A {cb / ca:.3f}", flush=True)
    print(f"median: A {statistics.median(A):.3f} {unit}, B {statistics.median(B):.3f}, "
          f"B/A {statistics.median(ratios):.3f} (pairs: {', '.join(f'{r:.3f}' for r in ratios)})")

if __name__ == "__main__":
    main()
