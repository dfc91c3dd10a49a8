#!/usr/bin/python3
"""The wall time of a step from a cube's checkpoint, for two builds in turn.

A softened state (a crack running, a tail past the load loss) is reached only
after most of a run: take it from a run's checkpoint.npz (`ldem cube ...
--checkpoint-minutes M`, or the one an interrupted run leaves) and time the
steps from there. Each build restores the checkpoint on one thread, takes
`--warm` steps, then times `--steps`; the builds alternate, pair by pair, and
the ratio B/A of each pair is printed with the medians.

    dev/checkpoint_step_cost.py --a OLD/build/python --b build/python RUN/checkpoint.npz --pairs 3
"""
import argparse
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from simulated_ms_cost import alternate  # noqa: E402  (the pairs and their medians)

# The timed part, run in a fresh interpreter for each build (each has its own _core).
TIMED = """
import dataclasses, sys, time
from ldem.cube import CubeTest
from ldem.io import read_checkpoint
state, params, _ = read_checkpoint(sys.argv[1])
known = {f.name for f in dataclasses.fields(CubeTest)}
sim = CubeTest(**{k: v for k, v in params.items() if k in known and k != "threads"}, threads=1).simulation()
sim.restore(state)
for _ in range(int(sys.argv[2])): sim.step()
t = time.perf_counter()
for _ in range(int(sys.argv[3])): sim.step()
print(1e3 * (time.perf_counter() - t) / int(sys.argv[3]))
"""


def step_ms(pythonpath, a):
    """Wall milliseconds per step of one build from the checkpoint."""
    env = dict(os.environ, PYTHONPATH=pythonpath, OMP_WAIT_POLICY="passive")
    out = subprocess.run([sys.executable, "-c", TIMED, a.checkpoint, str(a.warm), str(a.steps)], check=True,
                         capture_output=True, text=True, env=env).stdout
    return float(out.split()[-1])


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("checkpoint", help="a cube run's checkpoint.npz")
    p.add_argument("--a", required=True, help="PYTHONPATH of build A (before)")
    p.add_argument("--b", required=True, help="PYTHONPATH of build B (after)")
    p.add_argument("--steps", type=int, default=300)
    p.add_argument("--warm", type=int, default=20)
    p.add_argument("--pairs", type=int, default=3)
    a = p.parse_args(argv)
    alternate(a.pairs, lambda path: (step_ms(path, a), None), a.a, a.b, "ms/step")

if __name__ == "__main__":
    main()
