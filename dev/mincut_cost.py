#!/usr/bin/python3
"""The cheapest cut's max-flow: scipy's Dinic in int32 (ldem's before 64c175c)
against `_core.max_flow` (pkg/ldem/MaxFlow.cpp), alternately on the same graph
of one cube, with the ratio pair by pair (docs/performance.md).

    dev/mincut_cost.py --size 0.96 --pairs 3
"""
import argparse
import statistics
import time

import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import maximum_flow

from ldem import _core, mincut
from ldem.cube import CubeTest


def graph(size, seed):
    """The cut's integer graph, as ldem.mincut.cheapest_cut builds it."""
    sim = CubeTest(size=size, seed=seed, threads=1).simulation()
    bars = sim.lattice.bar_table()
    n1, n2 = np.asarray(bars["n1"], np.int64), np.asarray(bars["n2"], np.int64)
    e = np.asarray(sim.rupture_energy, np.float64)
    top, bottom = (np.asarray(sim.group(sim.measures[k]), np.int64) for k in ("loaded", "support"))
    unit = mincut._face_cut(e, n1, n2, top) / mincut._UNITS
    return sim.lattice.n_nodes, n1, n2, np.minimum(np.floor(e / unit), mincut._UNITS + 1).astype(np.int64), top, bottom


def dinic(n, n1, n2, cap, top, bottom):
    inf = mincut._UNITS + 1
    rows = np.concatenate([n1, n2, np.full(top.size, n), bottom])
    cols = np.concatenate([n2, n1, top, np.full(bottom.size, n + 1)])
    data = np.concatenate([cap, cap, np.full(top.size + bottom.size, inf)])
    keep = data > 0
    g = csr_matrix((data[keep], (rows[keep], cols[keep])), shape=(n + 2, n + 2))
    g.data = np.minimum(g.data, inf).astype(np.int32)
    return int(maximum_flow(g, n, n + 1, method="dinic").flow_value)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=float, default=0.96)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--pairs", type=int, default=3)
    a = ap.parse_args()
    g = graph(a.size, a.seed)
    times = {"scipy dinic": [], "push-relabel": []}
    for _ in range(a.pairs):
        flows = []
        for name, f in (("scipy dinic", dinic), ("push-relabel", _core.max_flow)):
            t0 = time.perf_counter()
            flows.append(f(*g))
            times[name].append(time.perf_counter() - t0)
        assert flows[0] == flows[1], flows
    print(f"{a.size} m, seed {a.seed}, {g[1].size} bars, flow {flows[0]} units")
    for name, t in times.items():
        print(f"  {name}: median {statistics.median(t):.2f} s of {', '.join(f'{x:.2f}' for x in t)}")
    print("  ratios:", ", ".join(f"{x / y:.2f}" for x, y in zip(*times.values())))


if __name__ == "__main__":
    main()
