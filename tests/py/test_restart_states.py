"""Every state of every dynamic part across a restart and an extension, through
the Python path (ldem.run_cube: checkpoint.npz and final_state.npz written and
read by ldem.io, Simulation.restore from the bindings' dict): at each record
after the restart, each part's state (checkpoint.npz's part_ROLE_NAME: the
drive, the load-loss test, the stop rules, the dampings, the quasi-static
flag) and the run's events are those of the run that never stopped, field by
field, bit for bit. The checkpoints are taken past the load loss, where every
part that keeps a state has one (a part restored fresh shows at once)."""
import json

import numpy as np
import pytest

import ldem
from conftest import run_cli

EVENTS = ("load_loss", "separation", "converged", "counters")


class States:
    """An observer: each record's part states and events, by step."""

    def __init__(self, sim):
        self.sim, self.by_step = sim, {}

    def __call__(self, row):
        c = self.sim.checkpoint()
        self.by_step[int(row["step"])] = {k: np.array(v) for k, v in c.items()
                                          if k.startswith("part_") or k in EVENTS}


def run(test, out=None, **kw):
    """test run with States recorded (run_cube, no pictures): (result, States)."""
    sim = test.simulation()
    states = States(sim)
    kw.setdefault("writers", ["curve", "summary"] + (["checkpoint"] if kw.get("checkpoint_every") else [])
                  + (["final_state"] if kw.get("final_state") or kw.get("extend") else []))
    result = ldem.run_cube(test, out=out, progress=False, simulation=sim, observers=[states] + kw.pop("also", []),
                           **kw)
    return result, states


def assert_same_states(after, whole, since, kept=()):
    """Every record of `after` (a restarted or extended run) past step `since`
    has the parts' states and events of `whole`'s record at that step (but the
    events `kept` from before the extension)."""
    steps = sorted(s for s in after.by_step if s > since)
    assert steps, "no record after the restart"
    for step in steps:  # field by field first: a failure names the part
        a, w = after.by_step[step], whole.by_step.get(step, {})
        assert sorted(a) == sorted(w), f"step {step}: {sorted(a)} against {sorted(w)}"
        for key in sorted(set(w) - set(kept)):
            assert np.array_equal(a[key], w[key]), f"{key} at step {step}: {a[key]} against {w[key]}"
    assert steps == sorted(s for s in whole.by_step if s > since)  # and it stopped where the whole run did


def assert_every_part_holds_a_state(state):
    """At the restart point every part that keeps a state has one: restoring it fresh would show."""
    parts = {k: v for k, v in state.items() if k.startswith("part_") and np.size(v)}
    assert len(parts) >= 5, sorted(parts)
    fresh = [k for k, v in parts.items() if not np.any(v)]
    assert not fresh, f"parts still in their initial state at the checkpoint: {fresh}"


CONVERGED = dict(size=0.04, stop_at="converged", converged_growth=0.05, final_strain=1.0, threads=1)


@pytest.mark.parametrize("drive,dashpots", [("adaptive", "lagged"), ("fixed", "lagged"), ("adaptive", "predicted")])
def test_a_restart_past_the_load_loss_restores_every_part(tmp_path, drive, dashpots):
    """The 0.04 m cube to convergence (0.9 s): interrupted past its load loss
    and its first rung, restarted from checkpoint.npz; also with the bar dashpots
    read at the predicted velocity (their forces in a second pass)."""
    test = ldem.CubeTest(tail_drive=drive, dashpot_velocity=dashpots, **CONVERGED)
    whole, states = run(test)
    assert whole.summary["stop_reason"] == "converged"
    steps = sorted(states.by_step)
    loss = steps.index(whole.summary["load_loss"]["step"])
    every = (loss + len(steps)) // 2 + 1  # rows: the checkpoint lands halfway from the load loss to the end
    assert loss + 1 < every < len(steps)
    seen = []

    def interrupt(row):
        seen.append(row)
        if len(seen) == every + 2:
            raise KeyboardInterrupt

    out = str(tmp_path / "cut")
    with pytest.raises(KeyboardInterrupt):
        run(test, out, checkpoint_every=every, also=[interrupt])
    saved = dict(np.load(tmp_path / "cut" / "checkpoint.npz"))
    at = int(saved["counters"][0])
    assert at == steps[every - 1] > steps[loss]
    assert_every_part_holds_a_state(saved)
    again, restarted = run(test, out, restart=True)
    assert_same_states(restarted, states, at)
    assert again.summary["converged"] == whole.summary["converged"]


@pytest.mark.parametrize("stop", [dict(stop_at="load_loss"), dict(final_strain=4e-3),
                                  dict(stop_at="converged", converged_growth=0.05)],
                         ids=["at_load_loss", "at_final_strain", "converged"])
def test_an_extension_restores_every_part_whatever_stopped_the_run(tmp_path, stop):
    """A run stopped by each stop rule that leaves a final state, extended with
    final_state.npz to separation: from there on, the states of a run to
    separation from the start. (The 0.04 m cube, measured: it loses its load at
    mean strain 1.9e-3, converges at 7.8e-3 and separates at 0.19.)"""
    base = dict(size=0.04, threads=1)
    out = str(tmp_path / "short")
    short, _ = run(ldem.CubeTest(**base, **stop), out, final_state=True)
    assert short.summary["stop_reason"] != "separated" and short.summary["load_loss"], short.summary["stop_reason"]
    saved = dict(np.load(tmp_path / "short" / "final_state.npz"))
    assert_every_part_holds_a_state(saved)
    kept = {k: v for k, v in stop.items() if k not in ("stop_at", "final_strain")}  # all but the stop
    longer = ldem.CubeTest(**base, **kept, final_strain=1.0)
    extended, after = run(longer, out, extend=True)
    straight, whole = run(longer)
    assert straight.summary["stop_reason"] == extended.summary["stop_reason"] == "separated"
    # A converged run extended keeps its convergence (U_final) beside the separation to come.
    kept = ("converged",) if stop.get("stop_at") == "converged" else ()
    assert_same_states(after, whole, int(saved["counters"][0]), kept)
    assert extended.summary["U_num_J"] == straight.summary["U_num_J"]
    for event in kept:
        assert extended.summary[event] == short.summary[event]


def test_the_command_extends_a_run_that_stopped_at_its_load_loss(tmp_path):
    """`ldem cube --restart DIR --extend STRAIN` takes a run stopped at its load
    loss on (its stop becomes separation): curve.csv byte for byte that of the
    run to separation from the start."""
    args = ["--size", "0.04", "--threads", "1", "--no-progress", "--no-plots"]
    short, whole = tmp_path / "short", tmp_path / "whole"
    r = run_cli("cube", *args, "--stop-at", "load_loss", "--out", str(short))
    assert r.returncode == 0, r.stderr
    assert json.loads((short / "summary.json").read_text())["stop_reason"] == "load_lost"
    r = run_cli("cube", "--restart", str(short), "--extend", "1", "--no-progress", "--no-plots")
    assert r.returncode == 0, r.stderr
    assert run_cli("cube", *args, "--final-strain", "1", "--out", str(whole)).returncode == 0
    assert json.loads((short / "summary.json").read_text())["stop_reason"] == "separated"
    assert (short / "curve.csv").read_bytes() == (whole / "curve.csv").read_bytes()
