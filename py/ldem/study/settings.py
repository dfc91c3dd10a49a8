"""What the size-effect study sets beside CubeTest's defaults, and its cases
(`ldem study size-effect`, `ldem study damping`): the stop of each load, the
damping of the tail past the load loss, and the drive's pace."""
from __future__ import annotations

from typing import Iterable, List

from ..cube import CubeTest


# What ends a case of the size-effect study. The uniform cube separates: U_num.
# The triangular one hinges and never does. What the study reports of it (its
# peaks, strains at the peak, curves and crack pictures) is in the record by 10
# x its strain at the peak, so by default it stops there (stop_at past_peak:
# dynamics/PastPeakStop.hpp). Its load loss (1 %) comes much later, and its
# U_final (dynamics/ConvergedStop.hpp) later still, as the columns beside the
# hinge break: both are options, at their cost in steps
# (results/archive/size-effect/study_hour/README.md).
STUDY_STOP = {"uniform": "separation", "triangular": "past_peak"}
TRIANGULAR_STOPS = ("past_peak", "load_loss", "converged")
TRIANGULAR_CONVERGED_COST = ("about 55 min a 0.96 m case on 2 cores, 5.5 h for its six seeds, measured with the "
                             "fixed tail drive (results/archive/size-effect/study_in_an_hour.md); today's drive "
                             "bounds its drag and was not timed so far")


# Past its load loss a cube's upper half hangs from the drive, which then runs
# faster. From 0.72 m on the study damps each node's velocity less its own mean
# there (tail_damping relative, dynamics/MassDamping.hpp), so that the speed-up
# drags nothing: U_num is then the absolute damping's in fewer steps. Below 0.72
# m the tail breaks much of U_num, and the relative damping is the farther from
# a run with no speed-up (results/dynamics/relative_damping.md): the absolute
# damping stays there, and its drive bounds its drag.
# --set tail_damping=... sets it for every size.
RELATIVE_TAIL_FROM_M = 0.72


def tail_settings(size: float) -> dict:
    return {"tail_damping": "relative"} if size >= RELATIVE_TAIL_FROM_M else {}


# The study's drive is the cube's (cube.CUBE_DEFAULTS): it slows to a sixteenth
# of its rate near the peak and while a crack runs (dynamics/CrackPace.hpp). At
# a constant rate a large cube snaps back at its peak while the drive keeps
# working, and its cracks take that work: the energy past its load loss then
# fails the spec's test of a numerical aid, the quarter rate. A crack runs while
# bars soften and the specimen's own kinetic energy is above crack_kinetic x the
# work, high enough that the triangular cube's ringing after its snap does not
# hold the pace (results/dynamics/cube_rate.md). --set crack_pace=1 runs the
# constant rate.

# Past its snap a triangular cube hangs on its hinge and softens slowly, at a
# tenth to a fiftieth of its peak, to the study's stop at 10 x its strain at the
# peak. From 0.72 m on (the relative tail) the tail's drive (AdaptiveDrive.hpp)
# takes over once the hinge carries less than a tenth of the peak: the study's
# triangular "load loss" is at stop_fraction 0.1 there (its columns in cases.csv),
# which saves steps and moves U at the stop less than the quarter rate does
# (results/size-effect/README.md).
TRIANGULAR_TAIL_FRACTION = 0.1


def study_settings(size: float, load: str = "uniform", stop: str = "separation") -> dict:
    """What the size-effect study sets beside CubeTest's defaults for a cube of this size, load and stop."""
    tail = tail_settings(size)
    hinge = {"stop_fraction": TRIANGULAR_TAIL_FRACTION} if tail and (load, stop) == ("triangular", "past_peak") else {}
    return {**tail, **hinge}


def size_effect_tests(sizes: Iterable[float], seeds: int, loads: Iterable[str], triangular_stop: str = "past_peak",
                      **common) -> List[CubeTest]:
    """The study's cases; triangular_stop: what ends a triangular case (TRIANGULAR_STOPS)."""
    if triangular_stop not in TRIANGULAR_STOPS:
        raise ValueError(f"triangular_stop must be one of {', '.join(TRIANGULAR_STOPS)}, not {triangular_stop!r}")
    stop = {**STUDY_STOP, "triangular": triangular_stop}
    return [CubeTest(size=s, load=ld, seed=k, **{"stop_at": stop[ld], **study_settings(s, ld, stop[ld]), **common})
            for ld in loads for s in sizes for k in range(1, seeds + 1)]


def damping_tests(size: float, zetas: Iterable[float], loads: Iterable[str], seed: int = 1,
                  **common) -> List[CubeTest]:
    return [CubeTest(size=size, load=ld, seed=seed, zeta=z, **common) for ld in loads for z in zetas]
