"""A run with its files: test.run given the writers named for it (ldem.io's
registry: this module knows no file name) and the progress bar (used by
`ldem cube`, `ldem run`, the studies and scripts).

    import ldem
    result = ldem.run_cube(ldem.CubeTest(size=0.24), out="out/t024")
"""
from __future__ import annotations

import os
from typing import Optional, Sequence

from . import io, parallel
from .cube import CubeResult, CubeTest
from .progress import ProgressBar
from .signals import SignalsAtRecords


# Where a run that did not separate stopped, in words (summary.json's stop_reason).
STOP_WORDS = {"final_strain": "the final strain", "past_peak": "peak_stop_strain_ratio x the strain at the peak",
              "stopped": "an observer's request"}


def stopped_short(test, stop_reason: str) -> bool:
    """Whether a run meant to separate (or to converge) stopped before that at
    a limit of its own (the final strain): its fracture energy is then not
    U_num. A stop an observer asked for (a study's beam past its peak) is
    where the case was meant to end."""
    return stop_reason != "stopped" and getattr(test, "stop_at", None) in ("separation", "converged")


def default_writers(plots: bool = True, checkpoints: bool = False, final_state: bool = False) -> list:
    """The writers of `ldem cube` and `ldem run`: the curve and the summary,
    with plots the pictures and the ParaView files, with checkpoints those,
    with final_state the state a finished run can be extended from."""
    return ["curve", "summary"] + (["figures", "vtk"] if plots else []) + (["checkpoint"] if checkpoints else []) \
        + (["final_state"] if final_state else [])


def run_cube(test: CubeTest, out: Optional[str] = None, progress: Optional[bool] = None, plots: bool = True,
             simulation=None, figure_format: str = "png", snapshots: Sequence[float] = (),
             checkpoint_every: int = 0, restart: bool = False, observers: Sequence = (),
             checkpoint_seconds: float = 0.0, writers: Optional[Sequence[str]] = None,
             title: str = "", final_state: bool = False, extend: bool = False) -> CubeResult:
    """Runs test (an ldem.CubeTest, an ldem.specimen.SpecimenTest, or any
    object with their parameters(), simulation() and run()); with out, the
    writers named in `writers` (ldem.io.writer_names(); default:
    default_writers(plots, checkpoints)) write their files: curve.csv (row by
    row), summary.json (also when the run fails or is interrupted: status says
    so) and, with plots, curve, energies and cracks pictures (figure_format:
    png, pdf or svg) and the ParaView series: bars_NNNN.vtu and crack_NNNN.vtu
    at each mean strain of `snapshots`, bars.vtu and crack.vtu at the end,
    bars.pvd and crack.pvd.
    progress: a bar on stderr (default: when stderr is a terminal).
    checkpoint_every: write out/checkpoint.npz every so many curve rows;
    checkpoint_seconds: every so many seconds of wall time (0: not on that count).
    observers: more callables given each curve row, after the writers.
    title: the title of the "slice" writer's cracks.png.
    restart: continue the run of out/checkpoint.npz (same parameters), bit for
    bit as if it had never stopped; curve.csv keeps its rows up to the
    checkpoint and gets the rest; summary.json's wall_s counts the run's wall
    time up to the checkpoint too, and restarted_at_step says where it
    continued.
    final_state: a run that does not separate leaves out/final_state.npz;
    extend: continue the finished run of out/final_state.npz (same
    parameters but the stop: test's final_strain beyond the strain it
    reached, stop_at) as if it had never stopped; implies restart."""
    if any(not (s > 0) for s in snapshots):
        raise ValueError(f"snapshot strains must be positive (got {list(snapshots)})")
    if checkpoint_every < 0 or not (checkpoint_seconds >= 0):
        raise ValueError(f"checkpoint intervals must be >= 0 rows and >= 0 s (got {checkpoint_every} rows, "
                         f"{checkpoint_seconds} s)")
    checkpoints = bool(checkpoint_every or checkpoint_seconds)
    restart = restart or extend
    names = io.check_writers(default_writers(plots, checkpoints, final_state) if writers is None else writers)
    if (restart or checkpoints or final_state) and out is None:
        raise ValueError("checkpoints need an output folder")
    if (restart or checkpoints or final_state) and parallel.ranks() > 1:
        raise ValueError("checkpoints and restarts of a run split over MPI ranks are not supported")
    sim = _set_up(test, out, simulation)  # refuses a drive too fast or too slow before any file is opened
    previous, wall_before = [], 0.0
    if restart:
        previous, wall_before = io.restore(test, sim, out, extend)
    root = parallel.is_root()  # under MPI, rank 0 writes the files every rank has (the curve, the summary)
    bar = ProgressBar(test.final_strain, enabled=progress if root else False, energy_tolerance=test.energy_tolerance,
                      energy_scale=sim.min_fracture_energy)
    run = io.Run(test, sim, out, previous, dict(snapshots=snapshots, figure_format=figure_format, restart=restart,
                                                checkpoint_every=checkpoint_every, title=title,
                                                checkpoint_seconds=checkpoint_seconds, wall_before=wall_before))
    files = io.open_writers(names, run) if out is not None else []
    held = SignalsAtRecords(next((w for w in files if isinstance(w, io.Checkpoints)), None), sim)
    everyone = [w for w in files if callable(w)] + [bar] + list(observers) + [held]
    try:
        with held:
            result = test.run(everyone, simulation=sim, previous_rows=previous)
    except BaseException as e:
        partial = getattr(e, "ldem_result", None)
        if partial is not None:
            _tell(files, "failed", partial.summary)
        raise
    finally:
        bar.close()
        _tell(files, "close")
    if restart:
        result.wall_s += wall_before
        result.summary.update(wall_s=result.wall_s, restarted_at_step=int(previous[-1]["step"]) if previous else 0)
    try:
        _tell(files, "finish", result)  # in rank order: the summary last, "done" means all is written
    except BaseException as e:  # the run is done, its outputs are not: the summary says so
        result.summary.update(status="interrupted" if isinstance(e, KeyboardInterrupt) else "failed",
                              error=f"writing the outputs: {e}")
        _tell(files, "failed", result.summary)
        raise
    return result


def _set_up(test: CubeTest, out: Optional[str], simulation=None):
    """The output folder, then test.simulation() (unless given); a signal
    meanwhile leaves a summary.json that says so, from the moment the folder
    exists (a signal between the folder and the simulation's set-up would
    otherwise leave none)."""
    try:
        if out is not None:
            io.prepare_dir(out)
        return simulation if simulation is not None else test.simulation()
    except KeyboardInterrupt:
        if out is not None and os.path.isdir(out):
            _tell(io.open_writers(["summary"], io.Run(test, None, out)), "failed",
                  {"status": "interrupted", "stop_reason": "interrupted", "error": "interrupted during set-up"})
        raise


def _tell(writers: Sequence, what: str, *args) -> None:
    """Calls method `what` of every writer that has one, in their order."""
    for w in writers:
        method = getattr(w, what, None)
        if method is not None:
            method(*args)
