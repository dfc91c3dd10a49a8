"""ldem against YADE on the same N^3 lattice, measured in one run on one machine
(issue 3): YADE 2023.02a with one sphere per node, one Cpm interaction per bar
(set up as Hillerborg's triangle by ldem.yade), no collider, NewtonIntegrator,
its OpenMP threads from `-j`; ldem through `ldem-bench` with the same threads.

Run: yade-double -j T -n -x dev/bench_vs_yade.py [--modules N] [--steps S] [--repeats R]
Prints one JSON line per engine and a last line with the ratio.
"""
import argparse
import json
import statistics
import subprocess
import sys
import time

import ldem.yade as ly
from ldem import _core
from ldem.bench import bench_program
from ldem.scene import exit_with


def parse(argv):
    p = argparse.ArgumentParser(prog="yade-double -j T -n -x dev/bench_vs_yade.py")
    p.add_argument("--modules", type=int, default=12, help="modules per side")
    p.add_argument("--steps", type=int, default=50, help="steps per timed repetition")
    p.add_argument("--repeats", type=int, default=3, help="repetitions (the median is reported)")
    return p.parse_args(argv)


def yade_ns_per_bar_step(n, steps, repeats):
    """Builds the cube in YADE, runs one step with ldem.yade's hooks (they give
    every interaction its ldem parameters), then times YADE's own loop alone:
    the Python hooks that drive the upper face are removed before timing."""
    O = ly._yade()["O"]
    threads = O.numThreads  # from -j; ldem must not change it (it sets OpenMP's count for the process)
    rp = _core.RunParams()
    rp.threads = threads
    t0 = time.time()
    sim = _core.Simulation(n, n, n, 0.02, _core.Material(), _core.LoadingParams(), rp)
    spec = ly.SimulationSpecimen(sim, damping=0.0)
    O.run(1, True)
    build_s = time.time() - t0
    O.engines = [e for e in O.engines if type(e).__name__ != "PyRunner"]
    times = []
    for _ in range(repeats):
        t = time.time()
        O.run(steps, True)
        times.append((time.time() - t) / steps)
    bars = len(spec.bars.interactions)
    return {"engine": "yade", "modules": n, "bars": bars, "nodes": len(O.bodies), "steps": steps,
            "threads": threads, "ns_per_bar_step": statistics.median(times) / bars * 1e9,
            "build_s": round(build_s, 1)}


def main(argv):
    a = parse(argv)
    yade = yade_ns_per_bar_step(a.modules, a.steps, a.repeats)
    out = subprocess.run([bench_program(), "--modules", str(a.modules), "--steps", str(max(a.steps, 100)),
                          "--threads", str(yade["threads"]), "--repeats", str(max(a.repeats, 3))],
                         capture_output=True, text=True, check=True).stdout
    ldem = dict(engine="ldem", **json.loads(out))
    print(json.dumps(yade))
    print(json.dumps(ldem))
    print(f"modules={a.modules} threads={yade['threads']} yade_ns_per_bar_step={yade['ns_per_bar_step']:.1f} "
          f"ldem_ns_per_bar_step={ldem['ns_per_bar_step']:.2f} speedup={yade['ns_per_bar_step'] / ldem['ns_per_bar_step']:.0f}")
    sys.stdout.flush()


exit_with(main, sys.argv[1:])
