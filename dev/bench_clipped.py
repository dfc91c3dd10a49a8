"""Speed of a clipped lattice against the box of about the same bar count
(issue 13 item 7): ldem-bench on the cylinder of diameter and height N modules
cut from an N^3 box, and on the M^3 box whose bar count is nearest, run in
alternation (the machine's load drifts: a ratio is measured within one round),
--rounds times; prints the medians and the median of the per-round ratios.

    /usr/bin/python3 dev/bench_clipped.py [--modules 24,48] [--rounds 5] [--threads 1]
"""
import argparse
import json
import statistics
import subprocess

from ldem import _core
from ldem.bench import bench_program


def bench(shape: str, n: int, steps: int, threads: int) -> dict:
    out = subprocess.run([bench_program(), "--shape", shape, "--modules", str(n), "--steps", str(steps),
                          "--threads", str(threads), "--repeats", "3"], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--modules", default="24,48")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--threads", type=int, default=1)
    args = ap.parse_args()
    print("| cylinder N | bars | box M | bars | ns/bar-step cylinder | box | ratio (median of rounds) |")
    print("|---|---|---|---|---|---|---|")
    for n in (int(x) for x in args.modules.split(",")):
        steps = max(20, int(2e7 / n ** 3))
        first = bench("cylinder", n, steps, args.threads)
        m = min(range(2, n + 1), key=lambda k: abs(_core.expected_bar_count(k, k, k) - first["bars"]))
        cyl, box, ratio = [], [], []
        for _ in range(args.rounds):
            c, b = bench("cylinder", n, steps, args.threads), bench("box", m, steps, args.threads)
            cyl.append(c["ns_per_bar_step"]), box.append(b["ns_per_bar_step"])
            ratio.append(c["ns_per_bar_step"] / b["ns_per_bar_step"])
        print(f"| {n} | {first['bars']} | {m} | {_core.expected_bar_count(m, m, m)} | {statistics.median(cyl):.2f} | "
              f"{statistics.median(box):.2f} | {statistics.median(ratio):.3f} ({min(ratio):.3f}-{max(ratio):.3f}) |",
              flush=True)


if __name__ == "__main__":
    main()
