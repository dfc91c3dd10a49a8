"""A run with its files: the wiring of CubeTest.run to the writers, the
progress bar and the pictures (used by `ldem cube`, the studies and scripts).

    import ldem
    result = ldem.run_cube(ldem.CubeTest(size=0.24), out="out/t024")
"""
from __future__ import annotations

import contextlib
import os
import signal
import threading
from typing import Optional, Sequence

from . import io, parallel
from .cube import CubeResult, CubeTest, refuse_drive_jump
from .progress import ProgressBar


def run_cube(test: CubeTest, out: Optional[str] = None, progress: Optional[bool] = None, plots: bool = True,
             simulation=None, figure_format: str = "png", snapshots: Sequence[float] = (),
             checkpoint_every: int = 0, restart: bool = False, observers: Sequence = (),
             checkpoint_seconds: float = 0.0) -> CubeResult:
    """Runs test (an ldem.CubeTest or an ldem.specimen.SpecimenTest); with out, writes curve.csv (row by row), summary.json (also
    when the run fails or is interrupted: status says so) and, with plots,
    curve, energies and cracks pictures (figure_format: png, pdf or svg) and
    the ParaView series: bars_NNNN.vtu and crack_NNNN.vtu at each mean strain of
    `snapshots`, bars.vtu and crack.vtu at the end, bars.pvd and crack.pvd.
    progress: a bar on stderr (default: when stderr is a terminal).
    checkpoint_every: write out/checkpoint.npz every so many curve rows;
    checkpoint_seconds: every so many seconds of wall time (0: not on that count).
    observers: more callables given each curve row, after the writers.
    restart: continue the run of out/checkpoint.npz (same parameters), bit for
    bit as if it had never stopped; curve.csv keeps its rows up to the
    checkpoint and gets the rest; summary.json's wall_s counts the run's wall
    time up to the checkpoint too, and restarted_at_step says where it
    continued."""
    if any(not (s > 0) for s in snapshots):
        raise ValueError(f"snapshot strains must be positive (got {list(snapshots)})")
    if checkpoint_every < 0 or not (checkpoint_seconds >= 0):
        raise ValueError(f"checkpoint intervals must be >= 0 rows and >= 0 s (got {checkpoint_every} rows, "
                         f"{checkpoint_seconds} s)")
    checkpoints = bool(checkpoint_every or checkpoint_seconds)
    if (restart or checkpoints) and out is None:
        raise ValueError("checkpoints need an output folder")
    if (restart or checkpoints) and parallel.ranks() > 1:
        raise ValueError("checkpoints and restarts of a run split over MPI ranks are not supported")
    if out is not None:
        io.prepare_dir(out)
    sim = simulation if simulation is not None else _set_up(test, out)
    if sim.steps == 0:
        refuse_drive_jump(test, sim.dt)  # as test.run would, before any file is opened
    previous, wall_before = [], 0.0
    if restart:
        previous, wall_before = _restore(test, sim, out)
    root = parallel.is_root()  # under MPI, rank 0 writes the files every rank has (the curve, the summary)
    bar = ProgressBar(test.final_strain, enabled=progress if root else False, energy_tolerance=test.energy_tolerance)
    csv = io.CurveCsv(os.path.join(out, "curve.csv"), append=restart) if out is not None and root else None
    series = io.Snapshots(sim, out, [s for s in snapshots if not previous or s > previous[-1]["mean_strain"]]) \
        if out is not None and plots else None
    saver = io.Checkpoints(sim, os.path.join(out, "checkpoint.npz"), checkpoint_every, test.parameters(),
                           checkpoint_seconds, wall_before) if checkpoints else None
    held = SignalsAtRecords(saver)
    everyone = [o for o in (csv, bar, series, saver) if o is not None] + list(observers) + [held]
    try:
        with held:
            result = test.run(everyone, simulation=sim, previous_rows=previous)
    except BaseException as e:
        partial = getattr(e, "ldem_result", None)
        if out is not None and partial is not None and root:
            _summary_after_failure(partial.summary, out)
        raise
    finally:
        bar.close()
        if csv is not None:
            csv.close()
    if restart:
        result.wall_s += wall_before
        result.summary.update(wall_s=result.wall_s, restarted_at_step=int(previous[-1]["step"]) if previous else 0)
    if out is not None:
        try:
            if plots:
                write_pictures(result, out, figure_format)
                series.finish(float(result.curve["mean_strain"][-1]))
        except BaseException as e:  # the run is done, its outputs are not: the summary says so
            result.summary.update(status="interrupted" if isinstance(e, KeyboardInterrupt) else "failed",
                                  error=f"writing the outputs: {e}")
            if root:
                _summary_after_failure(result.summary, out)
            raise
        if root:
            io.write_summary(result.summary, os.path.join(out, "summary.json"))  # last: "done" means all is written
        if checkpoints:  # the run is finished: no state left that a restart would silently run again
            with contextlib.suppress(FileNotFoundError):
                os.remove(os.path.join(out, "checkpoint.npz"))
    return result


class SignalsAtRecords:
    """SIGINT and SIGTERM during the loop, held to the end of the record being
    observed (the last observer: every other one has seen it, curve.csv has
    its row), then checkpoint.npz of that record and the signal's own handler
    (KeyboardInterrupt, or ldem.cli's Terminated). A restart continues from
    there bit for bit. The C++ loop hands back to Python only at records, so
    holding costs no delay. Only Python handlers are held (not the defaults,
    not off the main thread, where signals cannot be handled)."""

    SIGNALS = (signal.SIGINT, signal.SIGTERM)

    def __init__(self, saver=None):
        self.saver, self.pending, self.previous = saver, None, {}

    def __enter__(self):
        if threading.current_thread() is threading.main_thread():
            self.previous = {s: signal.getsignal(s) for s in self.SIGNALS if callable(signal.getsignal(s))}
            for s in self.previous:
                signal.signal(s, self._hold)
        return self

    def _hold(self, signum, frame):
        self.pending = signum

    def __call__(self, row: dict) -> None:
        if self.pending is not None:
            if self.saver is not None:
                self.saver.write()
            handler = self.previous.get(self.pending, signal.default_int_handler)
            self.__exit__()
            handler(self.pending, None)

    def __exit__(self, *exc):
        for s, handler in self.previous.items():
            signal.signal(s, handler)
        self.previous = {}


def _set_up(test: CubeTest, out: Optional[str]):
    """test.simulation(); a signal meanwhile leaves a summary.json that says so."""
    try:
        return test.simulation()
    except KeyboardInterrupt:
        if out is not None and parallel.is_root():
            _summary_after_failure({"status": "interrupted", "stop_reason": "interrupted",
                                    "error": "interrupted during set-up"}, out)
        raise


def _restore(test: CubeTest, sim, out: str) -> tuple:
    """sim set back to out/checkpoint.npz, curve.csv cut to its rows; returns
    them and the wall time the run had taken up to the checkpoint."""
    path = os.path.join(out, "checkpoint.npz")
    try:
        state, parameters, wall_s = io.read_checkpoint(path)
    except OSError as e:
        raise ValueError(f"cannot restart: {path}: {e.strerror or e}") from None
    mine = {k: v for k, v in test.parameters().items() if k != "threads"}
    if {k: v for k, v in parameters.items() if k != "threads"} != mine:
        raise ValueError(f"cannot restart: {path} is of other parameters")
    sim.restore(state)
    return io.cut_curve_after(os.path.join(out, "curve.csv"), int(state["counters"][0])), wall_s


def _summary_after_failure(summary: dict, out: str) -> None:
    """The summary of a run that failed or was interrupted, if the disk takes
    it; the first error is the one reported."""
    with contextlib.suppress(OSError):
        io.write_summary(summary, os.path.join(out, "summary.json"))


def write_pictures(result: CubeResult, out: str, fmt: str = "png") -> None:
    from . import plots

    if fmt not in plots.FIGURE_FORMATS:
        raise ValueError(f"unknown figure format '{fmt}' (expected one of {', '.join(plots.FIGURE_FORMATS)})")
    if parallel.is_root():
        plots.curve_figure(result, os.path.join(out, f"curve.{fmt}"))
        plots.energy_figure(result, os.path.join(out, f"energies.{fmt}"))
    plots.crack_figure(result.sim, os.path.join(out, f"cracks.{fmt}"),
                       title=f"{result.test.describe()}: "
                             f"mean strain {result.curve['mean_strain'][-1]:.2e}")
