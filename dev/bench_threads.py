#!/usr/bin/python3
"""The default thread count against --threads 1 and 2 (issue 40): `ldem cube`
runs of each size, the variants in turn (round after round), on the machine
as it is and beside a second CPU-bound job (`yes > /dev/null`); prints the
median wall time of the run (summary.json wall_s: set-up and loop) of each
variant, the threads the default chose, and default / the better of 1 and 2.

    dev/bench_threads.py --sizes 0.12,0.48 --final-strain 1e-4 --rounds 5
    dev/bench_threads.py --sizes 0.24 --variants 2,2:active --final-strain 2e-4   # the wait policy's cost

A variant is THREADS (0: the default) or THREADS:POLICY (OMP_WAIT_POLICY,
passive unless given). The load average is printed with each condition: on
a shared machine "alone" is only as quiet as the others leave it.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

LDEM = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "py", "bin", "ldem")


def run(size, final_strain, variant, out):
    threads, _, policy = variant.partition(":")
    env = dict(os.environ, OMP_WAIT_POLICY=policy or "passive")
    env.pop("OMP_NUM_THREADS", None)
    subprocess.run([sys.executable, LDEM, "cube", "--size", str(size), "--final-strain", str(final_strain),
                    "--threads", threads, "--no-plots", "--no-progress", "--checkpoint-minutes", "0", "--out", out],
                   check=True, capture_output=True, env=env)
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    return s["wall_s"], s["threads"]


def condition(sizes, final_strain, variants, rounds, busy):
    """{(size, variant): ([wall_s], [threads])} over the rounds, with a `yes` beside them if busy."""
    companion = subprocess.Popen(["yes"], stdout=subprocess.DEVNULL) if busy else None
    try:
        times = {}
        with tempfile.TemporaryDirectory() as tmp:
            for _ in range(rounds):
                for size in sizes:
                    for v in variants:
                        wall, threads = run(size, final_strain, v, os.path.join(tmp, "out"))
                        walls, used = times.setdefault((size, v), ([], []))
                        walls.append(wall), used.append(threads)
        return times
    finally:
        if companion is not None:
            companion.kill()
            companion.wait()


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--sizes", default="0.12,0.48", help="cube sides [m]")
    p.add_argument("--final-strain", type=float, default=1e-4)
    p.add_argument("--variants", default="0,1,2", help="THREADS[:POLICY], comma-separated (0: the default)")
    p.add_argument("--rounds", type=int, default=5)
    p.add_argument("--conditions", default="alone,busy", help="alone, busy (beside `yes`), or both")
    a = p.parse_args(argv)
    sizes = [float(s) for s in a.sizes.split(",")]
    variants = a.variants.split(",")
    print(f"{'condition':<8} {'load':>5} {'size':>5} " + " ".join(f"{v:>16}" for v in variants)
          + "  default/best(1,2)")
    for name in a.conditions.split(","):
        load = os.getloadavg()[0]
        times = condition(sizes, a.final_strain, variants, a.rounds, busy=name == "busy")
        for size in sizes:
            med = {v: statistics.median(times[(size, v)][0]) for v in variants}
            cells = " ".join(f"{med[v]:9.3f} s ({statistics.mode(times[(size, v)][1])}t)" for v in variants)
            best = [med[v] for v in ("1", "2") if v in med]
            ratio = f"{med['0'] / min(best):.2f}" if "0" in med and best else "-"
            print(f"{name:<8} {load:5.2f} {size:5.2f} {cells}  {ratio}", flush=True)


if __name__ == "__main__":
    main()
