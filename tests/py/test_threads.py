"""Issue 40, item 1: the default thread count (threads = 0) is as many as the
lattice can use (one per 50,000 bars: a small cube gets one) and at most the
cores free to the process; the count used is printed and in summary.json.
Its speed against --threads 1 and 2 is measured by dev/bench_threads.py."""
import json
import os
import subprocess

import pytest

from ldem import CubeTest, _core

# Bars of the study's cubes (L0 = 0.02 m): 0.12 m, 0.24 m, 0.48 m, 0.96 m.
BARS = {0.12: 3150, 0.24: 24660, 0.48: 195336, 0.96: 1555344}


@pytest.mark.direct
def test_the_rule_gives_small_lattices_one_thread_and_large_ones_the_free_cores():
    rule = _core.default_thread_count
    assert [rule(BARS[s], 2.0) for s in (0.12, 0.24, 0.48, 0.96)] == [1, 1, 2, 2]
    assert rule(99_999, 64.0) == 1 and rule(100_000, 64.0) == 2 and rule(BARS[0.96], 64.0) == 31  # one per 50,000
    assert rule(BARS[0.48], 1.0) == 1  # a second job on one of 2 cores: one thread
    assert rule(BARS[0.96], 1.6) == 2 and rule(BARS[0.96], 1.4) == 1  # to the nearest core
    assert rule(BARS[0.96], 0.0) == 1  # a machine busy everywhere: still one
    assert rule(BARS[0.96], 8.0, 4) == 2  # four MPI ranks share the free cores


def test_a_small_cube_runs_on_one_thread_and_says_so(cli, tmp_path, monkeypatch):
    """The 0.04 m cube (130 bars) with the default threads: one, whatever the
    cores; printed in the run's last lines and in summary.json."""
    monkeypatch.delenv("OMP_NUM_THREADS", raising=False)
    assert CubeTest(size=0.12).simulation().threads == 1
    r = cli("cube", "--size", "0.04", "--final-strain", "1e-4", "--no-plots", "--no-progress", "--out",
            str(tmp_path / "c"))
    assert r.returncode == 0, r.stderr
    assert " s wall on 1 thread\n" in r.stdout, r.stdout
    assert json.loads((tmp_path / "c" / "summary.json").read_text())["threads"] == 1


def test_a_large_cube_takes_what_the_rule_allows(monkeypatch):
    """0.48 m: at most two threads by its bars, at most the allowed cores; and
    --threads above the allowed cores is cut to them."""
    monkeypatch.delenv("OMP_NUM_THREADS", raising=False)
    cores = len(os.sched_getaffinity(0))
    assert _core.allowed_cores() == cores  # no cgroup quota below the affinity here
    sim = CubeTest(size=0.48).simulation()
    assert sim.total_bars == BARS[0.48] and 1 <= sim.threads <= min(2, cores)
    assert CubeTest(size=0.12, threads=cores + 3).simulation().threads == cores


def test_idle_cores_see_a_cpu_bound_job():
    """One `yes` per allowed core: at most half a core reads idle."""
    cores = _core.allowed_cores()
    hogs = [subprocess.Popen(["yes"], stdout=subprocess.DEVNULL) for _ in range(cores)]
    try:
        idle = _core.idle_cores(0.3)
    finally:
        for h in hogs:
            h.kill()
            h.wait()
    assert 0.0 <= idle <= 0.5, idle
