"""Why the large uniform cubes are weaker (issue 10, item 7): the study
ldem.study.ablation (one factor at a time on a cube, both loads, each run
stopped past its peak), its cases in OUT/cases/, resumed as every study's.

    /usr/bin/python3 scripts/peak_ablation.py SIZE SEEDS [THREADS [RUNS]] [--out DIR] [--jobs J]   e.g. 0.48 1,2,3 1
      RUNS: load:variant pairs, e.g. uniform:rollers,triangular:base (default: every pair)
      prints one JSON line per run (also in DIR/ablation.jsonl) and the table (DIR/ablation.md)
    /usr/bin/python3 scripts/peak_ablation.py --table RUNS.jsonl        the markdown table of those runs
"""
import argparse
import json
import sys

from ldem.study import ablation

if __name__ == "__main__":
    if sys.argv[1:2] == ["--table"]:
        print(ablation.ablation_table(ablation.read_runs(sys.argv[2])), end="")
        sys.exit(0)
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("size", type=float)
    ap.add_argument("seeds")
    ap.add_argument("threads", type=int, nargs="?", default=0)
    ap.add_argument("runs", nargs="?", default="")
    ap.add_argument("--out", default="ablation")
    ap.add_argument("--jobs", type=int, default=1)
    a = ap.parse_args()
    runs = [tuple(r.split(":")) for r in a.runs.split(",")] if a.runs else ablation.RUNS
    tests = ablation.ablation_tests(a.size, [int(s) for s in a.seeds.split(",")], a.threads, runs)
    rows = ablation.run_ablation(tests, a.out, a.jobs, log=lambda s: print(s, file=sys.stderr))
    print("".join(json.dumps(r) + "\n" for r in rows) + ablation.ablation_table(rows), end="")
