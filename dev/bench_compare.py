#!/usr/bin/python3
"""Two builds of ldem-bench, timed in turn (A B A B ...), with the median of
each figure and the median of the pair-by-pair ratios B/A: a speed-up claimed
on this noisy machine comes from here (docs/performance.md).

    dev/bench_compare.py OLD/pkg/ldem-bench NEW/pkg/ldem-bench --pairs 7 -- --modules 48 --threads 2

Everything after -- goes to both programs (ldem-bench --help lists it).
"""
import argparse
import json
import statistics
import subprocess
import sys

FIGURES = ("ns_per_bar_step", "ns_per_bar_forces", "ns_per_bar_integration", "damaged_ns_per_bar_step")


def run(program, args):
    out = subprocess.run([program, *args], check=True, capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    extra = []
    if "--" in argv:
        at = argv.index("--")
        argv, extra = argv[:at], argv[at + 1:]
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("a", help="the reference ldem-bench")
    p.add_argument("b", help="the ldem-bench to compare with it")
    p.add_argument("--pairs", type=int, default=7, help="A B pairs timed (default 7)")
    a = p.parse_args(argv)
    runs = {"a": [], "b": []}
    for k in range(a.pairs):
        runs["a"].append(run(a.a, extra))
        runs["b"].append(run(a.b, extra))
        print(f"pair {k + 1}/{a.pairs}: " + ", ".join(
            f"{f} {runs['a'][-1][f]:.3f} -> {runs['b'][-1][f]:.3f}" for f in FIGURES if f in runs["a"][-1]),
            file=sys.stderr, flush=True)
    print(f"{a.pairs} pairs, ldem-bench {' '.join(extra)}")
    print(f"{'figure':<26} {'A median':>9} {'B median':>9} {'B/A median':>11} {'B/A min':>8} {'B/A max':>8}")
    for f in FIGURES:
        if f not in runs["a"][0]:
            continue
        va, vb = [r[f] for r in runs["a"]], [r[f] for r in runs["b"]]
        ratios = [y / x for x, y in zip(va, vb)]
        print(f"{f:<26} {statistics.median(va):9.4f} {statistics.median(vb):9.4f} {statistics.median(ratios):11.3f} "
              f"{min(ratios):8.3f} {max(ratios):8.3f}")


if __name__ == "__main__":
    main()
