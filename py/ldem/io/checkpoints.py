"""checkpoint.npz: writing it as a run goes, and setting a run back to it.
Registers the writer "checkpoint"."""
from __future__ import annotations

import contextlib
import json
import os
import time

import numpy as np

from .files import atomic
from .registry import register_writer
from .tables import CURVE, cut_curve_after

CHECKPOINT = "checkpoint.npz"
FINAL_STATE = "final_state.npz"
# What may differ between a finished run and its extension: the stop.
EXTENSIBLE = ("final_strain", "stop_at")


def write_checkpoint(path: str, state: dict, parameters: dict, wall_s: float = 0.0) -> None:
    """checkpoint.npz: the arrays of Simulation.checkpoint() (nodes: u_*, v_*,
    f_* by component; bars: kappa, eps_r; rows: softening; the run's scalars,
    counters and events; part_NAME: each dynamic part's state, e.g.
    part_drive_adaptive, part_test_load_loss, part_stop_separation), the test's parameters as JSON and
    the wall time the run had taken. npz, not HDF5: numpy reads it with
    nothing else installed, and it holds named arrays, which is all a
    checkpoint is."""
    with atomic(path) as tmp:
        np.savez(tmp, parameters=np.array(json.dumps(parameters)), wall_s=np.array(wall_s), **state)


def read_checkpoint(path: str) -> tuple:
    """(state for Simulation.restore, parameters, wall time the run had taken [s])."""
    with np.load(path) as z:
        state = {k: z[k] for k in z.files if k not in ("parameters", "wall_s")}
        return state, json.loads(str(z["parameters"])), float(z["wall_s"]) if "wall_s" in z.files else 0.0


def case_checkpoint(out: str) -> tuple:
    """read_checkpoint of the run in folder out."""
    return read_checkpoint(os.path.join(out, CHECKPOINT))


def saved_step(out: str) -> int:
    """The step of out's checkpoint.npz, its counters alone read (a large state
    is not loaded); OSError if there is none."""
    with np.load(os.path.join(out, CHECKPOINT)) as z:
        return int(z["counters"][0])


def discard_checkpoint(out: str) -> None:
    """The run in out is done: its state is not needed any more."""
    with contextlib.suppress(FileNotFoundError):
        os.remove(os.path.join(out, CHECKPOINT))


def _fixed(parameters: dict, free: tuple) -> dict:
    """The parameters a restart must find unchanged: all but the free ones, at the top (a cube's) and
    under "parameters" (a specimen's, beside its description)."""
    kept = {k: v for k, v in parameters.items() if k not in free}
    if isinstance(kept.get("parameters"), dict):
        kept["parameters"] = _fixed(kept["parameters"], free)
    return kept


def restore(test, sim, out: str, extend: bool = False) -> tuple:
    """sim set back to out's checkpoint.npz (with extend: to its
    final_state.npz, the test's stop may be a later one), curve.csv cut to its
    rows; returns them and the wall time the run had taken up to that state."""
    path = os.path.join(out, FINAL_STATE if extend else CHECKPOINT)
    try:
        state, parameters, wall_s = read_checkpoint(path)
    except OSError as e:
        raise ValueError(f"cannot {'extend' if extend else 'restart'}: {path}: {e.strerror or e}") from None
    free = ("threads",) + (EXTENSIBLE if extend else ())
    if _fixed(parameters, free) != _fixed(test.parameters(), free):
        raise ValueError(f"cannot {'extend' if extend else 'restart'}: {path} is of other parameters")
    rows = cut_curve_after(os.path.join(out, CURVE), int(state["counters"][0]))
    reached = float(rows[-1]["mean_strain"]) if rows else 0.0
    if extend and not test.final_strain > reached:
        raise ValueError(f"cannot extend: the run reached mean strain {reached:.4g}; extend it to a larger one")
    sim.restore(state)
    return rows, wall_s


class Checkpoints:
    """An observer of CubeTest.run: checkpoint.npz every `every` curve rows
    and/or every `seconds` of wall time (0: not on that count); wall_before:
    the wall time of the run before this piece of it (a restart)."""

    def __init__(self, sim, path: str, every: int, parameters: dict, seconds: float = 0.0, wall_before: float = 0.0):
        self.sim, self.path, self.every, self.parameters, self.seconds = sim, path, every, parameters, seconds
        self.rows, self.wall_before = 0, wall_before
        self.start = self.last = time.monotonic()

    def __call__(self, row: dict) -> None:
        self.rows += 1
        now = time.monotonic()
        if (self.every and self.rows % self.every == 0) or (self.seconds and now - self.last >= self.seconds):
            self.write()

    def write(self) -> None:
        """checkpoint.npz of the record being observed (also at a SIGTERM or SIGINT: ldem.runner)."""
        self.last = now = time.monotonic()
        write_checkpoint(self.path, self.sim.checkpoint(), self.parameters, self.wall_before + now - self.start)

    def finish(self, result) -> None:
        """The run is finished: no state left that --restart would silently run again."""
        with contextlib.suppress(FileNotFoundError):
            os.remove(self.path)


def _checkpoint_writer(run) -> Checkpoints:
    o = run.options
    return Checkpoints(run.sim, os.path.join(run.out, CHECKPOINT), o.get("checkpoint_every", 0),
                       run.test.parameters(), o.get("checkpoint_seconds", 0.0), o.get("wall_before", 0.0))


class FinalState:
    """final_state.npz at the end of a run that did not separate (it stopped at
    its final strain, at load loss or on request): restore(..., extend=True)
    takes it on to a later stop. A run that separated has nothing to extend,
    and an older final state is removed."""

    def __init__(self, run):
        self.sim, self.path, self.parameters = run.sim, os.path.join(run.out, FINAL_STATE), run.test.parameters()

    def finish(self, result) -> None:
        if result.summary["stop_reason"] == "separated":
            with contextlib.suppress(FileNotFoundError):
                os.remove(self.path)
        else:
            write_checkpoint(self.path, self.sim.checkpoint(), self.parameters, result.wall_s)


register_writer("final_state", FinalState, 40, "final_state.npz: the last state of a run that did not separate")
register_writer("checkpoint", _checkpoint_writer, 30,
                "checkpoint.npz every checkpoint_every rows and/or checkpoint_seconds of wall time")
